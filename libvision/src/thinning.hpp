// Zhang & Suen (1984) thinning, shared by the simulated strokes and the fold detector.
#pragma once

#include <opencv2/core.hpp>

namespace drape::vision::detail {

/// Thins a CV_8UC1 image of 0/1 values to 1-pixel-wide 8-connected curves, in place.
/// \pre the first and last rows and columns are 0.
void thin(cv::Mat& img);

}  // namespace drape::vision::detail
