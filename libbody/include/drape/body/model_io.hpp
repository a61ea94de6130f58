// Body model files (HDF5; layout in docs/body-model-format.md) and mesh files
// (rigged glTF binary .glb, Wavefront OBJ) for bodies.
#pragma once

#include <drape/body/body_model.hpp>
#include <drape/body/pose.hpp>

#include <Eigen/Core>

#include <filesystem>

namespace drape::body {

/// Writes the whole model (template, faces, shape basis, skeleton, joint regressor, skin
/// weights, landmarks, semantic map, prior, units) to an HDF5 file, atomically.
/// \throw drape::IoError if the file cannot be written.
void save_model(const BodyModel& model, const std::filesystem::path& path);

/// Reads a model written by save_model or converted by a user (docs/body-model-format.md).
/// \throw drape::IoError if the file cannot be read; drape::InvalidInput naming the
///        dataset if its content is inconsistent (wrong shape, bad indices, NaN, ...).
BodyModel load_model(const std::filesystem::path& path);

/// Writes a posed body as a rigged glTF 2.0 binary: the shaped rest mesh bound to the
/// 22-joint skeleton (inverse bind matrices, <= 4 weights per vertex), with the pose set
/// on the joint nodes, so that a viewer shows the posed body and Blender imports a posable
/// armature. Written atomically. \throw drape::IoError, drape::InvalidInput.
void export_glb(const std::filesystem::path& path, const BodyModel& model,
                const ShapedBody& shaped, const Pose& pose);

/// Writes a triangle mesh (#V x 3, #F x 3) as OBJ with normals, atomically.
void export_obj(const std::filesystem::path& path, const Eigen::MatrixXd& V,
                const Eigen::MatrixXi& F);

/// A triangle mesh read from a file.
struct TriangleMesh {
    Eigen::MatrixXd V;  ///< #V x 3
    Eigen::MatrixXi F;  ///< #F x 3
};

/// Reads a glTF (.gltf/.glb) or OBJ mesh (all meshes merged, triangulated, duplicate
/// vertices welded), in the file's units and frame.
/// \throw drape::IoError if unreadable, drape::InvalidInput if it holds no triangles.
TriangleMesh import_mesh(const std::filesystem::path& path);

}  // namespace drape::body
