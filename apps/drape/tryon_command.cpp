// drape tryon: recovered garments on another body or into another photo (docs/tryon.md).
// drape eval-tryon: the acceptance: every synthetic scene's garments onto the 5th,
// 50th and 95th-percentile ANSUR II bodies of the other gender, in A-pose and walking.
// The pipeline is librecover's (tryon.hpp); the files drape::io's (tryon_files.hpp).
#include "commands.hpp"
#include "interrupt.hpp"

#include <drape/body/model_io.hpp>
#include <drape/body/semantic_shape.hpp>
#include <drape/core/errors.hpp>
#include <drape/fixtures/eval_bodies.hpp>
#include <drape/io/body_json.hpp>
#include <drape/io/json_io.hpp>
#include <drape/io/recovery_files.hpp>
#include <drape/io/tryon_files.hpp>
#include <drape/io/vision_json.hpp>
#include <drape/recover/tryon.hpp>
#include <drape/vision/image_io.hpp>
#include <drape/vision/strokes.hpp>

#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>

namespace drape::app {

using namespace io;

namespace {

namespace fs = std::filesystem;

struct TryOnArgs {
    std::vector<std::string> garments;
    std::string body;
    std::string pose = "a_pose";
    std::string photo;
    std::string joints;
    std::string strokes;
    std::string palette;
    std::optional<double> height_m;
    std::string gender;
    double edge_cm = recover::TryOnOptions{}.edge_cm;
    int threads = 2;
    std::string out;
};

// A progress line on stderr per stage and every 2 s; Ctrl-C / SIGTERM cancel.
std::function<bool(const recover::TryOnProgress&)> progress_printer(const std::string& prefix) {
    install_interrupt_handlers();
    struct Printer {
        std::string last_stage;
        std::chrono::steady_clock::time_point last = std::chrono::steady_clock::now() - std::chrono::seconds(10);
    };
    auto state = std::make_shared<Printer>();
    return [state, prefix](const recover::TryOnProgress& p) {
        const std::string stage = recover::tryon_stage_name(p.stage);
        const auto now = std::chrono::steady_clock::now();
        if (stage != state->last_stage || now - state->last > std::chrono::seconds(2)) {
            std::cerr << prefix << ": [" << std::fixed << std::setprecision(1) << p.seconds << " s] " << stage;
            if (p.stage == recover::TryOnStage::draping && p.step > 0) std::cerr << ", step " << p.step;
            std::cerr << "\n";
            state->last_stage = stage;
            state->last = now;
        }
        return !interrupted();
    };
}

recover::TryOnTarget read_target(const TryOnArgs& args) {
    recover::TryOnTarget t;
    const bool body = !args.body.empty(), photo = !args.photo.empty();
    if (body == photo) throw InvalidInput("give either --body P.json (with --pose) or --photo IMAGE --joints J.json");
    if (body) {
        if (!args.joints.empty() || !args.strokes.empty())
            throw InvalidInput("--joints and --strokes belong to a --photo target, not to --body");
        t.body = semantic_request_from_json(read_json_file(args.body), args.body);
        t.pose = resolve_pose(args.pose);
        return t;
    }
    if (args.joints.empty()) throw InvalidInput("--photo '" + args.photo + "' needs --joints J.json");
    t.photo_bgr = vision::load_image(args.photo);
    t.joints = read_vision_joints(args.joints, t.photo_bgr.cols, t.photo_bgr.rows);
    if (!args.strokes.empty()) {
        t.strokes = vision::load_strokes(args.strokes, read_stroke_palette(args.palette, vision::LabelTable::fashionista()));
        if (t.strokes.size() != t.photo_bgr.size())
            throw InvalidInput("strokes '" + args.strokes + "' are " + std::to_string(t.strokes.cols) + " x " +
                               std::to_string(t.strokes.rows) + " pixels but the photo '" + args.photo + "' is " +
                               std::to_string(t.photo_bgr.cols) + " x " + std::to_string(t.photo_bgr.rows));
    }
    t.height_m = args.height_m;
    if (!args.gender.empty()) t.gender = body::parse_gender(args.gender);
    return t;
}

void run_tryon(const TryOnArgs& args) {
    recover::TryOnInputs in;
    in.garments = read_tryon_garments(args.garments);
    in.target = read_target(args);
    recover::TryOnOptions options;
    options.edge_cm = args.edge_cm;
    options.threads = args.threads;
    options.on_progress = progress_printer("drape tryon");
    const body::BodyModel& model = body::BodyModel::default_model();
    recover::TryOnResult result;
    const recover::TryOnSummary s = recover::tryon(model, in, options, result);
    std::cerr << "drape tryon: " << s.brief_report() << "\n";
    if (s.termination == recover::TryOnTermination::cancelled)
        throw CommandExit{130, "tryon: cancelled; '" + args.out + "' is unchanged"};
    if (s.termination != recover::TryOnTermination::draped) throw std::runtime_error("tryon: " + s.brief_report());
    if (!write_tryon(args.out, model, in, options, result, s, [] { return !interrupted(); }))
        throw CommandExit{130, "tryon: cancelled; '" + args.out + "' is unchanged"};
    std::cout << "drape tryon: " << result.garments.size() << " garment(s) in " << args.out << "\n";
    for (const auto& g : result.garments)
        std::cout << "  " << g.source.name << " from " << g.source.source << ": " << g.grading.brief_report()
                  << "; drape " << (g.drape.usable ? "usable" : "NOT usable") << std::fixed << std::setprecision(2)
                  << " (penetration " << 1000 * g.drape.penetration_max_m << " mm, seam gap "
                  << 1000 * g.drape.seam_gap_max_m << " mm, " << g.drape.self_intersections << " crossings)\n";
    if (!in.target.body)
        std::cout << "  own garment still showing: " << std::setprecision(1) << 100 * result.own_garment_fraction
                  << " % of it (own_garment_mask.png)\n";
    if (!s.usable(result)) throw CommandExit{1, "tryon: a drape or a grading is not usable (see tryon.json)"};
}

// ---- eval-tryon

struct EvalTryOnArgs {
    std::string suite;
    std::string out;
    std::string bodies = "p50,p5,p95";
    std::string poses = "a_pose,walking";
    std::string scenes;   // comma-separated names; empty: every folder with truth.json
    double edge_cm = recover::TryOnOptions{}.edge_cm;
    int limit = 0;        // stop after this many try-ons (0: all)
    bool grade_only = false;
};

std::vector<std::string> split(const std::string& s) {
    std::vector<std::string> out;
    std::stringstream ss(s);
    std::string part;
    while (std::getline(ss, part, ','))
        if (!part.empty()) out.push_back(part);
    return out;
}

// The ANSUR II percentile bodies (stature and body mass at the same percentile, each of its
// gender): fixtures' kEvalBodies, plus the men's median computed the same way from the
// survey's male file (4,082 records): stature 1,755 mm, weight 84.6 kg.
body::SemanticRequest percentile_body(body::Gender gender, const std::string& percentile) {
    const std::string name = std::string(body::to_string(gender)) + "_" + percentile;
    double height = 0, weight = 0;
    for (const auto& b : garment::kEvalBodies)
        if (name == b.name) height = b.height_m, weight = b.weight_kg;
    if (name == "male_p50") height = 1.755, weight = 84.6;
    if (height == 0) throw InvalidInput("--bodies: '" + percentile + "' is not p5, p50 or p95");
    body::SemanticRequest r;
    r.gender = gender;
    r[body::Semantic::height_m] = height;
    r[body::Semantic::weight_kg] = weight;
    return r;
}

void run_eval_tryon(const EvalTryOnArgs& args) {
    install_interrupt_handlers();
    std::vector<fs::path> scenes;
    const std::vector<std::string> only = split(args.scenes);
    std::error_code ec;
    if (!fs::is_directory(args.suite, ec)) throw IoError("suite folder '" + args.suite + "' does not exist");
    for (const auto& e : fs::directory_iterator(args.suite))
        if (e.is_directory() && fs::exists(e.path() / "truth.json") &&
            (only.empty() || std::find(only.begin(), only.end(), e.path().filename().string()) != only.end()))
            scenes.push_back(e.path());
    std::sort(scenes.begin(), scenes.end());
    if (scenes.empty()) throw InvalidInput("suite folder '" + args.suite + "' holds no scene with truth.json");
    const std::vector<std::string> bodies = split(args.bodies), poses = split(args.poses);
    for (const auto& p : poses) resolve_pose(p);  // bad names fail before the slow work
    const body::BodyModel& model = body::BodyModel::default_model();

    nlohmann::json runs = nlohmann::json::array();
    int done = 0, usable = 0, converged = 0, closed = 0, penetration_ok = 0, no_crossing = 0, style_ok = 0;
    double worst_penetration = 0, worst_style = 0, seconds = 0;
    const auto write = [&] {
        nlohmann::json summary = {{"tryons", done},          {"usable", usable},
                                  {"converged", converged},  {"seams_closed", closed},
                                  {"penetration_within_1mm", penetration_ok}, {"no_crossing", no_crossing},
                                  {"style_within_2_percent", style_ok},       {"worst_penetration_mm", worst_penetration},
                                  {"worst_style_change_percent", worst_style}, {"seconds", seconds}};
        write_json_file(args.out, {{"format", "drape.eval-tryon"}, {"suite", args.suite}, {"edge_cm", args.edge_cm},
                                   {"grade_only", args.grade_only},
                                   {"summary", summary}, {"runs", runs}});
    };
    // Combinations in the order (body, pose) outer, scene inner: a run cut short still covers
    // every scene for the first combinations.
    for (const std::string& pose_name : poses)
        for (const std::string& percentile : bodies)
            for (const fs::path& scene : scenes) {
                if (interrupted()) throw CommandExit{130, "eval-tryon: cancelled; " + args.out + " holds the runs so far"};
                if (args.limit > 0 && done >= args.limit) break;
                recover::TryOnInputs in;
                in.garments = read_tryon_garments({scene.string()});
                const std::optional<body::Gender> source = in.garments[0].source_body.gender;
                if (!source) throw InvalidInput(scene.string() + "/truth.json: the body has no gender");
                const body::Gender other = *source == body::Gender::female ? body::Gender::male : body::Gender::female;
                in.target.body = percentile_body(other, percentile);
                in.target.pose = resolve_pose(pose_name);
                recover::TryOnOptions options;
                options.edge_cm = args.edge_cm;
                options.drape = !args.grade_only;
                options.on_progress = [](const recover::TryOnProgress&) { return !interrupted(); };
                recover::TryOnResult r;
                const recover::TryOnSummary s = recover::tryon(model, in, options, r);
                if (s.termination == recover::TryOnTermination::cancelled)
                    throw CommandExit{130, "eval-tryon: cancelled; " + args.out + " holds the runs so far"};
                ++done;
                seconds += s.seconds;
                const std::string target = std::string(body::to_string(other)) + "_" + percentile;
                nlohmann::json garments = nlohmann::json::array();
                bool all_converged = s.drape.converged, all_closed = true, all_pen = true, all_nocross = true, all_style = true;
                for (const auto& g : r.garments) {
                    all_closed &= g.drape.seam_gap_max_m < s.drape.seam_gap_tolerance_m;
                    all_pen &= g.drape.penetration_max_m <= 1e-3;
                    all_nocross &= g.drape.self_intersections == 0;
                    all_style &= g.grading.max_style_change <= 0.02;
                    worst_penetration = std::max(worst_penetration, 1000 * g.drape.penetration_max_m);
                    worst_style = std::max(worst_style, 100 * g.grading.max_style_change);
                    garments.push_back({{"garment", g.source.name},
                                        {"grade", g.grading.grade.text},
                                        {"grading", g.grading.brief_report()},
                                        {"max_style_change", g.grading.max_style_change},
                                        {"clamped", g.grading.clamped},
                                        {"drape", drape_json(g.drape)}});
                }
                all_nocross &= s.drape.self_intersections == 0;  // crossings between garments too
                bool ok = s.usable(r);
                if (args.grade_only) {  // only the grading's criteria
                    ok = s.termination == recover::TryOnTermination::graded && all_style;
                    all_converged = all_closed = all_pen = all_nocross = false;
                }
                usable += ok;
                converged += all_converged;
                closed += all_closed;
                penetration_ok += all_pen;
                no_crossing += all_nocross;
                style_ok += all_style;
                runs.push_back({{"scene", scene.filename().string()},
                                {"target", target},
                                {"pose", pose_name},
                                {"usable", ok},
                                {"summary", s.brief_report()},
                                {"seconds", s.seconds},
                                {"garments", garments}});
                std::cout << "eval-tryon: " << scene.filename().string() << " -> " << target << " " << pose_name << ": "
                          << (ok ? "usable" : "NOT usable") << ", " << s.brief_report() << std::endl;
                write();
            }
    write();
    std::cout << "eval-tryon: " << done << " try-ons, " << usable << " usable; converged " << converged
              << ", seams closed " << closed << ", penetration <= 1 mm " << penetration_ok << ", no crossing "
              << no_crossing << ", style within 2 % " << style_ok << "; worst penetration " << std::fixed
              << std::setprecision(2) << worst_penetration << " mm, worst style change " << worst_style << " %; "
              << std::setprecision(0) << seconds << " s\n";
}

}  // namespace

void add_tryon_commands(CLI::App& app) {
    auto args = std::make_shared<TryOnArgs>();
    CLI::App* cmd = app.add_subcommand(
        "tryon", "Put recovered garments on another body or into another photo: grades each garment's sizing to the "
                 "new body (keeping its fabric and style), dresses and drapes the outfit; writes DIR/tryon.json, "
                 "garment_N.glb/.obj, pattern_N.svg/.dxf/.json, grading_N.svg, body.glb, outfit.glb, report.html "
                 "(and overlay.png, mask.png, own_garment_mask.png for a photo)");
    cmd->add_option("--garment", args->garments,
                    "a result folder of drape recover (or a synthetic scene): DIR (every garment) or DIR:N; repeat "
                    "for an outfit, inner first")
        ->required();
    cmd->add_option("--body", args->body, "the target body (P.json, as drape body --params)");
    cmd->add_option("--pose", args->pose, "a_pose|arms_down|walking|t_pose or POSE.json (with --body)");
    cmd->add_option("--photo", args->photo, "the target photo (JPEG/PNG)");
    cmd->add_option("--joints", args->joints, "the target photo's 14 joints (JSON)");
    cmd->add_option("--strokes", args->strokes, "user strokes of the target photo (PNG); none = automatic");
    cmd->add_option("--palette", args->palette, "colour -> class table for colour-coded strokes");
    cmd->add_option("--height", args->height_m, "the target person's stature, metres (photo)");
    cmd->add_option("--gender", args->gender, "female|male (photo)");
    cmd->add_option("--edge", args->edge_cm, "mesh edge of the drape, cm (default 3)");
    cmd->add_option("--threads", args->threads, "worker threads (default 2)");
    cmd->add_option("--out", args->out, "output folder")->required();
    cmd->callback([args] { run_tryon(*args); });

    auto eval = std::make_shared<EvalTryOnArgs>();
    CLI::App* ev = app.add_subcommand(
        "eval-tryon", "Try every synthetic scene's garments on the 5th/50th/95th-percentile ANSUR II bodies of the "
                      "other gender in A-pose and walking; writes R.json (per run and the counts of the acceptance)");
    ev->add_option("suite", eval->suite, "a suite folder (drape synth --suite): one folder with truth.json per scene")
        ->required();
    ev->add_option("--bodies", eval->bodies, "percentiles, comma-separated (default p50,p5,p95)");
    ev->add_option("--poses", eval->poses, "poses, comma-separated (default a_pose,walking)");
    ev->add_option("--scenes", eval->scenes, "only these scene folders (comma-separated names)");
    ev->add_option("--edge", eval->edge_cm, "mesh edge of the drape, cm (default 3)");
    ev->add_option("--limit", eval->limit, "stop after this many try-ons (0 = all)");
    ev->add_flag("--grade-only", eval->grade_only, "grade only (no drape): the grading figures of every combination in seconds");
    ev->add_option("--out", eval->out, "the result JSON")->required();
    ev->callback([eval] { run_eval_tryon(*eval); });
}

}  // namespace drape::app
