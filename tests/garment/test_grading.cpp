// Size grading (grading.hpp): a sizing made for a median woman graded to a large man keeps
// the ease over each girth (measured on the patterns), its style parameters and its design.
#include <drape/body/body_model.hpp>
#include <drape/body/measurements.hpp>
#include <drape/body/shape_body.hpp>
#include <drape/core/errors.hpp>
#include <drape/garment/grading.hpp>
#include <drape/garment/pattern_svg.hpp>
#include <drape/garment/sizing_proposal.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <string>

using namespace drape::garment;
namespace body = drape::body;

namespace {

struct Graded {
    body::ShapedBody shaped;
    GradingBody dims;
    body::BodyMeasurements m;
};

Graded shaped_body(body::Gender gender, double height_m, double weight_kg) {
    const body::BodyModel& model = body::BodyModel::default_model();
    body::SemanticRequest r;
    r.gender = gender;
    r[body::Semantic::height_m] = height_m;
    r[body::Semantic::weight_kg] = weight_kg;
    Graded g;
    const body::ShapeSummary s = body::shape_body(model, model.prior.complete(r), {}, g.shaped);
    REQUIRE(s.usable());
    g.dims = measure_for_grading(model, g.shaped);
    g.m = body::measure_body(model, g.shaped.vertices);
    return g;
}

// The ANSUR II median woman and 95th-percentile man (docs/tryon.md).
const Graded& woman() {
    static const Graded g = shaped_body(body::Gender::female, 1.626, 66.8);
    return g;
}
const Graded& man() {
    static const Graded g = shaped_body(body::Gender::male, 1.870, 110.6);
    return g;
}

double panel_width(const Pattern& p, const std::string& name) {
    Eigen::Vector2d lo, hi;
    p.panels[size_t(p.panel_index(name))].bounds(&lo, &hi);
    return hi.x() - lo.x();
}

}  // namespace

TEST_CASE("grading: measure_for_grading gives the body's own dimensions", "[garment][grading]") {
    const Graded& w = woman();
    CHECK(w.dims.is_valid());
    CHECK(w.dims.height_cm == Approx(100 * w.m.height_m));
    CHECK(w.dims.chest_girth_cm == Approx(100 * w.m.chest_girth_m));
    // A median woman: waistband a little under the navel girth, arm 50-60 cm, neck 30-40 cm.
    CHECK(w.dims.waistband_girth_cm <= w.dims.waist_girth_cm + 1e-9);
    CHECK(w.dims.arm_length_cm > 45);
    CHECK(w.dims.arm_length_cm < 65);
    CHECK(w.dims.neck_girth_cm > 28);
    CHECK(w.dims.neck_girth_cm < 45);
    CHECK(man().dims.arm_length_cm > w.dims.arm_length_cm);
}

TEST_CASE("grading: to the same body grading changes nothing", "[garment][grading]") {
    const Graded& w = woman();
    for (const GarmentType type : {GarmentType::skirt, GarmentType::pants, GarmentType::tshirt, GarmentType::dress}) {
        INFO(garment_type_name(type));
        const GarmentSizing g = proposed_sizing(type, body::BodyModel::default_model(), w.shaped, w.m);
        GarmentSizing h;
        const GradingSummary s = grade_sizing(g, w.dims, w.dims, {}, h);
        CHECK(s.termination == GradingTermination::graded);
        CHECK(s.grade.sizes == 0);
        CHECK(s.grade.text == "same size");
        const std::vector<double> a = sizing_values(g), b = sizing_values(h);
        for (size_t i = 0; i < a.size(); ++i) CHECK(b[i] == Approx(a[i]).margin(1e-9));
    }
}

