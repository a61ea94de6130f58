// Simulated user strokes: what a user would scribble, derived from a ground-truth label map
// by a deterministic procedure (docs/vision.md, "Simulated strokes"). Used by the
// evaluation and by `drape strokes`; never a copy of the labels.
#pragma once

#include <opencv2/core.hpp>

#include <string>

namespace drape::vision {

struct StrokeOptions {
    /// Regions are eroded by this fraction of the image diagonal (at least 1 px) before
    /// their medial axis is taken, so strokes stay clear of the region boundary.
    double erosion_fraction = 0.008;      ///< >= 0
    /// Connected regions smaller than this fraction of the image get no stroke.
    double min_region_fraction = 0.0004;  ///< >= 0
    int max_strokes_per_region = 3;       ///< >= 1
    /// A stroke shorter than this fraction of the image diagonal is dropped (except the
    /// first stroke of a region, which is always kept).
    double min_stroke_fraction = 0.02;    ///< >= 0
    int stroke_width_px = 1;              ///< >= 1, pen width of the drawn medial path
    /// Hard cap on marked pixels as a fraction of the image (shortest strokes go first).
    double max_marked_fraction = 0.03;    ///< in (0, 1]

    bool is_valid(std::string* why = nullptr) const;
};

/// Strokes for every class of `labels` (8-bit single-channel class ids): per connected
/// region (8-connected) of each class, erode, thin to the medial axis (Zhang-Suen), then
/// take the longest geodesic path through the axis as the first stroke and up to
/// max_strokes_per_region - 1 further longest paths through the axis pixels not yet
/// covered. Marked pixels hold the class id, others kUnmarked (255).
/// \throw drape::InvalidInput for a non-CV_8UC1 or empty map, or invalid options.
cv::Mat simulate_strokes(const cv::Mat& labels, const StrokeOptions& options = {});

/// Fraction of pixels of a stroke map that are marked (not 255).
double marked_fraction(const cv::Mat& strokes);

}  // namespace drape::vision
