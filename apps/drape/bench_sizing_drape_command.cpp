// drape bench-sizing-drape [--garments skirt,pants,tshirt,dress] [--edge CM] [--samples N]
//                          [--perturb F] [--compare N] [--seed S] [--time-step S] [--max-steps N]
//                          [--min-steps N] [--settled J/KG] [--warm base|last] [--material NAME|PATH] [--out R.json]
// The fast re-drape of garment recovery (garment::SizingDrape) against the full pipeline:
// per template on the mean female in the A-pose, dress_outfit's seconds at the edge, then
// evaluate() for random sizings within ±F of the proposed one (median seconds, Newton
// iterations, settled rate) and, for the first N of them, the vertex distance to a full
// fresh drape (dressing + simulation) of the same morphed mesh (docs/benchmarks.md).
#include "commands.hpp"
#include <drape/io/json_io.hpp>
#include <drape/io/material_arg.hpp>

#include <drape/body/body_model.hpp>
#include <drape/body/pose.hpp>
#include <drape/body/shape_body.hpp>
#include <drape/core/errors.hpp>
#include <drape/garment/dress_outfit.hpp>
#include <drape/garment/sizing_drape.hpp>

#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>
#include <random>
#include <sstream>

namespace drape::app {

using namespace io;

namespace {

struct BenchSizingDrapeArgs {
    std::string garments = "skirt,pants,tshirt,dress";
    double edge_cm = 6.0;
    int samples = 10;
    double perturb = 0.1;
    int compare = 3;
    unsigned seed = 1;
    double time_step_s = 0;  // 0: SizingDrapeOptions' default
    int max_steps = 0;       // 0: SizingDrapeOptions' default
    int min_steps = -1;      // -1: SizingDrapeOptions' default
    double settled = 0;      // 0: SizingDrapeOptions' default
    std::string warm = "base";
    std::string material = "gray-interlock";
    std::string out;
};

double median(std::vector<double> v) {
    if (v.empty()) return 0;
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// A sizing with every parameter scaled by a uniform factor in [1 - f, 1 + f] that makes a
// valid pattern the mesh can be morphed to (at most 50 draws).
garment::GarmentSizing random_sizing(const garment::GarmentSizing& g, double f, std::mt19937& rng,
                                     const garment::PatternMorph& morph) {
    std::uniform_real_distribution<double> u(1 - f, 1 + f);
    for (int attempt = 0; attempt < 50; ++attempt) {
        std::vector<double> v = garment::sizing_values(g);
        for (double& x : v) x *= u(rng);
        const garment::GarmentSizing out = garment::with_sizing_values(g, v);
        try {
            (void)morph.panel_points_cm(garment::make_pattern(out));
            return out;
        } catch (const InvalidInput&) {
        }
    }
    throw std::runtime_error("drape bench-sizing-drape: no valid random sizing in 50 draws");
}

void run(const BenchSizingDrapeArgs& a) {
    require(a.edge_cm > 0.2 && a.edge_cm <= 20, "drape bench-sizing-drape: --edge ", a.edge_cm, " must be in (0.2, 20]");
    require(a.samples >= 1 && a.samples <= 1000, "drape bench-sizing-drape: --samples ", a.samples, " must be in [1, 1000]");
    require(a.perturb >= 0 && a.perturb < 0.5, "drape bench-sizing-drape: --perturb ", a.perturb, " must be in [0, 0.5)");
    require(a.compare >= 0 && a.compare <= a.samples, "drape bench-sizing-drape: --compare ", a.compare,
            " must be in [0, --samples]");
    require(a.warm == "base" || a.warm == "last", "drape bench-sizing-drape: --warm ", a.warm, " must be base or last");
    const cloth::Material fabric = load_material_arg(a.material, "");
    const body::BodyModel& model = body::BodyModel::default_model();
    body::ShapedBody shaped;
    require(body::shape_body(model, model.prior.complete(body::SemanticRequest{}), body::ShapeOptions{}, shaped).usable(),
            "drape bench-sizing-drape: shaping the mean female failed");
    const body::Pose pose = body::named_pose(body::NamedPose::a_pose);
    std::mt19937 rng(a.seed);
    nlohmann::json rows = nlohmann::json::array();
    std::printf("mean female, A-pose, %s, edge %.1f cm, %d random sizings within ±%.0f %%, warm start %s\n",
                a.material.c_str(), a.edge_cm, a.samples, 100 * a.perturb, a.warm.c_str());
    std::printf("%-7s %6s %9s %9s %9s %7s %8s %9s %9s %9s %8s %9s %9s %9s\n", "garment", "verts", "full s", "eval s",
                "max s", "steps", "Newton", "settled", "mean mm", "max mm", "hem mm", "moved mm", "settle mm",
                "s-hem mm");
    std::stringstream list(a.garments);
    for (std::string name; std::getline(list, name, ',');) {
        garment::GarmentRequest request;
        request.type = garment::garment_type_from_name(name);
        request.material = fabric;
        garment::DressOutfitOptions options;
        options.mesh.target_edge_cm = a.edge_cm;
        garment::DressedOutfit outfit;
        const auto t_full = std::chrono::steady_clock::now();
        const garment::DressOutfitSummary full = garment::dress_outfit(model, shaped, pose, {request}, options, outfit);
        const double full_s = seconds_since(t_full);
        nlohmann::json row = {{"garment", name}, {"full_seconds", full_s}, {"full_usable", full.usable()}};
        if (full.termination != garment::DressOutfitTermination::draped) {
            std::printf("%-7s full drape failed: %s\n", name.c_str(), full.brief_report().c_str());
            rows.push_back(row);
            continue;
        }
        garment::SizingDrapeOptions so;
        so.drape = options.drape;
        if (a.time_step_s > 0) so.time_step_s = a.time_step_s;
        if (a.max_steps > 0) so.max_steps = a.max_steps;
        if (a.min_steps >= 0) so.min_steps = a.min_steps;
        if (a.settled > 0) so.settled_kinetic_energy_j_per_kg = a.settled;
        so.min_steps = std::min(so.min_steps, so.max_steps);
        so.warm_start = a.warm == "last" ? garment::SizingDrapeOptions::WarmStart::last_settled
                                         : garment::SizingDrapeOptions::WarmStart::base;
        garment::SizingDrape fast(outfit, 0, model.faces, fabric, so);
        const garment::PatternMorph morph(outfit.patterns[0], outfit.meshes[0]);
        std::vector<double> secs, steps, newton, mean_mm, max_mm, hem_mm, moved_mm, settle_mean_mm, settle_hem_mm;
        int settled = 0, usable = 0;
        for (int k = 0; k < a.samples; ++k) {
            const garment::GarmentSizing g = random_sizing(outfit.sizings[0], a.perturb, rng, morph);
            const garment::SizingDrapeResult r = fast.evaluate(g);
            secs.push_back(r.seconds);
            steps.push_back(r.steps);
            newton.push_back(r.newton_iterations);
            settled += r.converged ? 1 : 0;
            usable += r.usable(so.drape) ? 1 : 0;
            if (k >= a.compare) continue;
            // The full pipeline on the same morphed mesh: dressed afresh and draped.
            const garment::Pattern pattern = garment::make_pattern(g);
            const garment::GarmentMesh mesh = fast.mesh();
            Eigen::MatrixX3d fresh;
            garment::dress_and_drape(pattern, mesh, model, shaped, outfit.pose, fabric, options.dressing, options.drape,
                                     fresh);
            const Eigen::VectorXd d = (fresh - r.positions).rowwise().norm();
            mean_mm.push_back(1e3 * d.mean());
            max_mm.push_back(1e3 * d.maxCoeff());
            // The lowest point (hem) of both, and how far the fresh drape is from the base
            // drape of the old sizing (what the sizing change moved, folds included).
            hem_mm.push_back(1e3 * std::abs(fresh.col(1).minCoeff() - r.positions.col(1).minCoeff()));
            moved_mm.push_back(1e3 * (fresh - outfit.positions[0]).rowwise().norm().mean());
            // The drape's own simulation (drape_garment, its settling criteria and step
            // budget) from the same start, the base drape: what the re-drape truncates.
            std::vector<int> face_material(size_t(mesh.cloth.face_count()), 0);
            for (int f : garment::waistband_faces(pattern, mesh, options.drape.waistband_width_cm))
                face_material[size_t(f)] = 1;
            Eigen::MatrixX3d settled_x;
            garment::drape_garment(mesh, outfit.positions[0], {outfit.body_vertices}, model.faces,
                                   {fabric, garment::waistband_material(fabric, options.drape.waistband_stretching_factor)},
                                   face_material, options.drape, settled_x);
            settle_mean_mm.push_back(1e3 * (settled_x - r.positions).rowwise().norm().mean());
            settle_hem_mm.push_back(1e3 * std::abs(settled_x.col(1).minCoeff() - r.positions.col(1).minCoeff()));
        }
        const int nv = outfit.meshes[0].cloth.vertex_count();
        row.update({{"vertices", nv},
                    {"evaluate_median_seconds", median(secs)},
                    {"evaluate_max_seconds", *std::max_element(secs.begin(), secs.end())},
                    {"median_steps", median(steps)},
                    {"median_newton_iterations", median(newton)},
                    {"settled_rate", double(settled) / a.samples},
                    {"usable_rate", double(usable) / a.samples},
                    {"compared", mean_mm.size()},
                    {"fresh_mean_mm", mean_mm.empty() ? 0.0 : median(mean_mm)},
                    {"fresh_max_mm", max_mm.empty() ? 0.0 : *std::max_element(max_mm.begin(), max_mm.end())},
                    {"fresh_hem_mm", median(hem_mm)},
                    {"fresh_vs_base_mean_mm", median(moved_mm)},
                    {"settled_mean_mm", median(settle_mean_mm)},
                    {"settled_hem_mm", median(settle_hem_mm)}});
        std::printf("%-7s %6d %9.2f %9.3f %9.3f %7.0f %8.0f %5d/%-3d %9.1f %9.1f %8.1f %9.1f %9.1f %9.1f\n",
                    name.c_str(), nv, full_s, median(secs), row["evaluate_max_seconds"].get<double>(), median(steps),
                    median(newton), settled, a.samples, row["fresh_mean_mm"].get<double>(),
                    row["fresh_max_mm"].get<double>(), median(hem_mm), median(moved_mm), median(settle_mean_mm),
                    median(settle_hem_mm));
        std::fflush(stdout);
        rows.push_back(row);
    }
    std::printf("(eval s: median of evaluate(); mean mm: median over the compared sizings of the mean vertex distance "
                "to a full fresh drape of the same morphed mesh; max mm: the largest; hem mm: median |difference| of the lowest "
                "point; moved mm: median mean distance of the fresh drape from the base drape; settle mm, s-hem mm: median mean "
                "vertex and hem distance to drape_garment's own settling from the base drape)\n");
    if (!a.out.empty()) write_json_file(a.out, nlohmann::json{{"edge_cm", a.edge_cm}, {"rows", rows}});
}

}  // namespace

void add_bench_sizing_drape_command(CLI::App& app) {
    auto args = std::make_shared<BenchSizingDrapeArgs>();
    CLI::App* cmd = app.add_subcommand(
        "bench-sizing-drape", "Time the fast re-drape of recovery (SizingDrape) against the full dress pipeline");
    cmd->add_option("--garments", args->garments, "comma-separated templates (default skirt,pants,tshirt,dress)");
    cmd->add_option("--edge", args->edge_cm, "mesh edge, cm (default 6)");
    cmd->add_option("--samples", args->samples, "random sizings per template (default 10)");
    cmd->add_option("--perturb", args->perturb, "each parameter scaled within ±this (default 0.1)");
    cmd->add_option("--compare", args->compare, "of them, compared with a full fresh drape (default 3)");
    cmd->add_option("--seed", args->seed, "random seed (default 1)");
    cmd->add_option("--time-step", args->time_step_s, "time step of the re-drape, s (default: SizingDrapeOptions' 0.02)");
    cmd->add_option("--max-steps", args->max_steps, "dynamic steps per evaluation at most");
    cmd->add_option("--min-steps", args->min_steps, "dynamic steps per evaluation at least");
    cmd->add_option("--settled", args->settled, "kinetic energy per mass counted as settled, J/kg (default 1e-4)");
    cmd->add_option("--warm", args->warm, "warm start: base (the base drape) or last (the last settled)");
    cmd->add_option("--material", args->material, "built-in fabric name or material file");
    cmd->add_option("--out", args->out, "also write the figures to this JSON file");
    cmd->callback([args] { run(*args); });
}

}  // namespace drape::app
