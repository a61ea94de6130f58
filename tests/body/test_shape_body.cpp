// Shaping the built-in model from semantic parameters, and the ANSUR II acceptance test:
// 200 surveyed people requested as z must measure as requested on the generated mesh.
#include <drape/body/body_model.hpp>
#include <drape/body/measurements.hpp>
#include <drape/body/shape_body.hpp>
#include <drape/core/errors.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <thread>
#include <vector>

#include <drape/fixtures/ansur_records.hpp>
#include "test_paths.hpp"

using namespace drape::body;

namespace {

double percentile(std::vector<double> v, double p) {
    std::sort(v.begin(), v.end());
    const double pos = p * static_cast<double>(v.size() - 1);
    const size_t i = static_cast<size_t>(pos);
    const double f = pos - static_cast<double>(i);
    return i + 1 < v.size() ? (1 - f) * v[i] + f * v[i + 1] : v[i];
}

}  // namespace

TEST_CASE("the built-in model is valid and a plausible adult", "[body][model]") {
    const BodyModel& model = BodyModel::default_model();
    std::string why;
    REQUIRE(model.is_valid(&why));
    CHECK(model.vertex_count() >= 8000);
    CHECK(model.vertex_count() <= 20000);
    const BodyMeasurements m = measure_body(model, model.template_vertices);
    CHECK(m.height_m == Approx(1.70).margin(0.06));
    CHECK(m.weight_kg > 50);
    CHECK(m.weight_kg < 90);
    CHECK(m.crotch_height_m < m.shoulder_height_m);
    CHECK(m.shoulder_height_m < m.height_m);
}

TEST_CASE("the linear semantic map alone lands close to the request", "[body][shape]") {
    const BodyModel& model = BodyModel::default_model();
    SemanticRequest req;
    req.gender = Gender::male;
    req[Semantic::height_m] = 1.85;
    req[Semantic::weight_kg] = 88.0;
    const SemanticShape shape = model.prior.complete(req);
    ShapedBody body;
    ShapeOptions opt;
    opt.match_measurements = false;
    const ShapeSummary s = shape_body(model, shape, opt, body);
    CHECK(s.termination == ShapeTermination::linear_only);
    CHECK(s.max_relative_error < 0.04);
}

TEST_CASE("shape_body matches every requested girth and height", "[body][shape]") {
    const BodyModel& model = BodyModel::default_model();
    for (Gender g : {Gender::female, Gender::male}) {
        SemanticRequest req;
        req.gender = g;
        req[Semantic::height_m] = g == Gender::female ? 1.58 : 1.92;
        req[Semantic::weight_kg] = g == Gender::female ? 52.0 : 105.0;
        const SemanticShape shape = model.prior.complete(req);
        ShapedBody body;
        const ShapeSummary s = shape_body(model, shape, ShapeOptions{}, body);
        INFO(s.brief_report());
        REQUIRE(s.termination == ShapeTermination::converged);
        const BodyMeasurements m = measure_body(model, body.vertices);
        CHECK(m.height_m == Approx(shape[Semantic::height_m]).epsilon(2e-3));
        CHECK(m.chest_girth_m == Approx(shape[Semantic::chest_girth_m]).epsilon(2e-3));
        CHECK(m.waist_girth_m == Approx(shape[Semantic::waist_girth_m]).epsilon(2e-3));
        CHECK(m.hip_girth_m == Approx(shape[Semantic::hip_girth_m]).epsilon(2e-3));
        CHECK(m.thigh_girth_m == Approx(shape[Semantic::thigh_girth_m]).epsilon(2e-3));
        CHECK(m.calf_girth_m == Approx(shape[Semantic::calf_girth_m]).epsilon(2e-3));
        CHECK(m.shoulder_height_m == Approx(shape[Semantic::shoulder_height_m]).epsilon(2e-3));
        CHECK(m.crotch_height_m == Approx(shape[Semantic::crotch_height_m]).epsilon(2e-3));
        // Weight follows from the volume: close to the request for typical bodies.
        CHECK(m.weight_kg == Approx(shape[Semantic::weight_kg]).epsilon(0.12));
        // The shaped mesh stays a valid closed surface with joints inside the limbs.
        CHECK(mesh_volume(body.vertices, model.faces) > 0);
    }
}

