// The C API's try-on: a skirt made for a median woman (a result folder in truth.json's schema,
// as `drape synth` and `drape recover` leave them) tried on a large man given as a body handle:
// graded, draped usable, read back through the handles, written as a folder; bad input named;
// a cancel within a bound. Compiled as C++ (drape.h in a C++ translation unit).
#include <drape/drape.h>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "../common/skirt_scene.hpp"
#include "capi_test_util.hpp"
#include "test_paths.hpp"

namespace fs = std::filesystem;
using drape::test::last_error;
using drape::test::take_json;
using drape::test::write_skirt_scene;

namespace {

// The 95th-percentile man of ANSUR II (1.87 m, 110.6 kg), other values from the prior.
drape_body large_man() {
    drape_body body = nullptr;
    REQUIRE(drape_body_create(nullptr, &body) == DRAPE_OK);
    drape_shape_params p;
    p.struct_size = sizeof p;
    REQUIRE(drape_shape_params_init(&p) == DRAPE_OK);
    p.gender = DRAPE_GENDER_MALE;
    p.height_m = 1.87;
    p.weight_kg = 110.6;
    REQUIRE(drape_body_set_shape(body, &p) == DRAPE_OK);
    return body;
}

drape_tryon_inputs inputs_of(const std::vector<const char*>& garments, drape_body body) {
    drape_tryon_inputs in;
    in.struct_size = sizeof in;
    REQUIRE(drape_tryon_inputs_init(&in) == DRAPE_OK);
    in.garments = garments.data();
    in.garment_count = garments.size();
    in.body = body;
    return in;
}


}  // namespace

TEST_CASE("tryon: a skirt graded to a large man, draped, read back and written", "[capi][tryon]") {
    const fs::path dir = drape::test::scratch_dir("capi_tryon");
    const std::string scene = write_skirt_scene(dir / "scene").string() + ":0";
    drape_body man = large_man();
    const std::vector<const char*> garments = {scene.c_str()};
    const drape_tryon_inputs in = inputs_of(garments, man);
    drape_tryon_options o;
    o.struct_size = sizeof o;
    REQUIRE(drape_tryon_options_init(&o) == DRAPE_OK);
    CHECK(o.edge_cm == 3.0);
    o.edge_cm = 8.0;  // coarse: the test's time
    struct Stages {
        std::vector<std::string> seen;
    } stages;
    drape_monitor m;
    m.struct_size = sizeof m;
    REQUIRE(drape_monitor_init(&m) == DRAPE_OK);
    m.user = &stages;
    m.progress = [](void* user, const drape_progress* p) -> int32_t {
        auto* s = static_cast<Stages*>(user);
        if (s->seen.empty() || s->seen.back() != p->stage) s->seen.emplace_back(p->stage);
        CHECK(std::string(p->operation) == "tryon");
        return 1;
    };
    drape_tryon_result r = nullptr;
    const drape_status st = drape_tryon(nullptr, &in, &o, &m, &r);
    INFO(last_error());
    REQUIRE(st == DRAPE_OK);
    REQUIRE(r != nullptr);
    CHECK(std::find(stages.seen.begin(), stages.seen.end(), "grading") != stages.seen.end());
    CHECK(std::find(stages.seen.begin(), stages.seen.end(), "draping") != stages.seen.end());

    char* text = nullptr;
    REQUIRE(drape_tryon_json(r, &text) == DRAPE_OK);
    const nlohmann::json j = take_json(text);
    const nlohmann::json& g = j.at("garments").at(0);
    CHECK(g["drape"]["usable"] == true);
    CHECK(g["drape"]["penetration_max_m"].get<double>() <= 1e-3);
    CHECK(g["drape"]["self_intersections"] == 0);
    CHECK(g["sizing"]["l1"].get<double>() > 40.0 + 5.0);  // graded up to his waistband
    CHECK(g["sizing"]["alpha"].get<double>() == Approx(90.0));  // the flare kept
    CHECK(g["grading"]["grade"]["sizes"].get<int>() >= 2);
    CHECK(g["material"]["base_fabric"] == "gray-interlock");

    size_t count = 0;
    REQUIRE(drape_tryon_get_garment_count(r, &count) == DRAPE_OK);
    REQUIRE(count == 1);
    drape_garment_mesh mesh = nullptr;
    REQUIRE(drape_tryon_get_garment_mesh(r, 0, &mesh) == DRAPE_OK);
    drape_garment_mesh none = nullptr;
    CHECK(drape_tryon_get_garment_mesh(r, 1, &none) == DRAPE_ERROR_INVALID_ARGUMENT);
    CHECK(none == nullptr);
    size_t nv = 0;
    REQUIRE(drape_garment_mesh_get_counts(mesh, &nv, nullptr, nullptr) == DRAPE_OK);
    std::vector<double> X(3 * nv);
    REQUIRE(drape_garment_mesh_get_vertices(mesh, X.data(), X.size(), nullptr) == DRAPE_OK);
    double ymin = 9, ymax = -1;
    for (size_t i = 0; i < nv; ++i) ymin = std::min(ymin, X[3 * i + 1]), ymax = std::max(ymax, X[3 * i + 1]);
    CHECK(ymax < 1.3);  // around his hips, not at the origin
    CHECK(ymin > 0.3);
    drape_body body = nullptr;
    REQUIRE(drape_tryon_get_body(r, &body) == DRAPE_OK);
    drape_measurements meas;
    meas.struct_size = sizeof meas;
    REQUIRE(drape_measurements_init(&meas) == DRAPE_OK);
    REQUIRE(drape_body_measure(body, &meas) == DRAPE_OK);
    CHECK(meas.height_m == Approx(1.87).margin(0.01));

    const fs::path out = dir / "out";
    fs::remove_all(out);
    REQUIRE(drape_tryon_write_folder(r, out.string().c_str(), nullptr) == DRAPE_OK);
    for (const char* f : {"tryon.json", "garment_0.glb", "grading_0.svg", "outfit.glb", "report.html"})
        CHECK(fs::exists(out / f));
    // A cancel before the move leaves a folder as it was.
    const fs::path kept = dir / "kept";
    fs::remove_all(kept);
    drape_cancel_flag flag = nullptr;
    REQUIRE(drape_cancel_flag_create(&flag) == DRAPE_OK);
    drape_cancel_flag_set(flag);
    drape_monitor cancel;
    cancel.struct_size = sizeof cancel;
    REQUIRE(drape_monitor_init(&cancel) == DRAPE_OK);
    cancel.cancel = flag;
    CHECK(drape_tryon_write_folder(r, kept.string().c_str(), &cancel) == DRAPE_ERROR_CANCELLED);
    CHECK_FALSE(fs::exists(kept / "tryon.json"));
    drape_cancel_flag_destroy(flag);
    drape_body_destroy(body);
    drape_garment_mesh_destroy(mesh);
    drape_tryon_destroy(r);
    drape_body_destroy(man);
}

