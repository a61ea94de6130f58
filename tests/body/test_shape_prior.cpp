// The ANSUR II semantic shape prior: embedded figures, conditional completion, validation.
#include <drape/body/semantic_shape.hpp>
#include <drape/body/shape_prior.hpp>
#include <drape/core/errors.hpp>

#include <drape/fixtures/ansur_records.hpp>
#include "test_paths.hpp"

#include <catch2/catch.hpp>

#include <Eigen/Dense>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

using drape::body::Gender;
using drape::body::GaussianPrior;
using drape::body::kSemanticCount;
using drape::body::Semantic;
using drape::body::SemanticRequest;
using drape::body::SemanticShape;
using drape::body::ShapePrior;
using drape::test::AnsurRecord;

namespace {

constexpr int idx(Semantic s) { return static_cast<int>(s); }

using Vec = Eigen::Matrix<double, kSemanticCount, 1>;
using Mat = Eigen::Matrix<double, kSemanticCount, kSemanticCount>;

// Mean and unbiased covariance of a set of records, the test's own estimate.
GaussianPrior fit_gaussian(const std::vector<const AnsurRecord*>& records) {
    GaussianPrior p;
    const double n = static_cast<double>(records.size());
    p.mean.setZero();
    for (const AnsurRecord* r : records) p.mean += r->values / n;
    p.covariance.setZero();
    for (const AnsurRecord* r : records) {
        const Vec d = r->values - p.mean;
        p.covariance += d * d.transpose() / (n - 1.0);
    }
    p.sample_count = static_cast<int>(records.size());
    return p;
}

std::vector<const AnsurRecord*> of_gender(const std::vector<AnsurRecord>& all, Gender g) {
    std::vector<const AnsurRecord*> out;
    for (const AnsurRecord& r : all)
        if (r.gender == g) out.push_back(&r);
    return out;
}

template <class F>
std::string message_of(F&& f) {
    try {
        f();
    } catch (const drape::InvalidInput& e) {
        return e.what();
    }
    return "(no drape::InvalidInput thrown)";
}

}  // namespace

TEST_CASE("gender strings round-trip and unknown ones are named", "[body][prior]") {
    CHECK(drape::body::to_string(Gender::female) == "female");
    CHECK(drape::body::to_string(Gender::male) == "male");
    CHECK(drape::body::parse_gender("female") == Gender::female);
    CHECK(drape::body::parse_gender("male") == Gender::male);
    CHECK_THROWS_AS(drape::body::parse_gender("robot"), drape::InvalidInput);
    CHECK_THAT(message_of([] { drape::body::parse_gender("Mle"); }),
               Catch::Contains("\"Mle\""));
    CHECK_THROWS_AS(drape::body::parse_gender(""), drape::InvalidInput);
}

TEST_CASE("embedded ANSUR II means and SDs match the survey summary", "[body][prior]") {
    const ShapePrior prior = ShapePrior::ansur2();
    CHECK(prior.female.sample_count == 1986);
    CHECK(prior.male.sample_count == 4082);

    // The README's table (mm, weight 0.1 kg): mean and population SD, rounded to 1 unit.
    struct Row { Semantic s; double male_mean, male_sd, female_mean, female_sd, unit; };
    const Row rows[] = {
        {Semantic::height_m, 1756, 69, 1629, 64, 1e-3},
        {Semantic::weight_kg, 855, 142, 678, 110, 0.1},
        {Semantic::chest_girth_m, 1059, 87, 947, 83, 1e-3},
        {Semantic::waist_girth_m, 941, 112, 861, 100, 1e-3},
        {Semantic::hip_girth_m, 1020, 77, 1021, 76, 1e-3},
        {Semantic::thigh_girth_m, 625, 58, 616, 56, 1e-3},
        {Semantic::calf_girth_m, 392, 30, 373, 29, 1e-3},
        {Semantic::shoulder_height_m, 1441, 63, 1335, 58, 1e-3},
        {Semantic::crotch_height_m, 846, 47, 782, 45, 1e-3},
    };
    for (const Row& r : rows) {
        const int k = idx(r.s);
        INFO(drape::body::kSemanticKeys[static_cast<std::size_t>(k)]);
        // Rounded to one unit: +-1 unit (1 mm, 0.1 kg) covers the rounding.
        CHECK(prior.male.mean[k] == Approx(r.male_mean * r.unit).margin(r.unit));
        CHECK(prior.female.mean[k] == Approx(r.female_mean * r.unit).margin(r.unit));
        CHECK(std::sqrt(prior.male.covariance(k, k)) == Approx(r.male_sd * r.unit).margin(r.unit));
        CHECK(std::sqrt(prior.female.covariance(k, k)) ==
              Approx(r.female_sd * r.unit).margin(r.unit));
    }
    // Muscle proxy: a normal CDF of a standardised residual, so about uniform on (0, 1).
    for (const GaussianPrior* p : {&prior.female, &prior.male}) {
        CHECK(p->mean[idx(Semantic::muscle)] == Approx(0.5).margin(0.01));
        CHECK(std::sqrt(p->covariance(idx(Semantic::muscle), idx(Semantic::muscle))) ==
              Approx(std::sqrt(1.0 / 12.0)).margin(0.01));
    }
}

