// Pose-derived layout of the automatic segmentation: where background, skin, hair, upper
// and lower garment can be, from the 14 joints (docs/vision.md, "Segmentation").
#pragma once

#include <drape/vision/joints.hpp>

#include <opencv2/core.hpp>

#include <array>

namespace drape::vision::detail {

/// Label indices of the automatic segmentation.
enum AutoLabel : int { kBackground = 0, kSkin = 1, kHair = 2, kUpper = 3, kLower = 4 };
inline constexpr int kAutoLabels = 5;

struct BodyLayout {
    std::array<cv::Mat, kAutoLabels> prior;  ///< CV_32F spatial costs per label
    std::array<cv::Mat, kAutoLabels> seed;   ///< CV_8UC1 regions for the first colour models
    cv::Mat hard;                            ///< CV_8UC1 label index or 255 (free)
};

/// The layout for an image of `size` whose joints (in that image's pixels) are `joints`.
BodyLayout body_layout(cv::Size size, const Joints& joints, double weight);

}  // namespace drape::vision::detail