TEST_CASE("tryon: bad input is named, and a cancel returns within a step", "[capi][tryon]") {
    const fs::path dir = drape::test::scratch_dir("capi_tryon_bad");
    const std::string scene = write_skirt_scene(dir / "scene").string();
    const std::string empty = write_skirt_scene(dir / "empty", false).string();
    drape_body man = large_man();
    drape_tryon_result r = nullptr;

    SECTION("a result folder without a garment") {
        const std::vector<const char*> g = {empty.c_str()};
        const drape_tryon_inputs in = inputs_of(g, man);
        CHECK(drape_tryon(nullptr, &in, nullptr, nullptr, &r) == DRAPE_ERROR_INVALID_ARGUMENT);
        CHECK(last_error().find("no garment") != std::string::npos);
        CHECK(last_error().find("empty") != std::string::npos);
    }
    SECTION("a garment number out of range") {
        const std::string spec = scene + ":3";
        const std::vector<const char*> g = {spec.c_str()};
        const drape_tryon_inputs in = inputs_of(g, man);
        CHECK(drape_tryon(nullptr, &in, nullptr, nullptr, &r) == DRAPE_ERROR_INVALID_ARGUMENT);
        CHECK(last_error().find(":3") != std::string::npos);
    }
    SECTION("no such folder") {
        const std::string spec = (dir / "missing").string();
        const std::vector<const char*> g = {spec.c_str()};
        const drape_tryon_inputs in = inputs_of(g, man);
        CHECK(drape_tryon(nullptr, &in, nullptr, nullptr, &r) == DRAPE_ERROR_IO);
        CHECK(last_error().find("missing") != std::string::npos);
    }
    SECTION("no garment, both targets or neither") {
        const std::vector<const char*> g = {scene.c_str()};
        drape_tryon_inputs in = inputs_of(g, man);
        in.garment_count = 0;
        CHECK(drape_tryon(nullptr, &in, nullptr, nullptr, &r) == DRAPE_ERROR_INVALID_ARGUMENT);
        CHECK(last_error().find("garments") != std::string::npos);
        in = inputs_of(g, man);
        in.image_path = "photo.jpg";
        CHECK(drape_tryon(nullptr, &in, nullptr, nullptr, &r) == DRAPE_ERROR_INVALID_ARGUMENT);
        CHECK(last_error().find("either body") != std::string::npos);
        in = inputs_of(g, nullptr);
        CHECK(drape_tryon(nullptr, &in, nullptr, nullptr, &r) == DRAPE_ERROR_INVALID_ARGUMENT);
        in.image_path = "photo.jpg";
        CHECK(drape_tryon(nullptr, &in, nullptr, nullptr, &r) == DRAPE_ERROR_INVALID_ARGUMENT);
        CHECK(last_error().find("joints_path") != std::string::npos);
    }
    SECTION("bad options") {
        const std::vector<const char*> g = {scene.c_str()};
        const drape_tryon_inputs in = inputs_of(g, man);
        drape_tryon_options o;
        o.struct_size = sizeof o;
        REQUIRE(drape_tryon_options_init(&o) == DRAPE_OK);
        o.edge_cm = -1;
        CHECK(drape_tryon(nullptr, &in, &o, nullptr, &r) == DRAPE_ERROR_INVALID_ARGUMENT);
        CHECK(last_error().find("edge") != std::string::npos);
    }
    SECTION("cancelled by another thread while draping: returns within a step") {
        const std::vector<const char*> g = {scene.c_str()};
        const drape_tryon_inputs in = inputs_of(g, man);
        drape_tryon_options o;
        o.struct_size = sizeof o;
        REQUIRE(drape_tryon_options_init(&o) == DRAPE_OK);
        o.edge_cm = 4.0;
        drape::test::CancelProbe probe("draping", 3);
        const drape_status st = probe.run([&] { return drape_tryon(nullptr, &in, &o, probe.monitor(), &r); });
        REQUIRE(probe.armed());
        CHECK(st == DRAPE_ERROR_CANCELLED);
        WARN("drape_tryon returned " << probe.latency() << " s after the cancel; the step before took "
                                   << probe.interval() << " s");
        // The monitor is asked after every step: the call returns at the next one.
        CHECK(probe.latency() < 2 * probe.interval() + 0.5);
    }
    CHECK(r == nullptr);
    drape_body_destroy(man);
}
