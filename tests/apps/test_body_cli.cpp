// `drape body` end to end: parameters in, glb/obj out, measurements printed.
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>

#include "cli_runner.hpp"
#include "test_paths.hpp"

using drape::test::run_drape;

namespace {

std::string write(const std::filesystem::path& p, const std::string& text) {
    std::ofstream(p) << text;
    return "\"" + p.string() + "\"";
}

nlohmann::json last_json_object(const std::string& out) {
    const auto start = out.find('{');
    REQUIRE(start != std::string::npos);
    return nlohmann::json::parse(out.substr(start));
}

}  // namespace

TEST_CASE("drape body builds, poses, exports and measures a body", "[apps][body]") {
    const auto dir = drape::test::scratch_dir("cli_body");
    const std::string params = write(dir / "p.json", R"({"gender": "male", "height_m": 1.82, "weight_kg": 84, "waist_girth_m": 0.95})");
    const std::string pose = write(dir / "pose.json", R"({"preset": "walking", "rotations": {"head": [0, 0.2, 0]}})");
    const auto r = run_drape("body --params " + params + " --pose " + pose + " --out \"" +
                             (dir / "body.glb").string() + "\" --obj \"" + (dir / "body.obj").string() +
                             "\" --measure");
    INFO(r.out);
    REQUIRE(r.exit_code == 0);
    const nlohmann::json m = last_json_object(r.out);
    CHECK(m["gender"] == "male");
    CHECK(m["height_m"].get<double>() == Approx(1.82).margin(0.002));
    CHECK(m["waist_girth_m"].get<double>() == Approx(0.95).margin(0.002));
    for (const char* key : {"weight_kg", "muscle", "chest_girth_m", "hip_girth_m", "thigh_girth_m",
                            "calf_girth_m", "shoulder_height_m", "crotch_height_m"})
        CHECK(m.contains(key));
    CHECK(std::filesystem::file_size(dir / "body.glb") > 100000);
    CHECK(std::filesystem::file_size(dir / "body.obj") > 100000);
    // glb header: magic "glTF", version 2.
    std::ifstream glb(dir / "body.glb", std::ios::binary);
    char magic[4];
    glb.read(magic, 4);
    CHECK(std::string(magic, 4) == "glTF");
}

TEST_CASE("drape body explains bad input and writes nothing", "[apps][body]") {
    const auto dir = drape::test::scratch_dir("cli_body_errors");
    const std::string out = " --out \"" + (dir / "x.glb").string() + "\"";
    auto r = run_drape("body --params \"" + (dir / "missing.json").string() + "\"" + out);
    CHECK(r.exit_code == 3);
    CHECK_THAT(r.out, Catch::Contains("missing.json"));
    r = run_drape("body --params " + write(dir / "typo.json", R"({"hieght_m": 1.7})") + out);
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.out, Catch::Contains("hieght_m"));
    r = run_drape("body --params " + write(dir / "g.json", R"({"gender": "robot"})") + out);
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.out, Catch::Contains("robot"));
    r = run_drape("body --params " + write(dir / "neg.json", R"({"height_m": -1.7})") + out);
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.out, Catch::Contains("height_m"));
    r = run_drape("body --params " + write(dir / "bad.json", "{not json") + out);
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.out, Catch::Contains("bad.json"));
    r = run_drape("body --pose " + write(dir / "pose.json", R"({"rotations": {"elbow": [0,0,1]}})") + out);
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.out, Catch::Contains("elbow"));
    CHECK_FALSE(std::filesystem::exists(dir / "x.glb"));
    r = run_drape("body --out \"" + (dir / "no" / "such" / "dir.glb").string() + "\"");
    CHECK(r.exit_code == 3);
}
