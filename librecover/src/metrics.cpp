#include <drape/recover/metrics.hpp>

#include <drape/core/errors.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace drape::recover {

double relative_accuracy(double est, double gt) {
    if (gt == 0) return est == 0 ? 1.0 : 0.0;
    return std::max(0.0, 1.0 - std::abs(est - gt) / std::abs(gt));
}

double sizing_accuracy(const garment::GarmentSizing& est, const garment::GarmentSizing& gt) {
    if (est.type != gt.type)
        throw InvalidInput("sizing accuracy: a " + garment::garment_type_name(est.type) + " against a " +
                           garment::garment_type_name(gt.type));
    const auto e = garment::sizing_values(est), g = garment::sizing_values(gt);
    double sum = 0;
    for (size_t i = 0; i < e.size(); ++i) sum += relative_accuracy(e[i], g[i]);
    return e.empty() ? 0.0 : sum / static_cast<double>(e.size());
}

double material_accuracy(const cloth::Material& est, const cloth::Material& gt) {
    double sum = 0;
    int n = 0;
    for (size_t r = 0; r < 3; ++r)
        for (size_t c = 0; c < 5; ++c, ++n)
            sum += relative_accuracy(est.bending_n_m[r][c] * est.bending_scale, gt.bending_n_m[r][c] * gt.bending_scale);
    for (size_t r = 0; r < 6; ++r)
        for (size_t c = 0; c < 4; ++c, ++n)
            sum += relative_accuracy(est.stretching_n_per_m[r][c] * est.stretching_scale,
                                     gt.stretching_n_per_m[r][c] * gt.stretching_scale);
    return sum / n;
}

double bending_log_error(const cloth::Material& est, const cloth::Material& gt) {
    return std::abs(std::log10(est.bending_scale / gt.bending_scale));
}

double curvature_accuracy(double k_est, double k_gt) { return relative_accuracy(k_est, k_gt); }

GarmentScore score_garment(const garment::GarmentSizing& est, const garment::GarmentSizing& est_initial,
                           const cloth::Material& est_material, double est_k, const garment::GarmentSizing& gt,
                           const cloth::Material& gt_material, double gt_k) {
    GarmentScore s;
    s.sizing = sizing_accuracy(est, gt);
    s.initial_sizing = sizing_accuracy(est_initial, gt);
    s.material = material_accuracy(est_material, gt_material);
    s.bending_log10 = bending_log_error(est_material, gt_material);
    s.curvature = curvature_accuracy(est_k, gt_k);
    return s;
}

const std::vector<int>& group_ids(GarmentGroup g) {
    static const std::vector<int> upper = {5, 6, 38, 48, 49, 51, 54}, lower = {25, 27, 31, 40, 42}, dress = {14};
    switch (g) {
        case GarmentGroup::upper: return upper;
        case GarmentGroup::lower: return lower;
        case GarmentGroup::dress: return dress;
    }
    return upper;
}

std::string group_name(GarmentGroup g) {
    switch (g) {
        case GarmentGroup::upper: return "upper";
        case GarmentGroup::lower: return "lower";
        case GarmentGroup::dress: return "dress";
    }
    return "";
}

namespace {

constexpr int kSkinId = 41;  // labels.txt
constexpr int kHairId = 19;

// The row below which `fraction` of the histogram's pixels lie (rows weighted by count).
double row_percentile(const std::vector<long>& per_row, long total, double fraction) {
    const double want = fraction * static_cast<double>(total);
    long seen = 0;
    for (size_t y = 0; y < per_row.size(); ++y) {
        seen += per_row[y];
        if (static_cast<double>(seen) >= want && per_row[y] > 0) return static_cast<double>(y);
    }
    return static_cast<double>(per_row.size()) - 1;
}

}  // namespace

const std::array<const char*, 5>& false_positive_names() {
    static const std::array<const char*, 5> n = {"skin", "hair", "background", "garment", "other"};
    return n;
}

const std::array<const char*, 3>& false_negative_names() {
    static const std::array<const char*, 3> n = {"body", "background", "garment"};
    return n;
}