TEST_CASE("grading: a skirt graded to a large man keeps its waist ease on the pattern and its flare",
          "[garment][grading]") {
    const Graded& w = woman();
    const Graded& m = man();
    GarmentSizing g;
    g.type = GarmentType::skirt;
    g.skirt = propose_skirt_sizing(w.m, w.dims.waistband_girth_cm / 100);
    g.skirt.alpha = 130;  // a flared design
    GarmentSizing h;
    const GradingSummary s = grade_sizing(g, w.dims, m.dims, {}, h);
    INFO(s.brief_report());
    REQUIRE(s.usable());
    REQUIRE(s.termination == GradingTermination::graded);
    // The waist on the pattern: both panels' waist arcs (edge 2).
    const auto waist = [](const Pattern& p) { return p.panels[0].edges[2].length() + p.panels[1].edges[2].length(); };
    const double ease_before = waist(make_pattern(g)) - w.dims.waistband_girth_cm;
    const double ease_after = waist(make_pattern(h)) - m.dims.waistband_girth_cm;
    CHECK(ease_before > 0);
    CHECK(ease_after == Approx(ease_before).margin(0.05));
    CHECK(h.skirt.alpha == g.skirt.alpha);
    CHECK(h.skirt.r1 / h.skirt.l1 == Approx(g.skirt.r1 / g.skirt.l1).epsilon(1e-9));
    // Longer for the taller body, by its navel height.
    CHECK(h.skirt.r2 / g.skirt.r2 == Approx(m.dims.height_cm / w.dims.height_cm).epsilon(1e-9));
    CHECK(s.max_style_change < 1e-9);
    // Waist girth 79 -> 104 cm-ish: several EN 13402-3 sizes up, as the chart's step says.
    CHECK(s.grade.dimension == "waist");
    CHECK(s.grade.sizes == std::lround((m.dims.waist_girth_cm - w.dims.waist_girth_cm) / 4.0));
    CHECK(s.grade.sizes >= 3);
}

TEST_CASE("grading: a t-shirt graded up keeps its chest ease on the pattern and its sleeve length ratio",
          "[garment][grading]") {
    const Graded& w = woman();
    const Graded& m = man();
    const GarmentSizing g = proposed_sizing(GarmentType::tshirt, body::BodyModel::default_model(), w.shaped, w.m);
    GarmentSizing h;
    const GradingSummary s = grade_sizing(g, w.dims, m.dims, {}, h);
    INFO(s.brief_report());
    REQUIRE(s.usable());
    const Pattern before = make_pattern(g), after = make_pattern(h);
    const double ease_before = 2 * panel_width(before, "front") - w.dims.chest_girth_cm;
    const double ease_after = 2 * panel_width(after, "front") - m.dims.chest_girth_cm;
    CHECK(ease_after == Approx(ease_before).margin(0.1));
    for (const EaseCheck& e : s.ease) {
        INFO(e.name);
        CHECK(e.graded_cm == Approx(e.original_cm).margin(1e-6));
    }
    CHECK(h.tshirt.l1 / m.dims.arm_length_cm == Approx(g.tshirt.l1 / w.dims.arm_length_cm).epsilon(1e-9));
    CHECK(s.max_style_change <= 0.02);
    CHECK(s.grade.dimension == "chest");
    CHECK(s.grade.sizes > 0);
    CHECK(s.grade.text.find("up") != std::string::npos);
}

TEST_CASE("grading: pants and a dress graded down stay valid and keep the waist seam", "[garment][grading]") {
    const Graded& w = woman();
    const Graded& m = man();
    for (const GarmentType type : {GarmentType::pants, GarmentType::dress}) {
        INFO(garment_type_name(type));
        const GarmentSizing g = proposed_sizing(type, body::BodyModel::default_model(), m.shaped, m.m);
        GarmentSizing h;
        const GradingSummary s = grade_sizing(g, m.dims, w.dims, {}, h);
        INFO(s.brief_report());
        CHECK(s.termination != GradingTermination::invalid_pattern);
        CHECK_NOTHROW(make_pattern(h));
        CHECK(s.grade.sizes < 0);
        if (type == GarmentType::pants) {
            CHECK(h.pants.w4 / h.pants.w3 == Approx(g.pants.w4 / g.pants.w3).epsilon(0.02));
            CHECK(h.pants.w1 - w.dims.waist_girth_cm == Approx(g.pants.w1 - m.dims.waist_girth_cm).margin(1e-6));
        } else {
            CHECK(h.dress.skirt.l1 == Approx(h.dress.bodice.w2).epsilon(0.01));
        }
    }
}