TEST_CASE("embedded covariances are symmetric positive definite, ranges bracket the means",
          "[body][prior]") {
    const ShapePrior prior = ShapePrior::ansur2();
    for (const GaussianPrior* p : {&prior.female, &prior.male}) {
        CHECK((p->covariance - p->covariance.transpose()).cwiseAbs().maxCoeff() == 0.0);
        const Eigen::SelfAdjointEigenSolver<Mat> eig(p->covariance);
        CHECK(eig.eigenvalues().minCoeff() > 0.0);
        for (int k = 0; k < kSemanticCount; ++k) {
            INFO(drape::body::kSemanticKeys[static_cast<std::size_t>(k)]);
            CHECK(p->min[k] < p->mean[k]);
            CHECK(p->mean[k] < p->max[k]);
        }
        // Strong correlations we rely on: stature with shoulder and crotch height.
        const auto corr = [&](Semantic a, Semantic b) {
            return p->covariance(idx(a), idx(b)) /
                   std::sqrt(p->covariance(idx(a), idx(a)) * p->covariance(idx(b), idx(b)));
        };
        CHECK(corr(Semantic::height_m, Semantic::shoulder_height_m) > 0.95);
        CHECK(corr(Semantic::height_m, Semantic::crotch_height_m) > 0.8);
        CHECK(corr(Semantic::weight_kg, Semantic::hip_girth_m) > 0.85);
    }
    // The plausible ranges are the 0.5th / 99.5th percentiles: e.g. male stature.
    CHECK(prior.male.min[idx(Semantic::height_m)] == Approx(1.580).margin(0.002));
    CHECK(prior.male.max[idx(Semantic::height_m)] == Approx(1.946).margin(0.002));
}

TEST_CASE("complete: everything given returns the input, nothing given returns the mean",
          "[body][prior]") {
    const ShapePrior prior = ShapePrior::ansur2();

    SemanticRequest everything;
    everything.gender = Gender::male;
    const double values[kSemanticCount] = {1.80, 90.0, 0.7, 1.10, 0.95, 1.05, 0.64, 0.40, 1.48, 0.86};
    for (int k = 0; k < kSemanticCount; ++k) everything.values[static_cast<std::size_t>(k)] = values[k];
    const SemanticShape full = prior.complete(everything);
    CHECK(full.gender == Gender::male);
    for (int k = 0; k < kSemanticCount; ++k) CHECK(full.values[k] == values[k]);

    const SemanticShape nothing = prior.complete(SemanticRequest{});
    CHECK(nothing.gender == Gender::female);
    CHECK((nothing.values - prior.female.mean).cwiseAbs().maxCoeff() == 0.0);
    CHECK(prior.mahalanobis2(nothing) == Approx(0.0).margin(1e-12));

    SemanticRequest male_only;
    male_only.gender = Gender::male;
    CHECK((prior.complete(male_only).values - prior.male.mean).cwiseAbs().maxCoeff() == 0.0);
}

