// `drape tryon` end to end: a skirt made for a median woman tried on a large man at a coarse
// mesh edge (graded, draped usable, every output written), and clear errors for bad input.
// The acceptance over the synthetic suite is `drape eval-tryon` (docs/tryon.md).
#include <catch2/catch.hpp>

#include <drape/io/json_io.hpp>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>

#include "../common/skirt_scene.hpp"
#include "cli_runner.hpp"
#include "test_paths.hpp"

using drape::test::run_drape;
namespace fs = std::filesystem;

namespace {

// A path quoted for the shell.
std::string q(const fs::path& p) { return '"' + p.string() + '"'; }

}  // namespace

TEST_CASE("drape tryon grades a skirt to a large man and drapes it usable", "[apps][tryon]") {
    const fs::path dir = drape::test::scratch_dir("tryon_real");
    const fs::path scene = drape::test::write_skirt_scene(dir / "scene");
    std::ofstream(dir / "man.json") << R"({"gender": "male", "height_m": 1.87, "weight_kg": 110.6})";
    const auto r = run_drape("tryon --garment " + q(scene) + ":0 --body " + q(dir / "man.json") +
                             " --edge 8 --out " + q(dir / "out"));
    INFO(r.out);
    REQUIRE(r.exit_code == 0);
    for (const char* f : {"tryon.json", "garment_0.glb", "garment_0.obj", "pattern_0.svg", "pattern_0.dxf",
                          "pattern_0.json", "grading_0.svg", "body.glb", "outfit.glb", "report.html"})
        CHECK(fs::exists(dir / "out" / f));
    CHECK_FALSE(fs::exists(dir / "out" / "overlay.png"));  // a body target has no photo
    const nlohmann::json j = drape::io::read_json_file(dir / "out" / "tryon.json");
    const nlohmann::json& g = j["garments"][0];
    CHECK(g["drape"]["usable"] == true);
    CHECK(g["drape"]["penetration_max_m"].get<double>() <= 1e-3);
    CHECK(g["drape"]["self_intersections"] == 0);
    // Graded up: a bigger waist by the waistband girth difference, the flare kept, several sizes up.
    CHECK(g["sizing"]["l1"].get<double>() > 40.0 + 5.0);
    CHECK(g["sizing"]["alpha"].get<double>() == Approx(90.0));
    CHECK(g["grading"]["grade"]["sizes"].get<int>() >= 2);
    CHECK(g["grading"]["max_style_change"].get<double>() < 1e-9);
    const nlohmann::json& ease = g["grading"]["ease"][0];
    CHECK(ease["graded_cm"].get<double>() == Approx(ease["original_cm"].get<double>()).margin(1e-6));
    // The material is kept.
    CHECK(g["material"]["base_fabric"] == "gray-interlock");
    CHECK(j["summary"]["usable"] == true);
    std::ifstream svg(dir / "out" / "grading_0.svg");
    const std::string text((std::istreambuf_iterator<char>(svg)), std::istreambuf_iterator<char>());
    CHECK(text.find("original") != std::string::npos);
    CHECK(text.find("sizes up") != std::string::npos);
}

TEST_CASE("drape tryon refuses bad input with a clear error", "[apps][tryon]") {
    const fs::path dir = drape::test::scratch_dir("tryon_bad");
    const fs::path scene = drape::test::write_skirt_scene(dir / "scene");
    const fs::path empty = drape::test::write_skirt_scene(dir / "empty", false);
    std::ofstream(dir / "man.json") << R"({"gender": "male", "height_m": 1.87, "weight_kg": 110.6})";
    const std::string body = " --body " + q(dir / "man.json") + " --out " + q(dir / "out");

    SECTION("a result folder without a garment") {
        const auto r = run_drape("tryon --garment " + q(empty) + body);
        INFO(r.out);
        CHECK(r.exit_code == 2);
        CHECK(r.out.find("no garment") != std::string::npos);
        CHECK(r.out.find("empty") != std::string::npos);
    }
    SECTION("no such folder") {
        const auto r = run_drape("tryon --garment " + q(dir / "missing") + body);
        INFO(r.out);
        CHECK(r.exit_code == 3);
        CHECK(r.out.find("missing") != std::string::npos);
    }
    SECTION("a garment number out of range") {
        const auto r = run_drape("tryon --garment " + q(scene) + ":3" + body);
        INFO(r.out);
        CHECK(r.exit_code == 2);
        CHECK(r.out.find(":3") != std::string::npos);
    }
    SECTION("both a body and a photo, or neither") {
        const auto both = run_drape("tryon --garment " + q(scene) + " --photo " + q(dir / "p.jpg") + body);
        CHECK(both.exit_code == 2);
        CHECK(both.out.find("either --body") != std::string::npos);
        const auto neither = run_drape("tryon --garment " + q(scene) + " --out " + q(dir / "out"));
        CHECK(neither.exit_code == 2);
    }
    SECTION("a photo without joints") {
        const auto r = run_drape("tryon --garment " + q(scene) + " --photo " + q(dir / "p.jpg") + " --out " + q(dir / "out"));
        INFO(r.out);
        CHECK(r.exit_code == 2);
        CHECK(r.out.find("--joints") != std::string::npos);
    }
    SECTION("an unknown pose") {
        const auto r = run_drape("tryon --garment " + q(scene) + body + " --pose dancing");
        INFO(r.out);
        CHECK(r.exit_code == 2);
        CHECK(r.out.find("dancing") != std::string::npos);
    }
    SECTION("a bad mesh edge") {
        const auto r = run_drape("tryon --garment " + q(scene) + body + " --edge 0");
        INFO(r.out);
        CHECK(r.exit_code == 2);
        CHECK(r.out.find("edge_cm") != std::string::npos);
    }
    CHECK_FALSE(fs::exists(dir / "out" / "tryon.json"));
}
