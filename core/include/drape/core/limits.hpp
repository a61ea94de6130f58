// Resource limits on external input, in one place (docs/hardening.md, "Resource limits").
// Every reader of a file from outside checks them before doing the work they bound, and
// refuses with drape::InvalidInput naming the file, the measured size and the limit. They
// are generous for real use (a 50-megapixel photo, a result folder's JSON, a scanned body)
// and small enough that a hostile or corrupt file cannot exhaust memory or the stack.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace drape::limits {

/// Images (photos, masks, label maps, stroke images): width and height each, and their
/// product. Checked on the dimensions in the file's header before any pixel is decoded.
inline constexpr int kMaxImageSidePx = 12000;
inline constexpr std::int64_t kMaxImagePixels = 50'000'000;
/// An image file's size in bytes, checked before it is read.
inline constexpr std::int64_t kMaxImageFileBytes = 200'000'000;

/// A JSON file's size in bytes, checked before it is read (the largest JSON Drape writes,
/// a result.json or a pattern, is well under 1 MB).
inline constexpr std::int64_t kMaxJsonFileBytes = 64'000'000;
/// Nesting depth of JSON arrays and objects (Drape's own files nest at most 5 deep).
/// Deeper input is refused before it is parsed: parsing, copying and printing nested values
/// recurse once per level.
inline constexpr int kMaxJsonDepth = 64;

/// Vertices of a triangle mesh read from a file (body_model, import_mesh) or made by
/// meshing a sewing pattern (an estimate from the panels' area and outline, checked before
/// triangulating). The built-in body has about 7000 vertices, a garment at 1.5 cm edges
/// about 5000.
inline constexpr std::int64_t kMaxMeshVertices = 2'000'000;
/// Triangles of a mesh handed over as arrays (the C API's simulator and obstacle): twice
/// kMaxMeshVertices, what a closed mesh of that many vertices has.
inline constexpr std::int64_t kMaxMeshFaces = 2 * kMaxMeshVertices;
/// A mesh file's size in bytes, checked before it is read.
inline constexpr std::int64_t kMaxMeshFileBytes = 1'000'000'000;
/// A body model file's size in bytes (HDF5), checked before it is read into memory: twice
/// kMaxModelDatasetElements doubles.
inline constexpr std::int64_t kMaxModelFileBytes = 1'024'000'000;
/// Elements of any one dataset of a body model file (HDF5), checked on the declared extent
/// before it is allocated: 64 million doubles are 512 MB, room for a 7000-vertex body with
/// 3000 shape components.
inline constexpr std::int64_t kMaxModelDatasetElements = 64'000'000;

/// The whole file as bytes, refusing one larger than `max_bytes` before reading it.
/// \param what names the file's role in messages ("JSON file", "material file").
/// \throw drape::IoError naming the file if it is missing or unreadable;
///        drape::InvalidInput naming the file, its size and the limit if it is too large.
std::string read_file_capped(const std::filesystem::path& path, std::int64_t max_bytes, const std::string& what);

/// Checks JSON text against kMaxJsonFileBytes and kMaxJsonDepth without parsing it (brackets
/// inside strings do not count). Malformed text passes: the parser reports it.
/// \param where names the text in messages (the file).
/// \throw drape::InvalidInput naming `where`, the size or depth and the limit.
void check_json_text(std::string_view text, const std::string& where);

}  // namespace drape::limits
