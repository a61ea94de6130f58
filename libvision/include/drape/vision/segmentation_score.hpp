// Scoring a parse against a reference label map: the masks of a label role and their
// intersection over union, as `drape eval-segment` reports them (docs/vision.md,
// "Evaluation") and the tests check them.
#pragma once

#include <drape/vision/label_table.hpp>

#include <opencv2/core.hpp>

namespace drape::vision {

/// The pixels of `labels` whose class plays `role` in `table` (the union of those classes).
/// \param labels CV_8UC1 class ids.
/// \return CV_8UC1 of labels' size, 255 inside, 0 outside.
/// \throw drape::InvalidInput if labels is not CV_8UC1.
cv::Mat role_mask(const cv::Mat& labels, const LabelTable& table, LabelRole role);

/// Intersection over union of two masks (non-zero = inside); 1 when both are empty.
/// \param a, b single-channel masks of the same size.
/// \throw drape::InvalidInput on different sizes or a multi-channel mask.
double iou(const cv::Mat& a, const cv::Mat& b);

}  // namespace drape::vision
