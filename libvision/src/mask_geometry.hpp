// Small measurements on binary masks shared by the classifier and the features.
#pragma once

#include <drape/vision/joints.hpp>

#include <opencv2/core.hpp>

#include <vector>

namespace drape::vision::detail {

/// The mask without connected pieces smaller than `fraction` of its largest piece (stray
/// bits such as sandal straps labelled like the garment would move its extent).
cv::Mat main_pieces(const cv::Mat& mask, double fraction = 0.15);

/// True when a set pixel of `mask` lies within `radius` px of point p (image frame).
bool covered(const cv::Mat& mask, const Eigen::Vector2d& p, int radius);

/// Row indices (q-th percentile, q in [0,1]) of the set pixels; -1 if none.
int row_percentile(const cv::Mat& mask, double q);

/// Set pixels on row y (0 outside the image) and the number of runs of them.
int row_width(const cv::Mat& mask, int y, int* runs = nullptr);

/// x of the point at row y on the polyline a -> b -> c (clamped to its ends).
double polyline_x_at(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                     const Eigen::Vector2d& c, double y);

/// Mid-point between the legs at row y (each leg: hip -> knee -> ankle).
Eigen::Vector2d between_legs(const Joints& j, double y);

/// Length along one arm (shoulder -> elbow -> hand) covered by the mask continuously from
/// the shoulder, allowing gaps of `max_gap` px; and the arm's length.
double sleeve_run(const cv::Mat& mask, const Eigen::Vector2d& shoulder,
                  const Eigen::Vector2d& elbow, const Eigen::Vector2d& hand, int radius,
                  double max_gap, double* arm_length);

}  // namespace drape::vision::detail
