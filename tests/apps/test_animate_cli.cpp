// `drape animate`'s bad input: each is refused with a clear message before any simulation.
#include "cli_runner.hpp"
#include "test_paths.hpp"

#include <drape/io/body_json.hpp>
#include <drape/io/garment_json.hpp>
#include <drape/io/json_io.hpp>

#include <drape/body/body_model.hpp>
#include <drape/body/pose.hpp>
#include <drape/cloth/material.hpp>

#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <string>

namespace fs = std::filesystem;
using namespace drape;
using drape::test::run_drape;

namespace {

// A result folder holding `garments` (result.json), for the mean female body in the rest A-pose.
fs::path result_folder(const std::string& name, const nlohmann::json& garments) {
    const fs::path dir = test::scratch_dir("apps_animate_" + name);
    const body::SemanticShape shape = body::BodyModel::default_model().prior.complete(body::SemanticRequest{});
    io::write_json_file(dir / "result.json",
                        {{"format", "drape.recovery"},
                         {"body", {{"params", io::to_json(shape)}, {"pose", io::to_json(body::Pose::rest())}}},
                         {"garments", garments}});
    return dir;
}

nlohmann::json skirt(bool supported) {
    garment::GarmentSizing g;
    g.type = garment::GarmentType::skirt;
    return {{"type", "skirt"}, {"garment", "skirt"}, {"supported", supported}, {"sizing", io::to_json(g)},
            {"material", io::material_to_json(cloth::builtin_material("gray-interlock"), "gray-interlock")}};
}

std::string q(const fs::path& p) { return "\"" + p.string() + "\""; }

}  // namespace

TEST_CASE("drape animate: bad input gets a clear error naming it", "[apps][animate]") {
    const fs::path good = result_folder("good", nlohmann::json::array({skirt(true)}));
    const fs::path out = test::scratch_dir("apps_animate_out");

    auto r = run_drape("animate --garment " + q(good) + " --fps -30 --out " + q(out));
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.out, Catch::Contains("--fps -30"));

    r = run_drape("animate --garment " + q(good) + " --seconds 0 --out " + q(out));
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.out, Catch::Contains("--seconds"));

    r = run_drape("animate --garment " + q(good) + " --wind 1,2 --out " + q(out));
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.out, Catch::Contains("--wind '1,2'"));

    const fs::path empty = result_folder("empty", nlohmann::json::array());
    r = run_drape("animate --garment " + q(empty) + " --out " + q(out));
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.out, Catch::Contains("no garment"));

    const fs::path unsupported = result_folder("unsupported", nlohmann::json::array({skirt(false)}));
    r = run_drape("animate --garment " + q(unsupported) + " --out " + q(out));
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.out, Catch::Contains("unsupported"));

    r = run_drape("animate --garment " + q(good) + " --motion dance --out " + q(out));
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.out, Catch::Contains("--motion 'dance'"));

    const fs::path garbage = test::scratch_dir("apps_animate_bvh") / "garbage.bvh";
    std::ofstream(garbage) << "HIERARCHY\nROOT Hips\n{\n OFFSET 0 0\n";
    r = run_drape("animate --garment " + q(good) + " --motion " + q(garbage) + " --out " + q(out));
    CHECK(r.exit_code == 3);
    CHECK_THAT(r.out, Catch::Contains("does not parse"));

    // A capture of the upper body only: the joint map needs legs.
    const fs::path torso = test::scratch_dir("apps_animate_bvh") / "torso.bvh";
    std::ofstream(torso) << "HIERARCHY\nROOT Hips\n{\n OFFSET 0 90 0\n CHANNELS 6 Xposition Yposition Zposition "
                            "Zrotation Xrotation Yrotation\n JOINT Spine\n {\n  OFFSET 0 10 0\n  CHANNELS 3 Zrotation "
                            "Xrotation Yrotation\n  End Site\n  {\n   OFFSET 0 10 0\n  }\n }\n}\nMOTION\nFrames: 1\n"
                            "Frame Time: 0.033333\n0 90 0 0 0 0 0 0 0\n";
    r = run_drape("animate --garment " + q(good) + " --motion " + q(torso) + " --out " + q(out));
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.out, Catch::Contains("does not fit"));
    CHECK_FALSE(fs::exists(out / "animation.glb"));
}
