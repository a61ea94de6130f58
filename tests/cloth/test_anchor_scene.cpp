// The anchor scene of issue 3 (1 m square dropped on a 0.5 m sphere) against ArcSim 0.3.1's
// measured rest state, and contact behaviour on smaller versions of it.
#include <drape/cloth/intersections.hpp>
#include <drape/fixtures/cloth_scenes.hpp>
#include <drape/cloth/simulator.hpp>

#include <catch2/catch.hpp>

#include "gray_interlock_fixture.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>

using namespace drape::cloth;

namespace {

struct AnchorResult {
    double centre_z = 0, lowest_z = 0, seconds_per_step = 0;
    int failed_steps = 0, newton_iterations = 0;
    ContactReport report;
};

AnchorResult run_anchor(int n, double duration_s, bool verbose) {
    AnchorScene scene = make_anchor_scene(n);
    Simulator sim(scene.cloth, drape::test::gray_interlock_material(), scene.options);
    sim.set_obstacle(Obstacle(scene.sphere.positions, scene.sphere.faces));
    const int steps = static_cast<int>(std::lround(duration_s / scene.options.time_step_s));
    AnchorResult r;
    const auto t0 = std::chrono::steady_clock::now();
    for (int k = 0; k < steps; ++k) {
        const StepSummary s = sim.step();
        r.newton_iterations += s.newton_iterations;
        if (!s.usable()) ++r.failed_steps;
        if (verbose && (k % 20 == 0 || !s.usable()))
            std::printf("step %d t=%.3f centre z %.5f: %s\n", k, (k + 1) * scene.options.time_step_s,
                        sim.positions()(scene.centre_vertex, 2), s.brief_report().c_str());
    }
    r.seconds_per_step =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() / steps;
    r.centre_z = sim.positions()(scene.centre_vertex, 2);
    r.lowest_z = sim.positions().col(2).minCoeff();
    r.report = sim.contact_report();
    return r;
}

}  // namespace

TEST_CASE("anchor scene N = 32 vs ArcSim 0.3.1", "[cloth][anchor][.bench]") {
    const char* seconds = std::getenv("DRAPE_ANCHOR_SECONDS");  // shorter runs while developing
    const AnchorResult r = run_anchor(32, seconds ? std::atof(seconds) : 2.0, true);
    std::printf("N=32: centre z %.5f (ArcSim 0.5048), lowest z %.4f (ArcSim 0.074), %.1f ms/step, "
                "%d Newton iterations, %d failed steps, penetration %.2f mm, %d inside, "
                "%d self-intersections\n",
                r.centre_z, r.lowest_z, r.seconds_per_step * 1e3, r.newton_iterations, r.failed_steps,
                r.report.max_penetration_m * 1e3, r.report.vertices_inside, r.report.self_intersections);
    CHECK(r.failed_steps == 0);
    CHECK(std::abs(r.centre_z - 0.5048) <= 0.002);
    CHECK(std::abs(r.lowest_z - 0.074) <= 0.01);
    CHECK(r.report.max_penetration_m <= 0.001);
    CHECK(r.report.self_intersections == 0);
}

TEST_CASE("anchor scene N = 64 vs ArcSim 0.3.1", "[cloth][anchor][.bench]") {
    const AnchorResult r = run_anchor(64, 2.0, false);
    std::printf("N=64: centre z %.5f (ArcSim 0.5048), lowest z %.4f, %.1f ms/step (ArcSim 329), "
                "%d Newton iterations, %d failed steps, penetration %.2f mm, %d self-intersections\n",
                r.centre_z, r.lowest_z, r.seconds_per_step * 1e3, r.newton_iterations, r.failed_steps,
                r.report.max_penetration_m * 1e3, r.report.self_intersections);
    CHECK(r.failed_steps == 0);
    CHECK(std::abs(r.centre_z - 0.5048) <= 0.002);
    CHECK(r.report.max_penetration_m <= 0.001);
    CHECK(r.report.self_intersections == 0);
}

