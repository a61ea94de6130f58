// True-scale printable SVG of a sewing pattern.
#pragma once

#include <drape/garment/pattern.hpp>

#include <filesystem>
#include <string>

namespace drape::garment {

struct SvgOptions {
    double seam_allowance_cm = 1.0;  ///< offset outline drawn around each piece; [0, 5]
    double gap_cm = 5.0;             ///< spacing between pieces in the layout; [0, 100]
    bool is_valid(std::string* why = nullptr) const;
};

/// The SVG document: width/height in cm and viewBox in cm, so 1 cm prints as 1 cm. Per
/// piece: cut line (solid), seam allowance outline (dashed), seam line of sewn edges,
/// piece name, grain-line arrow, notches, internal lines.
/// \throw drape::InvalidInput if the pattern or options are invalid.
std::string pattern_to_svg(const Pattern& pattern, const SvgOptions& options = {});

/// Writes pattern_to_svg() atomically. \throw drape::IoError on write failure.
void write_pattern_svg(const std::filesystem::path& path, const Pattern& pattern,
                       const SvgOptions& options = {});

}  // namespace drape::garment
