// The shading of a garment, with the steps of its print removed (docs/vision.md, "Wrinkle
// density", step 1): a Retinex-style intrinsic decomposition of the log luminance.
#pragma once

#include <drape/vision/wrinkle_density.hpp>

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
    /// How the shading is found under the edges:
    /// - gradient_fill: the edges' gradients replaced as above and the whole box integrated
    ///   by one Poisson solve (each region between edges floats on its own band);
    /// - albedo_classes: the regions between the edges 2-coloured through the borders they
    ///   share, the class of the smaller area mapped onto the other's shading by a linear
    ///   map of log colour fitted on every crossing of a band (and a shrunk offset per
    ///   region from its own crossings), the band filled by a membrane; a garment that is
    ///   not a two-colour print keeps its luminance, unless edges cover
    ///   fallback_band_fraction of it (a fine print: below).
    WrinkleOptions::PrintMethod method = WrinkleOptions::PrintMethod::gradient_fill;
    /// albedo_classes: regions smaller than this (pixels) are filled like the band.
    int min_region_px = 6;
    /// albedo_classes: a crossing of the band spans at most this many band pixels.
    int max_crossing_px = 12;
    /// albedo_classes: a border between two regions counts when crossed this many times.
    int min_crossings = 3;
    /// albedo_classes: a print has at least this many regions on its borders, at least
    /// min_crossing_density crossings per garment pixel, and at most max_conflict_fraction
    /// of its crossings on borders that contradict the 2-colouring.
    int min_print_regions = 12;
    double min_crossing_density = 0.015;
    double max_conflict_fraction = 0.15;
    /// albedo_classes: each mapped region's own offset (the median residual of the map
    /// across its crossings) is shrunk by n / (n + this) for n crossings.
    double region_offset_prior = 20;
    /// A garment with edges on at least this fraction of its pixels has a print finer than
    /// the edges' band (plain garments: 0.3-12 % of their pixels, the suite's prints
    /// 33-95 %): with either method (albedo_classes: when the graph cannot follow it) its
    /// log luminance is averaged over the print's period (a box one period wide, twice), the
    /// period from the swings of the log luminance along rows or columns, when that period
    /// is at most fine_print_max_period_px; a coarser one gets gradient_fill.
    double fallback_band_fraction = 0.25;
    /// Pixels of the working grid (the body 800 px tall): 2.5 % of the body height (the
    /// detector's scales are 0.6-1.3 % of it). Chosen on the skirts of
    /// data/synth/skirt_bending.json: their fine checks (period 14-16 px) came to 1.08 and
    /// 0.78 of plain P averaged (0.19 and 0.23 with gradient_fill), their dots (period
    /// 24-29 px) to 3.6 and 3.5 (0.90 and 0.58 with gradient_fill).
    double fine_print_max_period_px = 20;
};

/// The shading luminance of a crop. gradient_fill: the log luminance's gradients (forward
/// differences), those on the print's edges (and dilate_px pixels around them) replaced as
/// ShadingOptions says, integrated back by a Neumann Poisson solve (DCT) and exponentiated,
/// at the level of the luminance on `mask` off the edges. albedo_classes: see Method.
/// Where no edge is found (or, with albedo_classes, no two-colour print) the result is the
/// luminance itself, and `edges` is all zero.
/// \param bgr CV_8UC3 crop
/// \param mask CV_8UC1 of the crop's size (non-zero = garment; sets the output's level)
/// \param edges receives the CV_8UC1 map of the removed edges when not null
/// \return CV_32F luminance in [0, 1] units (BGR2GRAY / 255 where nothing is removed)
cv::Mat shading_luminance(const cv::Mat& bgr, const cv::Mat& mask, const ShadingOptions& options,
                          cv::Mat* edges = nullptr);

}  // namespace drape::vision::detail
