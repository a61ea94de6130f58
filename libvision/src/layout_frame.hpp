// The joint-normalised body frame of the learned layout prior (docs/vision.md,
// "Segmentation", automatic): a point is described by its nearest bone of the 14-joint
// skeleton, how far along that bone it lies and its signed distance from it in body
// heights. The tool tools/derive_layout_prior.cpp counts the hand-labelled classes per cell
// of this frame; segment_automatic turns the counts into spatial costs. Both include this
// header, so the cells cannot drift apart.
#pragma once

#include <drape/vision/joints.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

namespace drape::vision::detail {

/// Bones of the frame between two joints: limbs from the trunk outwards, the trunk's four
/// sides and neck -> head. The 14th bone, the spine (neck -> mid-hip), is added by
/// frame_segments.
inline constexpr std::array<std::pair<Joint, Joint>, 13> kFrameBones = {{
    {Joint::right_hip, Joint::right_knee},     {Joint::right_knee, Joint::right_ankle},
    {Joint::left_hip, Joint::left_knee},       {Joint::left_knee, Joint::left_ankle},
    {Joint::right_shoulder, Joint::right_elbow}, {Joint::right_elbow, Joint::right_hand},
    {Joint::left_shoulder, Joint::left_elbow},   {Joint::left_elbow, Joint::left_hand},
    {Joint::right_shoulder, Joint::left_shoulder}, {Joint::right_hip, Joint::left_hip},
    {Joint::right_shoulder, Joint::right_hip},   {Joint::left_shoulder, Joint::left_hip},
    {Joint::neck, Joint::head}}};

/// Cells: bone x position along it (kFrameAlong bins over [0, 1]) x signed distance
/// (kFrameAcross bins of kFrameAcrossStep body heights, the outer bins open-ended).
inline constexpr int kFrameBoneCount = 14;
inline constexpr int kFrameAlong = 10;
inline constexpr int kFrameAcross = 24;
inline constexpr double kFrameAcrossStep = 0.02;
inline constexpr int kFrameCells = kFrameBoneCount * kFrameAlong * kFrameAcross;

/// The skeleton's 14 segments in the image frame: kFrameBones, then the spine (neck ->
/// mid-hip), which has no joint of its own.
inline std::array<std::pair<Eigen::Vector2d, Eigen::Vector2d>, kFrameBoneCount> frame_segments(
    const Joints& j) {
    std::array<std::pair<Eigen::Vector2d, Eigen::Vector2d>, kFrameBoneCount> out;
    for (int b = 0; b < kFrameBoneCount - 1; ++b)
        out[size_t(b)] = {j[kFrameBones[size_t(b)].first], j[kFrameBones[size_t(b)].second]};
    out[kFrameBoneCount - 1] = {j[Joint::neck], j.mid_hip()};
    return out;
}

/// The frame cell of point `p` (image frame), given the segments and the body height.
inline int frame_cell(const std::array<std::pair<Eigen::Vector2d, Eigen::Vector2d>, kFrameBoneCount>& seg,
                      double body_height, const Eigen::Vector2d& p) {
    int best = 0;
    double best_d2 = 1e300, best_t = 0, best_side = 0;
    for (int b = 0; b < kFrameBoneCount; ++b) {
        const Eigen::Vector2d& a = seg[size_t(b)].first;
        const Eigen::Vector2d ab = seg[size_t(b)].second - a;
        const double len2 = std::max(1e-9, ab.squaredNorm());
        const double t = std::clamp((p - a).dot(ab) / len2, 0.0, 1.0);
        const Eigen::Vector2d q = a + t * ab;
        const double d2 = (p - q).squaredNorm();
        if (d2 < best_d2) {
            best_d2 = d2;
            best = b;
            best_t = t;
            best_side = ab.x() * (p - a).y() - ab.y() * (p - a).x();
        }
    }
    const double d = std::sqrt(best_d2) / std::max(1e-9, body_height) * (best_side < 0 ? -1.0 : 1.0);
    const int along = std::min(kFrameAlong - 1, int(best_t * kFrameAlong));
    const int across = std::clamp(int(std::floor(d / kFrameAcrossStep)) + kFrameAcross / 2, 0,
                                  kFrameAcross - 1);
    return (best * kFrameAlong + along) * kFrameAcross + across;
}

}  // namespace drape::vision::detail