TEST_CASE("complete: predictions follow the survey's correlations", "[body][prior]") {
    const ShapePrior prior = ShapePrior::ansur2();
    const auto given_height = [&](double h) {
        SemanticRequest r;
        r.gender = Gender::female;
        r[Semantic::height_m] = h;
        return prior.complete(r);
    };
    const SemanticShape short_f = given_height(1.55), tall_f = given_height(1.75);
    // Taller -> longer leg, higher shoulder; about 0.6 m of leg and 0.85 m of shoulder per
    // metre of stature (the regression slopes).
    const double leg_slope =
        (tall_f[Semantic::crotch_height_m] - short_f[Semantic::crotch_height_m]) / 0.20;
    const double shoulder_slope =
        (tall_f[Semantic::shoulder_height_m] - short_f[Semantic::shoulder_height_m]) / 0.20;
    CHECK(leg_slope == Approx(0.59).margin(0.05));
    CHECK(shoulder_slope == Approx(0.88).margin(0.05));
    CHECK(tall_f[Semantic::weight_kg] > short_f[Semantic::weight_kg]);

    // The documented example: a 1.70 m, 65 kg woman.
    SemanticRequest r;
    r.gender = Gender::female;
    r[Semantic::height_m] = 1.70;
    r[Semantic::weight_kg] = 65.0;
    const SemanticShape s = prior.complete(r);
    CHECK(s[Semantic::height_m] == 1.70);
    CHECK(s[Semantic::weight_kg] == 65.0);
    // Lighter than average for a taller-than-average woman: girths below the means.
    CHECK(s[Semantic::waist_girth_m] < prior.female.mean[idx(Semantic::waist_girth_m)]);
    CHECK(s[Semantic::hip_girth_m] < prior.female.mean[idx(Semantic::hip_girth_m)]);
    // The figures quoted in docs/shape-prior.md.
    CHECK(s[Semantic::waist_girth_m] == Approx(0.802).margin(0.002));
    CHECK(s[Semantic::hip_girth_m] == Approx(0.990).margin(0.002));
    CHECK(s[Semantic::crotch_height_m] == Approx(0.828).margin(0.002));
    CHECK(s.is_valid());
}

TEST_CASE("complete: height-only prediction equals least squares on the survey",
          "[body][prior]") {
    DRAPE_REQUIRE_SHARED(dir, "data/anthropometry");
    const std::vector<AnsurRecord> all = drape::test::load_ansur_all(dir);
    const ShapePrior prior = ShapePrior::ansur2();
    for (const Gender g : {Gender::female, Gender::male}) {
        // Independent simple regression crotch = a + b * stature on the raw records.
        const auto rs = of_gender(all, g);
        Eigen::MatrixXd X(static_cast<Eigen::Index>(rs.size()), 2);
        Eigen::VectorXd y(static_cast<Eigen::Index>(rs.size()));
        for (std::size_t i = 0; i < rs.size(); ++i) {
            const auto row = static_cast<Eigen::Index>(i);
            X(row, 0) = 1.0;
            X(row, 1) = rs[i]->values[idx(Semantic::height_m)];
            y[row] = rs[i]->values[idx(Semantic::crotch_height_m)];
        }
        const Eigen::Vector2d ab = X.colPivHouseholderQr().solve(y);
        CHECK(ab[1] > 0.0);  // taller -> longer leg
        for (const double h : {1.50, 1.65, 1.80, 1.95}) {
            SemanticRequest r;
            r.gender = g;
            r[Semantic::height_m] = h;
            INFO(drape::body::to_string(g) << " height " << h);
            CHECK(prior.complete(r)[Semantic::crotch_height_m] ==
                  Approx(ab[0] + ab[1] * h).margin(0.002));
        }
    }
}

TEST_CASE("complete: held-out waist from height and weight beats the marginal SD",
          "[body][prior]") {
    DRAPE_REQUIRE_SHARED(dir, "data/anthropometry");
    const std::vector<AnsurRecord> all = drape::test::load_ansur_all(dir);
    const ShapePrior embedded = ShapePrior::ansur2();
    for (const Gender g : {Gender::female, Gender::male}) {
        // Fit on even-indexed subjects (sorted by id), predict the odd-indexed ones.
        const auto rs = of_gender(all, g);
        std::vector<const AnsurRecord*> train, test;
        for (std::size_t i = 0; i < rs.size(); ++i) (i % 2 == 0 ? train : test).push_back(rs[i]);
        ShapePrior fold = embedded;  // keeps the plausible ranges
        GaussianPrior& p = g == Gender::female ? fold.female : fold.male;
        const GaussianPrior fitted = fit_gaussian(train);
        p.mean = fitted.mean;
        p.covariance = fitted.covariance;

        double sum2 = 0.0, sum2_marginal = 0.0;
        for (const AnsurRecord* r : test) {
            SemanticRequest q;
            q.gender = g;
            q[Semantic::height_m] = r->values[idx(Semantic::height_m)];
            q[Semantic::weight_kg] = r->values[idx(Semantic::weight_kg)];
            const double truth = r->values[idx(Semantic::waist_girth_m)];
            const double e = fold.complete(q)[Semantic::waist_girth_m] - truth;
            const double e0 = p.mean[idx(Semantic::waist_girth_m)] - truth;
            sum2 += e * e;
            sum2_marginal += e0 * e0;
        }
        const double rms = std::sqrt(sum2 / static_cast<double>(test.size()));
        const double rms_marginal = std::sqrt(sum2_marginal / static_cast<double>(test.size()));
        INFO(drape::body::to_string(g) << ": held-out waist RMS " << rms << " m vs marginal "
                                       << rms_marginal << " m");
        CHECK(rms_marginal > 0.09);
        CHECK(rms < 0.6 * rms_marginal);
        CHECK(rms < 0.06);
    }
}

