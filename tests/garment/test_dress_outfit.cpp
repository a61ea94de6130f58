// dress_outfit: the one pipeline from a body to draped garments.
#include <drape/body/body_model.hpp>
#include <drape/body/pose.hpp>
#include <drape/cloth/material.hpp>
#include <drape/core/errors.hpp>
#include <drape/garment/dress_outfit.hpp>
#include <drape/garment/sizing_proposal.hpp>

#include <catch2/catch.hpp>

#include "mean_female.hpp"

using namespace drape::garment;
namespace body = drape::body;
namespace cloth = drape::cloth;

namespace {

using drape::test::MeanFemale;

DressOutfitOptions coarse() {
    DressOutfitOptions o;
    o.mesh.target_edge_cm = 4.0;
    return o;
}

GarmentRequest skirt_request() {
    GarmentRequest r;
    r.type = GarmentType::skirt;
    r.material = cloth::builtin_material("gray-interlock");
    return r;
}

}  // namespace

TEST_CASE("dress_outfit: a proposed skirt on the mean female is draped, checked and usable",
          "[garment][drape][outfit]") {
    const MeanFemale b;
    DressedOutfit out;
    const DressOutfitSummary s =
        dress_outfit(b.model, b.shaped, body::named_pose(body::NamedPose::a_pose), {skirt_request()}, coarse(), out);
    INFO(s.brief_report() << "; " << s.drape.brief_report());
    CHECK(s.termination == DressOutfitTermination::draped);
    CHECK(s.usable());
    CHECK(s.checks_pass(out));
    REQUIRE(out.positions.size() == 1);
    CHECK(out.sizings[0].type == GarmentType::skirt);
    CHECK(out.positions[0].rows() == out.meshes[0].cloth.vertex_count());
    CHECK(out.checks.size() == 1);
    CHECK(out.dressing.size() == 1);
    CHECK(s.garments == 1);
    CHECK(s.vertices == out.meshes[0].cloth.vertex_count());
    CHECK(s.seconds >= s.seconds_drape);
    CHECK(out.body_vertices.rows() == b.model.vertex_count());
    CHECK(s.brief_report().find("outfit draped") == 0);
}

TEST_CASE("dress_outfit: cancelling from the progress callback is reported in the summary",
          "[garment][drape][outfit]") {
    const MeanFemale b;
    DressOutfitOptions o = coarse();
    o.drape.on_progress = [](const DrapeProgress& p) { return p.step < 3; };
    DressedOutfit out;
    const DressOutfitSummary s =
        dress_outfit(b.model, b.shaped, body::named_pose(body::NamedPose::a_pose), {skirt_request()}, o, out);
    CHECK(s.termination == DressOutfitTermination::cancelled);
    CHECK(s.drape.termination == DrapeTermination::cancelled);
    CHECK_FALSE(s.usable());
    CHECK_FALSE(s.checks_pass(out));
    CHECK(out.positions.size() == 1);
}

TEST_CASE("dress_outfit: bad requests are rejected naming the garment", "[garment][outfit]") {
    const MeanFemale b;
    const body::Pose pose = body::named_pose(body::NamedPose::a_pose);
    DressedOutfit out;
    CHECK_THROWS_AS(dress_outfit(b.model, b.shaped, pose, {}, coarse(), out), drape::InvalidInput);
    GarmentRequest wrong = skirt_request();
    wrong.sizing = GarmentSizing{};
    wrong.sizing->type = GarmentType::pants;
    CHECK_THROWS_WITH(dress_outfit(b.model, b.shaped, pose, {wrong}, coarse(), out),
                      Catch::Contains("garment 0 (skirt)"));
    GarmentRequest soft = skirt_request();
    soft.material.density_kg_per_m2 = -1;
    CHECK_THROWS_WITH(dress_outfit(b.model, b.shaped, pose, {soft}, coarse(), out), Catch::Contains("material"));
    DressOutfitOptions bad = coarse();
    bad.mesh.target_edge_cm = -1;
    CHECK_THROWS_AS(dress_outfit(b.model, b.shaped, pose, {skirt_request()}, bad, out), drape::InvalidInput);
}
