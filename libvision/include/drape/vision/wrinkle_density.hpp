// The average wrinkle density P of a garment (paper section 4.2, "Image Information
// Extraction", after Popa et al. 2009): fold edges from multi-scale ridge/valley detection
// on the shading, smoothed by low-curvature quadric fits, merged across small gaps, paired
// into folds; unpaired edges are dropped. P = folds per square metre of garment.
//
// Every length scale is a fraction of the body height in pixels, so P does not change
// when the photo is resized.
#pragma once

#include <drape/vision/joints.hpp>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include <string>
#include <vector>

namespace drape::vision {

struct WrinkleOptions {
    double person_height_m = 1.70;   ///< > 0; the stature that turns pixels into metres
    /// Gaussian scales of the Hessian ridge filter, fractions of the body height.
    std::vector<double> scale_fractions = {0.006, 0.009, 0.013};
    /// The garment is resampled so that the body is this many pixels tall before filtering.
    double working_body_height_px = 800;  ///< >= 100
    /// Threshold on the scale-normalised ridge strength sigma^2 |lambda| of the luminance
    /// in [0, 1] (about the depth of a shading groove, as a fraction of white).
    double ridge_threshold = 0.012;  ///< > 0
    double min_edge_fraction = 0.025;    ///< drop edges shorter than this x body height
    double merge_gap_fraction = 0.02;    ///< merge pieces whose ends are this close
    double merge_angle_deg = 20;         ///< ... and whose directions differ by less
    double max_curvature_fraction = 4.0; ///< |quadric coefficient| x edge length^2 / length
    double pair_min_gap_fraction = 0.004;///< ridge-valley distance of a fold, min ...
    double pair_max_gap_fraction = 0.03; ///< ... and max, x body height
    double pair_angle_deg = 20;          ///< max direction difference of a pair
    double pair_min_overlap = 0.5;       ///< overlap along the edges / shorter length
    /// Mask border band (x body height) where edges are ignored: the silhouette boundary
    /// and occlusion borders are not folds.
    double border_fraction = 0.008;
    /// A fold whose ridge/valley overlap is at least this x body height counts as one fold
    /// in P; shorter folds count in proportion to their length (0 = every fold counts 1).
    double full_fold_fraction = 0.1;
    /// Number of detections averaged into P, at working body heights spread geometrically
    /// over working_body_height_px x 1.15^[-1, 1] (1 = a single detection). One detection
    /// depends on the sampling grid through its thresholds; the mean does much less.
    int resolution_ensemble = 10;  ///< >= 1
    /// The photo's own blur, a Gaussian sigma in the photo's pixels (optics, demosaicing,
    /// JPEG, resampling). A Hessian scale sigma (working pixels) is reached by blurring the
    /// resampled garment by sqrt(sigma^2 - (source_blur_px x working/photo scale)^2) only,
    /// so that the filters see the garment at the same total blur whatever the photo's
    /// resolution (a small photo, upsampled more, already carries more of it). 0 = off.
    double source_blur_px = 0.3;  ///< >= 0
    /// Detections per working resolution, each on the working grid shifted by a different
    /// sub-pixel offset (1: none; 2: also shifted by half a pixel in x and y; 4: all four
    /// half-pixel shifts). P is the mean over resolution_ensemble x phase_ensemble runs.
    int phase_ensemble = 4;  ///< 1, 2 or 4
    /// Threads for the ensemble's detections (0 = all cores). P does not depend on it.
    int threads = 0;  ///< >= 0
    /// Detection limit: an ensemble mean below this many full-length folds is reported as
    /// no fold (P = 0, folds_detected false). On a plain garment a few of the ensemble's
    /// grids still pair two short edges (0.03-0.12 folds on the shared photos), a count with
    /// no stable ratio across resolutions.
    double min_fold_count = 0.25;  ///< >= 0
    /// P is not measured (garment_too_small) on a garment smaller than this x body height
    /// squared: the default, 0.01 = full_fold_fraction^2, is the square of one full-length
    /// fold; a smaller patch cannot hold one.
    double min_garment_area_fraction = 0.01;  ///< >= 0
    /// Ridge-profile test (issue 20, folds not prints): a ridge or valley pixel is dropped
    /// when the luminance slope across it, relative to its curvature, sigma |dL/dn| /
    /// (sigma^2 |d2L/dn2|) at its scale, exceeds this. It is 0 on the axis of a symmetric
    /// bump or groove (a fold's crest, a crease) and 1 on the Hessian ridges beside an
    /// ideal step (a print edge). 0 = off.
    double max_step_ratio = 0;  ///< >= 0
    /// Folds, not prints (issue 20; docs/vision.md, "Wrinkle density", "Prints"): when true
    /// the detector runs on the garment's shading, its luminance with the steps of its
    /// print removed on the working grid (an intrinsic decomposition, print_method below).
    /// Off by default: measured, it keeps P of a printed garment nearer P of the plain one
    /// (24-30 of 102 suite ratios within 20 %, against 14 on the luminance) but not for every
    /// garment, fine high-contrast prints lose their folds, the P -> curvature calibration
    /// was fitted on the luminance, and gradient_fill broke the scale stability of P on the
    /// photos (the notes).
    bool suppress_prints = false;
    /// With suppress_prints, how the shading under the print's edges is found:
    /// - gradient_fill: the edges' log-luminance gradients replaced by those of the smoothed
    ///   shading around them, and the whole box integrated back by a Poisson solve;
    /// - albedo_classes: a two-colour print's regions 2-coloured through the borders they
    ///   share, the smaller colour mapped onto the other's shading by a linear map of log
    ///   colour fitted on every crossing of the edges, the edges filled by a membrane. Any
    ///   other garment keeps its luminance, so plain garments keep the default detector's
    ///   P, unless its edges cover a quarter of its pixels or more (below).
    /// With either method, a print finer than the edges' band (edges on a quarter of the
    /// garment or more) whose period is at most 2.5 % of the body height is averaged over
    /// that period (its log luminance, a box one period wide, twice); a coarser one gets
    /// gradient_fill (docs/vision.md, "Prints", "Fine prints").
    enum class PrintMethod { gradient_fill, albedo_classes };
    /// albedo_classes measured better where it was tuned: 16 against 11 of 27 skirt ratios
    /// within 20 %. On the suite (not tuned on) the two are within the renders' scatter:
    /// 24 against 30 of 102 on one VM's renders, 29 against 27 on another's.
    PrintMethod print_method = PrintMethod::albedo_classes;
    /// With suppress_prints, a print edge: a step of log luminance of at least this ...
    double print_step_threshold = 0.3;  ///< > 0
    /// ... or of log chromaticity (log R/G, log B/G) of at least this, measured by the
    /// gradients at print_edge_sigma_px (working-grid pixels).
    double print_chroma_threshold = 0.15;  ///< > 0
    double print_edge_sigma_px = 0.7;      ///< [0.7, 100)

