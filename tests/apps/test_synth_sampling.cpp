// drape::synth sampling (libsynth/include/drape/synth/sampling.hpp): determinism, the
// independence of the random streams, and option checks. Draping, rendering and the files
// are covered through the CLI (test_synth_cli.cpp).
#include <catch2/catch.hpp>

#include <drape/core/errors.hpp>
#include <drape/synth/sampling.hpp>

using namespace drape;

TEST_CASE("a scene's sampling is deterministic and its streams independent", "[apps][synth][sampling]") {
    synth::SynthOptions o;
    o.seed = 7;
    o.garments = {garment::GarmentType::skirt};
    o.pose = body::NamedPose::a_pose;
    const synth::SynthScene a = synth::sample_synth_scene(o), b = synth::sample_synth_scene(o);
    CHECK(a.shape.values == b.shape.values);
    CHECK(a.pose.rotations == b.pose.rotations);
    CHECK(a.camera.focal_px == b.camera.focal_px);
    CHECK(a.camera.offset_px == b.camera.offset_px);
    REQUIRE(a.garments.size() == 1);
    CHECK(a.garments[0].sizing.skirt.r2 == b.garments[0].sizing.skirt.r2);
    CHECK(a.garments[0].look.colour_srgb == b.garments[0].look.colour_srgb);
    CHECK(a.garments[0].label == 42);
    CHECK(a.pose_name == "a_pose");

    // Another pose draws from the pose stream only: body, sizing, fabric, look and camera stay.
    o.pose = body::NamedPose::walking;
    const synth::SynthScene c = synth::sample_synth_scene(o);
    CHECK(c.pose_name == "walking");
    CHECK(c.shape.values == a.shape.values);
    CHECK(c.garments[0].sizing.skirt.r2 == a.garments[0].sizing.skirt.r2);
    CHECK(c.garments[0].base_fabric == a.garments[0].base_fabric);
    CHECK(c.garments[0].look.colour_srgb == a.garments[0].look.colour_srgb);
    CHECK(c.camera.offset_px == a.camera.offset_px);
    CHECK(c.pose.rotations != a.pose.rotations);
}

TEST_CASE("a forced print changes the print kind and nothing else", "[apps][synth][sampling][prints]") {
    synth::SynthOptions o;
    o.seed = 913577;
    const synth::SynthScene drawn = synth::sample_synth_scene(o);
    for (render::PrintKind kind : {render::PrintKind::solid, render::PrintKind::checks}) {
        o.print = kind;
        const synth::SynthScene s = synth::sample_synth_scene(o);
        CHECK(s.shape.values == drawn.shape.values);
        CHECK(s.pose.rotations == drawn.pose.rotations);
        CHECK(s.camera.offset_px == drawn.camera.offset_px);
        CHECK(s.skin_srgb == drawn.skin_srgb);
        REQUIRE(s.garments.size() == drawn.garments.size());
        for (std::size_t i = 0; i < s.garments.size(); ++i) {
            CHECK(s.garments[i].base_fabric == drawn.garments[i].base_fabric);
            CHECK(s.garments[i].material.bending_scale == drawn.garments[i].material.bending_scale);
            CHECK(s.garments[i].look.colour_srgb == drawn.garments[i].look.colour_srgb);
            CHECK(s.garments[i].look.print.second_colour_srgb == drawn.garments[i].look.print.second_colour_srgb);
            CHECK(s.garments[i].look.print.period == drawn.garments[i].look.print.period);
            CHECK(s.garments[i].look.print.kind == kind);
        }
    }
}

TEST_CASE("synth options reject what cannot be made", "[apps][synth][sampling]") {
    using garment::GarmentType;
    synth::SynthOptions o;
    CHECK(o.is_valid());
    o.garments = {GarmentType::tshirt, GarmentType::pants};  // the upper garment must come last
    CHECK_FALSE(o.is_valid());
    o.garments = {GarmentType::pants, GarmentType::tshirt, GarmentType::skirt};
    CHECK_FALSE(o.is_valid());
    o.garments = {GarmentType::dress, GarmentType::tshirt};
    CHECK_FALSE(o.is_valid());
    o.garments = {GarmentType::skirt, GarmentType::tshirt};
    CHECK(o.is_valid());
    o.pose = body::NamedPose::t_pose;
    std::string why;
    CHECK_FALSE(o.is_valid(&why));
    CHECK(why.find("pose") != std::string::npos);
    CHECK_THROWS_AS(synth::sample_synth_scene(o), InvalidInput);
    o.pose.reset();
    o.fabric = "no-such-fabric";
    CHECK_THROWS_AS(synth::sample_synth_scene(o), InvalidInput);
}
