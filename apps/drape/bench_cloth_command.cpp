// drape bench-cloth [--scene square-sphere] [--grid 32] [--steps N | --seconds 2]
//                   [--material NAME|PATH] [--threads N] [--json] [--out R.json]
// The anchor scene of issue 3 (a 1 m square dropped on a 0.5 m sphere), timed, with the
// rest-state figures to compare against ArcSim 0.3.1 (docs/cloth.md, docs/benchmarks.md).
#include "commands.hpp"
#include <drape/io/json_io.hpp>
#include <drape/io/material_arg.hpp>

#include <drape/cloth/material.hpp>
#include <drape/fixtures/cloth_scenes.hpp>
#include <drape/cloth/simulator.hpp>
#include <drape/core/errors.hpp>

#include <CLI/CLI.hpp>
#include <tbb/global_control.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

namespace drape::app {

using namespace io;

namespace {

struct BenchClothArgs {
    std::string scene = "square-sphere";
    int grid = 32;
    int steps = -1;        // -1: --seconds decides
    double seconds = 2.0;
    std::string material = "gray-interlock";
    int threads = 0;
    int max_newton = 0;    // 0: the scene's default
    int max_nonconvex = -1;  // -1: the scene's default
    double tolerance = 0;  // 0: the scene's default
    double move_tolerance = -1;  // < 0: the scene's default
    std::string out;
    bool json = false;
    bool quiet = false;
};

void run_bench_cloth(const BenchClothArgs& args) {
    require(args.scene == "square-sphere", "drape bench-cloth: --scene ", args.scene,
            " is not a known scene (known: square-sphere)");
    require(args.grid >= 2 && args.grid % 2 == 0 && args.grid <= 512, "drape bench-cloth: --grid ",
            args.grid, " must be even and in [2, 512]");
    require(args.steps == -1 || (args.steps >= 1 && args.steps <= 100000), "drape bench-cloth: --steps ", args.steps,
            " must be in [1, 100000]");
    require(std::isfinite(args.seconds) && args.seconds > 0 && args.seconds <= 60,
            "drape bench-cloth: --seconds ", args.seconds, " must be in (0, 60]");
    require(args.threads >= 0, "drape bench-cloth: --threads ", args.threads, " must be >= 0");
    std::optional<tbb::global_control> limit;
    if (args.threads > 0) limit.emplace(tbb::global_control::max_allowed_parallelism, args.threads);

    require(args.max_newton >= 0 && args.max_newton <= 1000, "drape bench-cloth: --max-newton ",
            args.max_newton, " must be in [1, 1000]");
    require(args.max_nonconvex >= -1 && args.max_nonconvex <= 1000, "drape bench-cloth: --max-nonconvex ",
            args.max_nonconvex, " must be in [0, 1000]");
    require(std::isfinite(args.tolerance) && args.tolerance >= 0, "drape bench-cloth: --step-tolerance ",
            args.tolerance, " must be > 0");
    require(args.move_tolerance < 0 || (std::isfinite(args.move_tolerance) && args.move_tolerance <= 0.01),
            "drape bench-cloth: --step-move-tolerance ", args.move_tolerance, " must be in [0, 0.01] m");
    cloth::AnchorScene scene = cloth::make_anchor_scene(args.grid);
    if (args.move_tolerance >= 0) scene.options.step_displacement_tolerance_m = args.move_tolerance;
    if (args.max_newton > 0) scene.options.max_newton_iterations = args.max_newton;
    if (args.tolerance > 0) scene.options.step_relative_tolerance = args.tolerance;
    if (args.max_nonconvex >= 0) scene.options.max_nonconvex_step_iterations = args.max_nonconvex;
    cloth::Simulator sim(scene.cloth, load_material_arg(args.material, ""), scene.options);
    sim.set_obstacle(cloth::Obstacle(scene.sphere.positions, scene.sphere.faces));
    const double dt = scene.options.time_step_s;
    const int steps = args.steps >= 1 ? args.steps : std::max(1, static_cast<int>(std::lround(args.seconds / dt)));
    int slowest_step = 0;
    std::string slowest_report;
    int failed = 0, iterations = 0, refactorisations = 0, factorisations = 0;
    double slowest = 0, assembly = 0, solve = 0, contact = 0;
    const auto t0 = std::chrono::steady_clock::now();
    for (int k = 0; k < steps; ++k) {
        const cloth::StepSummary s = sim.step();
        iterations += s.newton_iterations;
        refactorisations += s.regularised_factorisations;
        factorisations += s.factorisations;
        failed += s.usable() ? 0 : 1;
        if (s.seconds_total > slowest) {
            slowest = s.seconds_total;
            slowest_step = k;
            slowest_report = s.brief_report();
        }
        assembly += s.seconds_assembly;
        solve += s.seconds_solve;
        contact += s.seconds_contact;
        if (!args.quiet && (k + 1) % 40 == 0)
            std::printf("t = %.2f s: centre z %.4f m, %s\n", (k + 1) * dt,
                        sim.positions()(scene.centre_vertex, 2), s.brief_report().c_str());
    }
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const cloth::ContactReport report = sim.contact_report();
    const double ms = 1e3 * wall / steps;
    nlohmann::json j;
    j["scene"] = args.scene;
    j["grid"] = args.grid;
    j["nodes"] = sim.mesh().vertex_count();
    j["material"] = args.material;
    j["time_step_s"] = dt;
    j["steps"] = steps;
    j["seconds_simulated"] = steps * dt;
    j["threads"] = args.threads > 0 ? args.threads
                                    : static_cast<int>(tbb::global_control::active_value(
                                          tbb::global_control::max_allowed_parallelism));
    j["ms_per_step"] = ms;
    j["ms_assembly_per_step"] = 1e3 * assembly / steps;
    j["ms_solve_per_step"] = 1e3 * solve / steps;
    j["ms_contact_per_step"] = 1e3 * contact / steps;
    j["slowest_step_ms"] = 1e3 * slowest;
    j["slowest_step"] = slowest_step;
    j["newton_iterations_per_step"] = static_cast<double>(iterations) / steps;
    j["regularised_factorisations_per_step"] = static_cast<double>(refactorisations) / steps;
    j["factorisations_per_step"] = static_cast<double>(factorisations) / steps;
    j["failed_steps"] = failed;
    j["max_nonconvex_step_iterations"] = scene.options.max_nonconvex_step_iterations;
    j["step_displacement_tolerance_m"] = scene.options.step_displacement_tolerance_m;
    j["centre_z_m"] = sim.positions()(scene.centre_vertex, 2);
    j["min_z_m"] = sim.positions().col(2).minCoeff();
    j["max_penetration_m"] = report.max_penetration_m;
    j["self_intersections"] = report.self_intersections;
    // ArcSim 0.3.1 on this machine (issue 3): rest state for N = 32 after 2 s, time per step
    // for N = 32 and 64 with 2 threads.
    nlohmann::json arcsim = {{"centre_z_m", 0.5048}};
    if (args.grid == 32) {
        arcsim["min_z_m"] = 0.074;
        arcsim["ms_per_step"] = 69;
    } else if (args.grid == 64) {
        arcsim["ms_per_step"] = 329;
    }
    j["arcsim_0_3_1"] = arcsim;

    std::printf("square-sphere, grid %d (%d nodes), %s, dt %.0f ms, %d steps (%.2f s)\n", args.grid,
                sim.mesh().vertex_count(), args.material.c_str(), dt * 1e3, steps, steps * dt);
    std::printf("  %.1f ms per step: assembly %.1f, factorisation + solve %.1f, contact detection %.1f, "
                "other %.1f; %.2f Newton iterations (+%.2f regularised factorisations) per step, slowest step %.1f ms, %d failed\n",
                ms, 1e3 * assembly / steps, 1e3 * solve / steps, 1e3 * contact / steps,
                std::max(0.0, ms - 1e3 * (assembly + solve + contact) / steps),
                static_cast<double>(iterations) / steps, static_cast<double>(refactorisations) / steps,
                1e3 * slowest, failed);
    std::printf("  %.2f Cholesky factorisations per step\n", static_cast<double>(factorisations) / steps);
    std::printf("  slowest: step %d (t = %.3f s), %s\n", slowest_step, (slowest_step + 1) * dt,
                slowest_report.c_str());
    std::printf("  centre z %.5f m, lowest z %.4f m, max penetration %.2f mm, %d self-intersections\n",
                j["centre_z_m"].get<double>(), j["min_z_m"].get<double>(), report.max_penetration_m * 1e3,
                report.self_intersections);
    if (arcsim.contains("ms_per_step"))
        std::printf("  ArcSim 0.3.1: %.0f ms per step (speed-up over it: %.2fx)%s\n", arcsim["ms_per_step"].get<double>(),
                    arcsim["ms_per_step"].get<double>() / ms,
                    args.grid == 32 ? ", centre z 0.5048 m, lowest z 0.074 m" : "");
    if (!args.out.empty()) write_json_file(args.out, j);
    if (args.json) std::printf("%s\n", j.dump().c_str());
}

}  // namespace

void add_bench_cloth_command(CLI::App& app) {
    auto args = std::make_shared<BenchClothArgs>();
    CLI::App* cmd = app.add_subcommand(
        "bench-cloth", "Time the cloth simulator on the anchor scene (square dropped on a sphere)");
    cmd->add_option("--scene", args->scene, "scene (square-sphere: issue 3's anchor scene)");
    cmd->add_option("--grid,--n", args->grid, "grid cells per side (32: 1089 nodes, 64: 4225 nodes)");
    auto* steps = cmd->add_option("--steps", args->steps, "number of 5 ms steps (default: --seconds)");
    cmd->add_option("--seconds", args->seconds, "simulated time (s), default 2")->excludes(steps);
    cmd->add_option("--material", args->material, "built-in fabric name or material file");
    cmd->add_option("--threads", args->threads, "worker threads (0 = all cores)");
    cmd->add_option("--max-newton", args->max_newton, "Newton iterations per step at most (default 100)");
    cmd->add_option("--max-nonconvex", args->max_nonconvex,
                    "end a step after this many regularised (not convex) Newton iterations, 0 = never "
                    "(default 4)");
    cmd->add_option("--step-move-tolerance", args->move_tolerance,
                    "a step ends on a full Newton step moving no vertex farther than this (m; 0 = off)");
    cmd->add_option("--step-tolerance", args->tolerance,
                    "Newton tolerance of a step relative to the largest vertex weight (default 0.01)");
    cmd->add_option("--out", args->out, "also write the figures to this JSON file");
    cmd->add_flag("--json", args->json, "print the figures as one JSON object on the last line");
    cmd->add_flag("--quiet", args->quiet, "no progress lines");
    cmd->callback([args] { run_bench_cloth(*args); });
}

}  // namespace drape::app
