// The calibrated P -> K / s_b mapping (curvature_calibration.hpp): the embedded fit is
// reproduced from its embedded table, satisfies the least-squares normal equations, is
// monotone over the data, and bad input is refused; the paper's interpolation.
#include <drape/core/errors.hpp>
#include <drape/garment/curvature_calibration.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <vector>

using namespace drape::garment;

namespace {

constexpr GarmentType kTypes[] = {GarmentType::skirt, GarmentType::pants, GarmentType::tshirt, GarmentType::dress};

void require_same_model(const WrinkleModel& a, const WrinkleModel& b) {
    REQUIRE(a.form == b.form);
    for (size_t t = 0; t < 4; ++t) {
        CHECK(a.offset[t] == Approx(b.offset[t]).margin(1e-9));
        CHECK(a.slope[t] == Approx(b.slope[t]).margin(1e-9));
    }
    CHECK(a.censored_offset == Approx(b.censored_offset).margin(1e-9));
    CHECK(a.residual_low == Approx(b.residual_low).margin(1e-9));
    CHECK(a.residual_high == Approx(b.residual_high).margin(1e-9));
    CHECK(a.censored_residual_low == Approx(b.censored_residual_low).margin(1e-9));
    CHECK(a.censored_residual_high == Approx(b.censored_residual_high).margin(1e-9));
}

// The least-squares normal equations, written out per column of the model's design:
// residuals sum to zero over each offset's observations, over the censored ones, and
// weighted by ln P over each slope's observations.
void require_normal_equations(const WrinkleModel& m, const std::vector<WrinkleObservation>& obs) {
    const bool per_type_offset = m.form != WrinkleModelForm::shared_line;
    const bool has_slope = m.form != WrinkleModelForm::type_constant;
    const bool per_type_slope = m.form == WrinkleModelForm::type_line;
    std::vector<double> off(4, 0), slope(4, 0);
    double cens = 0, scale = 0;
    for (const auto& o : obs) {
        const double r = o.y - m.predict(o.type, o.p_per_m2);
        const size_t t = size_t(o.type);
        off[per_type_offset ? t : 0] += r;
        if (has_slope && o.p_per_m2 > 0) slope[per_type_slope ? t : 0] += r * std::log(o.p_per_m2);
        if (has_slope && o.p_per_m2 == 0) cens += r;
        scale += std::abs(r);
    }
    for (size_t t = 0; t < 4; ++t) {
        CHECK(off[t] == Approx(0).margin(1e-9 * (1 + scale)));
        CHECK(slope[t] == Approx(0).margin(1e-9 * (1 + scale)));
    }
    CHECK(cens == Approx(0).margin(1e-9 * (1 + scale)));
}

}  // namespace

TEST_CASE("embedded curvature calibration: the stored table reproduces the stored fit", "[curvature_calibration]") {
    const WrinkleCalibration& c = embedded_wrinkle_calibration();
    REQUIRE(c.fabric == "gray-interlock");
    const WrinkleCalibration refit =
        fit_wrinkle_calibration(c.samples, c.fabric, c.curvature.form, c.bending.form, c.lighting);
    require_same_model(refit.curvature, c.curvature);
    require_same_model(refit.bending, c.bending);
    CHECK(refit.log10_bending_min == Approx(c.log10_bending_min).margin(1e-12));
    CHECK(refit.log10_bending_max == Approx(c.log10_bending_max).margin(1e-12));
    CHECK(refit.errors.garments == c.errors.garments);
    CHECK(refit.errors.curvature_accuracy == Approx(c.errors.curvature_accuracy).margin(1e-9));
    CHECK(refit.errors.curvature_abs_log10 == Approx(c.errors.curvature_abs_log10).margin(1e-9));
    CHECK(refit.errors.bending_abs_log10 == Approx(c.errors.bending_abs_log10).margin(1e-9));
    CHECK(refit.errors.paper_curvature_accuracy == Approx(c.errors.paper_curvature_accuracy).margin(1e-9));
    CHECK(refit.errors.paper_curvature_abs_log10 == Approx(c.errors.paper_curvature_abs_log10).margin(1e-9));

    // The coefficients are the least-squares solution on the table's observations.
    require_normal_equations(c.curvature, wrinkle_observations(c.samples, c.fabric, false, c.lighting));
    require_normal_equations(c.bending, wrinkle_observations(c.samples, c.fabric, true, c.lighting));
}

TEST_CASE("embedded curvature calibration: its data covers the paper's space", "[curvature_calibration]") {
    const WrinkleCalibration& c = embedded_wrinkle_calibration();
    std::set<GarmentType> types;
    int of_fabric = 0;
    for (const auto& s : c.samples) {
        CHECK(s.k_per_m > 0);
        CHECK(s.p_midday_per_m2 >= 0);
        CHECK(s.p_sunset_per_m2 >= 0);
        if (s.fabric != c.fabric) continue;
        ++of_fabric;
        types.insert(s.type);
    }
    CHECK(of_fabric >= 38);
    CHECK(of_fabric == c.errors.garments);
    CHECK(types.size() == 4);
    CHECK(c.log10_bending_min == Approx(0).margin(1e-12));
    CHECK(c.log10_bending_max == Approx(2).margin(1e-12));
    // The reason it exists: closer to the simulated curvature than the paper's interpolation.
    CHECK(c.errors.curvature_accuracy > c.errors.paper_curvature_accuracy);
    CHECK(c.errors.curvature_abs_log10 < c.errors.paper_curvature_abs_log10);
}

