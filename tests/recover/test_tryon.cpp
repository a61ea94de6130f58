// tryon() (tryon.hpp) at the library level, without the drape: a garment graded from its own
// body to the target keeps its material and style; bad input is named. The drape itself is
// tested through the CLI (tests/apps/test_tryon_cli.cpp); the acceptance is `drape eval-tryon`.
#include <drape/body/body_model.hpp>
#include <drape/cloth/material.hpp>
#include <drape/core/errors.hpp>
#include <drape/recover/tryon.hpp>

#include <catch2/catch.hpp>

using namespace drape;

namespace {

body::SemanticRequest request(body::Gender g, double height_m, double weight_kg) {
    body::SemanticRequest r;
    r.gender = g;
    r[body::Semantic::height_m] = height_m;
    r[body::Semantic::weight_kg] = weight_kg;
    return r;
}

recover::TryOnInputs pants_on_a_tall_man() {
    recover::TryOnInputs in;
    recover::TryOnGarment g;
    g.type = garment::GarmentType::pants;
    g.name = "pants";
    g.sizing.type = garment::GarmentType::pants;
    g.material = cloth::builtin_material("gray-interlock");
    g.material.bending_scale = 3.0;
    g.source_body = request(body::Gender::female, 1.525, 51.3);
    in.garments.push_back(g);
    in.target.body = request(body::Gender::male, 1.87, 110.6);
    return in;
}

}  // namespace

TEST_CASE("tryon: grading only gives the graded sizing of the target body", "[recover][tryon]") {
    const body::BodyModel& model = body::BodyModel::default_model();
    recover::TryOnOptions options;
    options.drape = false;
    recover::TryOnResult r;
    const recover::TryOnSummary s = recover::tryon(model, pants_on_a_tall_man(), options, r);
    INFO(s.brief_report());
    REQUIRE(s.termination == recover::TryOnTermination::graded);
    REQUIRE(r.garments.size() == 1);
    const recover::TriedOnGarment& g = r.garments[0];
    INFO(g.grading.brief_report());
    CHECK(g.grading.usable());
    CHECK(g.grading.grade.sizes > 2);  // a small woman's waist to a large man's
    CHECK(g.sizing.pants.w1 > g.source.sizing.pants.w1 + 8);
    CHECK(g.sizing.pants.h1 > g.source.sizing.pants.h1);
    CHECK(g.sizing.pants.w4 / g.sizing.pants.w3 == Approx(g.source.sizing.pants.w4 / g.source.sizing.pants.w3));
    CHECK(g.source.material.bending_scale == 3.0);  // the fabric is kept
    CHECK(g.class_id == recover::tryon_class_id(garment::GarmentType::pants));
    CHECK_FALSE(s.usable(r));  // not draped
    CHECK(r.shaped.vertices.rows() == model.vertex_count());
}

TEST_CASE("tryon: bad input is named", "[recover][tryon]") {
    const body::BodyModel& model = body::BodyModel::default_model();
    recover::TryOnResult r;
    recover::TryOnInputs none = pants_on_a_tall_man();
    none.garments.clear();
    CHECK_THROWS_WITH(recover::tryon(model, none, {}, r), Catch::Contains("no garment"));
    recover::TryOnInputs mismatch = pants_on_a_tall_man();
    mismatch.garments[0].sizing.type = garment::GarmentType::skirt;
    CHECK_THROWS_WITH(recover::tryon(model, mismatch, {}, r), Catch::Contains("another template"));
    recover::TryOnInputs bad = pants_on_a_tall_man();
    bad.garments[0].sizing.pants.w1 = -3;
    CHECK_THROWS_WITH(recover::tryon(model, bad, {}, r), Catch::Contains("w1"));
    recover::TryOnInputs photo = pants_on_a_tall_man();
    photo.target.body.reset();
    CHECK_THROWS_WITH(recover::tryon(model, photo, {}, r), Catch::Contains("photo"));
    recover::TryOnOptions o;
    o.edge_cm = 0;
    CHECK_THROWS_WITH(recover::tryon(model, pants_on_a_tall_man(), o, r), Catch::Contains("edge_cm"));
}
