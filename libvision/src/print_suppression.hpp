// The shading of a garment, with the steps of its print removed (docs/vision.md, "Wrinkle
// density", step 1): a Retinex-style intrinsic decomposition of the log luminance.
#pragma once

#include <opencv2/core.hpp>

namespace drape::vision::detail {

struct ShadingOptions {
    /// Gaussian scale (pixels, >= 0.7) of the gradients that find the print's edges.
    double edge_sigma_px = 0.7;
    /// An edge of the print: a step of log luminance at least this large (a ratio of
    /// exp(threshold) between the two sides) ...
    double step_threshold = 0.3;
    /// ... or a step of log chromaticity (log R/G, log B/G) at least this large.
    double chroma_threshold = 0.15;
    /// An edge's gradients are set to zero (the shading held flat across it), then
    /// fill_passes times replaced by those of the shading solved so far, smoothed by this
    /// Gaussian scale (pixels); 0 = held flat.
    double fill_sigma_px = 1.5;
    int fill_passes = 2;
    int dilate_px = 1;  ///< the edges widened by this many pixels
};

/// The shading luminance of a crop: the log luminance's gradients (forward differences),
/// those on the print's edges (and dilate_px pixels around them) replaced as ShadingOptions
/// says, integrated back by a Neumann Poisson solve (DCT) and exponentiated, at the level
/// of the luminance on `mask` off the edges.
/// Where no edge is found the result is the luminance itself.
/// \param bgr CV_8UC3 crop
/// \param mask CV_8UC1 of the crop's size (non-zero = garment; sets the output's level)
/// \param edges receives the CV_8UC1 map of the removed edges when not null
/// \return CV_32F luminance in [0, 1] units (BGR2GRAY / 255 where nothing is removed)
cv::Mat shading_luminance(const cv::Mat& bgr, const cv::Mat& mask, const ShadingOptions& options,
                          cv::Mat* edges = nullptr);

}  // namespace drape::vision::detail
