// drape bench-cloth [--n 32] [--seconds 2] [--material NAME|PATH] [--threads N] [--out R.json]
// The anchor scene of issue 3 (a 1 m square dropped on a 0.5 m sphere), timed, with the
// rest-state figures to compare against ArcSim 0.3.1 (docs/cloth.md, docs/benchmarks.md).
#include "commands.hpp"
#include "json_io.hpp"
#include "material_arg.hpp"

#include <drape/cloth/material.hpp>
#include <drape/cloth/scenes.hpp>
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

namespace {

struct BenchClothArgs {
    int n = 32;
    double seconds = 2.0;
    std::string material = "gray-interlock";
    int threads = 0;
    std::string out;
    bool quiet = false;
};

void run_bench_cloth(const BenchClothArgs& args) {
    require(args.n >= 2 && args.n % 2 == 0 && args.n <= 512, "drape bench-cloth: --n ", args.n,
            " must be even and in [2, 512]");
    require(std::isfinite(args.seconds) && args.seconds > 0 && args.seconds <= 60,
            "drape bench-cloth: --seconds ", args.seconds, " must be in (0, 60]");
    require(args.threads >= 0, "drape bench-cloth: --threads ", args.threads, " must be >= 0");
    std::optional<tbb::global_control> limit;
    if (args.threads > 0) limit.emplace(tbb::global_control::max_allowed_parallelism, args.threads);

    const cloth::AnchorScene scene = cloth::make_anchor_scene(args.n);
    cloth::Simulator sim(scene.cloth, load_material_arg(args.material, ""), scene.options);
    sim.set_obstacle(cloth::Obstacle(scene.sphere.positions, scene.sphere.faces));
    const int steps = static_cast<int>(std::lround(args.seconds / scene.options.time_step_s));
    int failed = 0, iterations = 0;
    double slowest = 0;
    const auto t0 = std::chrono::steady_clock::now();
    for (int k = 0; k < steps; ++k) {
        const cloth::StepSummary s = sim.step();
        iterations += s.newton_iterations;
        failed += s.usable() ? 0 : 1;
        slowest = std::max(slowest, s.seconds_total);
        if (!args.quiet && (k + 1) % 40 == 0)
            std::printf("t = %.2f s: centre z %.4f m, %s\n", (k + 1) * scene.options.time_step_s,
                        sim.positions()(scene.centre_vertex, 2), s.brief_report().c_str());
    }
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const cloth::ContactReport report = sim.contact_report();
    nlohmann::json j;
    j["scene"] = {{"n", args.n}, {"nodes", sim.mesh().vertex_count()}, {"seconds_simulated", args.seconds},
                  {"time_step_s", scene.options.time_step_s}, {"material", args.material}};
    j["centre_z_m"] = sim.positions()(scene.centre_vertex, 2);
    j["lowest_z_m"] = sim.positions().col(2).minCoeff();
    j["max_penetration_m"] = report.max_penetration_m;
    j["self_intersections"] = report.self_intersections;
    j["failed_steps"] = failed;
    j["newton_iterations_per_step"] = static_cast<double>(iterations) / steps;
    j["ms_per_step"] = 1e3 * wall / steps;
    j["slowest_step_ms"] = 1e3 * slowest;
    // ArcSim 0.3.1 on this machine (issue 3): rest state for N = 32, time for N = 32 and 64.
    nlohmann::json arcsim = {{"centre_z_m", 0.5048}};
    if (args.n == 32) {
        arcsim["lowest_z_m"] = 0.074;
        arcsim["ms_per_step"] = 69;
    } else if (args.n == 64) {
        arcsim["ms_per_step"] = 329;
    }
    j["arcsim_0_3_1"] = arcsim;
    std::printf("%s\n", j.dump(2).c_str());
    if (!args.out.empty()) write_json_file(args.out, j);
}

}  // namespace

void add_bench_cloth_command(CLI::App& app) {
    auto args = std::make_shared<BenchClothArgs>();
    CLI::App* cmd = app.add_subcommand(
        "bench-cloth", "Time the cloth simulator on the anchor scene (square dropped on a sphere)");
    cmd->add_option("--n", args->n, "grid cells per side (32: 1089 nodes, 64: 4225 nodes)");
    cmd->add_option("--seconds", args->seconds, "simulated time (s)");
    cmd->add_option("--material", args->material, "built-in fabric name or material file");
    cmd->add_option("--threads", args->threads, "worker threads (0 = all cores)");
    cmd->add_option("--out", args->out, "also write the figures to this JSON file");
    cmd->add_flag("--quiet", args->quiet, "no progress lines");
    cmd->callback([args] { run_bench_cloth(*args); });
}

}  // namespace drape::app
