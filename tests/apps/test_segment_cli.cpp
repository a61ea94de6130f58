// `drape segment`, `drape strokes` and `drape eval-segment` end to end on a shared photo.
// The full 30-photo evaluation is the CLI command in docs/vision.md.
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>

#include "cli_runner.hpp"
#include "test_paths.hpp"

using drape::test::run_drape;
namespace fs = std::filesystem;

namespace {

std::string q(const fs::path& p) { return "\"" + p.string() + "\""; }

/// The files of the skirt + t-shirt photo used here.
struct PhotoFiles {
    fs::path image, joints, labels;
};
PhotoFiles skirt_photo(const fs::path& photos) {
    const std::string name = "fashionista_002149";
    return {photos / "images" / (name + ".jpg"), photos / "joints" / (name + ".json"),
            photos / "labels" / (name + ".png")};
}

nlohmann::json read_json(const fs::path& p) {
    std::ifstream f(p);
    return nlohmann::json::parse(f);
}

}  // namespace

TEST_CASE("drape segment writes labels, garments, overlays (auto and strokes)", "[apps][segment]") {
    DRAPE_REQUIRE_SHARED(photos, "data/photos");
    const auto [image, joints, labels] = skirt_photo(photos);
    const fs::path dir = drape::test::scratch_dir("segment_cli");

    const auto strokes = run_drape("strokes " + q(labels) + " --out " +
                                   q(dir / "strokes.png"));
    INFO(strokes.out);
    REQUIRE(strokes.exit_code == 0);
    REQUIRE(fs::exists(dir / "strokes.png"));

    for (const std::string mode : {"auto", "strokes"}) {
        const fs::path out = dir / mode;
        std::string cmd = "segment " + q(image) + " --joints " + q(joints) + " --out " + q(out);
        if (mode == "strokes") cmd += " --strokes " + q(dir / "strokes.png");
        const auto r = run_drape(cmd);
        INFO(r.out);
        REQUIRE(r.exit_code == 0);
        for (const char* f : {"labels.png", "overlay.png", "folds.png", "occlusion.png"})
            CHECK(fs::exists(out / f));
        const nlohmann::json g = read_json(out / "garments.json");
        CHECK(g["segmentation"]["mode"] == mode);
        REQUIRE(g["garments"].size() >= 2);
        bool lower = false;
        for (const auto& e : g["garments"]) {
            // Strokes carry the skirt class; the automatic classifier calls this ankle-length
            // skirt "pants" (docs/vision.md, "Garment type"), so only the part is checked.
            lower |= mode == "strokes" ? e["type"] == "skirt"
                                       : (e["type"] == "skirt" || e["type"] == "pants");
            CHECK(e["wrinkle_density_per_m2"].get<double>() >= 0);
            CHECK(e["occlusion_fraction"].get<double>() >= 0);
            CHECK(e["occlusion_fraction"].get<double>() < 1);
            REQUIRE(!e["silhouette"].empty());
            CHECK(e["silhouette"][0]["outer"].size() >= 3);
            CHECK(e["features"].contains("length"));
        }
        CHECK(lower);
    }
}

TEST_CASE("drape segment reads hand-drawn colour-coded strokes like class-id strokes", "[apps][segment]") {
    DRAPE_REQUIRE_SHARED(photos, "data/photos");
    const auto [image, joints, labels] = skirt_photo(photos);
    const fs::path dir = drape::test::scratch_dir("segment_cli_colour");
    // This photo's labels hold a necklace, which the default palette has no colour for.
    std::ofstream(dir / "palette.json") << R"({"tolerance": 30, "colours": {"null": "#0000ff",
        "skin": "#ff8000", "hair": "#800000", "t-shirt": "#ff0000", "skirt": "#ffff00",
        "bag": "#808000", "shoes": "#80ff00", "necklace": "#ff0080"}})";
    auto r = run_drape("strokes " + q(labels) + " --out " + q(dir / "ids.png"));
    REQUIRE(r.exit_code == 0);
    r = run_drape("strokes " + q(labels) + " --colour --out " + q(dir / "default.png"));
    REQUIRE(r.exit_code == 0);
    CHECK(r.out.find("left out: necklace") != std::string::npos);
    r = run_drape("strokes " + q(labels) + " --colour --palette " + q(dir / "palette.json") + " --out " +
                  q(dir / "colour.png"));
    REQUIRE(r.exit_code == 0);
    CHECK(r.out.find("left out") == std::string::npos);
    const std::string base = "segment " + q(image) + " --joints " + q(joints) + " --strokes ";
    r = run_drape(base + q(dir / "ids.png") + " --out " + q(dir / "a"));
    REQUIRE(r.exit_code == 0);
    r = run_drape(base + q(dir / "colour.png") + " --palette " + q(dir / "palette.json") + " --out " + q(dir / "b"));
    INFO(r.out);
    REQUIRE(r.exit_code == 0);
    CHECK(r.out.find("colour-coded strokes:") != std::string::npos);
    CHECK(r.out.find("skirt") != std::string::npos);
    std::ifstream fa(dir / "a" / "labels.png", std::ios::binary), fb(dir / "b" / "labels.png", std::ios::binary);
    const std::string a((std::istreambuf_iterator<char>(fa)), {}), b((std::istreambuf_iterator<char>(fb)), {});
    CHECK(!a.empty());
    CHECK(a == b);  // the same labels, byte for byte
}

