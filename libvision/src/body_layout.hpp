// Pose-derived layout of the automatic segmentation, from the 14 joints (docs/vision.md,
// "Segmentation"): hand-placed seeds and hard constraints (body_layout) and the learned
// spatial prior, p(label | cell of the body frame) (learned_layout).
#pragma once

#include <drape/vision/joints.hpp>
#include <drape/vision/label_table.hpp>

#include <opencv2/core.hpp>

#include <array>

namespace drape::vision::detail {

/// Label indices of the automatic segmentation.
/// kOther: what is neither background, skin, hair nor a garment of the parse (bags, belts,
/// outerwear, shoes, tights, accessories).
enum AutoLabel : int { kBackground = 0, kSkin = 1, kHair = 2, kUpper = 3, kLower = 4, kOther = 5 };
inline constexpr int kAutoLabels = 6;

/// The automatic label a class of role `role` counts as in the learned layout: occluders
/// (bags, belts, outerwear, ...) and every other worn class (shoes, tights, ...) are
/// kOther; a dress (full_garment) is kUpper above the natural waist, kLower below it.
AutoLabel auto_label_of(LabelRole role, bool below_waist);

/// Smoothing of learned_layout: samples of the overall class frequencies added to each cell.
inline constexpr double kLayoutPseudoCount = 20.0;
/// "Other"'s first colour model: the pixels where learned_layout gives it more than this.
inline constexpr double kOtherSeedProbability = 0.5;

struct BodyLayout {
    std::array<cv::Mat, kAutoLabels> seed;   ///< CV_8UC1 regions for the first colour models (kOther: empty)
    cv::Mat hard;                            ///< CV_8UC1 label index or 255 (free)
};

/// Seeds and hard constraints for an image of `size` whose joints (in that image's
/// pixels) are `joints`.
BodyLayout body_layout(cv::Size size, const Joints& joints);

/// Learned layout: p(label | cell of the body frame) per pixel (CV_32F), from the class
/// counts of hand-labelled photos per cell (layout_prior_data.hpp), each cell's counts
/// smoothed towards the overall class frequencies by `pseudo_count` samples.
std::array<cv::Mat, kAutoLabels> learned_layout(cv::Size size, const Joints& joints,
                                                double pseudo_count);

}  // namespace drape::vision::detail
