// True-scale printable SVG of a sewing pattern.
#pragma once

#include <drape/garment/pattern.hpp>

#include <filesystem>
#include <string>
#include <vector>

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

/// One size of a grading sheet: its pattern and its label ("original", "graded: two sizes up").
struct GradedSize {
    const Pattern* pattern = nullptr;
    std::string label;
};

/// A grading sheet (true scale, as pattern_to_svg): every panel of every size nested on one
/// piece, as a pattern maker's grade nest shows them. Each size's panel is placed so that its
/// bounding box's bottom centre (hem, centre of the piece) is the same point for all sizes;
/// sizes are drawn in distinct colours, listed in a legend.
/// \pre every pattern has the same panels (names, in order): sizes of one template.
/// 	hrow drape::InvalidInput if sizes is empty, a pattern is null or invalid, or the panels
///        differ (naming the panel).
std::string grading_sheet_to_svg(const std::vector<GradedSize>& sizes);

/// Writes grading_sheet_to_svg() atomically. 	hrow drape::IoError on write failure.
void write_grading_sheet_svg(const std::filesystem::path& path, const std::vector<GradedSize>& sizes);

}  // namespace drape::garment
