#include <drape/core/errors.hpp>
#include <drape/garment/curvature_calibration.hpp>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <set>
#include <string>
#include <vector>

namespace drape::garment {

namespace {

constexpr int kTypes = 4;

void require_density(double p_per_m2) {
    require(std::isfinite(p_per_m2) && p_per_m2 >= 0,
            "wrinkle density P must be finite and >= 0 (1/m^2), got ", p_per_m2);
}

int type_index(GarmentType type) { return static_cast<int>(type); }

// Columns of the design matrix: per-type offsets (or one), per-type slopes (or one, or
// none), the censored level (none for type_constant).
struct Design {
    int offsets = 0;   // 1 or kTypes
    int slopes = 0;    // 0, 1 or kTypes
    bool censored = false;
    int columns() const { return offsets + slopes + (censored ? 1 : 0); }
};

Design design_of(WrinkleModelForm form) {
    switch (form) {
        case WrinkleModelForm::type_constant: return {kTypes, 0, false};
        case WrinkleModelForm::shared_line: return {1, 1, true};
        case WrinkleModelForm::type_offset_line: return {kTypes, 1, true};
        case WrinkleModelForm::type_line: return {kTypes, kTypes, true};
    }
    throw InvalidInput("unknown wrinkle model form");
}

Eigen::RowVectorXd design_row(const Design& d, GarmentType type, double p) {
    Eigen::RowVectorXd row = Eigen::RowVectorXd::Zero(d.columns());
    const int t = type_index(type);
    row(d.offsets == 1 ? 0 : t) = 1;
    if (p > 0) {
        if (d.slopes == 1) row(d.offsets) = std::log(p);
        if (d.slopes == kTypes) row(d.offsets + t) = std::log(p);
    } else if (d.censored) {
        row(d.offsets + d.slopes) = 1;
    }
    return row;
}

// Linear-interpolated percentile (q in [0, 1]) of `v` (not empty).
double percentile(std::vector<double> v, double q) {
    std::sort(v.begin(), v.end());
    const double at = q * double(v.size() - 1);
    const size_t i = size_t(std::floor(at));
    if (i + 1 >= v.size()) return v.back();
    return v[i] + (at - double(i)) * (v[i + 1] - v[i]);
}

constexpr double kLowPercentile = 0.1;
constexpr double kHighPercentile = 0.9;

}  // namespace

std::string wrinkle_model_form_name(WrinkleModelForm form) {
    switch (form) {
        case WrinkleModelForm::type_constant: return "type_constant";
        case WrinkleModelForm::shared_line: return "shared_line";
        case WrinkleModelForm::type_offset_line: return "type_offset_line";
        case WrinkleModelForm::type_line: return "type_line";
    }
    return "unknown";
}

double WrinkleModel::predict(GarmentType type, double p_per_m2) const {
    require_density(p_per_m2);
    const int t = type_index(type);
    require(t >= 0 && t < kTypes, "unknown garment type");
    if (form == WrinkleModelForm::type_constant) return offset[size_t(t)];
    if (p_per_m2 > 0) return offset[size_t(t)] + slope[size_t(t)] * std::log(p_per_m2);
    return offset[size_t(t)] + censored_offset;
}

WrinkleModel fit_wrinkle_model(const std::vector<WrinkleObservation>& observations, WrinkleModelForm form) {
    const Design d = design_of(form);
    const int n = int(observations.size());
    Eigen::MatrixXd a(n, d.columns());
    Eigen::VectorXd y(n);
    for (int i = 0; i < n; ++i) {
        const WrinkleObservation& o = observations[size_t(i)];
        require(std::isfinite(o.y), "wrinkle calibration: observation ", i, " has a non-finite value ", o.y);
        require_density(o.p_per_m2);
        a.row(i) = design_row(d, o.type, o.p_per_m2);
        y(i) = o.y;
    }
    // Keep the columns the data determines (a type without observations, no censored
    // observation: an all-zero column); their coefficients stay 0.
    std::vector<int> used;
    for (int c = 0; c < d.columns(); ++c)
        if (a.col(c).cwiseAbs().maxCoeff() > 0) used.push_back(c);
    require(n >= int(used.size()) && !used.empty(), "wrinkle calibration (", wrinkle_model_form_name(form), "): ",
            n, " observations for ", used.size(), " coefficients");
    Eigen::MatrixXd au(n, Eigen::Index(used.size()));
    for (size_t k = 0; k < used.size(); ++k) au.col(Eigen::Index(k)) = a.col(used[k]);
    const Eigen::VectorXd xu = au.colPivHouseholderQr().solve(y);
    Eigen::VectorXd x = Eigen::VectorXd::Zero(d.columns());
    for (size_t k = 0; k < used.size(); ++k) x(used[k]) = xu(Eigen::Index(k));

    WrinkleModel m;
    m.form = form;
    for (int t = 0; t < kTypes; ++t) {
        m.offset[size_t(t)] = d.offsets == 1 ? x(0) : x(t);
        m.slope[size_t(t)] = d.slopes == 0 ? 0.0 : d.slopes == 1 ? x(d.offsets) : x(d.offsets + t);
    }
    m.censored_offset = d.censored ? x(d.offsets + d.slopes) : 0.0;
    return m;
}

std::vector<double> leave_one_garment_out(const std::vector<WrinkleObservation>& fit_on,
                                          const std::vector<WrinkleObservation>& predict, WrinkleModelForm form) {
    std::vector<double> out(predict.size(), 0.0);
    std::set<int> garments;
    for (const auto& o : predict) garments.insert(o.garment);
    for (const int g : garments) {
        std::vector<WrinkleObservation> train;
        for (const auto& o : fit_on)
            if (o.garment != g) train.push_back(o);
        const WrinkleModel m = fit_wrinkle_model(train, form);
        for (size_t i = 0; i < predict.size(); ++i)
            if (predict[i].garment == g) out[i] = m.predict(predict[i].type, predict[i].p_per_m2);
    }
    return out;
}

WrinkleModel cross_validate_wrinkle_model(const std::vector<WrinkleObservation>& fit_on,
                                          const std::vector<WrinkleObservation>& predict, WrinkleModelForm form) {
    WrinkleModel m = fit_wrinkle_model(fit_on, form);
    const std::vector<double> loo = leave_one_garment_out(fit_on, predict, form);
    std::vector<double> residual, censored;
    for (size_t i = 0; i < predict.size(); ++i)
        (predict[i].p_per_m2 > 0 ? residual : censored).push_back(predict[i].y - loo[i]);
    if (!residual.empty()) {
        m.residual_low = percentile(residual, kLowPercentile);
        m.residual_high = percentile(residual, kHighPercentile);
    }
    if (censored.size() >= 3) {
        m.censored_residual_low = percentile(censored, kLowPercentile);
        m.censored_residual_high = percentile(censored, kHighPercentile);
    }
    return m;
}

std::vector<WrinkleObservation> wrinkle_observations(const std::vector<WrinkleCalibrationSample>& samples,
                                                     const std::string& fabric, bool bending,
                                                     WrinkleLighting lighting) {
    std::vector<WrinkleObservation> out;
    for (size_t i = 0; i < samples.size(); ++i) {
        const WrinkleCalibrationSample& s = samples[i];
        if (s.fabric != fabric) continue;
        require(s.k_per_m > 0 && std::isfinite(s.k_per_m), "wrinkle calibration sample ", s.scene,
                ": mean curvature must be > 0, got ", s.k_per_m);
        require(s.bending_scale > 0 && std::isfinite(s.bending_scale), "wrinkle calibration sample ", s.scene,
                ": bending scale must be > 0, got ", s.bending_scale);
        const double y = bending ? std::log10(s.bending_scale) : std::log(s.k_per_m);
        out.push_back({s.type, s.p_midday_per_m2, y, int(i)});
        if (lighting == WrinkleLighting::both) out.push_back({s.type, s.p_sunset_per_m2, y, int(i)});
    }
    return out;
}

WrinkleCalibration fit_wrinkle_calibration(const std::vector<WrinkleCalibrationSample>& samples,
                                           const std::string& fabric, WrinkleModelForm curvature_form,
                                           WrinkleModelForm bending_form, WrinkleLighting lighting) {
    WrinkleCalibration c;
    c.fabric = fabric;
    c.lighting = lighting;
    c.samples = samples;
    const auto k_fit = wrinkle_observations(samples, fabric, false, lighting);
    const auto k_all = wrinkle_observations(samples, fabric, false, WrinkleLighting::both);
    const auto b_fit = wrinkle_observations(samples, fabric, true, lighting);
    const auto b_all = wrinkle_observations(samples, fabric, true, WrinkleLighting::both);
    require(!k_all.empty(), "wrinkle calibration: no sample of fabric ", fabric);
    double bmin = b_all.front().y, bmax = b_all.front().y;
    for (const auto& o : b_all) bmin = std::min(bmin, o.y), bmax = std::max(bmax, o.y);
    c.log10_bending_min = bmin;
    c.log10_bending_max = bmax;
    c.curvature = cross_validate_wrinkle_model(k_fit, k_all, curvature_form);
    c.bending = cross_validate_wrinkle_model(b_fit, b_all, bending_form);

    const std::vector<double> k_loo = leave_one_garment_out(k_fit, k_all, curvature_form);
    const std::vector<double> b_loo = leave_one_garment_out(b_fit, b_all, bending_form);
    std::set<int> garments;
    WrinkleCalibrationErrors& e = c.errors;
    for (size_t i = 0; i < k_all.size(); ++i) {
        garments.insert(k_all[i].garment);
        const double k = std::exp(k_all[i].y);
        const double k_hat = std::exp(k_loo[i]);
        e.curvature_accuracy += std::max(0.0, 1 - std::abs(k_hat - k) / k);
        e.curvature_abs_log10 += std::abs(std::log10(k_hat / k));
        const double b_hat = std::clamp(b_loo[i], bmin, bmax);
        e.bending_abs_log10 += std::abs(b_hat - b_all[i].y);
        const double k_paper = paper_curvature_from_wrinkle_density(k_all[i].p_per_m2);
        e.paper_curvature_accuracy += std::max(0.0, 1 - std::abs(k_paper - k) / k);
        e.paper_curvature_abs_log10 += std::abs(std::log10(k_paper / k));
    }
    const double n = double(k_all.size());
    e.garments = int(garments.size());
    e.curvature_accuracy /= n;
    e.curvature_abs_log10 /= n;
    e.bending_abs_log10 /= n;
    e.paper_curvature_accuracy /= n;
    e.paper_curvature_abs_log10 /= n;
    return c;
}

CurvatureTarget wrinkle_calibration_target(const WrinkleCalibration& calibration, GarmentType type,
                                           double p_per_m2) {
    require_density(p_per_m2);
    CurvatureTarget t;
    t.fabric = calibration.fabric;
    t.censored = p_per_m2 == 0;
    const bool own_censored_interval = calibration.curvature.censored_residual_low != 0 ||
                                       calibration.curvature.censored_residual_high != 0;
    const double yk = calibration.curvature.predict(type, p_per_m2);
    const double k_lo = t.censored && own_censored_interval ? calibration.curvature.censored_residual_low
                                                            : calibration.curvature.residual_low;
    const double k_hi = t.censored && own_censored_interval ? calibration.curvature.censored_residual_high
                                                            : calibration.curvature.residual_high;
    t.k_per_m = std::exp(yk);
    t.k_low_per_m = std::exp(yk + k_lo);
    t.k_high_per_m = std::exp(yk + k_hi);

    const WrinkleModel& b = calibration.bending;
    const bool own_b = b.censored_residual_low != 0 || b.censored_residual_high != 0;
    const double yb = b.predict(type, p_per_m2);
    const double b_lo = t.censored && own_b ? b.censored_residual_low : b.residual_low;
    const double b_hi = t.censored && own_b ? b.censored_residual_high : b.residual_high;
    const auto clamp = [&](double v) {
        return std::clamp(v, calibration.log10_bending_min, calibration.log10_bending_max);
    };
    t.log10_bending_scale = clamp(yb);
    t.log10_bending_low = clamp(yb + b_lo);
    t.log10_bending_high = clamp(yb + b_hi);
    return t;
}

CurvatureTarget curvature_from_wrinkle_density(GarmentType type, double p_per_m2) {
    return wrinkle_calibration_target(embedded_wrinkle_calibration(), type, p_per_m2);
}

double paper_curvature_from_wrinkle_density(double p_per_m2) {
    require_density(p_per_m2);
    constexpr double p0 = 1, p1 = 50, k0 = 1e-4, k1 = 1e5;
    const double p = std::clamp(p_per_m2, p0, p1);
    return k0 + (p - p0) * (k1 - k0) / (p1 - p0);
}

}  // namespace drape::garment