std::array<GroupIou, 3> group_ious(const cv::Mat& predicted, const cv::Mat& truth) {
    if (predicted.size() != truth.size() || predicted.type() != CV_8UC1 || truth.type() != CV_8UC1)
        throw InvalidInput("group IoU: the label maps must be 8-bit and of one size (" + std::to_string(predicted.cols) +
                           " x " + std::to_string(predicted.rows) + " against " + std::to_string(truth.cols) + " x " +
                           std::to_string(truth.rows) + ")");
    std::array<GroupIou, 3> out;
    const double total = static_cast<double>(truth.total());
    const double nan = std::numeric_limits<double>::quiet_NaN();
    for (int gi = 0; gi < 3; ++gi) {
        const auto group = static_cast<GarmentGroup>(gi);
        const auto& ids = group_ids(group);
        auto in = [&](int id) { return std::find(ids.begin(), ids.end(), id) != ids.end(); };
        long inter = 0, uni = 0, t = 0, p = 0;
        std::array<long, 5> fp{};
        std::array<long, 3> fn{};
        // 0 skin, 1 hair, 2 background, 3 another group's garment, 4 anything else.
        const auto fp_kind = [&](int id) {
            if (id == kSkinId) return 0;
            if (id == kHairId) return 1;
            if (id == 0) return 2;
            for (int o = 0; o < 3; ++o)
                if (o != gi) {
                    const auto& other = group_ids(static_cast<GarmentGroup>(o));
                    if (std::find(other.begin(), other.end(), id) != other.end()) return 3;
                }
            return 4;
        };
        std::vector<long> p_rows(static_cast<size_t>(truth.rows), 0), t_rows(static_cast<size_t>(truth.rows), 0);
        for (int y = 0; y < truth.rows; ++y)
            for (int x = 0; x < truth.cols; ++x) {
                const bool a = in(predicted.at<std::uint8_t>(y, x)), b = in(truth.at<std::uint8_t>(y, x));
                inter += a && b;
                uni += a || b;
                t += b;
                p += a;
                if (a && !b) ++fp[static_cast<size_t>(fp_kind(truth.at<std::uint8_t>(y, x)))];
                if (b && !a) {
                    const int id = predicted.at<std::uint8_t>(y, x);
                    ++fn[id == kSkinId ? 0 : id == 0 ? 1 : 2];
                }
                p_rows[static_cast<size_t>(y)] += a;
                t_rows[static_cast<size_t>(y)] += b;
            }
        GroupIou& g = out[static_cast<size_t>(gi)];
        g.group = group;
        g.truth_fraction = t / total;
        g.counted = t >= 0.01 * total;
        g.iou = uni ? static_cast<double>(inter) / static_cast<double>(uni) : 0.0;
        g.precision = p ? static_cast<double>(inter) / static_cast<double>(p) : nan;
        g.recall = t ? static_cast<double>(inter) / static_cast<double>(t) : nan;
        for (size_t k = 0; k < fp.size(); ++k) g.false_positive_shares[k] = p ? double(fp[k]) / double(p) : nan;
        for (size_t k = 0; k < fn.size(); ++k) g.false_negative_shares[k] = t ? double(fn[k]) / double(t) : nan;
        if (p && t) {
            g.top_row_error_px = row_percentile(p_rows, p, 0.02) - row_percentile(t_rows, t, 0.02);
            g.bottom_row_error_px = row_percentile(p_rows, p, 0.98) - row_percentile(t_rows, t, 0.98);
            double sum = 0;
            int rows = 0;
            for (size_t y = 0; y < p_rows.size(); ++y)
                if (p_rows[y] > 0 && t_rows[y] > 0) {
                    sum += static_cast<double>(p_rows[y] - t_rows[y]);
                    ++rows;
                }
            g.width_error_px = rows ? sum / rows : nan;
        } else {
            g.top_row_error_px = g.bottom_row_error_px = g.width_error_px = nan;
        }
    }
    return out;
}

}  // namespace drape::recover
