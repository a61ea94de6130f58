#include "body_layout.hpp"
#include "layout_prior_data.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>

namespace drape::vision::detail {

namespace {

cv::Point pt(const Eigen::Vector2d& p) {
    return {static_cast<int>(std::floor(p.x())), static_cast<int>(std::floor(p.y()))};
}

void line(cv::Mat& m, const Eigen::Vector2d& a, const Eigen::Vector2d& b, double thickness) {
    cv::line(m, pt(a), pt(b), cv::Scalar(255), std::max(1, static_cast<int>(std::lround(thickness))),
             cv::LINE_8);
}

void disc(cv::Mat& m, const Eigen::Vector2d& c, double r) {
    cv::circle(m, pt(c), std::max(1, static_cast<int>(std::lround(r))), cv::Scalar(255), cv::FILLED);
}

/// Euclidean distance (px) to the set pixels of `region`.
cv::Mat distance_to(const cv::Mat& region) {
    cv::Mat inv = region == 0, d;
    cv::distanceTransform(inv, d, cv::DIST_L2, 3, CV_32F);
    return d;
}

Eigen::Vector2d lerp(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double t) {
    return a + t * (b - a);
}

}  // namespace

BodyLayout body_layout(cv::Size size, const Joints& j) {
    using J = Joint;
    const double H = j.body_height_px();
    const cv::Mat zero = cv::Mat::zeros(size, CV_8UC1);
    BodyLayout out;
    const Eigen::Vector2d hip = j.mid_hip(), sh = j.mid_shoulder(), neck = j[J::neck],
                          head = j[J::head];
    const double head_len = (head - neck).norm();

    // Skeleton lines.
    cv::Mat skel = zero.clone();
    const J limbs[][2] = {{J::right_ankle, J::right_knee}, {J::right_knee, J::right_hip},
                          {J::left_ankle, J::left_knee},   {J::left_knee, J::left_hip},
                          {J::right_hip, J::left_hip},     {J::right_shoulder, J::left_shoulder},
                          {J::right_shoulder, J::right_hip}, {J::left_shoulder, J::left_hip},
                          {J::right_shoulder, J::right_elbow}, {J::right_elbow, J::right_hand},
                          {J::left_shoulder, J::left_elbow},   {J::left_elbow, J::left_hand},
                          {J::neck, J::head}};
    for (const auto& l : limbs) line(skel, j[l[0]], j[l[1]], 1);
    line(skel, neck, hip, 1);
    const cv::Mat d_skel = distance_to(skel);

    // Seeds for the first colour models, and hard constraints.
    for (auto& s : out.seed) s = zero.clone();
    out.seed[kBackground] = d_skel > 0.15 * H;
    const Eigen::Vector2d face = lerp(neck, head, 0.4);
    disc(out.seed[kSkin], face, 0.18 * head_len);
    disc(out.seed[kSkin], j[J::right_hand], 0.015 * H);
    disc(out.seed[kSkin], j[J::left_hand], 0.015 * H);
    disc(out.seed[kHair], lerp(head, neck, 0.12), 0.22 * head_len);
    cv::Mat face_big = zero.clone();
    disc(face_big, face, 0.3 * head_len);
    out.seed[kHair] &= ~face_big;
    line(out.seed[kUpper], lerp(sh, hip, 0.25), lerp(sh, hip, 0.55), 0.05 * H);
    for (auto side : {std::pair{J::right_hip, J::right_knee}, std::pair{J::left_hip, J::left_knee}})
        line(out.seed[kLower], lerp(j[side.first], j[side.second], 0.1),
             lerp(j[side.first], j[side.second], 0.3), 0.03 * H);
    cv::Mat hands = zero.clone();
    disc(hands, j[J::right_hand], 0.06 * H);
    disc(hands, j[J::left_hand], 0.06 * H);
    out.seed[kUpper] &= ~hands;
    out.seed[kLower] &= ~hands;

    out.hard = cv::Mat(size, CV_8UC1, cv::Scalar(255));
    out.hard.setTo(kBackground, d_skel > 0.22 * H);
    cv::Mat core_upper = zero.clone(), core_lower = zero.clone(), core_face = zero.clone();
    line(core_upper, lerp(sh, hip, 0.3), lerp(sh, hip, 0.5), 0.015 * H);
    for (auto side : {std::pair{J::right_hip, J::right_knee}, std::pair{J::left_hip, J::left_knee}})
        line(core_lower, lerp(j[side.first], j[side.second], 0.12),
             lerp(j[side.first], j[side.second], 0.25), 0.01 * H);
    disc(core_face, face, 0.1 * head_len);
    out.hard.setTo(kUpper, core_upper & ~hands);
    out.hard.setTo(kLower, core_lower & ~hands);
    out.hard.setTo(kSkin, core_face);
    return out;
}

AutoLabel auto_label_of(LabelRole role, bool below_waist) {
    switch (role) {
        case LabelRole::background: return kBackground;
        case LabelRole::skin: return kSkin;
        case LabelRole::hair: return kHair;
        case LabelRole::upper_garment: return kUpper;
        case LabelRole::lower_garment: return kLower;
        case LabelRole::full_garment: return below_waist ? kLower : kUpper;
        default: return kOther;
    }
}

std::array<cv::Mat, kAutoLabels> learned_layout(cv::Size size, const Joints& j,
                                                double pseudo_count) {
    static_assert(kLayoutPriorClasses == kAutoLabels, "the table's classes are the AutoLabels");
    // Per-cell probabilities.
    std::array<double, kAutoLabels> total{};
    for (int c = 0; c < kFrameCells; ++c)
        for (int l = 0; l < kAutoLabels; ++l) total[size_t(l)] += kLayoutPriorCounts[c][l];
    double all = 0;
    for (double t : total) all += t;
    std::vector<float> prob(size_t(kFrameCells) * kAutoLabels);
    for (int c = 0; c < kFrameCells; ++c) {
        double n = 0;
        for (int l = 0; l < kAutoLabels; ++l) n += kLayoutPriorCounts[c][l];
        for (int l = 0; l < kAutoLabels; ++l) {
            const double prior = all > 0 ? total[size_t(l)] / all : 1.0 / kAutoLabels;
            const double p = (kLayoutPriorCounts[c][l] + pseudo_count * prior) / (n + pseudo_count);
            prob[size_t(c) * kAutoLabels + size_t(l)] = float(p);
        }
    }
    std::array<cv::Mat, kAutoLabels> out;
    for (auto& m : out) m = cv::Mat(size, CV_32F);
    const auto seg = frame_segments(j);
    const double H = j.body_height_px();
    for (int y = 0; y < size.height; ++y)
        for (int x = 0; x < size.width; ++x) {
            const int c = frame_cell(seg, H, {x + 0.5, y + 0.5});
            for (int l = 0; l < kAutoLabels; ++l)
                out[size_t(l)].at<float>(y, x) = prob[size_t(c) * kAutoLabels + size_t(l)];
        }
    return out;
}

}  // namespace drape::vision::detail