TEST_CASE("shape_body rejects invalid shapes", "[body][shape]") {
    const BodyModel& model = BodyModel::default_model();
    SemanticShape shape = model.prior.complete(SemanticRequest{});
    shape[Semantic::crotch_height_m] = 2.0;  // above the shoulders
    ShapedBody body;
    CHECK_THROWS_AS(shape_body(model, shape, ShapeOptions{}, body), drape::InvalidInput);
    shape = model.prior.complete(SemanticRequest{});
    shape[Semantic::waist_girth_m] = std::nan("");
    CHECK_THROWS_WITH(shape_body(model, shape, ShapeOptions{}, body), Catch::Contains("waist_girth_m"));
}

// Acceptance (issue 2): for 200 ANSUR II records (100 per gender) requested as z, the mesh
// measures within 1.5 % median and 4 % 95th percentile of every requested girth and height.
// Writes the table to docs/ when DRAPE_WRITE_DOCS is set (see docs/body-model.md).
TEST_CASE("ANSUR II acceptance: 200 records measure as requested", "[body][shape][ansur]") {
    DRAPE_REQUIRE_SHARED(dir, "data/anthropometry");
    const auto records = drape::test::load_ansur_sample(dir, 100);
    REQUIRE(records.size() == 200);
    const BodyModel& model = BodyModel::default_model();
    const int matched[] = {0, 3, 4, 5, 6, 7, 8, 9};  // every girth and height (Semantic)
    std::vector<std::vector<double>> err(kSemanticCount);
    std::vector<double> weight_err;
    std::vector<int> not_converged(records.size(), 0);
    std::vector<Eigen::Matrix<double, kSemanticCount, 1>> measured(records.size());
    auto work = [&](size_t begin, size_t step) {
        for (size_t i = begin; i < records.size(); i += step) {
            SemanticShape shape;
            shape.gender = records[i].gender;
            shape.values = records[i].values;
            ShapedBody body;
            const ShapeSummary s = shape_body(model, shape, ShapeOptions{}, body);
            not_converged[i] = s.termination != ShapeTermination::converged;
            measured[i] = s.measured.as_semantic();
        }
    };
    std::thread t(work, 1, 2);
    work(0, 2);
    t.join();
    for (size_t i = 0; i < records.size(); ++i) {
        for (int k : matched)
            err[k].push_back(std::abs(measured[i][k] - records[i].values[k]) / records[i].values[k]);
        weight_err.push_back(std::abs(measured[i][1] - records[i].values[1]) / records[i].values[1]);
    }
    std::ostringstream table;
    table << "| measurement | median error | 95th percentile | max |\n|---|---|---|---|\n"
          << std::fixed << std::setprecision(3);
    for (int k : matched) {
        const double med = percentile(err[k], 0.5), p95 = percentile(err[k], 0.95);
        table << "| " << kSemanticKeys[k] << " | " << 100 * med << " % | " << 100 * p95 << " % | "
              << 100 * percentile(err[k], 1.0) << " % |\n";
        INFO(kSemanticKeys[k] << ": median " << 100 * med << " %, p95 " << 100 * p95 << " %");
        CHECK(med <= 0.015);
        CHECK(p95 <= 0.04);
    }
    table << "| weight_kg (not matched: volume x density) | " << 100 * percentile(weight_err, 0.5)
          << " % | " << 100 * percentile(weight_err, 0.95) << " % | " << 100 * percentile(weight_err, 1.0)
          << " % |\n";
    const int failures = static_cast<int>(std::count(not_converged.begin(), not_converged.end(), 1));
    table << "\nRecords not converged to 0.1 %: " << failures << " of " << records.size() << "\n";
    WARN("ANSUR acceptance table\n" << table.str());
    if (const char* out = std::getenv("DRAPE_WRITE_DOCS"); out && *out)
        std::ofstream(std::string(out) + "/ansur-acceptance-table.md") << table.str();
}
