// SLIC superpixels (Achanta et al. 2012) for the boundary refinement: compact clusters in
// (Lab colour, position) whose borders follow the image's colour edges.
#pragma once

#include <opencv2/core.hpp>

namespace drape::vision::detail {

/// Superpixel index per pixel (CV_32S, 0..count-1) of a BGR image; `size_px` is the grid
/// step, `compactness` SLIC's m (Lab units per grid step). Returns the count.
int slic_superpixels(const cv::Mat& image_bgr, int size_px, double compactness, int iterations,
                     cv::Mat& index);

/// Re-labels `labels` (CV_8UC1 class ids) so every superpixel takes the majority class of
/// its pixels; pixels where `fixed` (CV_8UC1 ids, 255 = free; may be empty) is set keep
/// that class.
void majority_vote(const cv::Mat& index, int count, const cv::Mat& fixed, cv::Mat& labels);

}  // namespace drape::vision::detail
