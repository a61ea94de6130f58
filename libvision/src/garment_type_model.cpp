#include "garment_type_model.hpp"

#include "mask_geometry.hpp"

#include <drape/vision/classify_garment.hpp>

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>

namespace drape::vision::detail {

namespace {

cv::Mat to_lab(const cv::Mat& bgr) {
    cv::Mat lab;
    cv::cvtColor(bgr, lab, cv::COLOR_BGR2Lab);
    return lab;
}

double lab_step(const cv::Vec3b& a, const cv::Vec3b& b) {
    double s = 0;
    for (int k = 0; k < 3; ++k) s += (double(a[k]) - b[k]) * (double(a[k]) - b[k]);
    return std::sqrt(s);
}

/// 8x8x8 Lab histogram, mean and mean of L^2 of the pixels of `mask` (rows y0..y1-1).
struct RegionStats {
    std::vector<double> hist = std::vector<double>(512, 0.0);
    cv::Vec3d sum{0, 0, 0};
    double l2 = 0;
    double n = 0;
    void add(const cv::Vec3b& p) {
        hist[size_t((p[0] >> 5) * 64 + (p[1] >> 5) * 8 + (p[2] >> 5))] += 1;
        for (int k = 0; k < 3; ++k) sum[k] += p[k];
        l2 += double(p[0]) * p[0];
        n += 1;
    }
    cv::Vec3d mean() const { return n > 0 ? sum / n : cv::Vec3d(0, 0, 0); }
    double std_l() const {
        if (n <= 0) return 0;
        const double m = sum[0] / n;
        return std::sqrt(std::max(0.0, l2 / n - m * m));
    }
};

double bhattacharyya(const RegionStats& a, const RegionStats& b) {
    if (a.n <= 0 || b.n <= 0) return 0;
    double s = 0;
    for (size_t i = 0; i < a.hist.size(); ++i) s += std::sqrt(a.hist[i] / a.n * b.hist[i] / b.n);
    return s;
}

double mean_distance(const RegionStats& a, const RegionStats& b) {
    if (a.n <= 0 || b.n <= 0) return 0;
    return cv::norm(a.mean() - b.mean());
}

double median(std::vector<double> v, double fallback) {
    if (v.empty()) return fallback;
    std::nth_element(v.begin(), v.begin() + long(v.size() / 2), v.end());
    return v[v.size() / 2];
}

}  // namespace

std::array<double, kDressFeatureCount> dress_features(const cv::Mat& image, const cv::Mat& upper,
                                                      const cv::Mat& lower, const Joints& j) {
    std::array<double, kDressFeatureCount> f{};
    const cv::Mat lab = to_lab(image);
    const double H = j.body_height_px();
    const double sh_y = j.mid_shoulder().y(), hip_y = j.mid_hip().y();
    // Torso columns: between the hip joints.
    const int x0 = std::max(0, int(std::floor(std::min(j[Joint::right_hip].x(), j[Joint::left_hip].x())))),
              x1 = std::min(image.cols - 1, int(std::ceil(std::max(j[Joint::right_hip].x(), j[Joint::left_hip].x()))));
    const int max_gap = std::max(2, int(std::lround(0.02 * H)));
    std::vector<double> transitions;
    std::vector<std::pair<int, int>> edges;  // (x, y) of each column's transition
    int columns = 0;
    for (int x = x0; x <= x1; ++x) {
        ++columns;
        int last_upper = -1, first_lower = -1;
        for (int y = std::max(0, int(sh_y)); y < image.rows; ++y) {
            if (upper.at<std::uint8_t>(y, x) && first_lower < 0) last_upper = y;
            if (lower.at<std::uint8_t>(y, x) && last_upper >= 0 && first_lower < 0) first_lower = y;
        }
        if (last_upper >= 0 && first_lower > last_upper && first_lower - last_upper <= max_gap) {
            const int t = (last_upper + first_lower) / 2;
            transitions.push_back(t);
            edges.emplace_back(x, t);
        }
    }
    const double waist_y = sh_y + 0.62 * (hip_y - sh_y);
    const double boundary = median(transitions, waist_y);
    f[9] = columns > 0 ? double(transitions.size()) / columns : 0.0;
    f[5] = (boundary - sh_y) / std::max(1.0, hip_y - sh_y);
    const double band = 0.08 * H;
    // Whole-region statistics leave out the natural-waist band (6 % H either side of the
    // line 62 % shoulder -> hip on each side), as the colour rule of segmentation.cpp:
    // belts and sashes are not the dress's fabric (001630's gold sash).
    const Eigen::Vector2d waist_r = j[Joint::right_shoulder] + 0.62 * (j[Joint::right_hip] - j[Joint::right_shoulder]),
                          waist_l = j[Joint::left_shoulder] + 0.62 * (j[Joint::left_hip] - j[Joint::left_shoulder]);
    const Eigen::Vector2d waist_dir = (waist_l - waist_r).norm() > 0 ? Eigen::Vector2d((waist_l - waist_r).normalized())
                                                                     : Eigen::Vector2d(1, 0);
    const double waist_band = 0.06 * H;
    RegionStats au, al, bu, bl, wu, wl;  // w*: whole regions including the waist band
    double step_sum = 0;
    long step_n = 0;
    for (int y = 0; y < image.rows; ++y) {
        const auto* u = upper.ptr<std::uint8_t>(y);
        const auto* l = lower.ptr<std::uint8_t>(y);
        const auto* p = lab.ptr<cv::Vec3b>(y);
        for (int x = 0; x < image.cols; ++x) {
            if (!u[x] && !l[x]) continue;
            const Eigen::Vector2d d = Eigen::Vector2d(x + 0.5, y + 0.5) - waist_r;
            const bool in_waist = std::abs(d.x() * waist_dir.y() - d.y() * waist_dir.x()) < waist_band;
            if (u[x]) {
                wu.add(p[x]);
                if (!in_waist) au.add(p[x]);
                if (y >= boundary - band && y < boundary) bu.add(p[x]);
            } else {
                wl.add(p[x]);
                if (!in_waist) al.add(p[x]);
                if (y >= boundary && y < boundary + band) bl.add(p[x]);
            }
            if ((x + y) % 2 == 0 && y >= 2 && y + 2 < image.rows) {
                step_sum += lab_step(lab.at<cv::Vec3b>(y - 2, x), lab.at<cv::Vec3b>(y + 2, x));
                ++step_n;
            }
        }
    }
    // A part left smaller than a garment's minimum area (0.2 % of the image) outside the
    // band: the whole regions.
    const double min_kept = 0.002 * double(image.total());
    if (au.n < min_kept || al.n < min_kept) {
        au = wu;
        al = wl;
    }
    f[0] = bhattacharyya(au, al);
    f[1] = bhattacharyya(bu, bl);
    f[2] = mean_distance(bu, bl);
    f[3] = mean_distance(au, al);
    double edge_sum = 0;
    for (const auto& [x, t] : edges) {
        double best = 0;
        for (int y = t - 2; y <= t + 2; ++y)
            if (y >= 2 && y + 2 < image.rows)
                best = std::max(best, lab_step(lab.at<cv::Vec3b>(y - 2, x), lab.at<cv::Vec3b>(y + 2, x)));
        edge_sum += best;
    }
    const double step_mean = step_n > 0 ? step_sum / double(step_n) : 0.0;
    f[4] = edges.empty() ? 0.0 : (edge_sum / double(edges.size())) / (step_mean + 1.0);
    f[6] = measure_shape_cues(lower, j).hem_fraction;
    f[7] = (wu.n + wl.n) > 0 ? wu.n / (wu.n + wl.n) : 0.0;
    const double su = au.std_l(), sl = al.std_l();
    f[8] = std::abs(su - sl) / (su + sl + 1.0);
    return f;
}

std::array<double, kLowerFeatureCount> lower_features(const cv::Mat& image, const cv::Mat& full_lower,
                                                      const Joints& j, const cv::Mat& hiding) {
    std::array<double, kLowerFeatureCount> f{};
    const GarmentShapeCues c = measure_shape_cues(full_lower, j, hiding);
    f[0] = c.hem_fraction;
    f[1] = c.leg_fraction;
    f[2] = c.between_legs_fraction;
    f[3] = c.knee_width_ratio;
    const cv::Mat mask = main_pieces(full_lower);
    const int bottom = row_percentile(mask, 0.98), top = row_percentile(mask, 0.02);
    if (bottom < 0) return f;
    const double hip_y = j.mid_hip().y(), knee_y = j.mid_knee().y(), ankle_y = j.mid_ankle().y();
    const double thigh = std::max(upper_thigh_width(mask, j), 1.0);
    auto mean_width = [&](double yc) { return mean_row_width(mask, yc, j); };
    f[4] = mean_width(hip_y + 0.25 * (ankle_y - hip_y)) / thigh;
    f[5] = mean_width(hip_y + 0.50 * (ankle_y - hip_y)) / thigh;
    f[6] = mean_width(hip_y + 0.75 * (ankle_y - hip_y)) / thigh;
    f[7] = mean_width(bottom - 0.03 * (bottom - top)) / thigh;
    const double crotch = hip_y + 0.15 * (knee_y - hip_y);
    int rows = 0;
    double runs_sum = 0;
    for (int y = int(std::ceil(crotch)); y <= bottom; ++y) {
        int runs = 0;
        if (row_width(mask, y, &runs) > 0) {
            runs_sum += runs;
            ++rows;
        }
    }
    f[8] = rows > 0 ? runs_sum / rows : 0.0;
    // Horizontal Lab step on the line between the legs (a seam or the shadow between two
    // trouser legs) against the garment's mean horizontal step.
    const cv::Mat lab = to_lab(image);
    double mid_sum = 0, all_sum = 0;
    long mid_n = 0, all_n = 0;
    for (int y = int(std::ceil(crotch)); y <= std::min(bottom, int(knee_y)); ++y) {
        const int xm = int(std::floor(between_legs(j, y + 0.5).x()));
        if (xm < 3 || xm + 3 >= image.cols || !mask.at<std::uint8_t>(y, xm)) continue;
        double best = 0;
        for (int x = xm - 2; x <= xm + 2; ++x)
            best = std::max(best, lab_step(lab.at<cv::Vec3b>(y, x - 1), lab.at<cv::Vec3b>(y, x + 1)));
        mid_sum += best;
        ++mid_n;
    }
    for (int y = top; y <= bottom; y += 2) {
        const auto* m = mask.ptr<std::uint8_t>(y);
        for (int x = 1; x + 1 < image.cols; x += 2)
            if (m[x]) {
                all_sum += lab_step(lab.at<cv::Vec3b>(y, x - 1), lab.at<cv::Vec3b>(y, x + 1));
                ++all_n;
            }
    }
    f[9] = mid_n > 0 ? (mid_sum / double(mid_n)) / (all_n > 0 ? all_sum / double(all_n) + 1.0 : 1.0) : 0.0;
    return f;
}

std::vector<double> LinearTypeModel::probabilities(const double* x) const {
    std::vector<double> s(classes.size(), 0.0);
    double top = -1e300;
    for (size_t c = 0; c < classes.size(); ++c) {
        s[c] = bias[c];
        for (size_t k = 0; k < features.size(); ++k)
            s[c] += weight[c][k] * (x[size_t(features[k])] - mean[k]) / scale[k];
        top = std::max(top, s[c]);
    }
    double z = 0;
    for (auto& v : s) z += (v = std::exp(v - top));
    for (auto& v : s) v /= z;
    return s;
}

std::optional<bool> learned_is_dress(const cv::Mat& image, const cv::Mat& upper, const cv::Mat& lower,
                                     const Joints& joints) {
    if (!kDressModel.trained()) return std::nullopt;
    const auto f = dress_features(image, upper, lower, joints);
    const auto p = kDressModel.probabilities(f.data());
    for (size_t c = 0; c < p.size(); ++c)
        if (kDressModel.classes[c] == GarmentType::dress) return p[c] > kDressDecision;
    return std::nullopt;
}

std::optional<GarmentType> learned_lower_type(const cv::Mat& image, const cv::Mat& lower,
                                              const Joints& joints, const cv::Mat& hiding) {
    if (!kLowerModel.trained()) return std::nullopt;
    const auto f = lower_features(image, lower, joints, hiding);
    const auto p = kLowerModel.probabilities(f.data());
    return kLowerModel.classes[size_t(std::max_element(p.begin(), p.end()) - p.begin())];
}

}  // namespace drape::vision::detail
