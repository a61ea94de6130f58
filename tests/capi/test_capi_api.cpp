// The C API beyond bodies: patterns, garment meshes, the simulator, dressing, fitting and
// segmentation; monitors (progress, cancel with a measured bound), the error function, and
// argument checks that name the argument. Compiled as C++ (drape.h in a C++ translation unit).
#include <drape/drape.h>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "capi_test_util.hpp"
#include "test_paths.hpp"

namespace fs = std::filesystem;
using drape::test::last_error;
using drape::test::take_json;

namespace {

std::string head(const fs::path& p, size_t n) {
    std::ifstream f(p, std::ios::binary);
    std::string s(n, '\0');
    f.read(&s[0], static_cast<std::streamsize>(n));
    s.resize(static_cast<size_t>(f.gcount()));
    return s;
}

drape_monitor monitor_of(drape_progress_function progress, void* user, drape_cancel_flag cancel) {
    drape_monitor m;
    m.struct_size = sizeof m;
    drape_monitor_init(&m);
    m.progress = progress;
    m.user = user;
    m.cancel = cancel;
    return m;
}

using Clock = std::chrono::steady_clock;

}  // namespace

TEST_CASE("destroy(NULL) is a no-op for every handle", "[capi]") {
    drape_body_model_destroy(nullptr);
    drape_body_destroy(nullptr);
    drape_cancel_flag_destroy(nullptr);
    drape_segmentation_destroy(nullptr);
    drape_pattern_destroy(nullptr);
    drape_garment_mesh_destroy(nullptr);
    drape_outfit_destroy(nullptr);
    drape_simulator_destroy(nullptr);
    drape_recovery_destroy(nullptr);
    drape_free(nullptr);
    drape_cancel_flag_set(nullptr);
    CHECK(drape_cancel_flag_is_set(nullptr) == 0);
}

