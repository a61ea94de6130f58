// GarmentCode-compatible pattern JSON (Korosteleva & Sorkine-Hornung 2023 specification):
//   {"pattern": {"panels": {name: {"translation", "rotation", "vertices", "edges"}},
//                "stitches": [[{"panel", "edge"}, {"panel", "edge"}], ...],
//                "panel_order": [...]},
//    "parameters": {}, "parameter_order": [],
//    "properties": {"units_in_meter": 100, "curvature_coords": "relative", ...}}
#pragma once

#include <drape/garment/pattern.hpp>

#include <filesystem>
#include <string>

namespace drape::garment {

/// Serialises a pattern. Arcs become {"type": "circle", "params": [radius, large_arc,
/// right]}, cubics {"type": "cubic", "params": [[x, y], [x, y]]} in edge-relative
/// coordinates. Drape-only data (body part, grain, notches, internal lines, seam
/// orientation) goes under "drape_*" keys that GarmentCode ignores.
/// \throw drape::InvalidInput if the pattern is invalid.
std::string pattern_to_garmentcode_json(const Pattern& pattern);

/// Parses GarmentCode pattern JSON (units_in_meter 100 or other; absolute or relative
/// curvature coordinates; circle, quadratic and cubic edges; stitches). Stitches without
/// orientation are taken as reversed (GarmentCode's convention for panels sewn edge to
/// edge). Panel loops are reordered to follow edges and made counter-clockwise.
/// \throw drape::InvalidInput naming the JSON path of the first bad field.
Pattern pattern_from_garmentcode_json(const std::string& text);

void write_pattern_json(const std::filesystem::path& path, const Pattern& pattern);
/// \throw drape::IoError if the file cannot be read; InvalidInput naming the file if bad.
Pattern read_pattern_json(const std::filesystem::path& path);

}  // namespace drape::garment
