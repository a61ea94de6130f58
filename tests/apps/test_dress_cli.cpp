// `drape dress` end to end: a coarse skirt dressed and draped on the mean female, and bad
// input rejected with exit code 2.
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "cli_runner.hpp"
#include "test_paths.hpp"

using drape::test::run_drape;

TEST_CASE("drape dress drapes a skirt and writes the summary", "[apps][dress]") {
    DRAPE_REQUIRE_SHARED(material, "materials/gray-interlock.json");
    const auto dir = drape::test::scratch_dir("cli_dress");
    const auto r = run_drape("dress --garment skirt --sizing auto --material gray-interlock --materials \"" +
                             material.parent_path().string() + "\" --edge 4 --no-render --out \"" +
                             dir.string() + "\"");
    INFO(r.out);
    // Exit 0 when the drape is usable, 1 (after writing every file) when it is not.
    REQUIRE((r.exit_code == 0 || r.exit_code == 1));
    std::ifstream in(dir / "summary.json");
    const nlohmann::json s = nlohmann::json::parse(in);
    CHECK(s["garment"] == "skirt");
    CHECK(s["usable"].get<bool>() == (r.exit_code == 0));
    CHECK(s["converged"].is_boolean());
    CHECK(s["seam_gap_max_m"].get<double>() < 1e-3);
    CHECK(s["penetration_max_m"].get<double>() <= 1e-3);
    CHECK(s["self_intersections"].get<int>() >= 0);
    CHECK(s["crossings_repaired"].get<int>() >= 0);
    CHECK(s["contact_stiffened"].is_boolean());
    CHECK(s["vertices"].get<int>() > 50);
    CHECK(s["seconds"].get<double>() > 0);
    for (const char* key : {"l1", "r1", "r2", "alpha"}) CHECK(s["sizing"][key].is_number());
    // A-pose: the arms are clear of the trunk already, nothing raised.
    CHECK(s["arms_raised_deg"]["right"].get<double>() == 0.0);
    CHECK(s["arms_raised_deg"]["left"].get<double>() == 0.0);
    for (const char* file : {"garment.obj", "garment.glb", "pattern.svg", "pattern.dxf", "pattern.json"})
        CHECK(std::filesystem::file_size(dir / file) > 100);
    std::ifstream glb(dir / "garment.glb", std::ios::binary);
    char magic[4];
    glb.read(magic, 4);
    CHECK(std::string(magic, 4) == "glTF");
}

TEST_CASE("drape dress rejects bad input with exit code 2", "[apps][dress]") {
    const auto dir = drape::test::scratch_dir("cli_dress_bad");
    auto r = run_drape("dress --garment cape --sizing auto --material x.json --out \"" + dir.string() + "\"");
    INFO(r.out);
    CHECK(r.exit_code == 2);
    CHECK(r.out.find("cape") != std::string::npos);
    r = run_drape("dress --garment skirt --sizing auto --material no-such-fabric --materials \"" + dir.string() +
                  "\" --out \"" + dir.string() + "\"");
    INFO(r.out);
    CHECK(r.exit_code == 2);
    CHECK(r.out.find("no-such-fabric") != std::string::npos);
    r = run_drape("dress --garment skirt --sizing auto --material gray-interlock --materials \"" + dir.string() +
                  "\" --pose cartwheel --out \"" + dir.string() + "\"");
    CHECK(r.exit_code == 2);
    // Outfits are a top and a bottom; an outfit's sizing names its garments.
    r = run_drape("dress --garment tshirt+dress --sizing auto --material gray-interlock --out \"" + dir.string() + "\"");
    INFO(r.out);
    CHECK(r.exit_code == 2);
    CHECK(r.out.find("a top and a bottom") != std::string::npos);
    const auto sizing = dir / "outfit_sizing.json";
    std::ofstream(sizing) << R"({"skirt": {"l1": 70}})";
    r = run_drape("dress --garment tshirt+pants --sizing \"" + sizing.string() +
                  "\" --material gray-interlock --out \"" + dir.string() + "\"");
    INFO(r.out);
    CHECK(r.exit_code == 2);
    CHECK(r.out.find("'skirt'") != std::string::npos);
}

