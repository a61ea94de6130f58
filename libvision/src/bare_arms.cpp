#include <drape/vision/bare_arms.hpp>

#include <drape/vision/image_io.hpp>

#include "mask_geometry.hpp"

#include <drape/core/errors.hpp>

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

namespace drape::vision {

namespace {

/// Median (a*, b*) of the CIELAB pixels where `mask` is set; nullopt below `min_count` pixels.
std::optional<Eigen::Vector2d> median_chroma(const cv::Mat& lab, const cv::Mat& mask, int min_count) {
    std::vector<float> a, b;
    for (int y = 0; y < lab.rows; ++y) {
        const auto* m = mask.ptr<std::uint8_t>(y);
        const auto* p = lab.ptr<cv::Vec3b>(y);
        for (int x = 0; x < lab.cols; ++x)
            if (m[x]) {
                a.push_back(float(p[x][1]) - 128.f);  // 8-bit Lab: a* + 128, b* + 128
                b.push_back(float(p[x][2]) - 128.f);
            }
    }
    if (int(a.size()) < std::max(1, min_count)) return std::nullopt;
    auto median = [](std::vector<float>& v) {
        std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(v.size() / 2), v.end());
        return double(v[v.size() / 2]);
    };
    return Eigen::Vector2d(median(a), median(b));
}

}  // namespace

cv::Mat bare_arm_pixels(const cv::Mat& photo, const cv::Mat& garment, const cv::Mat& skin,
                        const Joints& j, const cv::Mat& hiding) {
    check_image(photo, CV_8UC3, "photo");
    for (const auto* m : {&garment, &skin})
        require(!m->empty() && m->type() == CV_8UC1 && m->size() == photo.size(),
                "bare_arm_pixels: the garment and skin masks must be CV_8UC1 of the photo's size");
    require(hiding.empty() || (hiding.type() == CV_8UC1 && hiding.size() == photo.size()),
            "bare_arm_pixels: the hiding mask must be empty or CV_8UC1 of the photo's size");
    constexpr double kArmHalfWidth = 0.025;  // of the body height: an arm is ~5 % H wide
    constexpr double kMinGarmentDistance = 10.0;  // a*b* units: clearly another colour
    constexpr double kSkinCloserFactor = 2.0;     // at most half as far from the skin
    cv::Mat out = cv::Mat::zeros(photo.size(), CV_8UC1);
    const cv::Mat g = garment != 0;
    const double H = j.body_height_px();
    const int half = std::max(1, int(std::lround(kArmHalfWidth * H)));
    const int min_count = half * half;

    cv::Mat torso = cv::Mat::zeros(photo.size(), CV_8UC1);
    const Joint corners[4] = {Joint::right_shoulder, Joint::left_shoulder, Joint::left_hip, Joint::right_hip};
    std::vector<cv::Point> quad;
    for (Joint c : corners) quad.emplace_back(int(std::floor(j[c].x())), int(std::floor(j[c].y())));
    cv::fillConvexPoly(torso, quad, cv::Scalar(255));

    cv::Mat lab;
    cv::cvtColor(photo, lab, cv::COLOR_BGR2Lab);
    const auto fabric = median_chroma(lab, g & torso, min_count);
    const auto bare = median_chroma(lab, skin != 0, min_count);
    if (!fabric || !bare) return out;

    const detail::ArmRuns runs = detail::sleeve_runs(detail::main_pieces(g), j, hiding);
    const Joint arms[2][3] = {{Joint::right_shoulder, Joint::right_elbow, Joint::right_hand},
                              {Joint::left_shoulder, Joint::left_elbow, Joint::left_hand}};
    for (int k = 0; k < 2; ++k) {
        cv::Mat band = cv::Mat::zeros(photo.size(), CV_8UC1);
        for (double s = 0; s <= runs.run_px[k]; s += 1.0) {
            Eigen::Vector2d p;
            if (!detail::arm_point(j[arms[k][0]], j[arms[k][1]], j[arms[k][2]], s, p)) continue;
            cv::circle(band, cv::Point(int(std::floor(p.x())), int(std::floor(p.y()))), half,
                       cv::Scalar(255), cv::FILLED);
        }
        band &= g & ~torso;
        const auto arm = median_chroma(lab, band, min_count);
        if (!arm) continue;
        const double to_fabric = (*arm - *fabric).norm(), to_skin = (*arm - *bare).norm();
        if (to_fabric < kMinGarmentDistance || kSkinCloserFactor * to_skin > to_fabric) continue;
        for (int y = 0; y < photo.rows; ++y)
            for (int x = 0; x < photo.cols; ++x) {
                if (!band.at<std::uint8_t>(y, x)) continue;
                const cv::Vec3b& v = lab.at<cv::Vec3b>(y, x);
                const Eigen::Vector2d q(double(v[1]) - 128.0, double(v[2]) - 128.0);
                if ((q - *bare).norm() < (q - *fabric).norm()) out.at<std::uint8_t>(y, x) = 255;
            }
    }
    return out;
}

}  // namespace drape::vision
