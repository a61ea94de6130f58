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
    /// Morph targets: absolute positions, each #V x 3 (written as glTF target displacements
    /// from V, named frame_K in the mesh's extras.targetNames). With GlbScene::animation
    /// they are its frames: one per key time.
    std::vector<Eigen::MatrixXd> morph_targets;
};

/// A keyframed animation (one glTF animation, linear interpolation): the skeleton's joints
/// move through node-local transforms, and every mesh with morph targets plays them as
/// frames — at times_s[k] target k has weight 1 and the others 0 (glTF "weights" channel on
/// the mesh's node), so the mesh passes through its K shapes in order.
struct GlbAnimation {
    std::string name = "animation";
    std::vector<double> times_s;  ///< K >= 1 key times, increasing, seconds
    /// Per skeleton joint, K node-local transforms (rotation + translation) at the key
    /// times; empty: the skeleton is not animated.
    std::vector<std::vector<Eigen::Isometry3d>> joint_local;
};

struct GlbScene {
    std::string root_name = "root";  ///< the root node's name
    /// Meshes in order; each mesh's node is a child of the root, in this order, followed
    /// by the skeleton's root joints.
    std::vector<GlbMesh> meshes;
    GlbSkeleton skeleton;
    /// Optional animation; meshes with morph targets then need one per key time and a node.
    std::optional<GlbAnimation> animation;
};

/// Writes `scene` as a glTF binary at `path`, atomically.
/// \throw drape::InvalidInput naming the mesh (by index and name) and the problem: no
///        vertices or faces, wrong column counts, non-finite values, indices out of range,
///        N / UV / skin sizes not matching V, skin joints outside the skeleton, a
///        skeleton whose vectors differ in size or whose parents are not earlier joints,
///        morph targets not #V x 3 finite, an animation whose times are not increasing,
///        whose joint transforms are not one per joint and key, or whose morph-animated
///        meshes lack a node or a target per key.
/// \throw drape::IoError if the file cannot be written (naming it and assimp's reason).
void write_glb(const std::filesystem::path& path, const GlbScene& scene);

}  // namespace drape::gltf
