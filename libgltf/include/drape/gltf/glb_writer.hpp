// Writing a glTF 2.0 binary (.glb) from plain data: triangle meshes with optional normals,
// uv and base colour, each in a named node, and an optional skeleton that skins them.
// One implementation (assimp's "glb2" exporter, private) for body.glb, garment_N.glb and
// outfit.glb. Written atomically (drape/core/atomic_file.hpp).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace drape::gltf {

/// A joint hierarchy for skinned meshes: joint j is a node named names[j] under
/// parents[j] (-1: under the scene's root node), with node-local transform local[j], and
/// its bone's inverse bind matrix inverse_bind[j].
struct GlbSkeleton {
    std::vector<std::string> names;
    std::vector<int> parents;  ///< parents[j] < j, or -1
    std::vector<Eigen::Isometry3d> local;
    std::vector<Eigen::Isometry3d> inverse_bind;

    bool empty() const { return names.empty(); }
};

struct GlbMesh {
    std::string mesh_name;      ///< the glTF mesh's name
    std::string node_name;      ///< the node holding it; empty: the scene's root node holds it
    std::string material_name;  ///< its own material
    Eigen::MatrixXd V;          ///< #V x 3 positions (written as float)
    Eigen::MatrixXi F;          ///< #F x 3 vertex indices
    Eigen::MatrixXd N;          ///< #V x 3 unit normals, or empty (none written)
    /// #V x 2 texture coordinates with v upwards, or empty; glTF's v runs downwards, so a
    /// glTF reader gets (u, 1 - v) and assimp's importer gives (u, v) back.
    Eigen::MatrixXd UV;
    /// The material's base colour, linear RGB in [0, 1] (glTF's baseColorFactor); none:
    /// the glTF default (white).
    std::optional<Eigen::Vector3d> base_colour_linear;
    /// Per vertex, its (joint, weight) pairs (at most 4, weights summing to 1) of
    /// GlbScene::skeleton; empty: a static mesh.
    std::vector<std::vector<std::pair<int, double>>> skin;
};

struct GlbScene {
    std::string root_name = "root";  ///< the root node's name
    /// Meshes in order; each mesh's node is a child of the root, in this order, followed
    /// by the skeleton's root joints.
    std::vector<GlbMesh> meshes;
    GlbSkeleton skeleton;
};

/// Writes `scene` as a glTF binary at `path`, atomically.
/// \throw drape::InvalidInput naming the mesh (by index and name) and the problem: no
///        vertices or faces, wrong column counts, non-finite values, indices out of range,
///        N / UV / skin sizes not matching V, skin joints outside the skeleton, a
///        skeleton whose vectors differ in size or whose parents are not earlier joints.
/// \throw drape::IoError if the file cannot be written (naming it and assimp's reason).
void write_glb(const std::filesystem::path& path, const GlbScene& scene);

}  // namespace drape::gltf