TEST_CASE("mahalanobis2 of surveyed people averages about the dimension", "[body][prior]") {
    DRAPE_REQUIRE_SHARED(dir, "data/anthropometry");
    const ShapePrior prior = ShapePrior::ansur2();
    const std::vector<AnsurRecord> sample = drape::test::load_ansur_sample(dir, 200);
    double sum = 0.0;
    for (const AnsurRecord& r : sample) {
        SemanticShape s;
        s.gender = r.gender;
        s.values = r.values;
        CHECK(s.is_valid());
        sum += prior.mahalanobis2(s);
    }
    CHECK(sum / static_cast<double>(sample.size()) == Approx(10.0).margin(1.5));
}

TEST_CASE("complete: gender is inferred from the given values", "[body][prior]") {
    const ShapePrior prior = ShapePrior::ansur2();
    SemanticRequest big;
    big[Semantic::height_m] = 1.85;
    big[Semantic::weight_kg] = 95.0;
    CHECK(prior.complete(big).gender == Gender::male);

    SemanticRequest small;
    small[Semantic::height_m] = 1.58;
    small[Semantic::weight_kg] = 55.0;
    CHECK(prior.complete(small).gender == Gender::female);

    // A given gender wins over the likelihood.
    big.gender = Gender::female;
    CHECK(prior.complete(big).gender == Gender::female);
}

TEST_CASE("complete: invalid values are rejected with the key and value", "[body][prior]") {
    const ShapePrior prior = ShapePrior::ansur2();
    const auto with = [](Semantic s, double v) {
        SemanticRequest r;
        r.gender = Gender::female;
        r[s] = v;
        return r;
    };
    const double nan = std::numeric_limits<double>::quiet_NaN();
    CHECK_THAT(message_of([&] { prior.complete(with(Semantic::height_m, nan)); }),
               Catch::Contains("height_m = nan") && Catch::Contains("not finite"));
    CHECK_THAT(message_of([&] {
                   prior.complete(with(Semantic::weight_kg, std::numeric_limits<double>::infinity()));
               }),
               Catch::Contains("weight_kg = inf"));
    CHECK_THAT(message_of([&] { prior.complete(with(Semantic::waist_girth_m, -0.8)); }),
               Catch::Contains("waist_girth_m = -0.8") && Catch::Contains("positive"));
    CHECK_THAT(message_of([&] { prior.complete(with(Semantic::height_m, 3.2)); }),
               Catch::Contains("height_m = 3.2 is outside the plausible range [") &&
                   Catch::Contains("] for female"));
    CHECK_THAT(message_of([&] { prior.complete(with(Semantic::weight_kg, 15.0)); }),
               Catch::Contains("weight_kg = 15 is outside the plausible range"));
    CHECK_THAT(message_of([&] { prior.complete(with(Semantic::muscle, 1.2)); }),
               Catch::Contains("muscle = 1.2") && Catch::Contains("[0, 1]"));
    // The edges of [0.5 * min, 1.5 * max] are accepted.
    const double hi = 1.5 * prior.female.max[idx(Semantic::height_m)];
    CHECK_NOTHROW(prior.complete(with(Semantic::height_m, hi)));
    CHECK_THROWS_AS(prior.complete(with(Semantic::height_m, hi * 1.001)), drape::InvalidInput);
    CHECK_NOTHROW(prior.complete(with(Semantic::muscle, 0.0)));
    CHECK_NOTHROW(prior.complete(with(Semantic::muscle, 1.0)));

    // Given heights out of order.
    SemanticRequest r = with(Semantic::height_m, 1.20);
    r[Semantic::crotch_height_m] = 1.25;
    CHECK_THAT(message_of([&] { prior.complete(r); }),
               Catch::Contains("crotch_height_m = 1.25 must be below height_m = 1.2"));
}

