// A garment mesh as a file: OBJ (text, with the pattern uv and a group per panel) and glTF
// binary (through drape::gltf), beside the pattern writers (pattern_svg, pattern_dxf, pattern_json).
#pragma once

#include <drape/garment/garment_mesh.hpp>
#include <drape/garment/pattern.hpp>

#include <Eigen/Core>

#include <filesystem>
#include <string>

namespace drape::garment {

/// The flat layout of `mesh` as positions for the writers below: (u, v, 0), the pattern
/// coordinates in metres, #V x 3 (`drape pattern`'s pattern_mesh.obj).
Eigen::MatrixX3d flat_layout(const GarmentMesh& mesh);

/// Writes `mesh` at `positions` as OBJ: `v` = positions (metres: the draped garment, or the
/// flat layout (u, v, 0)), `vt` = pattern uv, one group `g` per panel (named as in
/// `pattern`); `what` goes in the header comment. Written atomically.
/// \param positions #V x 3, #V = mesh.cloth.vertex_count().
/// \throw drape::InvalidInput if positions do not match the mesh; drape::IoError if the
///        file cannot be written.
void write_garment_obj(const std::filesystem::path& path, const Pattern& pattern, const GarmentMesh& mesh,
                       const Eigen::MatrixX3d& positions, const std::string& what);

/// Writes `mesh` at `positions` as a glTF 2.0 binary (.glb) with one mesh "garment":
/// POSITION (float, metres), TEXCOORD_0 (the pattern uv; glTF's v runs downwards, so a
/// reader gets (u, 1 - v)) and triangle indices. Written atomically.
/// \param positions #V x 3, #V = mesh.cloth.vertex_count().
/// \throw drape::InvalidInput if positions do not match the mesh; drape::IoError if the
///        file cannot be written.
void write_garment_glb(const std::filesystem::path& path, const GarmentMesh& mesh, const Eigen::MatrixX3d& positions);

}  // namespace drape::garment
