// outfit.glb: the posed body and its draped garments in one glTF binary, for any glTF
// viewer (docs/recovery.md, "Output files").
#pragma once

#include <drape/recover/outfit_meshes.hpp>

#include <filesystem>

namespace drape::recover {

/// Writes `outfit` as a glTF 2.0 binary through drape::gltf (write_glb), atomically: a root
/// node "outfit" with the nodes "body", "garment_0", "garment_1", ... in the outfit's
/// order, each holding one mesh (named "body" and by OutfitGarment::name, or "garment_K"
/// when unnamed) with POSITION (float, metres), NORMAL (area-weighted), for garments
/// TEXCOORD_0 (the pattern uv as garment_N.glb has it, when given) and a material of its
/// own ("body", "garment_K") whose base colour is the overlay's (render/preview.hpp: the
/// neutral skin tone, then blue, terracotta, olive, ...). The body is the static posed
/// mesh, not rigged: the garments are not skinned, so a rig would only let the body move
/// out of its clothes.
/// \throw drape::InvalidInput for an invalid outfit (OutfitMeshes::validate);
///        drape::IoError if the file cannot be written.
void write_outfit_glb(const std::filesystem::path& path, const OutfitMeshes& outfit);

}  // namespace drape::recover