TEST_CASE("complete: predicted heights stay ordered far from the survey", "[body][prior]") {
    const ShapePrior prior = ShapePrior::ansur2();
    // A short stature with a very long leg: the conditional mean of the shoulder height
    // would fall below the crotch, so it is placed proportionally between them.
    SemanticRequest r;
    r.gender = Gender::female;
    r[Semantic::height_m] = 1.3;
    r[Semantic::crotch_height_m] = 1.2;
    const SemanticShape s = prior.complete(r);
    std::string why;
    CHECK(s.is_valid(&why));
    INFO(why);
    const double mc = prior.female.mean[idx(Semantic::crotch_height_m)];
    const double ms = prior.female.mean[idx(Semantic::shoulder_height_m)];
    const double mh = prior.female.mean[idx(Semantic::height_m)];
    CHECK(s[Semantic::shoulder_height_m] == Approx(1.2 + 0.1 * (ms - mc) / (mh - mc)));
    CHECK(s[Semantic::height_m] == 1.3);
    CHECK(s[Semantic::crotch_height_m] == 1.2);

    // Only a short stature given: the conditional means keep the order on their own.
    SemanticRequest short_only;
    short_only[Semantic::height_m] = 0.95;
    const SemanticShape t0 = prior.complete(short_only);
    CHECK(t0.is_valid(&why));
    CHECK(t0[Semantic::crotch_height_m] < t0[Semantic::shoulder_height_m]);
    // Shorter still, the linear prediction of weight passes zero: a clear error, no clamp.
    short_only[Semantic::height_m] = 0.8;
    CHECK_THAT(message_of([&] { prior.complete(short_only); }),
               Catch::Contains("predicted weight_kg = -") && Catch::Contains("too far"));

    // Extremes within the accepted range still give valid shapes (muscle kept in [0, 1]).
    for (const double h : {0.9, 1.2, 2.2, 2.6}) {
        for (const double w : {40.0, 60.0, 100.0, 150.0}) {
            SemanticRequest q;
            q[Semantic::height_m] = h;
            q[Semantic::weight_kg] = w;
            INFO("height " << h << " weight " << w);
            const SemanticShape t = prior.complete(q);
            CHECK(t.is_valid(&why));
            INFO(why);
        }
    }
}

TEST_CASE("SemanticShape::is_valid explains the first failure", "[body][prior]") {
    SemanticShape s;
    s.values = ShapePrior::ansur2().male.mean;
    s.gender = Gender::male;
    std::string why = "stale";
    CHECK(s.is_valid(&why));
    CHECK(why.empty());

    SemanticShape bad = s;
    bad[Semantic::muscle] = -0.1;
    CHECK_FALSE(bad.is_valid(&why));
    CHECK_THAT(why, Catch::Contains("muscle = -0.1"));

    bad = s;
    bad[Semantic::calf_girth_m] = 0.0;
    CHECK_FALSE(bad.is_valid(&why));
    CHECK_THAT(why, Catch::Contains("calf_girth_m = 0"));

    bad = s;
    bad[Semantic::shoulder_height_m] = 2.0;
    CHECK_FALSE(bad.is_valid(&why));
    CHECK_THAT(why, Catch::Contains("shoulder_height_m = 2 is not below height_m"));

    bad = s;
    bad[Semantic::weight_kg] = std::numeric_limits<double>::quiet_NaN();
    CHECK_FALSE(bad.is_valid());
}

