#include "colour_model.hpp"

#include <cmath>

namespace drape::vision::detail {

cv::Mat colour_bins(const cv::Mat& image_bgr, int bins) {
    cv::Mat out(image_bgr.size(), CV_32S);
    for (int y = 0; y < image_bgr.rows; ++y) {
        const auto* src = image_bgr.ptr<cv::Vec3b>(y);
        auto* dst = out.ptr<int>(y);
        for (int x = 0; x < image_bgr.cols; ++x) dst[x] = colour_bin(src[x], bins);
    }
    return out;
}

ColourHistogram::ColourHistogram(int bins)
    : bins_(bins), counts_(static_cast<size_t>(bins) * bins * bins, 0.0) {}

void ColourHistogram::finish() {
    const int n = bins_;
    std::vector<double> h = counts_, tmp(h.size());
    auto idx = [n](int a, int b, int c) { return static_cast<size_t>((a * n + b) * n + c); };
    for (int axis = 0; axis < 3; ++axis) {
        for (int a = 0; a < n; ++a)
            for (int b = 0; b < n; ++b)
                for (int c = 0; c < n; ++c) {
                    int p[3] = {a, b, c};
                    double s = 2 * h[idx(a, b, c)], w = 2;
                    for (int d : {-1, 1}) {
                        int q[3] = {a, b, c};
                        q[axis] += d;
                        if (q[axis] < 0 || q[axis] >= n) continue;
                        s += h[idx(q[0], q[1], q[2])];
                        w += 1;
                    }
                    (void)p;
                    tmp[idx(a, b, c)] = s / w;
                }
        h.swap(tmp);
    }
    total_ = 0;
    for (double v : counts_) total_ += v;
    double sum = 0;
    for (double v : h) sum += v;
    prob_.assign(h.size(), 0.0);
    costs_.assign(h.size(), 0.0f);
    const double uniform = 1.0 / static_cast<double>(h.size());
    for (size_t i = 0; i < h.size(); ++i) {
        // A floor of 1 % of uniform keeps unseen colours possible (costs stay bounded).
        const double p = sum > 0 ? h[i] / sum : uniform;
        prob_[i] = p;
        costs_[i] = static_cast<float>(-std::log(p + 0.01 * uniform) + std::log(uniform));
    }
}

double ColourHistogram::similarity(const ColourHistogram& other) const {
    double s = 0;
    for (size_t i = 0; i < prob_.size() && i < other.prob_.size(); ++i)
        s += std::sqrt(prob_[i] * other.prob_[i]);
    return s;
}

}  // namespace drape::vision::detail