TEST_CASE("drape segment and eval-segment reject bad input with exit codes", "[apps][segment][errors]") {
    DRAPE_REQUIRE_SHARED(photos, "data/photos");
    const auto [image, joints, labels] = skirt_photo(photos);
    const fs::path dir = drape::test::scratch_dir("segment_cli_errors");
    // Missing photo: I/O error.
    auto r = run_drape("segment " + q(dir / "missing.jpg") + " --joints " + q(joints) + " --out " + q(dir / "o"));
    CHECK(r.exit_code == 3);
    // A colour photo as strokes: invalid input naming the problem.
    r = run_drape("segment " + q(image) + " --joints " + q(joints) + " --strokes " + q(image) +
                  " --out " + q(dir / "o"));
    CHECK(r.exit_code == 2);
    CHECK(r.out.find("looks like a photo, not strokes") != std::string::npos);
    // Palettes: colours too close, an unknown class, a bad tolerance; --palette alone.
    const std::pair<const char*, const char*> palettes[] = {
        {R"({"colours": {"skirt": "#ffff00", "coat": "#fafa0a"}})", "differ by 10"},
        {R"({"colours": {"skrt": "#ffff00"}})", "'skrt' is not a class"},
        {R"({"tolerance": 80, "colours": {"skirt": "#ffff00"}})", "field 'tolerance'"},
        {R"({"colours": {"skirt": "yellow"}})", "#rrggbb"}};
    for (const auto& [text, message] : palettes) {
        std::ofstream(dir / "palette.json") << text;
        r = run_drape("strokes " + q(labels) + " --colour --palette " + q(dir / "palette.json") + " --out " +
                      q(dir / "s.png"));
        INFO(text << " -> " << r.out);
        CHECK(r.exit_code == 2);
        CHECK(r.out.find(message) != std::string::npos);
    }
    r = run_drape("segment " + q(image) + " --joints " + q(joints) + " --palette " + q(dir / "palette.json") +
                  " --out " + q(dir / "o"));
    CHECK(r.exit_code == 2);
    CHECK(r.out.find("no --strokes") != std::string::npos);
    // Unknown hint.
    r = run_drape("segment " + q(image) + " --joints " + q(joints) + " --hint kilt --out " + q(dir / "o"));
    CHECK(r.exit_code == 2);
    // A joint off the image.
    nlohmann::json j = read_json(joints);
    j["joints"][13] = {100, -50};
    std::ofstream(dir / "off.json") << j.dump();
    r = run_drape("segment " + q(image) + " --joints " + q(dir / "off.json") + " --out " + q(dir / "o"));
    CHECK(r.exit_code == 2);
    CHECK(r.out.find("head") != std::string::npos);
}

TEST_CASE("drape eval-segment scores a photo against its hand labels", "[apps][segment]") {
    DRAPE_REQUIRE_SHARED(photos, "data/photos");
    const fs::path dir = drape::test::scratch_dir("eval_segment_cli");
    const auto r = run_drape("eval-segment " + q(photos) + " --names fashionista_008973 --out " +
                             q(dir / "eval.json"));
    INFO(r.out);
    REQUIRE(r.exit_code == 0);
    const nlohmann::json e = read_json(dir / "eval.json");
    REQUIRE(e["photos"].size() == 1);
    for (const char* mode : {"strokes", "auto"}) {
        INFO(mode);
        CHECK(e["summary"][mode]["garments"] == 2);
        CHECK(e["summary"][mode]["mean_garment_iou"].get<double>() > 0.7);
        CHECK(e["summary"][mode]["type_accuracy"].get<double>() >= 0.5);
    }
}
