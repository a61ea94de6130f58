// The 14 image joints (Fashionista / PARSE order) that seed the automatic segmentation and
// give the body scale. JSON files are read in the app layer; the library takes typed joints.
#pragma once

#include <drape/core/joint_marks.hpp>

#include <Eigen/Core>

#include <array>
#include <string_view>

namespace drape::vision {

/// Joint order of the Fashionista / PARSE (Yang & Ramanan) 14-joint annotation.
/// "left"/"right" are the person's own sides; hand = wrist; head = top of the head.
enum class Joint : int {
    right_ankle = 0, right_knee = 1, right_hip = 2, left_hip = 3, left_knee = 4,
    left_ankle = 5, right_hand = 6, right_elbow = 7, right_shoulder = 8, left_shoulder = 9,
    left_elbow = 10, left_hand = 11, neck = 12, head = 13,
};

inline constexpr int kJointCount = 14;

/// Names in file order ("right_ankle", ..., "head").
inline constexpr std::array<std::string_view, kJointCount> kJointNames = {
    "right_ankle", "right_knee",  "right_hip",      "left_hip",      "left_knee",
    "left_ankle",  "right_hand",  "right_elbow",    "right_shoulder", "left_shoulder",
    "left_elbow",  "left_hand",   "neck",           "head"};

/// What the 14 points mark (core/joint_marks.hpp).
using JointMarks = core::JointMarks;

/// 14 joints in the image frame: pixels, origin at the image's top-left corner, x right,
/// y down, the centre of pixel (column i, row j) at (i + 0.5, j + 0.5) (the libbody
/// camera.hpp convention; Fashionista's 1-based values convert by subtracting 0.5).
struct Joints {
    std::array<Eigen::Vector2d, kJointCount> px{};
    JointMarks marks = JointMarks::hand;  ///< what the points mark

    const Eigen::Vector2d& operator[](Joint j) const { return px[static_cast<size_t>(j)]; }
    Eigen::Vector2d& operator[](Joint j) { return px[static_cast<size_t>(j)]; }

    /// Mid-point of the hips, shoulders, knees, ankles.
    Eigen::Vector2d mid_hip() const;
    Eigen::Vector2d mid_shoulder() const;
    Eigen::Vector2d mid_knee() const;
    Eigen::Vector2d mid_ankle() const;

    /// The person's standing height in pixels, estimated from the skeleton: the path
    /// head -> neck -> mid-hip -> mid-knee -> mid-ankle, divided by 0.955 (the ankle joint
    /// sits about 4.5 % of stature above the sole). The path, not the vertical extent, so
    /// that a lean or a bent knee does not shrink it. Unit of every scale in libvision.
    double body_height_px() const;

    /// Throws drape::InvalidInput naming the first joint that is not finite or lies outside
    /// [0, width] x [0, height], or when the skeleton is degenerate (body height < 8 px).
    void validate(int width, int height) const;

    /// The joints of the same photo resized by `factor` (x and y alike).
    Joints scaled(double factor) const;
};

}  // namespace drape::vision
