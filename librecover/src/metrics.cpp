#include <drape/recover/metrics.hpp>

#include <drape/core/errors.hpp>

#include <algorithm>
#include <cmath>

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

std::array<GroupIou, 3> group_ious(const cv::Mat& predicted, const cv::Mat& truth) {
    if (predicted.size() != truth.size() || predicted.type() != CV_8UC1 || truth.type() != CV_8UC1)
        throw InvalidInput("group IoU: the label maps must be 8-bit and of one size (" + std::to_string(predicted.cols) +
                           " x " + std::to_string(predicted.rows) + " against " + std::to_string(truth.cols) + " x " +
                           std::to_string(truth.rows) + ")");
    std::array<GroupIou, 3> out;
    const double total = static_cast<double>(truth.total());
    for (int gi = 0; gi < 3; ++gi) {
        const auto group = static_cast<GarmentGroup>(gi);
        const auto& ids = group_ids(group);
        auto in = [&](int id) { return std::find(ids.begin(), ids.end(), id) != ids.end(); };
        long inter = 0, uni = 0, t = 0;
        for (int y = 0; y < truth.rows; ++y)
            for (int x = 0; x < truth.cols; ++x) {
                const bool a = in(predicted.at<std::uint8_t>(y, x)), b = in(truth.at<std::uint8_t>(y, x));
                inter += a && b;
                uni += a || b;
                t += b;
            }
        out[static_cast<size_t>(gi)].group = group;
        out[static_cast<size_t>(gi)].truth_fraction = t / total;
        out[static_cast<size_t>(gi)].counted = t >= 0.01 * total;
        out[static_cast<size_t>(gi)].iou = uni ? static_cast<double>(inter) / static_cast<double>(uni) : 0.0;
    }
    return out;
}

}  // namespace drape::recover