TEST_CASE("grading: a clamp is reported and measured against the style tolerance", "[garment][grading]") {
    const Graded& w = woman();
    GradingBody giant = man().dims;  // a body whose legs ask for a skirt longer than the template allows
    giant.height_cm *= 1.6;
    giant.shoulder_height_cm *= 1.6;
    giant.crotch_height_cm *= 1.6;
    GarmentSizing g;
    g.type = GarmentType::skirt;
    g.skirt = propose_skirt_sizing(w.m, w.dims.waistband_girth_cm / 100);
    g.skirt.r2 = 0.9 * SkirtSizing::parameters()[2].max;
    GarmentSizing h;
    const GradingSummary s = grade_sizing(g, w.dims, giant, {}, h);
    INFO(s.brief_report());
    CHECK(s.termination == GradingTermination::clamped);
    CHECK(s.clamped == 1);
    CHECK(h.skirt.r2 == SkirtSizing::parameters()[2].max);
    CHECK(s.max_style_change > 0.02);
    CHECK_FALSE(s.usable());
    CHECK(s.message.find("r2") != std::string::npos);
}

TEST_CASE("grading: bad input is named", "[garment][grading]") {
    GarmentSizing g;
    GarmentSizing h;
    GradingBody bad = woman().dims;
    bad.neck_girth_cm = 0;
    try {
        grade_sizing(g, woman().dims, bad, {}, h);
        FAIL("no throw");
    } catch (const drape::InvalidInput& e) {
        CHECK(std::string(e.what()).find("target body") != std::string::npos);
        CHECK(std::string(e.what()).find("neck_girth_cm") != std::string::npos);
    }
    g.skirt.alpha = -5;
    CHECK_THROWS_WITH(grade_sizing(g, woman().dims, woman().dims, {}, h), Catch::Contains("alpha"));
    GradingOptions o;
    o.chart.girth_step_cm = 0;
    CHECK_THROWS_WITH(grade_sizing(GarmentSizing{}, woman().dims, woman().dims, o, h), Catch::Contains("girth_step_cm"));
}

TEST_CASE("grading: size grade words", "[garment][grading]") {
    CHECK(size_grade_text(2) == "two sizes up");
    CHECK(size_grade_text(-1) == "one size down");
    CHECK(size_grade_text(0) == "same size");
    CHECK(size_grade_text(14) == "14 sizes up");
}

TEST_CASE("grading: the grading sheet nests both sizes of every panel", "[garment][grading]") {
    GarmentSizing g;
    g.type = GarmentType::tshirt;
    GarmentSizing h = g;
    h.tshirt.w2 += 6;
    h.tshirt.h2 += 4;
    const Pattern a = make_pattern(g), b = make_pattern(h);
    const std::string svg = grading_sheet_to_svg({{&a, "original"}, {&b, "graded: two sizes up"}});
    CHECK(svg.find("graded: two sizes up") != std::string::npos);
    for (const Panel& p : a.panels) CHECK(svg.find("<g id=\"" + p.name + "\"") != std::string::npos);
    // One outline per size per panel, plus the legend's and scale's strokes.
    size_t outlines = 0;
    for (size_t at = svg.find(" Z\""); at != std::string::npos; at = svg.find(" Z\"", at + 1)) ++outlines;
    CHECK(outlines == 2 * a.panels.size());
    GarmentSizing skirt;
    const Pattern c = make_pattern(skirt);
    CHECK_THROWS_AS(grading_sheet_to_svg({{&a, "t-shirt"}, {&c, "skirt"}}), drape::InvalidInput);
    CHECK_THROWS_AS(grading_sheet_to_svg({}), drape::InvalidInput);
}
