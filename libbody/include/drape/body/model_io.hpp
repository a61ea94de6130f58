// Body model files (HDF5; layout in docs/body-model-format.md) and mesh files
// (rigged glTF binary .glb, Wavefront OBJ) for bodies.
#pragma once

#include <drape/body/body_model.hpp>
#include <drape/body/motion.hpp>
#include <drape/body/pose.hpp>

#include <Eigen/Core>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace drape::body {

/// Writes the whole model (template, faces, shape basis, skeleton, joint regressor, skin
/// weights, landmarks, semantic map, prior, units) to an HDF5 file, atomically (an
/// existing file is replaced only once the new one is complete). Reading it back with
/// load_model() is bit-exact.
/// \throw drape::InvalidInput (nothing written) if the model breaks an invariant that
///        load_model() checks, naming the dataset it would go to;
///        drape::IoError if the file cannot be written (e.g. the folder does not exist).
void save_model(const BodyModel& model, const std::filesystem::path& path);

struct ModelLoadOptions {
    /// Read variable-length strings (h5py's default string type). They live in the file's
    /// global heap, which libhdf5 1.10 reads unchecked: a damaged one crashes or hangs the
    /// process (docs/hardening.md). Off: a file holding them is refused, naming the
    /// dataset, before libhdf5 reads them. Turn on only for files you trust.
    bool allow_variable_length_strings = false;
    /// Parse the file first in a child process (core::run_isolated), and only if that child
    /// finished cleanly parse it again here. libhdf5 1.10 has open crashes on damaged files
    /// (a heap overflow in its object-header parser, found by fuzzing: docs/hardening.md);
    /// isolated, such a file is an IoError, not a crash of the host. Costs one fork and a
    /// second parse (about 2x the load time). Off only for files you trust.
    bool isolate = true;
    /// With `isolate`: the child's time limit, seconds (a parse that hangs is killed).
    double isolation_timeout_s = 60.0;
};

/// Reads a model written by save_model or converted by a user (docs/body-model-format.md).
/// Never prints HDF5 diagnostics; every problem is reported by the exception.
/// The file is read into memory once (at most limits::kMaxModelFileBytes) and parsed from
/// there, so both parses see the same bytes.
/// \throw drape::IoError naming the path if the file is missing, unreadable or not HDF5, or
///        if the HDF5 library crashed or hung parsing it in the isolated child;
///        drape::InvalidInput naming the file and dataset if its content is inconsistent
///        (wrong shape, bad indices, NaN, different skeleton, weights not summing to 1,
///        variable-length strings not allowed by `options`, ...).
BodyModel load_model(const std::filesystem::path& path, const ModelLoadOptions& options = {});

/// Writes a posed body as a rigged glTF 2.0 binary: the shaped rest mesh bound to the
/// 22-joint skeleton (inverse bind matrices, <= 4 weights per vertex), with the pose set
/// on the joint nodes, so that a viewer shows the posed body and Blender imports a posable
/// armature. Written atomically. Joint node j carries global(parent)^-1 * global_j of
/// forward_kinematics(shaped.joints, pose), so skinning in the viewer reproduces
/// pose_body(model, shaped, pose) (to float precision).
/// \param shaped  rest vertices (#V x 3, the model's vertex count) and joints of the body.
/// \throw drape::InvalidInput on size mismatch, non-finite input or an invalid pose;
///        drape::IoError if the file cannot be written.
void export_glb(const std::filesystem::path& path, const BodyModel& model,
                const ShapedBody& shaped, const Pose& pose);

/// A mesh that moves frame by frame with an animated body (e.g. a simulated garment).
struct FrameMesh {
    std::string name;                    ///< its glTF mesh and node name (unique)
    Eigen::MatrixXi F;                   ///< #F x 3
    Eigen::MatrixXd UV;                  ///< #V x 2 (v upwards) or empty
    std::vector<Eigen::MatrixXd> frames; ///< one #V x 3 position set per motion frame
    std::optional<Eigen::Vector3d> colour_linear;  ///< base colour, linear RGB in [0, 1]
};

/// Writes an animation as a glTF 2.0 binary: the rigged body (as export_glb, posed in the
/// first frame) with one animation "motion" whose key k at k / motion.fps sets every joint
/// node's local transform (forward_kinematics of frame k), and each FrameMesh as a mesh
/// whose morph targets are its frames, played by the same animation's weights channel
/// (target k has weight 1 at key k). Blender imports the targets as shape keys driven by
/// the action; three.js plays it with an AnimationMixer. Written atomically.
/// 	hrow drape::InvalidInput on an invalid motion, a mesh without one frame per motion
///        frame, or as export_glb and gltf::write_glb; drape::IoError if it cannot be written.
void export_animated_glb(const std::filesystem::path& path, const BodyModel& model, const ShapedBody& shaped,
                         const Motion& motion, const std::vector<FrameMesh>& meshes);

/// Writes a triangle mesh (#V x 3, #F x 3) as OBJ with area-weighted vertex normals
/// (exact decimal coordinates), atomically.
/// \throw drape::InvalidInput on bad shapes / indices / non-finite values; drape::IoError.
void export_obj(const std::filesystem::path& path, const Eigen::MatrixXd& V,
                const Eigen::MatrixXi& F);

/// A triangle mesh read from a file.
struct TriangleMesh {
    Eigen::MatrixXd V;  ///< #V x 3
    Eigen::MatrixXi F;  ///< #F x 3
};

/// Reads a glTF (.gltf/.glb) or OBJ mesh (all meshes merged with their node transforms,
/// triangulated, exactly coincident vertices welded, degenerate triangles dropped), in the
/// file's units and frame. Coordinates pass through assimp in single precision.
/// \throw drape::IoError if unreadable, drape::InvalidInput if it holds no triangles.
TriangleMesh import_mesh(const std::filesystem::path& path);

}  // namespace drape::body
