// The C API's animation: a skirt recovered for a median woman (a scene folder) walks 0.4 s at
// 15 fps: every frame made and checked, the frames read back through the handle, the folder
// written; bad input named; a cancel within a bound. Compiled as C++.
#include <drape/drape.h>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

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

drape_animate_inputs inputs_of(const std::vector<const char*>& garments) {
    drape_animate_inputs in;
    in.struct_size = sizeof in;
    REQUIRE(drape_animate_inputs_init(&in) == DRAPE_OK);
    in.garments = garments.data();
    in.garment_count = garments.size();
    return in;
}

drape_animate_options short_walk() {
    drape_animate_options o;
    o.struct_size = sizeof o;
    REQUIRE(drape_animate_options_init(&o) == DRAPE_OK);
    CHECK(o.seconds == 5.0);
    CHECK(o.fps == 30.0);
    o.seconds = 0.4;
    o.fps = 15;
    o.edge_cm = 6.0;  // coarse: the test's time
    return o;
}


}  // namespace

TEST_CASE("animate: a skirt walks 0.4 s, every frame checked, read back and written", "[capi][animate]") {
    const fs::path dir = drape::test::scratch_dir("capi_animate");
    const std::string scene = write_skirt_scene(dir / "scene").string();
    const std::vector<const char*> garments = {scene.c_str()};
    const drape_animate_inputs in = inputs_of(garments);
    const drape_animate_options o = short_walk();
    struct Seen {
        bool draping = false, animating = false;
        double last_fraction = -1;
    } seen;
    drape_monitor m;
    m.struct_size = sizeof m;
    REQUIRE(drape_monitor_init(&m) == DRAPE_OK);
    m.user = &seen;
    m.progress = [](void* user, const drape_progress* p) -> int32_t {
        auto* s = static_cast<Seen*>(user);
        const std::string stage = p->stage;
        s->draping |= stage == "draping";
        if (stage == "animating") s->animating = true, s->last_fraction = p->fraction;
        return 1;
    };
    drape_animation a = nullptr;
    const drape_status st = drape_animate(nullptr, &in, &o, &m, &a);
    INFO(last_error());
    // DRAPE_OK: every frame within 2 mm of the body and free of crossings (before the
    // substep cap scaled with the frame rate this 15 fps walk went 2.6 mm deep at 6 cm and
    // 57 mm at 4 cm: docs/notes/animation.md).
    REQUIRE(st == DRAPE_OK);
    REQUIRE(a != nullptr);
    CHECK(seen.draping);
    CHECK(seen.animating);
    CHECK(seen.last_fraction == Approx(1.0));

    char* text = nullptr;
    REQUIRE(drape_animation_json(a, &text) == DRAPE_OK);
    const nlohmann::json j = take_json(text);
    CHECK(j.at("motion") == "walk");
    CHECK(j.at("fps").get<double>() == 15.0);
    CHECK(j.at("usable").get<bool>() == (st == DRAPE_OK));
    CHECK(j.at("max_self_intersections").get<int>() == 0);
    CHECK(j.at("max_penetration_m").get<double>() <= 2e-3);
    size_t frames = 0, garment_count = 0;
    REQUIRE(drape_animation_get_counts(a, &frames, &garment_count) == DRAPE_OK);
    CHECK(frames == 7);  // 0.4 s at 15 fps, both ends
    REQUIRE(garment_count == 1);

    drape_garment_mesh mesh = nullptr;
    REQUIRE(drape_animation_get_garment_mesh(a, 0, &mesh) == DRAPE_OK);
    size_t nv = 0;
    REQUIRE(drape_garment_mesh_get_counts(mesh, &nv, nullptr, nullptr) == DRAPE_OK);
    size_t required = 0;
    REQUIRE(drape_animation_get_frame_vertices(a, 0, 0, nullptr, 0, &required) == DRAPE_OK);
    REQUIRE(required == 3 * nv);
    std::vector<double> first(required), last(required);
    REQUIRE(drape_animation_get_frame_vertices(a, 0, 0, first.data(), first.size(), nullptr) == DRAPE_OK);
    REQUIRE(drape_animation_get_frame_vertices(a, 0, frames - 1, last.data(), last.size(), nullptr) == DRAPE_OK);
    CHECK(drape_animation_get_frame_vertices(a, 0, frames, last.data(), last.size(), nullptr) ==
          DRAPE_ERROR_INVALID_ARGUMENT);
    CHECK(drape_animation_get_frame_vertices(a, 1, 0, last.data(), last.size(), nullptr) ==
          DRAPE_ERROR_INVALID_ARGUMENT);
    // The skirt walks with the body: forward (+Z) by a stride's share, and stays finite.
    double dz = 0;
    for (size_t i = 0; i < nv; ++i) {
        REQUIRE(std::isfinite(last[3 * i]));
        dz += (last[3 * i + 2] - first[3 * i + 2]) / double(nv);
    }
    CHECK(dz > 0.2);

    const fs::path out = dir / "out";
    fs::remove_all(out);
    REQUIRE(drape_animation_write_folder(a, out.string().c_str(), nullptr) == DRAPE_OK);
    CHECK(fs::exists(out / "animation.glb"));
    CHECK(fs::exists(out / "animation.json"));
    CHECK(fs::exists(out / "frames" / "garment_0_0006.obj"));
    drape_garment_mesh_destroy(mesh);
    drape_animation_destroy(a);
}