TEST_CASE("curvature_from_wrinkle_density: monotone over the data, intervals around the value",
          "[curvature_calibration]") {
    const WrinkleCalibration& c = embedded_wrinkle_calibration();
    for (const GarmentType type : kTypes) {
        double lo = std::numeric_limits<double>::infinity(), hi = 0;
        for (const auto& s : c.samples)
            if (s.fabric == c.fabric && s.type == type)
                for (const double p : {s.p_midday_per_m2, s.p_sunset_per_m2})
                    if (p > 0) lo = std::min(lo, p), hi = std::max(hi, p);
        REQUIRE(hi > lo);
        CurvatureTarget previous = curvature_from_wrinkle_density(type, lo);
        for (int i = 1; i <= 20; ++i) {
            const double p = lo * std::pow(hi / lo, i / 20.0);
            const CurvatureTarget t = curvature_from_wrinkle_density(type, p);
            INFO(garment_type_name(type) << " P " << p);
            // More folds: more curvature, a softer fabric.
            CHECK(t.k_per_m >= previous.k_per_m);
            CHECK(t.log10_bending_scale <= previous.log10_bending_scale);
            CHECK_FALSE(t.censored);
            CHECK(t.fabric == "gray-interlock");
            CHECK(t.k_low_per_m <= t.k_per_m);
            CHECK(t.k_high_per_m >= t.k_per_m);
            CHECK(t.log10_bending_low <= t.log10_bending_scale);
            CHECK(t.log10_bending_high >= t.log10_bending_scale);
            CHECK(t.log10_bending_scale >= c.log10_bending_min);
            CHECK(t.log10_bending_scale <= c.log10_bending_max);
            previous = t;
        }
        const CurvatureTarget none = curvature_from_wrinkle_density(type, 0);
        CHECK(none.censored);
        CHECK(none.k_per_m > 0);
        CHECK(std::isfinite(none.k_per_m));
        CHECK(none.k_low_per_m <= none.k_per_m);
        CHECK(none.k_high_per_m >= none.k_per_m);
    }
}

TEST_CASE("curvature_from_wrinkle_density: bad P is refused", "[curvature_calibration]") {
    for (const double p : {-1e-3, -1.0, std::numeric_limits<double>::quiet_NaN(),
                           std::numeric_limits<double>::infinity()}) {
        CHECK_THROWS_AS(curvature_from_wrinkle_density(GarmentType::skirt, p), drape::InvalidInput);
        CHECK_THROWS_AS(paper_curvature_from_wrinkle_density(p), drape::InvalidInput);
    }
    CHECK_THROWS_WITH(curvature_from_wrinkle_density(GarmentType::pants, -2), Catch::Contains("-2"));
}

TEST_CASE("paper_curvature_from_wrinkle_density: K linear in P through I(1) and I(50)", "[curvature_calibration]") {
    CHECK(paper_curvature_from_wrinkle_density(1) == Approx(1e-4));
    CHECK(paper_curvature_from_wrinkle_density(50) == Approx(1e5));
    CHECK(paper_curvature_from_wrinkle_density(25.5) == Approx(0.5 * (1e-4 + 1e5)));
    CHECK(paper_curvature_from_wrinkle_density(0) == Approx(1e-4));   // clamped to [1, 50]
    CHECK(paper_curvature_from_wrinkle_density(80) == Approx(1e5));
}

TEST_CASE("fit_wrinkle_model recovers the coefficients of exact data", "[curvature_calibration]") {
    // y = a_t + b ln P (P > 0), a_t + c (P = 0), with a censored observation of every type.
    const double a[4] = {-0.5, 0.25, 1.0, 0.1}, b = 0.7, cens = -1.2;
    std::vector<WrinkleObservation> obs;
    int g = 0;
    for (const GarmentType type : kTypes)
        for (const double p : {0.0, 0.5, 2.0, 7.0, 30.0}) {
            const double y = a[int(type)] + (p > 0 ? b * std::log(p) : cens);
            obs.push_back({type, p, y, g++});
        }
    const WrinkleModel m = fit_wrinkle_model(obs, WrinkleModelForm::type_offset_line);
    for (size_t t = 0; t < 4; ++t) {
        CHECK(m.offset[t] == Approx(a[t]).margin(1e-12));
        CHECK(m.slope[t] == Approx(b).margin(1e-12));
    }
    CHECK(m.censored_offset == Approx(cens).margin(1e-12));
    // Exact data: every leave-one-out prediction is exact too.
    const std::vector<double> loo = leave_one_garment_out(obs, obs, WrinkleModelForm::type_offset_line);
    for (size_t i = 0; i < obs.size(); ++i) CHECK(loo[i] == Approx(obs[i].y).margin(1e-9));
    // One type without data: its coefficients stay 0; too few observations is an error.
    std::vector<WrinkleObservation> no_dress;
    for (const auto& o : obs)
        if (o.type != GarmentType::dress) no_dress.push_back(o);
    const WrinkleModel m2 = fit_wrinkle_model(no_dress, WrinkleModelForm::type_line);
    CHECK(m2.offset[3] == 0);
    CHECK(m2.slope[3] == 0);
    CHECK(m2.slope[0] == Approx(b).margin(1e-12));
    CHECK_THROWS_AS(fit_wrinkle_model({obs[1]}, WrinkleModelForm::type_offset_line), drape::InvalidInput);
}
