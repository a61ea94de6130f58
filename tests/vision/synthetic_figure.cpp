#include "synthetic_figure.hpp"

#include <opencv2/imgproc.hpp>

#include <cmath>

namespace drape::test {

namespace {
cv::Point P(double x, double y, double s) { return {int(std::lround(x * s)), int(std::lround(y * s))}; }
}  // namespace

SyntheticFigure make_figure(Bottom bottom, double s) {
    SyntheticFigure f;
    const int W = int(std::lround(400 * s)), H = int(std::lround(600 * s));
    using J = vision::Joint;
    const double pts[14][2] = {{178, 545}, {178, 430}, {180, 305}, {220, 305}, {222, 430},
                               {222, 545}, {118, 300}, {128, 215}, {160, 125}, {240, 125},
                               {272, 215}, {282, 300}, {200, 112}, {200, 28}};
    for (int i = 0; i < 14; ++i) f.joints.px[size_t(i)] = Eigen::Vector2d(pts[i][0], pts[i][1]) * s;
    cv::Mat L(H, W, CV_8UC1, cv::Scalar(0));
    const auto j = [&](J k) { return P(f.joints[k].x() / s, f.joints[k].y() / s, s); };
    const int t = std::max(1, int(std::lround(24 * s)));
    // Skin: legs, arms, neck, face.
    cv::line(L, j(J::right_hip), j(J::right_knee), 41, t);
    cv::line(L, j(J::right_knee), j(J::right_ankle), 41, t);
    cv::line(L, j(J::left_hip), j(J::left_knee), 41, t);
    cv::line(L, j(J::left_knee), j(J::left_ankle), 41, t);
    cv::line(L, j(J::right_shoulder), j(J::right_elbow), 41, int(t * 0.9));
    cv::line(L, j(J::right_elbow), j(J::right_hand), 41, int(t * 0.8));
    cv::line(L, j(J::left_shoulder), j(J::left_elbow), 41, int(t * 0.9));
    cv::line(L, j(J::left_elbow), j(J::left_hand), 41, int(t * 0.8));
    cv::rectangle(L, P(190, 80, s), P(210, 125, s), 41, cv::FILLED);
    cv::ellipse(L, P(200, 30, s), cv::Size(int(36 * s), int(28 * s)), 0, 0, 360, 19, cv::FILLED);
    cv::ellipse(L, P(200, 62, s), cv::Size(int(28 * s), int(36 * s)), 0, 0, 360, 41, cv::FILLED);
    // Bottom.
    if (bottom == Bottom::skirt) {
        const cv::Point skirt[4] = {P(168, 290, s), P(232, 290, s), P(262, 420, s), P(138, 420, s)};
        cv::fillConvexPoly(L, skirt, 4, 42);
    } else {
        const cv::Point top[4] = {P(166, 290, s), P(234, 290, s), P(238, 340, s), P(162, 340, s)};
        cv::fillConvexPoly(L, top, 4, 31);
        cv::line(L, P(180, 320, s), j(J::right_ankle), 31, t);
        cv::line(L, P(220, 320, s), j(J::left_ankle), 31, t);
    }
    // T-shirt: torso and short sleeves.
    const cv::Point torso[4] = {P(155, 118, s), P(245, 118, s), P(236, 300, s), P(164, 300, s)};
    cv::fillConvexPoly(L, torso, 4, 51);
    cv::line(L, j(J::right_shoulder), P(146, 170, s), 51, int(t * 1.3));
    cv::line(L, j(J::left_shoulder), P(254, 170, s), 51, int(t * 1.3));
    cv::ellipse(L, P(200, 118, s), cv::Size(int(14 * s), int(10 * s)), 0, 0, 180, 41, cv::FILLED);
    f.labels = L;

    // Photo: flat colours per class on a gradient background, soft shading and noise.
    cv::Mat img(H, W, CV_8UC3);
    cv::RNG rng(12345);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            cv::Vec3d c;
            switch (L.at<std::uint8_t>(y, x)) {
                case 19: c = {35, 40, 60}; break;
                case 41: c = {140, 170, 225}; break;
                case 51: c = {190, 120, 60}; break;
                case 42: c = {60, 50, 170}; break;
                case 31: c = {110, 70, 40}; break;
                default: c = {170 + 40.0 * y / H, 185, 195 - 30.0 * x / W};
            }
            for (int k = 0; k < 3; ++k)
                img.at<cv::Vec3b>(y, x)[k] = cv::saturate_cast<std::uint8_t>(c[k] + rng.gaussian(4.0));
        }
    cv::GaussianBlur(img, f.photo, cv::Size(3, 3), 0.7);
    return f;
}

void paint_folds(cv::Mat& photo, const cv::Mat& mask, int periods, double contrast) {
    const cv::Rect box = cv::boundingRect(mask);
    for (int y = box.y; y < box.y + box.height; ++y)
        for (int x = box.x; x < box.x + box.width; ++x) {
            if (!mask.at<std::uint8_t>(y, x)) continue;
            const double u = (x - box.x + 0.5) / box.width;
            const double g = 1.0 + contrast * std::sin(2 * M_PI * periods * u);
            cv::Vec3b& p = photo.at<cv::Vec3b>(y, x);
            for (int k = 0; k < 3; ++k) p[k] = cv::saturate_cast<std::uint8_t>(p[k] * g);
        }
}

}  // namespace drape::test
