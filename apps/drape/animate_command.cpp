// `drape animate` (recovered garments on a moving body) and `drape eval-animate` (the
// acceptance runs of issue 22's animation part). docs/animation.md.
#include "commands.hpp"
#include "interrupt.hpp"

#include <drape/io/animation_files.hpp>
#include <drape/io/json_io.hpp>
#include <drape/io/recovery_files.hpp>
#include <drape/recover/animate_garments.hpp>

#include <drape/body/model_io.hpp>
#include <drape/body/motion.hpp>
#include <drape/body/shape_body.hpp>
#include <drape/cloth/material.hpp>
#include <drape/core/errors.hpp>
#include <drape/garment/animate.hpp>
#include <drape/garment/dress_outfit.hpp>

#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <sstream>

namespace drape::app {

namespace {

namespace fs = std::filesystem;

struct AnimateArgs {
    std::vector<std::string> garments;
    std::string motion = "walk";
    std::string wind;
    double seconds = 5;
    double fps = 30;
    double edge_cm = 3.0;  // the recovery's default output resolution (final_edge_cm)
    std::string out;
};

Eigen::Vector3d parse_wind(const std::string& text) {
    if (text.empty()) return Eigen::Vector3d::Zero();
    Eigen::Vector3d w;
    char c1 = 0, c2 = 0;
    std::istringstream is(text);
    if (!(is >> w.x() >> c1 >> w.y() >> c2 >> w.z()) || c1 != ',' || c2 != ',' || !w.allFinite())
        throw InvalidInput("--wind '" + text + "' is not X,Y,Z in m/s (e.g. 3,0,0)");
    return w;
}

body::ShapedBody shape(const body::BodyModel& model, const body::SemanticRequest& request) {
    body::ShapedBody shaped;
    const body::ShapeSummary s = body::shape_body(model, model.prior.complete(request), body::ShapeOptions{}, shaped);
    if (!s.usable()) throw std::runtime_error("body shaping failed: " + s.brief_report());
    return shaped;
}


bool progress_bar(const char* who, const garment::AnimateProgress& p) {
    const int width = 30;
    const int done = p.frames > 0 ? int(std::lround(double(width) * p.frame / p.frames)) : 0;
    std::fprintf(stderr, "\r%s: %s [%.*s%*s] %d/%d frames, %.0f s", who, p.blending ? "blend " : "motion",
                 done, "##############################", width - done, "", p.frame, p.frames, p.seconds);
    if (!p.blending && p.frame == p.frames) std::fprintf(stderr, "\n");
    return !interrupted();
}

garment::DressOutfitOptions outfit_options(double edge_cm) {
    garment::DressOutfitOptions o;
    o.mesh.target_edge_cm = edge_cm;
    return o;
}

void run_animate(const AnimateArgs& args) {
    require(std::isfinite(args.fps) && args.fps > 0, "--fps ", args.fps, " must be > 0");
    require(args.fps <= 240, "--fps ", args.fps, " must be at most 240");
    require(std::isfinite(args.seconds) && args.seconds > 0 && args.seconds <= 120, "--seconds ", args.seconds,
            " must be in (0, 120]");
    require(args.edge_cm > 0 && args.edge_cm <= 20, "--edge ", args.edge_cm, " must be in (0, 20] cm");
    require(!args.garments.empty(), "--garment: give at least one RESULT_DIR[:N]");
    require(args.motion == "walk" || fs::path(args.motion).extension() == ".bvh", "--motion '", args.motion,
            "' is neither 'walk' nor a .bvh file");
    recover::AnimateGarmentsOptions options;
    options.fps = args.fps;
    options.seconds = args.seconds;
    options.edge_cm = args.edge_cm;
    options.wind_m_per_s = parse_wind(args.wind);
    install_interrupt_handlers();
    const recover::AnimateGarmentsInputs in = io::read_animation_inputs(args.garments, args.motion);
    std::cerr << "drape animate: dressing " << in.garments.size() << " garment(s)\n";
    options.on_progress = [](const recover::AnimateGarmentsProgress& p) {
        if (p.stage == recover::AnimateGarmentsStage::draping) return !interrupted();
        garment::AnimateProgress q;
        q.blending = p.stage == recover::AnimateGarmentsStage::blending;
        q.frame = p.step;
        q.frames = p.frames;
        q.seconds = p.seconds;
        return progress_bar("drape animate", q);
    };
    const body::BodyModel& model = body::BodyModel::default_model();
    recover::AnimateGarmentsResult r;
    const recover::AnimateGarmentsSummary s = recover::animate_garments(model, in, options, r);
    if (in.motion != "walk") {
        std::cerr << "drape animate: " << in.motion << ": " << r.bvh.file_frames << " frames at " << r.bvh.file_fps
                  << " fps, " << r.bvh.mapped_joints << " of 22 joints mapped, root scale " << r.bvh.root_scale << "\n";
        if (r.motion_seconds < args.seconds)
            std::cerr << "drape animate: the motion lasts " << r.motion_seconds << " s, shorter than --seconds "
                      << args.seconds << ": its last pose is held\n";
    }
    std::cerr << "\ndrape animate: " << s.brief_report() << "\n";
    if (s.termination == recover::AnimateGarmentsTermination::cancelled)
        throw CommandExit{130, "drape animate: cancelled; nothing written"};
    if (s.termination == recover::AnimateGarmentsTermination::drape_failed)
        throw CommandExit{1, "drape animate: the outfit could not be draped: " + s.message};
    const nlohmann::json report = io::animation_report(s, options, args.motion, args.garments);
    if (s.animate.frames == 0) throw CommandExit{1, "drape animate: no frame was simulated: " + s.animate.message};
    if (!io::write_animation(args.out, model, r.shaped, r.outfit, r.animation, r.names, report,
                             [] { return !interrupted(); }))
        throw CommandExit{130, "drape animate: cancelled; nothing written"};
    std::cout << "drape animate: wrote " << args.out << " (" << s.animate.frames << " frames)\n";
    if (!s.animate.usable()) throw CommandExit{1, "drape animate: " + s.animate.brief_report()};
}

// ---- eval-animate ----
struct EvalCase {
    std::string name;
    std::vector<garment::GarmentType> garments;
    Eigen::Vector3d wind = Eigen::Vector3d::Zero();
};

void run_eval_animate(const std::string& out, double seconds, double fps, double edge_cm, const std::string& only,
                      int max_substeps, int newton_iterations) {
    require(newton_iterations >= 0, "--newton-iterations ", newton_iterations,
            " must be >= 0 (0: the library's default)");
    require(std::isfinite(fps) && fps > 0, "--fps ", fps, " must be > 0");
    require(std::isfinite(seconds) && seconds > 0, "--seconds ", seconds, " must be > 0");
    install_interrupt_handlers();
    using garment::GarmentType;
    const std::vector<EvalCase> cases = {
        {"skirt", {GarmentType::skirt}, Eigen::Vector3d::Zero()},
        {"pants", {GarmentType::pants}, Eigen::Vector3d::Zero()},
        {"tshirt", {GarmentType::tshirt}, Eigen::Vector3d::Zero()},
        {"dress", {GarmentType::dress}, Eigen::Vector3d::Zero()},
        {"tshirt+pants", {GarmentType::pants, GarmentType::tshirt}, Eigen::Vector3d::Zero()},
        {"skirt-wind", {GarmentType::skirt}, Eigen::Vector3d(3.0, 0.0, -2.0)},
    };
    const body::BodyModel& model = body::BodyModel::default_model();
    const body::ShapedBody shaped = shape(model, body::SemanticRequest{});
    const body::Motion walk = body::walk_cycle(shaped.joints, seconds, fps);
    const cloth::Material fabric = cloth::builtin_material("gray-interlock");
    nlohmann::json results = nlohmann::json::array();
    std::printf("| case | vertices | substeps | frames | max penetration (mm) | max crossings | max slip (cm) | max speed (m/s) | s/frame (wall) | CPU s/frame | usable |\n");
    std::printf("|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (const EvalCase& c : cases) {
        if (!only.empty() && c.name != only) continue;
        std::vector<garment::GarmentRequest> requests;
        for (GarmentType t : c.garments) requests.push_back({t, std::nullopt, fabric});
        garment::DressedOutfit outfit;
        garment::DressOutfitOptions dress = outfit_options(edge_cm);
        dress.drape.on_progress = [](const garment::DrapeProgress&) { return !interrupted(); };
        const garment::DressOutfitSummary ds =
            garment::dress_outfit(model, shaped, body::named_pose(body::NamedPose::a_pose), requests, dress, outfit);
        if (ds.termination == garment::DressOutfitTermination::cancelled) throw CommandExit{130, "cancelled"};
        nlohmann::json r = {{"case", c.name}, {"drape", ds.brief_report()}, {"drape_usable", ds.usable()}};
        if (ds.termination == garment::DressOutfitTermination::draped) {
            garment::AnimateOptions options;
            options.fps = fps;
            options.seconds = seconds;
            options.wind_m_per_s = c.wind;
            if (max_substeps > 0) options.max_substeps = std::max(max_substeps, options.min_substeps);
            if (newton_iterations > 0) options.simulator.max_newton_iterations = newton_iterations;
            options.on_progress = [](const garment::AnimateProgress&) { return !interrupted(); };
            garment::AnimatedOutfit animated;
            const garment::AnimateSummary s = garment::animate_outfit(
                model, shaped, outfit, std::vector<cloth::Material>(requests.size(), fabric), walk, options, animated);
            if (s.termination == garment::AnimateTermination::cancelled) throw CommandExit{130, "cancelled"};
            r["animation"] = io::animation_json(s);
            r["wind_m_per_s"] = {c.wind.x(), c.wind.y(), c.wind.z()};
            std::printf("| %s | %d | %d | %d | %.2f | %d | %.1f | %.2f | %.3f | %.3f | %s |\n", c.name.c_str(), s.vertices,
                        s.checks.size() > 1 ? s.checks[1].substeps : 0, s.frames, s.max_penetration_m * 1e3,
                        s.max_self_intersections, s.max_slip_m * 1e2, s.max_speed_m_per_s, s.seconds_per_frame, s.cpu_seconds_per_frame,
                        s.usable() ? "yes" : "NO");
        } else {
            std::printf("| %s | - | - | 0 | - | - | - | - | - | - | NO (drape: %s) |\n", c.name.c_str(), ds.message.c_str());
        }
        std::fflush(stdout);
        results.push_back(r);
        io::write_json_file(out, {{"seconds", seconds}, {"fps", fps}, {"edge_cm", edge_cm}, {"cases", results}});
    }
}

}  // namespace

void add_animate_command(CLI::App& app) {
    auto args = std::make_shared<AnimateArgs>();
    CLI::App* cmd = app.add_subcommand("animate", "Animate recovered garments on a moving body (walk or BVH)");
    cmd->add_option("--garment", args->garments, "RESULT_DIR[:N] of drape recover (repeatable; inner first)")
        ->required();
    cmd->add_option("--motion", args->motion, "walk (built-in cycle) or a .bvh file");
    cmd->add_option("--wind", args->wind, "wind velocity X,Y,Z (m/s, world frame: +Y up, body faces +Z)");
    cmd->add_option("--seconds", args->seconds, "length of the animation (s)");
    cmd->add_option("--fps", args->fps, "frames per second");
    cmd->add_option("--edge", args->edge_cm, "garment mesh edge length (cm)");
    cmd->add_option("--out", args->out, "output folder")->required();
    cmd->callback([args] { run_animate(*args); });

    auto out = std::make_shared<std::string>();
    auto seconds = std::make_shared<double>(5.0);
    auto fps = std::make_shared<double>(30.0);
    auto edge = std::make_shared<double>(3.0);
    auto only = std::make_shared<std::string>();
    auto max_substeps = std::make_shared<int>(0);
    auto newton_iterations = std::make_shared<int>(0);
    CLI::App* eval = app.add_subcommand(
        "eval-animate", "Acceptance of animation: a walk of each template, t-shirt over pants, skirt in wind");
    eval->add_option("--out", *out, "results JSON")->required();
    eval->add_option("--seconds", *seconds, "walk length (s)");
    eval->add_option("--fps", *fps, "frames per second");
    eval->add_option("--edge", *edge, "garment mesh edge length (cm)");
    eval->add_option("--case", *only, "run only this case (skirt, pants, tshirt, dress, tshirt+pants, skirt-wind)");
    eval->add_option("--max-substeps", *max_substeps, "cap on simulation steps per frame (0: the library's)");
    eval->add_option("--newton-iterations", *newton_iterations,
                     "Newton iterations per simulation step at most (0: the library's)");
    eval->callback([=] { run_eval_animate(*out, *seconds, *fps, *edge, *only, *max_substeps, *newton_iterations); });
}

}  // namespace drape::app
