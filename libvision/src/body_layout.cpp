#include "body_layout.hpp"

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

/// cost = height * min(1, distance / reach)
cv::Mat ramp(const cv::Mat& dist, double reach, double height) {
    cv::Mat c;
    dist.convertTo(c, CV_32F, 1.0 / std::max(1e-6, reach));
    cv::min(c, 1.0, c);
    return c * height;
}

Eigen::Vector2d lerp(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double t) {
    return a + t * (b - a);
}

}  // namespace

BodyLayout body_layout(cv::Size size, const Joints& j, double weight) {
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

    // Torso quad.
    cv::Mat torso = zero.clone();
    const cv::Point quad[4] = {pt(j[J::right_shoulder]), pt(j[J::left_shoulder]),
                               pt(j[J::left_hip]), pt(j[J::right_hip])};
    cv::fillConvexPoly(torso, quad, 4, cv::Scalar(255));

    // Regions where each class may be.
    cv::Mat upper = torso.clone();
    cv::dilate(upper, upper, cv::getStructuringElement(cv::MORPH_ELLIPSE,
               {2 * int(0.03 * H) + 1, 2 * int(0.03 * H) + 1}));
    line(upper, j[J::right_shoulder], j[J::right_elbow], 0.07 * H);
    line(upper, j[J::right_elbow], j[J::right_hand], 0.06 * H);
    line(upper, j[J::left_shoulder], j[J::left_elbow], 0.07 * H);
    line(upper, j[J::left_elbow], j[J::left_hand], 0.06 * H);
    line(upper, neck, sh, 0.08 * H);

    const Eigen::Vector2d waist = lerp(sh, hip, 0.62);
    cv::Mat lower = zero.clone();
    {
        const Eigen::Vector2d rw = lerp(j[J::right_shoulder], j[J::right_hip], 0.62);
        const Eigen::Vector2d lw = lerp(j[J::left_shoulder], j[J::left_hip], 0.62);
        const Eigen::Vector2d side = (j[J::left_hip] - j[J::right_hip]).normalized() * 0.08 * H;
        const cv::Point poly[4] = {pt(rw), pt(lw), pt(j[J::left_knee] + side),
                                   pt(j[J::right_knee] - side)};
        cv::fillConvexPoly(lower, poly, 4, cv::Scalar(255));
        line(lower, j[J::right_knee], j[J::right_ankle], 0.07 * H);
        line(lower, j[J::left_knee], j[J::left_ankle], 0.07 * H);
        line(lower, j[J::right_hip], j[J::right_knee], 0.1 * H);
        line(lower, j[J::left_hip], j[J::left_knee], 0.1 * H);
    }
    cv::Mat hair = zero.clone();
    line(hair, head, neck, 0.16 * H);
    line(hair, neck, lerp(neck, hip, 0.3), 0.16 * H);
    disc(hair, head, 0.6 * head_len);

    const double reach = 0.05 * H;
    out.prior[kBackground] = ramp(0.06 * H - cv::min(d_skel, 0.06 * H), 0.06 * H, 4.0 * weight);
    out.prior[kUpper] = ramp(distance_to(upper), reach, 3.0 * weight);
    out.prior[kLower] = ramp(distance_to(lower), reach, 3.0 * weight);
    out.prior[kHair] = ramp(distance_to(hair), reach, 3.0 * weight);
    out.prior[kSkin] = ramp(d_skel, 0.12 * H, 3.0 * weight);

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
    (void)waist;

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

}  // namespace drape::vision::detail