TEST_CASE("NULL or invalid arguments name the argument", "[capi]") {
    struct Case {
        drape_status status;
        const char* names;
    };
    drape_pattern pattern = nullptr;
    drape_garment_mesh mesh = nullptr;
    drape_simulator sim = nullptr;
    drape_outfit outfit = nullptr;
    drape_recovery recovery = nullptr;
    drape_segmentation seg = nullptr;
    char* json = nullptr;
    size_t n = 0;
    const double v[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const int32_t f[3] = {0, 1, 2};
    const int32_t bad_f[3] = {0, 1, 3};
    const std::vector<Case> cases = {
        {drape_pattern_create(nullptr, nullptr, &pattern), "garment"},
        {drape_pattern_create("skirt", nullptr, nullptr), "out_pattern"},
        {drape_pattern_create_for_body("skirt", nullptr, &pattern), "body"},
        {drape_pattern_to_json(nullptr, &json), "pattern"},
        {drape_pattern_export(nullptr, "x.svg"), "pattern"},
        {drape_garment_mesh_create(nullptr, 2.0, &mesh), "pattern"},
        {drape_garment_mesh_get_vertices(nullptr, nullptr, 0, &n), "mesh"},
        {drape_garment_mesh_export(nullptr, "x.obj"), "mesh"},
        {drape_simulator_create(nullptr, 3, f, 1, v, nullptr, nullptr, &sim), "vertices"},
        {drape_simulator_create(v, 3, f, 1, nullptr, nullptr, nullptr, &sim), "pattern_coords"},
        {drape_simulator_create(v, 3, bad_f, 1, v, nullptr, nullptr, &sim), "faces[2] = 3"},
        {drape_simulator_create_from_garment(nullptr, nullptr, nullptr, &sim), "mesh"},
        {drape_simulator_step(nullptr, 1, nullptr), "simulator"},
        {drape_simulator_set_obstacle_body(nullptr, nullptr), "simulator"},
        {drape_dress(nullptr, nullptr, 1, nullptr, nullptr, &outfit), "body"},
        {drape_outfit_get_garment_mesh(nullptr, 0, &mesh), "outfit"},
        {drape_recover(nullptr, nullptr, nullptr, nullptr, &recovery), "inputs"},
        {drape_recovery_json(nullptr, &json), "recovery"},
        {drape_recovery_write_folder(nullptr, "out", nullptr), "recovery"},
        {drape_segment(nullptr, "j.json", nullptr, &seg), "image_path"},
        {drape_segment("a.png", nullptr, nullptr, &seg), "joints_path"},
        {drape_body_fit(nullptr, nullptr, nullptr, nullptr, nullptr), "body"},
        {drape_cancel_flag_create(nullptr), "out_flag"},
        {drape_monitor_init(nullptr), "monitor"},
    };
    int k = 0;
    for (const Case& c : cases) {
        INFO("case " << k++ << ": " << c.names);
        CHECK(c.status == DRAPE_ERROR_INVALID_ARGUMENT);
    }
    // The message of each names its argument (checked on a few; the cases above share code).
    CHECK(drape_pattern_create(nullptr, nullptr, &pattern) == DRAPE_ERROR_INVALID_ARGUMENT);
    CHECK(last_error() == "drape_pattern_create: garment must not be NULL");
    CHECK(drape_simulator_create(v, 3, bad_f, 1, v, nullptr, nullptr, &sim) == DRAPE_ERROR_INVALID_ARGUMENT);
    CHECK(last_error().find("faces[2] = 3 is outside [0, 3)") != std::string::npos);
    // Meshes handed over as arrays are bounded like mesh files, refused before a value is
    // read (so the small arrays here are never read past their end).
    CHECK(drape_simulator_create(v, 2'000'001, f, 1, v, nullptr, nullptr, &sim) == DRAPE_ERROR_INVALID_ARGUMENT);
    CHECK(last_error().find(": 2000001 vertices, more than the limit of 2000000") != std::string::npos);
    CHECK(sim == nullptr);
    CHECK(drape_simulator_create(v, 3, f, 4'000'001, v, nullptr, nullptr, &sim) == DRAPE_ERROR_INVALID_ARGUMENT);
    CHECK(last_error().find("faces: 4000001 triangles, more than the limit of 4000000") != std::string::npos);
    const double uv[6] = {0, 0, 1, 0, 0, 1};
    REQUIRE(drape_simulator_create(v, 3, f, 1, uv, nullptr, nullptr, &sim) == DRAPE_OK);
    CHECK(drape_simulator_set_obstacle(sim, v, 2'000'001, f, 1) == DRAPE_ERROR_INVALID_ARGUMENT);
    CHECK(last_error().find("more than the limit of 2000000") != std::string::npos);
    CHECK(drape_simulator_set_obstacle(sim, v, 3, f, 4'000'001) == DRAPE_ERROR_INVALID_ARGUMENT);
    CHECK(last_error().find("more than the limit of 4000000") != std::string::npos);
    drape_simulator_destroy(sim);
    sim = nullptr;
    CHECK(drape_pattern_create("coat", nullptr, &pattern) == DRAPE_ERROR_INVALID_ARGUMENT);
    CHECK(last_error().find("coat") != std::string::npos);
    CHECK(pattern == nullptr);
    drape_recover_inputs in;
    in.struct_size = 2;
    CHECK(drape_recover(nullptr, &in, nullptr, nullptr, &recovery) == DRAPE_ERROR_INVALID_ARGUMENT);
    CHECK(last_error().find("inputs->struct_size is 2") != std::string::npos);
    in.struct_size = sizeof in;
    drape_recover_inputs_init(&in);
    CHECK(drape_recover(nullptr, &in, nullptr, nullptr, &recovery) == DRAPE_ERROR_INVALID_ARGUMENT);
    CHECK(last_error().find("inputs->image_path") != std::string::npos);
    in.image_path = "/nonexistent/photo.jpg";
    in.joints_path = "/nonexistent/joints.json";
    CHECK(drape_recover(nullptr, &in, nullptr, nullptr, &recovery) == DRAPE_ERROR_IO);
    CHECK(last_error().find("/nonexistent/photo.jpg") != std::string::npos);
    CHECK(recovery == nullptr);
}

TEST_CASE("the error function sees every failure, on the failing thread", "[capi]") {
    struct Seen {
        int calls = 0;
        drape_status status = DRAPE_OK;
        std::string message;
    } seen;
    drape_set_error_function(
        [](void* user, drape_status status, const char* message) {
            auto* s = static_cast<Seen*>(user);
            ++s->calls;
            s->status = status;
            s->message = message;
        },
        &seen);
    drape_pattern pattern = nullptr;
    CHECK(drape_pattern_create("skirt", "{\"l1\": \"long\"}", &pattern) == DRAPE_ERROR_INVALID_ARGUMENT);
    CHECK(seen.calls == 1);
    CHECK(seen.status == DRAPE_ERROR_INVALID_ARGUMENT);
    CHECK(seen.message == last_error());
    CHECK(seen.message.find("l1") != std::string::npos);
    REQUIRE(drape_pattern_create("skirt", nullptr, &pattern) == DRAPE_OK);  // success: not called
    CHECK(seen.calls == 1);
    drape_set_error_function(nullptr, nullptr);
    CHECK(drape_pattern_export(pattern, "/nonexistent/dir/p.svg") == DRAPE_ERROR_IO);
    CHECK(seen.calls == 1);  // removed
    drape_pattern_destroy(pattern);
}

TEST_CASE("patterns and garment meshes: JSON, accessors, exports", "[capi][garment]") {
    const fs::path dir = drape::test::scratch_dir("capi_pattern");
    drape_body body = nullptr;
    REQUIRE(drape_body_create(nullptr, &body) == DRAPE_OK);
    drape_pattern given = nullptr, sized = nullptr;
    REQUIRE(drape_pattern_create("skirt", "{\"l1\": 55}", &given) == DRAPE_OK);
    REQUIRE(drape_pattern_create_for_body("tshirt", body, &sized) == DRAPE_OK);
    char* text = nullptr;
    REQUIRE(drape_pattern_to_json(given, &text) == DRAPE_OK);
    const nlohmann::json j = take_json(text);
    CHECK(j.at("garment") == "skirt");
    CHECK(j.at("sizing").at("l1").get<double>() == 55.0);
    CHECK(j.at("panels").get<int>() >= 1);
    CHECK(j.at("area_cm2").get<double>() > 1000);
    REQUIRE(drape_pattern_to_json(sized, &text) == DRAPE_OK);
    CHECK(take_json(text).at("garment") == "tshirt");

    for (const char* ext : {".svg", ".dxf", ".json"})
        REQUIRE(drape_pattern_export(given, (dir / (std::string("p") + ext)).string().c_str()) == DRAPE_OK);
    CHECK(head(dir / "p.svg", 200).find("<svg") != std::string::npos);
    CHECK(head(dir / "p.dxf", 200).find("\n0\nSECTION\n") != std::string::npos);
    CHECK(nlohmann::json::parse(std::ifstream(dir / "p.json")).is_object());
    CHECK(drape_pattern_export(given, (dir / "p.pdf").string().c_str()) == DRAPE_ERROR_INVALID_ARGUMENT);
    CHECK(last_error().find("p.pdf") != std::string::npos);

    drape_garment_mesh mesh = nullptr;
    REQUIRE(drape_garment_mesh_create(given, 4.0, &mesh) == DRAPE_OK);
    size_t nv = 0, nf = 0, ns = 0, req = 0;
    REQUIRE(drape_garment_mesh_get_counts(mesh, &nv, &nf, &ns) == DRAPE_OK);
    CHECK(nv > 50);
    CHECK(nf > nv);
    CHECK(ns > 0);
    REQUIRE(drape_garment_mesh_get_vertices(mesh, nullptr, 0, &req) == DRAPE_OK);
    CHECK(req == 3 * nv);
    std::vector<double> V(req);
    CHECK(drape_garment_mesh_get_vertices(mesh, V.data(), req - 1, nullptr) == DRAPE_ERROR_INVALID_ARGUMENT);
    REQUIRE(drape_garment_mesh_get_vertices(mesh, V.data(), req, nullptr) == DRAPE_OK);
    std::vector<int32_t> F(3 * nf), S(2 * ns);
    REQUIRE(drape_garment_mesh_get_faces(mesh, F.data(), F.size(), nullptr) == DRAPE_OK);
    REQUIRE(drape_garment_mesh_get_stitches(mesh, S.data(), S.size(), nullptr) == DRAPE_OK);
    for (int32_t i : F) REQUIRE((i >= 0 && static_cast<size_t>(i) < nv));
    for (int32_t i : S) REQUIRE((i >= 0 && static_cast<size_t>(i) < nv));
    std::vector<double> UV(2 * nv);
    REQUIRE(drape_garment_mesh_get_pattern_coords(mesh, UV.data(), UV.size(), nullptr) == DRAPE_OK);
    // The pattern coordinates are in metres: a skirt panel spans tens of centimetres.
    double umax = 0;
    for (size_t i = 0; i < nv; ++i) umax = std::max(umax, UV[2 * i]);
    CHECK(umax > 0.3);
    CHECK(umax < 5.0);
    REQUIRE(drape_garment_mesh_export(mesh, (dir / "g.obj").string().c_str()) == DRAPE_OK);
    REQUIRE(drape_garment_mesh_export(mesh, (dir / "g.glb").string().c_str()) == DRAPE_OK);
    CHECK(head(dir / "g.glb", 4) == "glTF");
    CHECK(fs::file_size(dir / "g.obj") > 1000);
    // The flat layout (drape pattern's pattern_mesh.obj): z = 0, x and y the pattern coordinates.
    REQUIRE(drape_garment_mesh_export_flat(mesh, (dir / "flat.obj").string().c_str()) == DRAPE_OK);
    {
        std::ifstream obj(dir / "flat.obj");
        std::string line;
        size_t vertices = 0;
        double zmax = 0, xmax = 0;
        while (std::getline(obj, line)) {
            if (line.rfind("v ", 0) != 0) continue;
            std::istringstream in(line.substr(2));
            double x = 0, y = 0, z = 0;
            in >> x >> y >> z;
            zmax = std::max(zmax, std::abs(z));
            xmax = std::max(xmax, x);
            ++vertices;
        }
        CHECK(vertices == nv);
        CHECK(zmax == 0.0);
        CHECK(xmax == Approx(umax).margin(1e-6));
    }
    REQUIRE(drape_garment_mesh_export_flat(mesh, (dir / "flat.glb").string().c_str()) == DRAPE_OK);
    CHECK(head(dir / "flat.glb", 4) == "glTF");
    CHECK(drape_garment_mesh_export_flat(mesh, (dir / "flat.stl").string().c_str()) == DRAPE_ERROR_INVALID_ARGUMENT);

    // A render of the body in the skirt's placed mesh: the preview look, its label map.
    {
        drape_render_options ro;
        ro.struct_size = sizeof ro;
        REQUIRE(drape_render_options_init(&ro) == DRAPE_OK);
        CHECK(ro.samples == 16);
        CHECK(ro.opacity == 1.0);
        CHECK(ro.camera == DRAPE_RENDER_CAMERA_AUTO);
        ro.samples = 2;
        ro.width = 120;
        ro.height = 180;
        const std::string labels = (dir / "render_labels.png").string();
        ro.labels_path = labels.c_str();
        int64_t reports = 0;
        drape_monitor m = monitor_of(
            [](void* user, const drape_progress* p) -> int32_t {
                ++*static_cast<int64_t*>(user);
                return std::string(p->operation) == "render" ? 1 : 0;
            },
            &reports, nullptr);
        REQUIRE(drape_render(body, &mesh, 1, &ro, &m, (dir / "render.png").string().c_str()) == DRAPE_OK);
        CHECK(reports > 2);
        const cv::Mat img = cv::imread((dir / "render.png").string(), cv::IMREAD_COLOR);
        REQUIRE(img.cols == 120);
        REQUIRE(img.rows == 180);
        const cv::Mat L = cv::imread(labels, cv::IMREAD_UNCHANGED);
        REQUIRE(L.size() == img.size());
        CHECK(cv::countNonZero(L == 41) > 100);  // the body
        CHECK(cv::countNonZero(L == 42) > 50);   // the skirt
        // The front camera frames the same scene; a FITTED camera needs a fitted body.
        ro.camera = DRAPE_RENDER_CAMERA_FRONT;
        ro.labels_path = nullptr;
        REQUIRE(drape_render(body, &mesh, 1, &ro, nullptr, (dir / "front.png").string().c_str()) == DRAPE_OK);
        ro.camera = DRAPE_RENDER_CAMERA_FITTED;
        CHECK(drape_render(body, &mesh, 1, &ro, nullptr, (dir / "fitted.png").string().c_str()) ==
              DRAPE_ERROR_INVALID_ARGUMENT);
        CHECK(last_error().find("not fitted") != std::string::npos);
        // A look-at camera as JSON text, as `drape render --camera FILE` reads it.
        ro.camera = DRAPE_RENDER_CAMERA_AUTO;
        ro.camera_json = "{\"eye\": [0, 1, 4], \"target\": [0, 1, 0], \"focal_px\": 300}";
        REQUIRE(drape_render(body, nullptr, 0, &ro, nullptr, (dir / "lookat.png").string().c_str()) == DRAPE_OK);
        ro.camera_json = "{\"eye\": [0, 1, 4]}";
        CHECK(drape_render(body, nullptr, 0, &ro, nullptr, (dir / "bad.png").string().c_str()) ==
              DRAPE_ERROR_INVALID_ARGUMENT);
        CHECK(last_error().find("target") != std::string::npos);
        ro.camera_json = nullptr;
        // Bad options are named, before any work.
        ro.samples = 0;
        CHECK(drape_render(body, &mesh, 1, &ro, nullptr, (dir / "bad.png").string().c_str()) ==
              DRAPE_ERROR_INVALID_ARGUMENT);
        CHECK(last_error().find("samples") != std::string::npos);
        ro.samples = 2;
        ro.lighting = "moonlight";
        CHECK(drape_render(body, &mesh, 1, &ro, nullptr, (dir / "bad.png").string().c_str()) ==
              DRAPE_ERROR_INVALID_ARGUMENT);
        CHECK(last_error().find("moonlight") != std::string::npos);
        ro.lighting = nullptr;
        CHECK(drape_render(body, &mesh, 1, &ro, nullptr, (dir / "bad.jpg").string().c_str()) ==
              DRAPE_ERROR_INVALID_ARGUMENT);
        CHECK(drape_render(body, nullptr, 1, &ro, nullptr, (dir / "bad.png").string().c_str()) ==
              DRAPE_ERROR_INVALID_ARGUMENT);
        CHECK_FALSE(fs::exists(dir / "bad.png"));
        // Cancelled by the monitor: DRAPE_ERROR_CANCELLED and no file.
        drape_monitor stop = monitor_of([](void*, const drape_progress*) -> int32_t { return 0; }, nullptr, nullptr);
        CHECK(drape_render(body, &mesh, 1, &ro, &stop, (dir / "cancelled.png").string().c_str()) ==
              DRAPE_ERROR_CANCELLED);
        CHECK_FALSE(fs::exists(dir / "cancelled.png"));
    }
    drape_pattern back = nullptr;
    REQUIRE(drape_garment_mesh_get_pattern(mesh, &back) == DRAPE_OK);
    REQUIRE(drape_pattern_to_json(back, &text) == DRAPE_OK);
    CHECK(take_json(text).at("sizing").at("l1").get<double>() == 55.0);
    drape_pattern_destroy(back);
    drape_garment_mesh_destroy(mesh);
    drape_pattern_destroy(given);  // the mesh kept its own copy; destroy order is free
    drape_pattern_destroy(sized);
    drape_body_destroy(body);
}

TEST_CASE("the simulator on a raw mesh: a square falls and lands on an obstacle", "[capi][cloth]") {
    // A 0.5 m square of 9 x 9 vertices at y = 0.5, a 2 m square obstacle at y = 0.
    const int n = 8;
    const double size = 0.5;
    std::vector<double> V, UV;
    std::vector<int32_t> F;
    for (int i = 0; i <= n; ++i)
        for (int k = 0; k <= n; ++k) {
            const double u = size * k / n, w = size * i / n;
            V.insert(V.end(), {u - size / 2, 0.5, w - size / 2});
            UV.insert(UV.end(), {u, w});
        }
    for (int i = 0; i < n; ++i)
        for (int k = 0; k < n; ++k) {
            const int a = i * (n + 1) + k, b = a + 1, c = a + n + 1, d = c + 1;
            F.insert(F.end(), {a, b, d, a, d, c});  // counter-clockwise in (u, w)
        }
    const size_t nv = V.size() / 3;
    drape_simulator_options o;
    o.struct_size = sizeof o;
    REQUIRE(drape_simulator_options_init(&o) == DRAPE_OK);
    CHECK(o.gravity_y == Approx(-9.8));
    o.max_newton_iterations = 20;
    drape_simulator sim = nullptr;
    REQUIRE(drape_simulator_create(V.data(), nv, F.data(), F.size() / 3, UV.data(), "gray-interlock", &o, &sim) ==
            DRAPE_OK);
    const double ground_v[] = {-1, 0, -1, 1, 0, -1, 1, 0, 1, -1, 0, 1};
    const int32_t ground_f[] = {0, 2, 1, 0, 3, 2};  // normal +Y
    REQUIRE(drape_simulator_set_obstacle(sim, ground_v, 4, ground_f, 2) == DRAPE_OK);

    // Cancelled before the first step: nothing moves.
    drape_cancel_flag flag = nullptr;
    REQUIRE(drape_cancel_flag_create(&flag) == DRAPE_OK);
    drape_cancel_flag_set(flag);
    drape_monitor m = monitor_of(nullptr, nullptr, flag);
    CHECK(drape_simulator_step(sim, 5, &m) == DRAPE_ERROR_CANCELLED);
    std::vector<double> X(V.size());
    REQUIRE(drape_simulator_get_vertices(sim, X.data(), X.size(), nullptr) == DRAPE_OK);
    CHECK(X == V);
    drape_cancel_flag_reset(flag);

    // 10 ms steps: after 0.1 s of free fall (with air drag) it is lower, but not yet down.
    int steps_seen = 0;
    m = monitor_of(
        [](void* user, const drape_progress* p) -> int32_t {
            ++*static_cast<int*>(user);
            return std::string(p->operation) == "simulate" && std::string(p->stage) == "step";
        },
        &steps_seen, flag);
    REQUIRE(drape_simulator_step(sim, 10, &m) == DRAPE_OK);
    CHECK(steps_seen == 10);
    REQUIRE(drape_simulator_get_vertices(sim, X.data(), X.size(), nullptr) == DRAPE_OK);
    double mean_y = 0;
    for (size_t i = 0; i < nv; ++i) mean_y += X[3 * i + 1] / nv;
    CHECK(mean_y < 0.5 - 0.01);
    CHECK(mean_y > 0.5 - 0.5 * 9.8 * 0.1 * 0.1 - 0.01);  // no faster than free fall
    // Then it lands and stays on the obstacle (contact thickness 5 mm).
    REQUIRE(drape_simulator_step(sim, 150, nullptr) == DRAPE_OK);
    REQUIRE(drape_simulator_get_vertices(sim, X.data(), X.size(), nullptr) == DRAPE_OK);
    double min_y = 1, max_y = -1;
    for (size_t i = 0; i < nv; ++i) {
        min_y = std::min(min_y, X[3 * i + 1]);
        max_y = std::max(max_y, X[3 * i + 1]);
    }
    CHECK(min_y > -1e-3);
    CHECK(max_y < 0.02);
    char* text = nullptr;
    REQUIRE(drape_simulator_report_json(sim, &text) == DRAPE_OK);
    CHECK(take_json(text).at("vertices_inside") == 0);
    size_t count_v = 0, count_f = 0;
    REQUIRE(drape_simulator_get_counts(sim, &count_v, &count_f) == DRAPE_OK);
    CHECK(count_v == nv);
    CHECK(count_f == F.size() / 3);
    // Without the obstacle the square falls through where it lay.
    REQUIRE(drape_simulator_clear_obstacle(sim) == DRAPE_OK);
    REQUIRE(drape_simulator_step(sim, 20, nullptr) == DRAPE_OK);
    REQUIRE(drape_simulator_get_vertices(sim, X.data(), X.size(), nullptr) == DRAPE_OK);
    double fallen_max_y = -1;
    for (size_t i = 0; i < nv; ++i) fallen_max_y = std::max(fallen_max_y, X[3 * i + 1]);
    CHECK(fallen_max_y < -0.01);
    // set_vertices checks its size.
    CHECK(drape_simulator_set_vertices(sim, V.data(), V.size() - 1) == DRAPE_ERROR_INVALID_ARGUMENT);
    REQUIRE(drape_simulator_set_vertices(sim, V.data(), V.size()) == DRAPE_OK);
    REQUIRE(drape_simulator_pin(sim, 0) == DRAPE_OK);
    CHECK(drape_simulator_pin(sim, nv) == DRAPE_ERROR_INVALID_ARGUMENT);

    // Cancelled in the middle by the flag, set from the 3rd step report (the callback says
    // "go on"): the call stops at its next check, a Newton iteration of the 4th step, and
    // keeps the steps done. Then the static solve, cancelled from its first report.
    struct Canceller {
        drape_cancel_flag flag = nullptr;
        const char* stage = "step";
        int reports = 0, set_at_report = 3;
        Clock::time_point set_at{};
    } c;
    c.flag = flag;
    m = monitor_of(
        [](void* user, const drape_progress* p) -> int32_t {
            auto* cc = static_cast<Canceller*>(user);
            if (std::string(p->stage) == cc->stage && ++cc->reports == cc->set_at_report) {
                cc->set_at = Clock::now();
                drape_cancel_flag_set(cc->flag);
            }
            return 1;
        },
        &c, flag);
    CHECK(drape_simulator_step(sim, 50, &m) == DRAPE_ERROR_CANCELLED);
    double latency = std::chrono::duration<double>(Clock::now() - c.set_at).count();
    CHECK(c.reports == 3);
    CHECK(latency < 2.0);  // one Newton iteration of an 81-vertex square
    REQUIRE(drape_simulator_get_vertices(sim, X.data(), X.size(), nullptr) == DRAPE_OK);
    mean_y = 0;
    for (size_t i = 0; i < nv; ++i) mean_y += X[3 * i + 1] / nv;
    CHECK(mean_y < 0.5 - 1e-4);  // the three steps done are kept
    drape_cancel_flag_reset(flag);
    c.stage = "static_solve";
    c.reports = 0;
    c.set_at_report = 1;
    CHECK(drape_simulator_solve_static(sim, &m) == DRAPE_ERROR_CANCELLED);
    latency = std::chrono::duration<double>(Clock::now() - c.set_at).count();
    CHECK(c.reports == 1);
    CHECK(latency < 2.0);
    CHECK(last_error() == "drape_simulator_solve_static: cancelled");
    drape_cancel_flag_destroy(flag);
    drape_simulator_destroy(sim);
}

TEST_CASE("dress: a skirt draped on a body, and a cancel within a bound", "[capi][garment]") {
    const fs::path dir = drape::test::scratch_dir("capi_dress");
    drape_body body = nullptr;
    REQUIRE(drape_body_create(nullptr, &body) == DRAPE_OK);
    drape_garment_spec spec;
    spec.struct_size = sizeof spec;
    REQUIRE(drape_garment_spec_init(&spec) == DRAPE_OK);
    spec.garment = "skirt";
    drape_dress_options o;
    o.struct_size = sizeof o;
    REQUIRE(drape_dress_options_init(&o) == DRAPE_OK);
    o.edge_cm = 4.0;

    SECTION("draped, usable, exported") {
        struct Count {
            int calls = 0;
            int64_t last_step = 0;
        } count;
        drape_monitor m = monitor_of(
            [](void* user, const drape_progress* p) -> int32_t {
                auto* c = static_cast<Count*>(user);
                ++c->calls;
                c->last_step = p->step;
                return 1;
            },
            &count, nullptr);
        drape_outfit outfit = nullptr;
        const drape_status st = drape_dress(body, &spec, 1, &o, &m, &outfit);
        INFO(last_error());
        REQUIRE(st == DRAPE_OK);
        REQUIRE(outfit != nullptr);
        char* text = nullptr;
        REQUIRE(drape_outfit_summary_json(outfit, &text) == DRAPE_OK);
        const nlohmann::json s = take_json(text);
        CHECK(s.at("usable") == true);
        CHECK(s.at("penetration_max_m").get<double>() <= 1e-3);
        CHECK(s.at("garments").size() == 1);
        CHECK(count.calls > 20);  // one per step at least 20 steps (DrapeOptions::min_steps)
        CHECK(count.last_step == s.at("steps").get<int64_t>());
        size_t garments = 0;
        REQUIRE(drape_outfit_get_garment_count(outfit, &garments) == DRAPE_OK);
        REQUIRE(garments == 1);
        drape_garment_mesh mesh = nullptr;
        REQUIRE(drape_outfit_get_garment_mesh(outfit, 0, &mesh) == DRAPE_OK);
        drape_garment_mesh none = nullptr;
        CHECK(drape_outfit_get_garment_mesh(outfit, 1, &none) == DRAPE_ERROR_INVALID_ARGUMENT);
        CHECK(none == nullptr);
        const drape_status exported = drape_garment_mesh_export(mesh, (dir / "skirt.glb").string().c_str());
        INFO(last_error());
        REQUIRE(exported == DRAPE_OK);
        CHECK(head(dir / "skirt.glb", 4) == "glTF");
        // The draped skirt hangs around the hips: within the body's height range, below the waist.
        size_t nv = 0;
        drape_garment_mesh_get_counts(mesh, &nv, nullptr, nullptr);
        std::vector<double> X(3 * nv);
        REQUIRE(drape_garment_mesh_get_vertices(mesh, X.data(), X.size(), nullptr) == DRAPE_OK);
        double ymax = -1, ymin = 9;
        for (size_t i = 0; i < nv; ++i) ymax = std::max(ymax, X[3 * i + 1]), ymin = std::min(ymin, X[3 * i + 1]);
        CHECK(ymax < 1.2);
        CHECK(ymin > 0.2);
        drape_pattern pattern = nullptr;
        REQUIRE(drape_garment_mesh_get_pattern(mesh, &pattern) == DRAPE_OK);
        REQUIRE(drape_pattern_export(pattern, (dir / "skirt.svg").string().c_str()) == DRAPE_OK);
        size_t nb = 0;
        REQUIRE(drape_outfit_get_body_vertices(outfit, nullptr, 0, &nb) == DRAPE_OK);
        CHECK(nb > 1000);
        drape_pattern_destroy(pattern);
        drape_garment_mesh_destroy(mesh);
        drape_outfit_destroy(outfit);
    }

    SECTION("cancelled by another thread during the simulation: returns within a step") {
        // The callback only says when the third simulation step has been reported; another
        // thread then sets the flag, as a host's UI would, and the call must notice it within
        // the next step (the flag is checked after every Newton iteration). The bound is the
        // duration of the step before (steps take 0.1-3 s depending on the machine's load).
        struct Cancel {
            drape_cancel_flag flag = nullptr;
            std::atomic<bool> armed{false};
            std::atomic<bool> done{false};
            Clock::time_point at{}, previous_report{};
            double step_seconds = 0;
        } c;
        REQUIRE(drape_cancel_flag_create(&c.flag) == DRAPE_OK);
        drape_monitor m = monitor_of(
            [](void* user, const drape_progress* p) -> int32_t {
                auto* state = static_cast<Cancel*>(user);
                const Clock::time_point now = Clock::now();
                if (std::string(p->stage) != "dressing" && p->step >= 2 && !state->armed) {
                    if (p->step == 3) {
                        state->step_seconds = std::chrono::duration<double>(now - state->previous_report).count();
                        state->armed = true;
                    }
                }
                state->previous_report = now;
                return 1;
            },
            &c, c.flag);
        std::thread canceller([&c] {
            while (!c.armed && !c.done) std::this_thread::sleep_for(std::chrono::milliseconds(1));
            if (c.done) return;
            c.at = Clock::now();
            drape_cancel_flag_set(c.flag);
        });
        drape_outfit outfit = nullptr;
        o.edge_cm = 1.5;  // the default resolution: a step takes what a real drape's does
        const drape_status st = drape_dress(body, &spec, 1, &o, &m, &outfit);
        const Clock::time_point returned = Clock::now();
        c.done = true;
        canceller.join();
        REQUIRE(c.armed);
        const double latency = std::chrono::duration<double>(returned - c.at).count();
        CHECK(st == DRAPE_ERROR_CANCELLED);
        CHECK(outfit == nullptr);
        CHECK(last_error() == "drape_dress: cancelled");
        WARN("drape_dress returned " << latency << " s after another thread set the cancel flag; the step before took "
                                     << c.step_seconds << " s");
        CHECK(latency < c.step_seconds + 0.2);
        drape_cancel_flag_destroy(c.flag);
    }
    drape_body_destroy(body);
}

TEST_CASE("fit a body to a shared photo, then segment it", "[capi][body][vision]") {
    DRAPE_REQUIRE_SHARED(photos, "data/photos");
    const std::string name = "fashionista_002149";
    const std::string image = (photos / "images" / (name + ".jpg")).string();
    const std::string joints = (photos / "joints" / (name + ".json")).string();
    const std::string labels = (photos / "labels" / (name + ".png")).string();
    drape_body body = nullptr;
    REQUIRE(drape_body_create(nullptr, &body) == DRAPE_OK);
    drape_fit_inputs in;
    in.struct_size = sizeof in;
    REQUIRE(drape_fit_inputs_init(&in) == DRAPE_OK);
    in.image_path = image.c_str();
    in.joints_path = joints.c_str();
    in.labels_path = labels.c_str();

    SECTION("cancelled at the first report: the body is unchanged") {
        char* before = nullptr;
        REQUIRE(drape_body_to_json(body, &before) == DRAPE_OK);
        drape_monitor m = monitor_of([](void*, const drape_progress*) -> int32_t { return 0; }, nullptr, nullptr);
        CHECK(drape_body_fit(body, &in, nullptr, &m, nullptr) == DRAPE_ERROR_CANCELLED);
        char* after = nullptr;
        REQUIRE(drape_body_to_json(body, &after) == DRAPE_OK);
        CHECK(std::string(before) == after);
        drape_free(before);
        drape_free(after);
    }
    SECTION("cancelled in the middle of the fit, by the flag: promptly, the body unchanged") {
        // The callback sets the flag when the fit first reports progress and says "go on":
        // the flag alone must stop the call, at its next check.
        struct Canceller {
            drape_cancel_flag flag = nullptr;
            Clock::time_point set_at{};
            bool set = false;
        } c;
        REQUIRE(drape_cancel_flag_create(&c.flag) == DRAPE_OK);
        drape_monitor m = monitor_of(
            [](void* user, const drape_progress* p) -> int32_t {
                auto* cc = static_cast<Canceller*>(user);
                if (!cc->set && std::string(p->stage) == "fitting" && p->fraction > 0) {
                    cc->set_at = Clock::now();
                    cc->set = true;
                    drape_cancel_flag_set(cc->flag);
                }
                return 1;
            },
            &c, c.flag);
        char* before = nullptr;
        REQUIRE(drape_body_to_json(body, &before) == DRAPE_OK);
        CHECK(drape_body_fit(body, &in, nullptr, &m, nullptr) == DRAPE_ERROR_CANCELLED);
        REQUIRE(c.set);
        const double latency = std::chrono::duration<double>(Clock::now() - c.set_at).count();
        WARN("fit cancelled " << latency << " s after the flag was set");
        CHECK(latency < 10.0);  // the fit checks at every solver iteration (docs/c-api.md)
        char* after = nullptr;
        REQUIRE(drape_body_to_json(body, &after) == DRAPE_OK);
        CHECK(std::string(before) == after);
        drape_free(before);
        drape_free(after);
        drape_cancel_flag_destroy(c.flag);
    }
    SECTION("fitted into a folder: the files of drape fit-body, the body shaped and posed; or nothing") {
        // (drape_body_fit's JSON without a folder: the options section below.)
        const fs::path dir = drape::test::scratch_dir("capi_fit_folder");
        const fs::path out = dir / "fit";
        char* text = nullptr;
        const drape_status st = drape_body_fit_to_folder(body, &in, nullptr, nullptr, out.string().c_str(), &text);
        INFO(last_error());
        REQUIRE(st == DRAPE_OK);
        const nlohmann::json j = take_json(text);
        CHECK(j.at("format") == "drape.body_fit");
        CHECK(j.at("fit").at("mean_joint_error_percent").get<double>() < 2.5);
        CHECK(j.at("pixel_origin") == "one_based");
        REQUIRE(drape_body_to_json(body, &text) == DRAPE_OK);
        const nlohmann::json b = take_json(text);
        CHECK(b.at("shape").at("height_m").get<double>() == Approx(j.at("shape").at("height_m").get<double>()));
        CHECK(b.at("pose") == j.at("pose"));
        std::ifstream f(out / "body.json");
        CHECK(nlohmann::json::parse(f) == j);
        CHECK(head(out / "body.glb", 4) == "glTF");
        CHECK(head(out / "overlay.png", 4) == "\x89PNG");
        for (const auto& e : fs::directory_iterator(out))
            CHECK(e.path().filename().string().rfind('.', 0) != 0);  // no staging folder left
        // A folder that cannot be made (under a regular file) is refused before the fit.
        std::ofstream(dir / "blocker") << "a file";
        const auto t0 = Clock::now();
        CHECK(drape_body_fit_to_folder(body, &in, nullptr, nullptr, (dir / "blocker" / "fit").string().c_str(),
                                       nullptr) == DRAPE_ERROR_IO);
        CHECK(last_error().find("blocker") != std::string::npos);
        CHECK(std::chrono::duration<double>(Clock::now() - t0).count() < 5.0);
        CHECK(drape_body_fit_to_folder(body, &in, nullptr, nullptr, nullptr, nullptr) == DRAPE_ERROR_INVALID_ARGUMENT);
        CHECK(last_error().find("folder") != std::string::npos);
    }
    SECTION("options: the posture priors and the image joints' convention") {
        drape_fit_options o;
        o.struct_size = sizeof o;
        REQUIRE(drape_fit_options_init(&o) == DRAPE_OK);
        CHECK(o.posture_weight == 100.0);
        CHECK(o.lean_weight == 1000.0);
        CHECK(o.image_joints == DRAPE_IMAGE_JOINTS_FROM_FILE);
        // Without the priors the body bends in depth (docs/body-fitting.md, "Posture").
        char* text = nullptr;
        REQUIRE(drape_body_fit(body, &in, &o, nullptr, &text) == DRAPE_OK);
        const nlohmann::json upright = take_json(text);
        o.posture_weight = 0;
        o.lean_weight = 0;
        o.image_joints = DRAPE_IMAGE_JOINTS_MODEL;
        REQUIRE(drape_body_fit(body, &in, &o, nullptr, &text) == DRAPE_OK);
        const nlohmann::json bent = take_json(text);
        CHECK(bent.at("fit").at("trunk_out_of_plane_deg").get<double>() >
              upright.at("fit").at("trunk_out_of_plane_deg").get<double>() + 10.0);
        // An older, smaller struct (without the new fields) gets the defaults.
        drape_fit_options old;
        old.struct_size = offsetof(drape_fit_options, posture_weight);
        REQUIRE(drape_fit_options_init(&old) == DRAPE_OK);
        REQUIRE(drape_body_fit(body, &in, &old, nullptr, &text) == DRAPE_OK);
        const nlohmann::json again = take_json(text);
        CHECK(again.at("pose") == upright.at("pose"));
        o.image_joints = 7;
        CHECK(drape_body_fit(body, &in, &o, nullptr, nullptr) == DRAPE_ERROR_INVALID_ARGUMENT);
        CHECK(last_error().find("image_joints") != std::string::npos);
        o.image_joints = DRAPE_IMAGE_JOINTS_MODEL;
        o.posture_weight = -1;
        CHECK(drape_body_fit(body, &in, &o, nullptr, nullptr) == DRAPE_ERROR_INVALID_ARGUMENT);
        CHECK(last_error().find("posture_weight") != std::string::npos);
        // The skin mask's weight (`drape fit-body --skin-weight`).
        drape_fit_options_init(&o);
        CHECK(o.skin_weight == 2.0);
        o.skin_weight = -1;
        CHECK(drape_body_fit(body, &in, &o, nullptr, nullptr) == DRAPE_ERROR_INVALID_ARGUMENT);
        CHECK(last_error().find("skin_weight") != std::string::npos);
        o.skin_weight = 0;  // no skin term: another fit
        REQUIRE(drape_body_fit(body, &in, &o, nullptr, &text) == DRAPE_OK);
        const nlohmann::json no_skin = take_json(text);
        CHECK(no_skin.at("coefficients") != upright.at("coefficients"));
    }
    SECTION("bad inputs name the file") {
        in.labels_path = nullptr;
        CHECK(drape_body_fit(body, &in, nullptr, nullptr, nullptr) == DRAPE_ERROR_INVALID_ARGUMENT);
        CHECK(last_error().find("silhouette") != std::string::npos);
        in.labels_path = "/nonexistent/labels.png";
        CHECK(drape_body_fit(body, &in, nullptr, nullptr, nullptr) == DRAPE_ERROR_IO);
        CHECK(last_error().find("/nonexistent/labels.png") != std::string::npos);
    }
    drape_body_destroy(body);

    SECTION("segmentation: labels and garments.json") {
        drape_segmentation seg = nullptr;
        REQUIRE(drape_segment(image.c_str(), joints.c_str(), nullptr, &seg) == DRAPE_OK);
        int32_t w = 0, h = 0;
        REQUIRE(drape_segmentation_get_size(seg, &w, &h) == DRAPE_OK);
        CHECK(w > 100);
        CHECK(h > 100);
        size_t req = 0;
        REQUIRE(drape_segmentation_get_labels(seg, nullptr, 0, &req) == DRAPE_OK);
        REQUIRE(req == static_cast<size_t>(w) * static_cast<size_t>(h));
        std::vector<uint8_t> L(req);
        REQUIRE(drape_segmentation_get_labels(seg, L.data(), L.size(), nullptr) == DRAPE_OK);
        char* text = nullptr;
        REQUIRE(drape_segmentation_garments_json(seg, &text) == DRAPE_OK);
        const nlohmann::json g = take_json(text);
        CHECK(g.at("format") == "drape.garments");
        REQUIRE(g.at("garments").size() >= 1);
        // Every garment's class covers pixels of the label map, as many as its area says.
        for (const auto& garment : g.at("garments")) {
            const int id = garment.at("label_id");
            const auto count = std::count(L.begin(), L.end(), static_cast<uint8_t>(id));
            CHECK(count == garment.at("area_px").get<long>());
        }
        const fs::path dir = drape::test::scratch_dir("capi_segment");
        REQUIRE(drape_segmentation_export_labels(seg, (dir / "labels.png").string().c_str()) == DRAPE_OK);
        CHECK(fs::file_size(dir / "labels.png") > 100);
        // The occlusion mask, in the labels' protocol: 0 or 255, something in front somewhere.
        size_t occ_req = 0;
        REQUIRE(drape_segmentation_get_occlusion(seg, nullptr, 0, &occ_req) == DRAPE_OK);
        REQUIRE(occ_req == req);
        std::vector<uint8_t> O(occ_req);
        CHECK(drape_segmentation_get_occlusion(seg, O.data(), O.size() - 1, nullptr) == DRAPE_ERROR_INVALID_ARGUMENT);
        REQUIRE(drape_segmentation_get_occlusion(seg, O.data(), O.size(), nullptr) == DRAPE_OK);
        CHECK(std::all_of(O.begin(), O.end(), [](uint8_t v) { return v == 0 || v == 255; }));
        CHECK(std::count(O.begin(), O.end(), uint8_t(255)) > 0);
        // The folder of drape segment.
        const fs::path folder = dir / "segment";
        REQUIRE(drape_segmentation_write_folder(seg, folder.string().c_str()) == DRAPE_OK);
        for (const char* file : {"labels.png", "occlusion.png", "overlay.png", "folds.png"})
            CHECK(head(folder / file, 4) == "\x89PNG");
        std::ifstream gf(folder / "garments.json");
        CHECK(nlohmann::json::parse(gf) == g);
        std::ofstream(dir / "blocker") << "a file";
        CHECK(drape_segmentation_write_folder(seg, (dir / "blocker" / "x").string().c_str()) == DRAPE_ERROR_IO);
        CHECK(last_error().find("blocker") != std::string::npos);
        CHECK(drape_segmentation_write_folder(seg, nullptr) == DRAPE_ERROR_INVALID_ARGUMENT);
        drape_segmentation_destroy(seg);
    }
}
