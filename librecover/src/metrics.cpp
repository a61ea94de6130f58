#include <drape/recover/metrics.hpp>

#include <drape/core/errors.hpp>
#include <drape/vision/label_table.hpp>

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

// Pixel counts of one garment group over a pair of label maps.
struct GroupCounts {
    long inter = 0, uni = 0, truth = 0, predicted = 0;
    std::array<long, 5> fp{};  // false_positive_names() order
    std::array<long, 3> fn{};  // false_negative_names() order
    std::vector<long> predicted_rows, truth_rows;
};

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
    const vision::LabelTable& table = vision::LabelTable::fashionista();  // labels.txt
    const int skin = table.skin_id(), hair = table.hair_id(), background = table.background_id();
    std::array<int, 256> group_of;  // class id -> garment group, -1 for none
    group_of.fill(-1);
    for (int gi = 0; gi < 3; ++gi)
        for (int id : group_ids(static_cast<GarmentGroup>(gi))) group_of[static_cast<size_t>(id)] = gi;
    std::array<GroupCounts, 3> c;
    for (GroupCounts& g : c) {
        g.predicted_rows.assign(static_cast<size_t>(truth.rows), 0);
        g.truth_rows.assign(static_cast<size_t>(truth.rows), 0);
    }
    for (int y = 0; y < truth.rows; ++y)
        for (int x = 0; x < truth.cols; ++x) {
            const int pid = predicted.at<std::uint8_t>(y, x), tid = truth.at<std::uint8_t>(y, x);
            const int pg = group_of[static_cast<size_t>(pid)], tg = group_of[static_cast<size_t>(tid)];
            for (int gi = 0; gi < 3; ++gi) {
                const bool a = pg == gi, b = tg == gi;
                if (!a && !b) continue;
                GroupCounts& g = c[static_cast<size_t>(gi)];
                g.inter += a && b;
                ++g.uni;
                g.truth += b;
                g.predicted += a;
                g.predicted_rows[static_cast<size_t>(y)] += a;
                g.truth_rows[static_cast<size_t>(y)] += b;
                if (a && !b)
                    ++g.fp[tid == skin ? 0 : tid == hair ? 1 : tid == background ? 2 : tg >= 0 ? 3 : 4];
                if (b && !a) ++g.fn[pid == skin ? 0 : pid == background ? 1 : 2];
            }
        }
    std::array<GroupIou, 3> out;
    const double total = static_cast<double>(truth.total());
    const double nan = std::numeric_limits<double>::quiet_NaN();
    for (int gi = 0; gi < 3; ++gi) {
        const GroupCounts& k = c[static_cast<size_t>(gi)];
        const long p = k.predicted, t = k.truth;
        GroupIou& g = out[static_cast<size_t>(gi)];
        g.group = static_cast<GarmentGroup>(gi);
        g.truth_fraction = t / total;
        g.counted = t >= 0.01 * total;
        g.iou = k.uni ? static_cast<double>(k.inter) / static_cast<double>(k.uni) : 0.0;
        g.precision = p ? static_cast<double>(k.inter) / static_cast<double>(p) : nan;
        g.recall = t ? static_cast<double>(k.inter) / static_cast<double>(t) : nan;
        for (size_t j = 0; j < k.fp.size(); ++j) g.false_positive_shares[j] = p ? double(k.fp[j]) / double(p) : nan;
        for (size_t j = 0; j < k.fn.size(); ++j) g.false_negative_shares[j] = t ? double(k.fn[j]) / double(t) : nan;
        g.top_row_error_px = g.bottom_row_error_px = g.width_error_px = nan;
        if (!(p && t)) continue;
        g.top_row_error_px = row_percentile(k.predicted_rows, p, 0.02) - row_percentile(k.truth_rows, t, 0.02);
        g.bottom_row_error_px = row_percentile(k.predicted_rows, p, 0.98) - row_percentile(k.truth_rows, t, 0.98);
        double sum = 0;
        int rows = 0;
        for (size_t y = 0; y < k.predicted_rows.size(); ++y)
            if (k.predicted_rows[y] > 0 && k.truth_rows[y] > 0) {
                sum += static_cast<double>(k.predicted_rows[y] - k.truth_rows[y]);
                ++rows;
            }
        if (rows) g.width_error_px = sum / rows;
    }
    return out;
}

}  // namespace drape::recover