TEST_CASE("ANSUR records: the sample is deterministic, spread out and in SI units",
          "[body][prior]") {
    CHECK_THROWS_AS(drape::test::load_ansur_all("/nonexistent/anthropometry"), drape::IoError);
    CHECK_THROWS_WITH(drape::test::load_ansur_sample("/nonexistent/anthropometry", 3),
                      Catch::Contains("/nonexistent/anthropometry"));

    DRAPE_REQUIRE_SHARED(dir, "data/anthropometry");
    const auto a = drape::test::load_ansur_sample(dir, 50);
    const auto b = drape::test::load_ansur_sample(dir, 50);
    REQUIRE(a.size() == 100);
    for (std::size_t i = 0; i < a.size(); ++i) {
        CHECK(a[i].subject_id == b[i].subject_id);
        CHECK(a[i].gender == (i < 50 ? Gender::female : Gender::male));
    }
    CHECK(a[0].subject_id < a[49].subject_id);
    // Metres and kilograms, not millimetres and 0.1 kg.
    for (const AnsurRecord& r : a) {
        CHECK(r.values[idx(Semantic::height_m)] > 1.3);
        CHECK(r.values[idx(Semantic::height_m)] < 2.1);
        CHECK(r.values[idx(Semantic::weight_kg)] > 35.0);
        CHECK(r.values[idx(Semantic::weight_kg)] < 160.0);
        CHECK(r.values[idx(Semantic::muscle)] > 0.0);
        CHECK(r.values[idx(Semantic::muscle)] < 1.0);
    }
    CHECK_THROWS_AS(drape::test::load_ansur_sample(dir, 0), drape::InvalidInput);
    CHECK_THROWS_AS(drape::test::load_ansur_sample(dir, 5000), drape::InvalidInput);

    const auto everyone = drape::test::load_ansur_all(dir);
    CHECK(everyone.size() == 1986 + 4082);
}

TEST_CASE("sample_ansur_bodies: both genders' stature and mass extremes, then seeded random records",
          "[body][prior]") {
    DRAPE_REQUIRE_SHARED(dir, "data/anthropometry");
    const std::vector<AnsurRecord> all = drape::test::load_ansur_all(dir);
    const std::vector<drape::test::AnsurSampledRecord> a = drape::test::sample_ansur_bodies(all, 14, 1);
    REQUIRE(a.size() == 14);
    // The first eight are the strata, female then male.
    const char* strata[] = {"height p1", "height p99", "weight p1", "weight p99"};
    for (int k = 0; k < 8; ++k) {
        INFO(k << ": " << a[size_t(k)].stratum);
        CHECK(a[size_t(k)].stratum == strata[k % 4]);
        CHECK(a[size_t(k)].record.gender == (k < 4 ? Gender::female : Gender::male));
    }
    for (size_t k = 8; k < a.size(); ++k) {
        CHECK(a[k].stratum == "random");
        CHECK(a[k].record.gender == (k % 2 == 0 ? Gender::female : Gender::male));
    }
    // Each stratum's record lies at its percentile of its gender: about 1 % of the gender's
    // records are below a p1 record, 99 % below a p99 one.
    for (int k = 0; k < 8; ++k) {
        const AnsurRecord& r = a[size_t(k)].record;
        const int s = k % 4 < 2 ? static_cast<int>(Semantic::height_m) : static_cast<int>(Semantic::weight_kg);
        int below = 0, n = 0;
        for (const AnsurRecord& o : all)
            if (o.gender == r.gender) {
                ++n;
                below += o.values[s] < r.values[s] ? 1 : 0;
            }
        const double share = double(below) / n, wanted = k % 2 == 0 ? 0.01 : 0.99;
        INFO(a[size_t(k)].stratum << ": " << 100 * share << " % below, value " << r.values[s]);
        CHECK(std::abs(share - wanted) < 0.015);
    }
    // Measured: the heaviest woman sampled is 97.3 kg, the heaviest man 124.1 kg.
    CHECK(a[3].record.values[static_cast<int>(Semantic::weight_kg)] == Approx(97.3));
    CHECK(a[7].record.values[static_cast<int>(Semantic::weight_kg)] == Approx(124.1));
    // No record twice; the same seed gives the same sample, another seed other random records.
    for (size_t i = 0; i < a.size(); ++i)
        for (size_t j = i + 1; j < a.size(); ++j)
            CHECK(!(a[i].record.subject_id == a[j].record.subject_id && a[i].record.gender == a[j].record.gender));
    const auto b = drape::test::sample_ansur_bodies(all, 14, 1), c = drape::test::sample_ansur_bodies(all, 14, 2);
    int same_random = 0;
    for (size_t k = 0; k < a.size(); ++k) {
        CHECK(b[k].record.subject_id == a[k].record.subject_id);
        if (k < 8) CHECK(c[k].record.subject_id == a[k].record.subject_id);
        else same_random += c[k].record.subject_id == a[k].record.subject_id ? 1 : 0;
    }
    CHECK(same_random < 2);
    CHECK_THROWS_AS(drape::test::sample_ansur_bodies(all, 7, 1), drape::InvalidInput);
}
