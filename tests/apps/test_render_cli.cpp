// `drape render` end to end: default body, garments from files, overlay on a photo with a
// fitted camera, determinism across thread counts, and clear errors.
#include <catch2/catch.hpp>

#include <drape/body/body_model.hpp>
#include <drape/body/camera.hpp>
#include <drape/body/pose.hpp>

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "cli_runner.hpp"
#include "test_paths.hpp"

using drape::test::run_drape;

namespace {

std::string q(const std::filesystem::path& p) { return "\"" + p.string() + "\""; }

/// An open cylinder (a tube skirt) around the hips: radius 0.25 m, y in [0.55, 0.95].
void write_tube_obj(const std::filesystem::path& p) {
    std::ofstream out(p);
    const int rings = 6, segments = 48;
    for (int r = 0; r < rings; ++r)
        for (int s = 0; s < segments; ++s) {
            const double th = 2 * 3.14159265358979 * s / segments;
            out << "v " << 0.25 * std::sin(th) << " " << 0.95 - 0.4 * r / (rings - 1) << " "
                << 0.25 * std::cos(th) << "\n";
        }
    for (int r = 0; r + 1 < rings; ++r)
        for (int s = 0; s < segments; ++s) {
            const int a = r * segments + s + 1, b = r * segments + (s + 1) % segments + 1;
            out << "f " << a << " " << a + segments << " " << b << "\n"
                << "f " << b << " " << a + segments << " " << b + segments << "\n";
        }
}

std::string file_bytes(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

}  // namespace

TEST_CASE("drape render draws the body and a garment with labels", "[apps][render]") {
    const auto dir = drape::test::scratch_dir("cli_render");
    write_tube_obj(dir / "skirt.obj");
    const auto r = run_drape("render --mesh " + q(dir / "skirt.obj") +
                             " --color 200,180,160 --color 30,60,200 --print stripes:0.05"
                             " --lighting midday --width 120 --height 180 --samples 2 --out " +
                             q(dir / "r.png") + " --labels " + q(dir / "l.png"));
    INFO(r.out);
    REQUIRE(r.exit_code == 0);
    const cv::Mat colour = cv::imread((dir / "r.png").string(), cv::IMREAD_UNCHANGED);
    const cv::Mat labels = cv::imread((dir / "l.png").string(), cv::IMREAD_UNCHANGED);
    REQUIRE(colour.type() == CV_8UC3);
    REQUIRE(labels.type() == CV_8UC1);
    CHECK(colour.cols == 120);
    CHECK(colour.rows == 180);
    CHECK(labels.size() == colour.size());
    int skin = 0, skirt = 0;
    for (int y = 0; y < labels.rows; ++y)
        for (int x = 0; x < labels.cols; ++x) {
            skin += labels.at<std::uint8_t>(y, x) == 41;
            skirt += labels.at<std::uint8_t>(y, x) == 42;  // from the file name
        }
    CHECK(skin > 500);
    CHECK(skirt > 300);
}

TEST_CASE("drape render overlays a fitted body exactly on its photo", "[apps][render]") {
    const auto dir = drape::test::scratch_dir("cli_render_overlay");
    const int K = drape::body::BodyModel::default_model().shape_count();
    drape::body::Camera cam;
    cam.model = drape::body::CameraModel::pinhole;
    cam.focal_px = 500.0;
    cam.distance_m = 5.0;
    cam.offset_px = {80.0, 200.0};
    nlohmann::json j;
    j["format"] = "drape.body_fit";
    j["coefficients"] = std::vector<double>(static_cast<size_t>(K), 0.0);
    j["pose"] = {{"preset", "arms_down"}};
    j["camera"] = {{"model", "pinhole"}, {"focal_px", cam.focal_px}, {"distance_m", cam.distance_m},
                   {"offset_px", {cam.offset_px.x(), cam.offset_px.y()}}};
    j["image"] = {{"file", "photo.png"}, {"width", 160}, {"height", 220}};
    std::ofstream(dir / "body.json") << j.dump(2);
    const cv::Mat photo(220, 160, CV_8UC3, cv::Scalar(0, 200, 0));
    REQUIRE(cv::imwrite((dir / "photo.png").string(), photo));

    const auto r = run_drape("render --body " + q(dir / "body.json") + " --photo " + q(dir / "photo.png") +
                             " --samples 2 --out " + q(dir / "o.png") + " --labels " + q(dir / "l.png"));
    INFO(r.out);
    REQUIRE(r.exit_code == 0);
    const cv::Mat out = cv::imread((dir / "o.png").string(), cv::IMREAD_UNCHANGED);
    const cv::Mat labels = cv::imread((dir / "l.png").string(), cv::IMREAD_UNCHANGED);
    REQUIRE(out.size() == photo.size());
    // Away from the body the photo shows through untouched (no stage with --photo).
    CHECK(out.at<cv::Vec3b>(5, 5) == cv::Vec3b(0, 200, 0));
    CHECK(out.at<cv::Vec3b>(215, 155) == cv::Vec3b(0, 200, 0));
    // The fitted camera places the body where drape::body::Camera projects it: the
    // pelvis-height centre line and the chest project onto body pixels; the floor level
    // (y = 0) far to the side does not.
    for (const Eigen::Vector3d& X : {Eigen::Vector3d(0, 0.9, 0.1), Eigen::Vector3d(0, 1.3, 0.1)}) {
        const Eigen::Vector2d p = cam.project(X);
        const int x = static_cast<int>(p.x()), y = static_cast<int>(p.y());
        CHECK(labels.at<std::uint8_t>(y, x) == 41);
        CHECK(out.at<cv::Vec3b>(y, x) != cv::Vec3b(0, 200, 0));
    }
    const Eigen::Vector2d side = cam.project({0.6, 0.9, 0});
    CHECK(labels.at<std::uint8_t>(static_cast<int>(side.y()), static_cast<int>(side.x())) == 0);

    // The body's label pixels are libbody's own silhouette of that body and camera (the
    // one `drape fit-body` compares with the photo's person mask).
    const auto& model = drape::body::BodyModel::default_model();
    const auto shaped = drape::body::shape_from_coefficients(model, Eigen::VectorXd::Zero(K));
    const auto posed = drape::body::pose_body(model, shaped, drape::body::named_pose(drape::body::NamedPose::arms_down));
    const drape::body::Mask sil = drape::body::render_silhouette(posed.vertices, model.faces, cam, 160, 220);
    int inter = 0, uni = 0;
    for (int y = 0; y < 220; ++y)
        for (int x = 0; x < 160; ++x) {
            const bool a = sil.inside(x, y), b = labels.at<std::uint8_t>(y, x) == 41;
            inter += a && b;
            uni += a || b;
        }
    REQUIRE(uni > 1000);
    INFO("IoU with body::render_silhouette " << static_cast<double>(inter) / uni << " over " << uni << " px");
    CHECK(static_cast<double>(inter) / uni >= 0.98);
}

TEST_CASE("drape render is deterministic across thread counts", "[apps][render]") {
    const auto dir = drape::test::scratch_dir("cli_render_determinism");
    const std::string common = "render --lighting sunset --width 90 --height 130 --samples 3";
    REQUIRE(run_drape(common + " --threads 1 --out " + q(dir / "a.png")).exit_code == 0);
    REQUIRE(run_drape(common + " --threads 2 --out " + q(dir / "b.png")).exit_code == 0);
    const std::string a = file_bytes(dir / "a.png");
    CHECK(a.size() > 1000);
    CHECK(a == file_bytes(dir / "b.png"));
}

TEST_CASE("drape render explains bad input and writes nothing", "[apps][render]") {
    const auto dir = drape::test::scratch_dir("cli_render_errors");
    const std::string out = " --samples 1 --width 20 --height 30 --out " + q(dir / "x.png");
    auto r = run_drape("render --lighting noon" + out);
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.out, Catch::Contains("noon"));
    r = run_drape("render --samples 1 --width 0 --height 30 --out " + q(dir / "x.png"));
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.out, Catch::Contains("--width"));
    r = run_drape("render --mesh " + q(dir / "missing.obj") + out);
    CHECK(r.exit_code == 3);
    CHECK_THAT(r.out, Catch::Contains("missing.obj"));
    r = run_drape("render --color 300,0,0" + out);
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.out, Catch::Contains("300,0,0"));
    r = run_drape("render --camera fitted" + out);
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.out, Catch::Contains("fit-body"));
    std::ofstream(dir / "cam.json") << R"({"eye": [0, 1, 3], "target": [0, 1, 3], "focal_px": 500})";
    r = run_drape("render --camera " + q(dir / "cam.json") + out);
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.out, Catch::Contains("coincide"));
    r = run_drape("render --samples 1 --width 20 --height 30 --out " + q(dir / "no" / "such" / "x.png"));
    CHECK(r.exit_code == 3);
    CHECK_THAT(r.out, Catch::Contains("does not exist"));
    CHECK_FALSE(std::filesystem::exists(dir / "x.png"));
}