TEST_CASE("drape eval-dress --docs replaces the table block of a Markdown file", "[apps][dress]") {
    DRAPE_REQUIRE_SHARED(material, "materials/gray-interlock.json");
    const auto dir = drape::test::scratch_dir("cli_eval_dress_docs");
    const auto docs = dir / "docs" / "dressing.md";
    std::filesystem::create_directories(docs.parent_path());
    {
        std::ofstream out(docs);
        out << "# Dressing\n\nbefore\n<!-- drape eval-dress: table begin -->\nold table\n"
               "<!-- drape eval-dress: table end -->\nafter\n";
    }
    const std::string common = "eval-dress --garments skirt --poses a_pose --bodies female_p50 --no-outfit --materials \"" +
                               material.parent_path().string() + "\" --out \"" + (dir / "out").string() + "\"";
    auto r = run_drape(common + " --docs \"" + docs.string() + "\"");
    INFO(r.out);
    REQUIRE(r.exit_code == 0);
    std::ifstream in(docs);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    CHECK(text.find("old table") == std::string::npos);
    CHECK(text.rfind("# Dressing\n\nbefore\n<!-- drape eval-dress: table begin -->\n| garment | body | pose", 0) == 0);
    CHECK(text.find("| skirt | female_p50 | a_pose |") != std::string::npos);  // (renders: the median woman)
    CHECK(text.find("1 of 1 cases usable (100.0 %);") != std::string::npos);
    CHECK(text.find(".\n<!-- drape eval-dress: table end -->\nafter\n") != std::string::npos);
    CHECK(std::filesystem::file_size(docs.parent_path() / "images" / "dress_eval.jpg") > 1000);
    // A file without the markers is rejected before anything is simulated, and kept.
    {
        std::ofstream out(docs);
        out << "no markers\n";
    }
    r = run_drape(common + " --docs \"" + docs.string() + "\"");
    CHECK(r.exit_code == 2);
    CHECK(r.out.find("drape eval-dress: table begin") != std::string::npos);
    std::ifstream again(docs);
    const std::string kept((std::istreambuf_iterator<char>(again)), std::istreambuf_iterator<char>());
    CHECK(kept == "no markers\n");
    r = run_drape(common + " --docs \"" + (dir / "missing.md").string() + "\"");
    CHECK(r.exit_code == 3);
}

TEST_CASE("drape eval-dress --ansur dresses a body sampled from the ANSUR II records", "[apps][dress]") {
    DRAPE_REQUIRE_SHARED(material, "materials/gray-interlock.json");
    DRAPE_REQUIRE_SHARED(anthropometry, "data/anthropometry");
    const auto dir = drape::test::scratch_dir("cli_eval_dress_ansur");
    // The shortest 1 % of the women comes first in every sample (female, stature p1:
    // subject 28740, 1.483 m, 44.2 kg); one skirt in A-pose keeps the run short.
    const std::string common = "eval-dress --seed 3 --ansur-dir \"" + anthropometry.string() +
                               "\" --materials \"" + material.parent_path().string() + "\" ";
    auto r = run_drape(common + "--ansur 8 --bodies f28740 --garments skirt --poses a_pose --no-outfit --out \"" +
                       dir.string() + "\"");
    INFO(r.out);
    REQUIRE(r.exit_code == 0);
    std::ifstream in(dir / "results.json");
    const nlohmann::json j = nlohmann::json::parse(in);
    CHECK(j["ansur"]["count"] == 8);
    CHECK(j["ansur"]["seed"] == 3);
    REQUIRE(j["cases"].size() == 1);
    const nlohmann::json& c = j["cases"][0];
    CHECK(c["body"] == "f28740");
    CHECK(c["subject_id"] == 28740);
    CHECK(c["garment"] == "skirt");
    CHECK(c["usable"].get<bool>());
    CHECK(c["seam_gap_max_m"].get<double>() < 1e-3);
    CHECK(c["penetration_max_m"].get<double>() <= 1e-3);
    // The per-body table names the record, its gender, stature and mass.
    std::ifstream bodies_md(dir / "bodies.md");
    const std::string bodies((std::istreambuf_iterator<char>(bodies_md)), std::istreambuf_iterator<char>());
    CHECK(bodies.find("| f28740 | 28740 | female | height p1 | 1.483 | 44.2 |") != std::string::npos);
    CHECK(bodies.find("1 of 1 cases usable (100.0 %)") != std::string::npos);
    // Fewer than the eight strata, or a name outside the sample, is refused.
    r = run_drape(common + "--ansur 4 --out \"" + dir.string() + "\"");
    CHECK(r.exit_code == 2);
    r = run_drape(common + "--ansur 8 --bodies female_p50 --out \"" + dir.string() + "\"");
    CHECK(r.exit_code == 2);
    CHECK(r.out.find("f28740") != std::string::npos);
}
