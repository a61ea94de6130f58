#include "superpixels.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

namespace drape::vision::detail {

int slic_superpixels(const cv::Mat& image_bgr, int size_px, double compactness, int iterations,
                     cv::Mat& index) {
    const int S = std::max(2, size_px);
    cv::Mat lab;
    cv::Mat f;
    image_bgr.convertTo(f, CV_32FC3, 1.0 / 255.0);
    cv::cvtColor(f, lab, cv::COLOR_BGR2Lab);
    const int w = lab.cols, h = lab.rows;
    struct Centre { float l, a, b, x, y; };
    std::vector<Centre> centres;
    for (int y = S / 2; y < h; y += S)
        for (int x = S / 2; x < w; x += S) {
            const cv::Vec3f c = lab.at<cv::Vec3f>(y, x);
            centres.push_back({c[0], c[1], c[2], float(x), float(y)});
        }
    if (centres.empty()) centres.push_back({0, 0, 0, w / 2.f, h / 2.f});
    index.create(lab.size(), CV_32S);
    index.setTo(0);
    cv::Mat dist(lab.size(), CV_32F);
    const float m2 = float(compactness * compactness), s2 = float(S * S);
    for (int it = 0; it < iterations; ++it) {
        dist.setTo(std::numeric_limits<float>::max());
        for (size_t k = 0; k < centres.size(); ++k) {
            const Centre& c = centres[k];
            const int x0 = std::max(0, int(c.x) - S), x1 = std::min(w - 1, int(c.x) + S);
            const int y0 = std::max(0, int(c.y) - S), y1 = std::min(h - 1, int(c.y) + S);
            for (int y = y0; y <= y1; ++y) {
                const auto* p = lab.ptr<cv::Vec3f>(y);
                auto* d = dist.ptr<float>(y);
                auto* idx = index.ptr<int>(y);
                for (int x = x0; x <= x1; ++x) {
                    const float dl = p[x][0] - c.l, da = p[x][1] - c.a, db = p[x][2] - c.b;
                    const float dx = x - c.x, dy = y - c.y;
                    const float D = dl * dl + da * da + db * db + (dx * dx + dy * dy) * m2 / s2;
                    if (D < d[x]) { d[x] = D; idx[x] = int(k); }
                }
            }
        }
        std::vector<std::array<double, 6>> acc(centres.size(), {0, 0, 0, 0, 0, 0});
        for (int y = 0; y < h; ++y) {
            const auto* p = lab.ptr<cv::Vec3f>(y);
            const auto* idx = index.ptr<int>(y);
            for (int x = 0; x < w; ++x) {
                auto& a = acc[static_cast<size_t>(idx[x])];
                a[0] += p[x][0]; a[1] += p[x][1]; a[2] += p[x][2]; a[3] += x; a[4] += y; a[5] += 1;
            }
        }
        for (size_t k = 0; k < centres.size(); ++k) {
            const auto& a = acc[k];
            if (a[5] <= 0) continue;
            centres[k] = {float(a[0] / a[5]), float(a[1] / a[5]), float(a[2] / a[5]),
                          float(a[3] / a[5]), float(a[4] / a[5])};
        }
    }
    return static_cast<int>(centres.size());
}

void majority_vote(const cv::Mat& index, int count, const cv::Mat& fixed, cv::Mat& labels) {
    std::vector<std::array<int, 256>> votes(static_cast<size_t>(count));
    for (auto& v : votes) v.fill(0);
    for (int y = 0; y < labels.rows; ++y) {
        const auto* idx = index.ptr<int>(y);
        const auto* lab = labels.ptr<std::uint8_t>(y);
        for (int x = 0; x < labels.cols; ++x) ++votes[static_cast<size_t>(idx[x])][lab[x]];
    }
    std::vector<std::uint8_t> winner(static_cast<size_t>(count), 0);
    for (size_t k = 0; k < votes.size(); ++k)
        winner[k] = static_cast<std::uint8_t>(
            std::max_element(votes[k].begin(), votes[k].end()) - votes[k].begin());
    for (int y = 0; y < labels.rows; ++y) {
        const auto* idx = index.ptr<int>(y);
        const auto* fx = fixed.empty() ? nullptr : fixed.ptr<std::uint8_t>(y);
        auto* lab = labels.ptr<std::uint8_t>(y);
        for (int x = 0; x < labels.cols; ++x)
            lab[x] = (fx && fx[x] != 255) ? fx[x] : winner[static_cast<size_t>(idx[x])];
    }
}

}  // namespace drape::vision::detail
