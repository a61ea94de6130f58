// The recovered body and garments as plain meshes: what the output writers (label mask,
// overlay, outfit glb) read, so that they depend on neither the recovery's nor try-on's
// own structs.
#pragma once

#include <Eigen/Core>

#include <string>
#include <vector>

namespace drape::recover {

/// labels.txt (../shared/data/photos/labels.txt) id of skin: the body's class in mask.png.
constexpr int kSkinClassId = 41;

/// One garment: its draped surface in the world frame of the body.
struct OutfitGarment {
    std::string name;    ///< e.g. "tshirt" (messages, the glb's mesh name); may be empty
    Eigen::MatrixXd V;   ///< #V x 3 world positions, metres
    Eigen::MatrixXi F;   ///< #F x 3 vertex indices
    Eigen::MatrixXd UV;  ///< #V x 2 pattern coordinates (the garment glb's uv), or empty
    int class_id = 0;    ///< labels.txt id of the garment (e.g. 51 t-shirt, 31 pants), 1..255
};

/// A body (posed, in the world frame: metres, +Y up, facing +Z) and its garments, inner
/// first (the order a dressing pipeline puts them on).
struct OutfitMeshes {
    Eigen::MatrixXd body_V;  ///< #B x 3 world positions, metres
    Eigen::MatrixXi body_F;  ///< #F x 3
    int body_class_id = kSkinClassId;  ///< 1..255
    std::vector<OutfitGarment> garments;

    /// Throws drape::InvalidInput naming the mesh ("body", "garment 1 'pants'") and the
    /// problem: no vertices or triangles, wrong column counts, non-finite positions, face
    /// indices out of range, UV not #V x 2, a class id outside 1..255.
    void validate() const;
};

/// "body" or "garment K" (with " 'name'" when named): how messages name mesh `index` of
/// the outfit (0 = body, 1 + k = garment k).
std::string outfit_mesh_name(const OutfitMeshes& outfit, std::size_t index);

}  // namespace drape::recover
