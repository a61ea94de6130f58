// Small measurements on binary masks shared by the classifier and the features.
#pragma once

#include <drape/vision/joints.hpp>

#include <opencv2/core.hpp>

#include <algorithm>
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

/// Mean row width over rows yc +- 1 % of the body height.
double mean_row_width(const cv::Mat& mask, double yc, const Joints& j);

/// The widest mean row width of the upper thighs (20-40 % of hip -> knee, below where a top
/// hanging over the hips or hands in pockets hide the garment's sides).
double upper_thigh_width(const cv::Mat& mask, const Joints& j);

/// x of the point at row y on the polyline a -> b -> c (clamped to its ends).
double polyline_x_at(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                     const Eigen::Vector2d& c, double y);

/// Mid-point between the legs at row y (each leg: hip -> knee -> ankle).
Eigen::Vector2d between_legs(const Joints& j, double y);

/// The point at arc length s (px) along the arm shoulder -> elbow -> hand (the upper arm
/// up to its length, then the forearm) and, if `direction` is given, the unit direction of
/// that segment. False where that segment has zero length.
bool arm_point(const Eigen::Vector2d& shoulder, const Eigen::Vector2d& elbow, const Eigen::Vector2d& hand,
               double s, Eigen::Vector2d& point, Eigen::Vector2d* direction = nullptr);

/// How far a garment runs down each arm from the shoulder (docs/vision.md, "Garment type").
struct ArmRuns {
    double run_px[2] = {0, 0};     ///< covered length from the shoulder, right and left arm
    double length_px[2] = {0, 0};  ///< shoulder -> elbow -> hand length, right and left arm
    /// The longer run as a fraction of its arm's length (0 for degenerate arms).
    double max_fraction() const;
    double max_run_px() const { return std::max(run_px[0], run_px[1]); }
};

/// Walks each arm (shoulder -> elbow -> hand, every pixel) while the mask covers it,
/// bridging gaps up to 2 % of the body height: a point counts when the mask lies within
/// 0.8 % H of the arm line and within 0.8 % H of the point 1.5 % H beside it on the side
/// away from the body's centre. A sleeve wraps the arm, so garment lies across the arm's
/// outer half (an arm is ~5 % H wide); a torso beside a hanging arm touches the arm line
/// from one side only and no longer lengthens the run.
/// Where `hiding` (optional, hair and occluders) lies on the arm line itself the walk goes
/// on without counting a gap or growing the run.
ArmRuns sleeve_runs(const cv::Mat& mask, const Joints& joints, const cv::Mat& hiding = cv::Mat());

}  // namespace drape::vision::detail