    bool is_valid(std::string* why = nullptr) const;
};

/// One smoothed fold edge: a quadric curve sampled as a polyline, image frame pixels.
struct FoldEdge {
    std::vector<Eigen::Vector2d> points_px;
    bool bright = false;  ///< a bright ridge (lit crest) or a dark valley (crease)
};

/// A fold: a bright ridge and a dark valley running side by side.
struct Fold {
    FoldEdge ridge;
    FoldEdge valley;
};

enum class WrinkleTermination { ok, garment_too_small, failed };

struct WrinkleSummary {
    WrinkleTermination termination = WrinkleTermination::failed;
    std::string message;
    // edges_detected, edges_merged, folds and the folds returned: the detection at
    // working_body_height_px; fold_count and P: the mean over the resolution ensemble.
    int edges_detected = 0;       ///< after quadric fitting and the length filter
    int edges_merged = 0;         ///< after merging
    int folds = 0;                ///< paired folds found
    double fold_count = 0;        ///< folds weighted by length (WrinkleOptions::full_fold_fraction), ensemble mean (also below the detection limit)
    bool folds_detected = false;  ///< fold_count reached WrinkleOptions::min_fold_count
    double garment_area_px = 0;
    double garment_area_m2 = 0;
    double density_per_m2 = 0;    ///< P = fold_count / garment_area_m2, 0 when !folds_detected
    double seconds = 0;

    bool usable() const { return termination == WrinkleTermination::ok; }
    std::string brief_report() const;
};

/// Detects the folds of a garment and its wrinkle density P.
/// \param image_bgr CV_8UC3 photo
/// \param mask CV_8UC1 garment mask of the photo's size (non-zero = garment)
/// \param occlusion optional CV_8UC1 mask (empty Mat = none) whose borders are ignored
/// \param folds receives the folds when not null
/// \throw drape::InvalidInput on type/size mismatches or invalid options.
WrinkleSummary detect_wrinkles(const cv::Mat& image_bgr, const cv::Mat& mask,
                               const cv::Mat& occlusion, const Joints& joints,
                               const WrinkleOptions& options, std::vector<Fold>* folds);

/// The photo, darkened outside `mask`, with each fold's ridge (yellow) and valley (blue)
/// drawn and joined.
cv::Mat draw_folds(const cv::Mat& image_bgr, const cv::Mat& mask, const std::vector<Fold>& folds);

}  // namespace drape::vision
