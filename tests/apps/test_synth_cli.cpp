// `drape synth` end to end: a coarse skirt scene is the same bytes twice, its joints fall on
// the body in the label map, the skirt is labelled where it is, and truth.json holds what
// was simulated. Outfits and the dress run under the hidden [.eval] tag.
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include <opencv2/imgcodecs.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>

#include "cli_runner.hpp"
#include "test_paths.hpp"

using drape::test::run_drape;
namespace fs = std::filesystem;

namespace {

// A small, quick skirt scene: 6 cm edges, 400 x 600, 2 samples per pixel.
const std::string kQuick = " --garment skirt --pose a --material gray-interlock --edge 6 --max-steps 150 "
                           "--width 400 --height 600 --samples 2";

std::string read_bytes(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

nlohmann::json read_json(const fs::path& p) {
    std::ifstream in(p);
    return nlohmann::json::parse(in);
}

std::string quoted(const fs::path& p) { return "\"" + p.string() + "\""; }

// The label at an image point (pixels, origin at the top-left corner).
int label_at(const cv::Mat& labels, double x, double y) {
    const int c = int(std::floor(x)), r = int(std::floor(y));
    if (c < 0 || r < 0 || c >= labels.cols || r >= labels.rows) return -1;
    return labels.at<unsigned char>(r, c);
}

// Whether a non-zero label lies within `radius` pixels of (x, y).
bool person_near(const cv::Mat& labels, double x, double y, int radius) {
    for (int dy = -radius; dy <= radius; ++dy)
        for (int dx = -radius; dx <= radius; ++dx)
            if (label_at(labels, x + dx, y + dy) > 0) return true;
    return false;
}

}  // namespace

TEST_CASE("drape synth writes the same bytes twice for a seed", "[apps][synth]") {
    const auto a = drape::test::scratch_dir("cli_synth_a"), b = drape::test::scratch_dir("cli_synth_b");
    const auto ra = run_drape("synth --seed 11" + kQuick + " --threads 1 --out " + quoted(a));
    INFO(ra.out);
    REQUIRE(ra.exit_code == 0);  // the skirt is usable (build d206168); 1 would mean not usable, files written
    const auto rb = run_drape("synth --seed 11" + kQuick + " --threads 2 --out " + quoted(b));
    INFO(rb.out);
    REQUIRE(rb.exit_code == ra.exit_code);
    for (const char* f : {"truth.json", "labels.png", "image_midday.png", "image_sunset.png", "strokes.png",
                          "joints.json", "summary.json"}) {
        INFO(f);
        const std::string x = read_bytes(a / f);
        CHECK(x.size() > 100);
        CHECK(x == read_bytes(b / f));
    }
}

TEST_CASE("drape synth --print renders the same drape plain and printed", "[apps][synth][prints]") {
    const auto a = drape::test::scratch_dir("cli_synth_plain"), b = drape::test::scratch_dir("cli_synth_checks");
    const auto ra = run_drape("synth --seed 11" + kQuick + " --print none --out " + quoted(a));
    INFO(ra.out);
    REQUIRE(ra.exit_code == 0);
    const auto rb = run_drape("synth --seed 11" + kQuick + " --print checks --out " + quoted(b));
    INFO(rb.out);
    REQUIRE(rb.exit_code == 0);
    // The same geometry: labels, joints and strokes are the same bytes ...
    for (const char* f : {"labels.png", "joints.json", "strokes.png"}) {
        INFO(f);
        CHECK(read_bytes(a / f) == read_bytes(b / f));
    }
    // ... the colours are not: the skirt's pixels differ, the rest of the image does not.
    const cv::Mat labels = cv::imread((a / "labels.png").string(), cv::IMREAD_UNCHANGED);
    const cv::Mat pa = cv::imread((a / "image_midday.png").string()), pb = cv::imread((b / "image_midday.png").string());
    REQUIRE(pa.size() == pb.size());
    int skirt = 0, skirt_changed = 0, other_changed = 0;
    for (int y = 0; y < pa.rows; ++y)
        for (int x = 0; x < pa.cols; ++x) {
            const bool changed = pa.at<cv::Vec3b>(y, x) != pb.at<cv::Vec3b>(y, x);
            if (labels.at<unsigned char>(y, x) == 42) {
                ++skirt;
                skirt_changed += changed;
            } else {
                other_changed += changed;
            }
        }
    CHECK(skirt_changed > skirt / 4);  // a checkerboard: about half of the skirt shows the second colour
    CHECK(other_changed < skirt / 20);  // shadows and reflections of the skirt only
    // The truth is the same but for P, measured on the render.
    nlohmann::json ta = read_json(a / "truth.json"), tb = read_json(b / "truth.json");
    ta["garments"][0].erase("wrinkle_density_per_m2");
    tb["garments"][0].erase("wrinkle_density_per_m2");
    CHECK(ta == tb);
    const auto bad = run_drape("synth --seed 11 --print plaid --out " + quoted(a));
    CHECK(bad.exit_code == 2);
    CHECK(bad.out.find("plaid") != std::string::npos);
    // The print check's detector is refused by name before any drape.
    const auto bad_shading = run_drape("synth --seed 11 --print-check --print-shading retinex --out " + quoted(a / "pc"));
    CHECK(bad_shading.exit_code == 2);
    CHECK(bad_shading.out.find("--print-shading 'retinex'") != std::string::npos);
    CHECK(!fs::exists(a / "pc"));
}

TEST_CASE("drape synth: joints on the body, skirt labels, truth as simulated", "[apps][synth]") {
    const auto dir = drape::test::scratch_dir("cli_synth");
    const auto r = run_drape("synth --seed 5" + kQuick + " --bending-scale 30 --out " + quoted(dir));
    INFO(r.out);
    REQUIRE(r.exit_code == 0);  // the skirt is usable (build d206168)
    const nlohmann::json summary = read_json(dir / "summary.json");
    CHECK(summary["usable"].get<bool>());

    const cv::Mat labels = cv::imread((dir / "labels.png").string(), cv::IMREAD_UNCHANGED);
    REQUIRE(labels.type() == CV_8UC1);
    CHECK(labels.cols == 400);
    CHECK(labels.rows == 600);
    std::set<int> ids;
    int skirt = 0, skin = 0;
    for (int y = 0; y < labels.rows; ++y)
        for (int x = 0; x < labels.cols; ++x) {
            const int id = labels.at<unsigned char>(y, x);
            ids.insert(id);
            skirt += id == 42;
            skin += id == 41;
        }
    CHECK(ids == std::set<int>{0, 41, 42});  // stage, "skin" (the mannequin), "skirt"
    CHECK(skirt > 0.01 * labels.total());
    CHECK(skin > 0.02 * labels.total());

    // Joints: 1-based like ../shared/data/photos; every one on the person, the head top
    // (on the silhouette's edge) within 3 px of it.
    const nlohmann::json joints = read_json(dir / "joints.json");
    REQUIRE(joints["joints"].size() == 14);
    CHECK(joints["joint_names"][13] == "head");
    CHECK(joints["image_size"] == nlohmann::json({400, 600}));
    CHECK(joints["pixel_origin"] == "one_based");
    CHECK(joints["marks"] == "model");  // the model's own joints (fit-body and recover then use no offsets)
    std::vector<std::array<double, 2>> px;
    for (const auto& j : joints["joints"]) px.push_back({j[0].get<double>() - 0.5, j[1].get<double>() - 0.5});
    for (int k = 0; k < 13; ++k) {
        INFO("joint " << k << " at " << px[k][0] << ", " << px[k][1]);
        CHECK(label_at(labels, px[k][0], px[k][1]) > 0);
    }
    CHECK(person_near(labels, px[13][0], px[13][1], 3));
    CHECK(px[13][1] < px[12][1]);  // head above neck
    CHECK(px[12][1] < px[2][1]);   // neck above hips
    CHECK(px[2][1] < px[1][1]);    // hip above knee
    // The skirt covers the hips: the point between the hip joints is labelled skirt.
    CHECK(label_at(labels, 0.5 * (px[2][0] + px[3][0]), 0.5 * (px[2][1] + px[3][1])) == 42);

    // Strokes use only the label map's classes.
    const cv::Mat strokes = cv::imread((dir / "strokes.png").string(), cv::IMREAD_UNCHANGED);
    REQUIRE(strokes.type() == CV_8UC1);
    int marked = 0;
    for (int y = 0; y < strokes.rows; ++y)
        for (int x = 0; x < strokes.cols; ++x) {
            const int id = strokes.at<unsigned char>(y, x);
            if (id == 255) continue;
            ++marked;
            CHECK(id == labels.at<unsigned char>(y, x));
        }
    CHECK(marked > 50);

    // truth.json: the schema and the simulated values.
    const nlohmann::json truth = read_json(dir / "truth.json");
    CHECK(truth.size() == 2);
    const auto& params = truth["body"]["params"];
    CHECK(params.size() == 11);
    for (const char* key : {"gender", "height_m", "weight_kg", "muscle", "chest_girth_m", "waist_girth_m",
                            "hip_girth_m", "thigh_girth_m", "calf_girth_m", "shoulder_height_m", "crotch_height_m"})
        CHECK(params.contains(key));
    CHECK(truth["body"]["pose"]["rotations"].size() == 22);
    CHECK(truth["body"]["camera"]["model"] == "pinhole");
    REQUIRE(truth["garments"].size() == 1);
    const auto& g = truth["garments"][0];
    CHECK(g["type"] == "skirt");
    CHECK(g["sizing"].size() == 4);
    CHECK(g["sizing"]["l1"].get<double>() >= 20);
    CHECK(g["sizing"]["l1"].get<double>() <= 120);
    CHECK(g["sizing"]["r2"].get<double>() >= 15);
    CHECK(g["sizing"]["alpha"].get<double>() >= 45);
    CHECK(g["sizing"]["alpha"].get<double>() <= 150);
    const auto& m = g["material"];
    CHECK(m["base_fabric"] == "gray-interlock");
    CHECK(m["bending_scale"].get<double>() == 30.0);
    CHECK(m["stretching_scale"].get<double>() == 1.0);
    const nlohmann::json fabric = read_json(drape::test::source_dir() / "data/materials/gray-interlock.json");
    CHECK(m["density"] == fabric["density_kg_per_m2"]);
    CHECK(m["stretching"] == fabric["stretching_n_per_m"]);
    CHECK(m["bending"] == fabric["bending_n_m"]);
    CHECK(m["stretching"].size() == 6);
    CHECK(m["bending"].size() == 3);
    CHECK(g["mean_curvature_per_m"].get<double>() > 0.1);
    CHECK(g["mean_curvature_per_m"].get<double>() < 1000);
    CHECK(g["wrinkle_density_per_m2"].get<double>() >= 0);

    // The truth reproduces the body: `drape body --params` with truth.body.params
    // measures as the params say.
    {
        std::ofstream p(dir / "params.json");
        p << params.dump();
    }
    const auto rb = run_drape("body --params " + quoted(dir / "params.json") + " --measure");
    INFO(rb.out);
    REQUIRE(rb.exit_code == 0);
    const nlohmann::json measured = nlohmann::json::parse(rb.out.substr(rb.out.find('{')));
    CHECK(measured["gender"] == params["gender"]);
    for (const char* key : {"height_m", "waist_girth_m", "hip_girth_m", "chest_girth_m"})
        CHECK(measured[key].get<double>() == Approx(params[key].get<double>()).epsilon(0.01));

    // The truth's sizing is a valid skirt pattern for `drape pattern`.
    {
        std::ofstream s(dir / "sizing.json");
        s << g["sizing"].dump();
    }
    const auto rp = run_drape("pattern --garment skirt --sizing " + quoted(dir / "sizing.json") + " --edge 6 --out " +
                              quoted(dir / "pattern"));
    INFO(rp.out);
    CHECK(rp.exit_code == 0);
}

TEST_CASE("drape synth rejects bad input with exit code 2", "[apps][synth]") {
    const auto dir = drape::test::scratch_dir("cli_synth_bad");
    const std::string out = " --out " + quoted(dir);
    auto r = run_drape("synth --seed 1 --garment cape" + out);
    CHECK(r.exit_code == 2);
    CHECK(r.out.find("cape") != std::string::npos);
    r = run_drape("synth --seed 1 --garment tshirt+dress" + out);
    CHECK(r.exit_code == 2);
    r = run_drape("synth --seed 1 --pose d" + out);
    CHECK(r.exit_code == 2);
    CHECK(r.out.find("'d'") != std::string::npos);
    r = run_drape("synth --seed 1 --material no-such-fabric" + out);
    CHECK(r.exit_code == 2);
    r = run_drape("synth --seed 1 --height 300" + out);
    CHECK(r.exit_code == 2);
    r = run_drape("synth --garment skirt" + out);  // no seed, no suite
    CHECK(r.exit_code == 2);
    r = run_drape("synth --suite " + quoted(dir / "missing.json") + out);
    CHECK(r.exit_code == 3);
}

TEST_CASE("the synthetic suite definition is well formed", "[apps][synth]") {
    const nlohmann::json suite = read_json(drape::test::source_dir() / "data/synth/suite.json");
    int table1 = 0, table2 = 0, random = 0;
    std::set<std::string> names;
    for (const auto& s : suite["scenes"]) {
        names.insert(s["name"].get<std::string>());
        const std::string group = s["group"];
        table1 += group == "table1" && s["garment"] == "tshirt+pants";
        table2 += group == "table2" && s["garment"] == "skirt";
        random += group == "random";
    }
    CHECK(names.size() == suite["scenes"].size());
    CHECK(table1 == 3);
    CHECK(table2 == 2);
    CHECK(random >= 10);
}

TEST_CASE("drape synth dresses an outfit: t-shirt over pants", "[.eval][synth]") {
    const auto dir = drape::test::scratch_dir("cli_synth_outfit");
    const auto r = run_drape("synth --seed 3 --garment tshirt+pants --pose b --material gray-interlock --edge 5 "
                             "--samples 4 --out " + quoted(dir));
    INFO(r.out);
    // Usable (exit 0): the outfit converges in 271 steps on build d206168.
    REQUIRE(r.exit_code == 0);
    CHECK(read_json(dir / "summary.json")["usable"].get<bool>());
    const cv::Mat labels = cv::imread((dir / "labels.png").string(), cv::IMREAD_UNCHANGED);
    int tshirt = 0, pants = 0;
    for (int y = 0; y < labels.rows; ++y)
        for (int x = 0; x < labels.cols; ++x) {
            tshirt += labels.at<unsigned char>(y, x) == 51;
            pants += labels.at<unsigned char>(y, x) == 31;
        }
    CHECK(tshirt > 0.01 * labels.total());
    CHECK(pants > 0.01 * labels.total());
    const nlohmann::json truth = read_json(dir / "truth.json");
    REQUIRE(truth["garments"].size() == 2);
    CHECK(truth["garments"][0]["type"] == "pants");
    CHECK(truth["garments"][1]["type"] == "tshirt");
    // Dressed and draped together (garment::dress_and_drape_outfit): one simulation, whose
    // steps both garments report; sizes stay per garment.
    const nlohmann::json summary = read_json(dir / "summary.json");
    REQUIRE(summary["drapes"].size() == 2);
    CHECK(summary["drapes"][0]["steps"] == summary["drapes"][1]["steps"]);
    CHECK(summary["drapes"][0]["self_intersections"] == summary["drapes"][1]["self_intersections"]);
    CHECK(summary["drapes"][0]["vertices"] != summary["drapes"][1]["vertices"]);
}

TEST_CASE("drape synth makes a dress scene", "[.eval][synth]") {
    const auto dir = drape::test::scratch_dir("cli_synth_dress");
    const auto r = run_drape("synth --seed 4 --garment dress --pose c --edge 5 --samples 4 --out " + quoted(dir));
    INFO(r.out);
    // Usable (exit 0): the dress converges in 297 steps on build d206168.
    REQUIRE(r.exit_code == 0);
    CHECK(read_json(dir / "summary.json")["usable"].get<bool>());
    const cv::Mat labels = cv::imread((dir / "labels.png").string(), cv::IMREAD_UNCHANGED);
    int dress = 0;
    for (int y = 0; y < labels.rows; ++y)
        for (int x = 0; x < labels.cols; ++x) dress += labels.at<unsigned char>(y, x) == 14;
    CHECK(dress > 0.02 * labels.total());
}