TEST_CASE("animate: bad input is named, and a cancel returns within a frame", "[capi][animate]") {
    const fs::path dir = drape::test::scratch_dir("capi_animate_bad");
    const std::string scene = write_skirt_scene(dir / "scene").string();
    const std::string empty = write_skirt_scene(dir / "empty", false).string();
    const std::vector<const char*> garments = {scene.c_str()};
    drape_animation a = nullptr;

    SECTION("a result folder without a garment") {
        const std::vector<const char*> g = {empty.c_str()};
        const drape_animate_inputs in = inputs_of(g);
        CHECK(drape_animate(nullptr, &in, nullptr, nullptr, &a) == DRAPE_ERROR_INVALID_ARGUMENT);
        CHECK(last_error().find("no garment") != std::string::npos);
    }
    SECTION("a motion that is neither walk nor a BVH, and a BVH that does not parse") {
        drape_animate_inputs in = inputs_of(garments);
        in.motion = "run";
        drape_animate_options o = short_walk();
        CHECK(drape_animate(nullptr, &in, &o, nullptr, &a) == DRAPE_ERROR_INVALID_ARGUMENT);
        CHECK(last_error().find("'run'") != std::string::npos);
        const std::string bvh = (dir / "broken.bvh").string();
        std::ofstream(bvh) << "HIERARCHY\nROOT Hips\n{\n  OFFSET 0 0\n";
        in.motion = bvh.c_str();
        const drape_status st = drape_animate(nullptr, &in, &o, nullptr, &a);
        CHECK((st == DRAPE_ERROR_INVALID_ARGUMENT || st == DRAPE_ERROR_IO));
        CHECK(last_error().find("broken.bvh") != std::string::npos);
    }
    SECTION("negative fps, no garment") {
        drape_animate_inputs in = inputs_of(garments);
        drape_animate_options o = short_walk();
        o.fps = -30;
        CHECK(drape_animate(nullptr, &in, &o, nullptr, &a) == DRAPE_ERROR_INVALID_ARGUMENT);
        CHECK(last_error().find("fps") != std::string::npos);
        in.garment_count = 0;
        CHECK(drape_animate(nullptr, &in, nullptr, nullptr, &a) == DRAPE_ERROR_INVALID_ARGUMENT);
        CHECK(last_error().find("garments") != std::string::npos);
    }
    SECTION("cancelled by another thread during the motion: returns within a frame") {
        const drape_animate_inputs in = inputs_of(garments);
        const drape_animate_options o = short_walk();
        drape::test::CancelProbe probe("animating", 2);
        const drape_status st = probe.run([&] { return drape_animate(nullptr, &in, &o, probe.monitor(), &a); });
        REQUIRE(probe.armed());
        CHECK(st == DRAPE_ERROR_CANCELLED);
        WARN("drape_animate returned " << probe.latency() << " s after the cancel; the frame before took "
                                   << probe.interval() << " s");
        // The monitor is asked after every frame: the call returns at the next one.
        CHECK(probe.latency() < 2 * probe.interval() + 0.5);
    }
    CHECK(a == nullptr);
}
