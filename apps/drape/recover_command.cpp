// drape recover: the body, garments, sewing patterns and fabrics of one photo
// (docs/recovery.md). The pipeline is librecover's; this file parses, reads, writes, prints.
#include "body_json.hpp"
#include "commands.hpp"
#include "garment_json.hpp"
#include "image_io.hpp"
#include "interrupt.hpp"
#include "json_io.hpp"
#include "vision_json.hpp"

#include <drape/body/model_io.hpp>
#include <drape/core/errors.hpp>
#include <drape/garment/garment_export.hpp>
#include <drape/garment/pattern_dxf.hpp>
#include <drape/garment/pattern_json.hpp>
#include <drape/garment/pattern_svg.hpp>
#include <drape/recover/recover.hpp>
#include <drape/vision/image_io.hpp>
#include <drape/vision/strokes.hpp>

#include <CLI/CLI.hpp>

#include <chrono>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <unistd.h>

namespace drape::app {

namespace {

namespace fs = std::filesystem;

struct RecoverArgs {
    std::string image;
    std::string joints;
    std::string strokes;
    std::string palette;
    std::string garment = "auto";
    std::optional<double> height_m;
    std::string gender;
    std::string quality = "default";
    std::string out;
    std::string model;
    int threads = 2;
    unsigned seed = 1;
};

nlohmann::json drape_json(const recover::DrapeState& d) {
    return {{"usable", d.usable},
            {"converged", d.converged},
            {"penetration_max_m", d.penetration_max_m},
            {"seam_gap_max_m", d.seam_gap_max_m},
            {"self_intersections", d.self_intersections}};
}

nlohmann::json summary_json(const recover::RecoverSummary& s) {
    static const char* names[] = {"recovered", "no_garment", "body_fit_failed", "drape_failed", "cancelled"};
    return {{"termination", names[static_cast<int>(s.termination)]},
            {"message", s.message},
            {"candidate_drapes", s.evaluations},
            {"seconds", {{"segment", s.seconds_segment},
                         {"body", s.seconds_fit},
                         {"dress", s.seconds_dress},
                         {"sizing", s.seconds_sizing},
                         {"material", s.seconds_material},
                         {"final_drape", s.seconds_final},
                         {"total", s.seconds}}}};
}

nlohmann::json garment_result_json(const recover::RecoveredGarment& g) {
    nlohmann::json material = material_to_json(g.material, g.base_fabric);
    material["nearest_fabric"] = g.nearest_fabric;
    material["bending_scale_range"] = {g.bending_low, g.bending_high};
    return {{"type", garment::garment_type_name(g.type)},
            {"garment", recover::garment_choice_name(g.choice)},
            {"class_id", g.label_id},
            {"class_name", g.class_name},
            {"supported", g.supported},
            {"unsupported_reason", g.unsupported_reason},
            {"initial_sizing", to_json(g.initial_sizing)},
            {"sizing", to_json(g.sizing)},
            {"material", material},
            {"mean_curvature_per_m", g.mean_curvature_per_m},
            {"target_curvature_per_m", g.target_curvature_per_m},
            {"wrinkle_density_per_m2", g.wrinkle_density_per_m2},
            {"silhouette_rms_px", g.silhouette_rms_px},
            {"drape", drape_json(g.drape)},
            {"objective_history", {{"sizing_px2", g.sizing_history}, {"material_relative2", g.material_history}}},
            {"seconds", {{"sizing", g.seconds_sizing}, {"material", g.seconds_material}}}};
}

// Every output goes to a staging folder beside DIR first; only a complete set is moved in
// (each file by an atomic rename), so a failed or cancelled run leaves DIR as it was.
class Staging {
  public:
    explicit Staging(const fs::path& out) : out_(out) {
        make_output_dir(out_);
        dir_ = out_ / (".partial-" + std::to_string(::getpid()));
        std::error_code ec;
        fs::remove_all(dir_, ec);
        if (!fs::create_directories(dir_, ec))
            throw IoError("cannot create the staging folder '" + dir_.string() + "': " + ec.message());
    }
    ~Staging() {
        std::error_code ec;
        fs::remove_all(dir_, ec);
    }
    fs::path operator/(const std::string& name) const { return dir_ / name; }
    void commit() {
        for (const auto& e : fs::directory_iterator(dir_)) {
            std::error_code ec;
            fs::rename(e.path(), out_ / e.path().filename(), ec);
            if (ec) throw IoError("cannot move '" + e.path().string() + "' into '" + out_.string() + "': " + ec.message());
        }
    }

  private:
    fs::path out_, dir_;
};

void run_recover(const RecoverArgs& args) {
    install_interrupt_handlers();
    const auto t0 = std::chrono::steady_clock::now();
    recover::RecoverInputs in;
    in.image_bgr = vision::load_image(args.image);
    in.joints = read_vision_joints(args.joints, in.image_bgr.cols, in.image_bgr.rows);
    if (!args.palette.empty() && args.strokes.empty())
        throw InvalidInput("--palette is for colour-coded --strokes; no --strokes given");
    if (!args.strokes.empty()) {
        const vision::StrokePalette palette = read_stroke_palette(args.palette, vision::LabelTable::fashionista());
        in.strokes = vision::load_strokes(args.strokes, palette);
        if (in.strokes.size() != in.image_bgr.size())
            throw InvalidInput("strokes '" + args.strokes + "' are " + std::to_string(in.strokes.cols) + " x " +
                               std::to_string(in.strokes.rows) + " pixels but the photo '" + args.image + "' is " +
                               std::to_string(in.image_bgr.cols) + " x " + std::to_string(in.image_bgr.rows));
    }
    if (args.garment != "auto") {
        std::stringstream ss(args.garment);
        std::string part;
        while (std::getline(ss, part, '+')) in.garments.push_back(recover::garment_choice_from_name(part));
    }
    in.height_m = args.height_m;
    if (!args.gender.empty()) in.gender = body::parse_gender(args.gender);

    recover::RecoverOptions options;
    options.quality = recover::quality_from_name(args.quality);
    recover::apply_quality(options);
    options.threads = args.threads;
    options.seed = args.seed;
    std::string last_stage;
    auto last_print = std::chrono::steady_clock::now() - std::chrono::seconds(10);
    options.on_progress = [&](const recover::RecoverProgress& p) {
        const std::string stage = recover::stage_name(p.stage);
        const auto now = std::chrono::steady_clock::now();
        if (stage != last_stage || now - last_print > std::chrono::seconds(2)) {
            std::ostringstream line;
            line << std::fixed << std::setprecision(1) << "drape recover: [" << p.seconds << " s] " << stage;
            if (p.garment >= 0) line << ", garment " << p.garment;
            if (p.round > 0) line << ", round " << p.round;
            line << ", " << p.evaluations << " drapes";
            if (p.stage == recover::Stage::sizing) line << ", best " << std::setprecision(2) << p.best_objective << " px²";
            if (p.eta_seconds >= 0) line << std::setprecision(0) << ", ETA " << p.eta_seconds << " s";
            std::cerr << line.str() << "\n";
            last_stage = stage;
            last_print = now;
        }
        return !interrupted();
    };

    const body::BodyModel loaded = args.model.empty() ? body::BodyModel() : body::load_model(args.model);
    const body::BodyModel& model = args.model.empty() ? body::BodyModel::default_model() : loaded;
    Staging staging(args.out);

    recover::RecoveryResult result;
    const recover::RecoverSummary s = recover::recover(model, in, options, result);
    std::cerr << "drape recover: " << s.brief_report() << "\n";
    if (s.termination == recover::RecoverTermination::cancelled)
        throw CommandExit{130, "recover: cancelled; '" + args.out + "' is unchanged"};
    if (s.termination == recover::RecoverTermination::no_garment)
        throw InvalidInput("no garment found in '" + args.image + "': " + s.message);
    if (s.termination != recover::RecoverTermination::recovered) throw std::runtime_error(s.brief_report());

    nlohmann::json garments = nlohmann::json::array();
    for (size_t i = 0; i < result.garments.size(); ++i) {
        const recover::RecoveredGarment& g = result.garments[i];
        const std::string n = std::to_string(i);
        garments.push_back(garment_result_json(g));
        garment::write_garment_glb(staging / ("garment_" + n + ".glb"), g.mesh, g.positions);
        garment::write_garment_obj(staging / ("garment_" + n + ".obj"), g.pattern, g.mesh, g.positions,
                                   "drape recover: " + garment::garment_type_name(g.type) + " from " + args.image);
        garment::write_pattern_svg(staging / ("pattern_" + n + ".svg"), g.pattern);
        garment::write_pattern_dxf(staging / ("pattern_" + n + ".dxf"), g.pattern);
        garment::write_pattern_json(staging / ("pattern_" + n + ".json"), g.pattern);
    }
    body::export_glb(staging / "body.glb", model, result.shaped, result.pose);
    write_png(staging / "mask.png", result.mask);
    write_png(staging / "segmentation.png", vision::draw_segmentation(in.image_bgr, result.segmentation.labels));
    nlohmann::json j = {
        {"format", "drape.recovery"},
        {"version", 1},
        {"image", {{"file", args.image}, {"width", in.image_bgr.cols}, {"height", in.image_bgr.rows}}},
        {"mode", in.strokes.empty() ? "auto" : "strokes"},
        {"quality", recover::quality_name(options.quality)},
        {"body", {{"params", to_json(result.fit.shape)}, {"pose", to_json(result.pose)}, {"camera", to_json(result.fit.camera)}}},
        {"garments", garments},
        {"summary", summary_json(s)},
        {"seconds", std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count()}};
    write_json_file(staging / "result.json", j);
    if (interrupted()) throw CommandExit{130, "recover: cancelled; '" + args.out + "' is unchanged"};
    staging.commit();
    std::cout << "drape recover: " << result.garments.size() << " garment(s) in " << args.out << "\n";
    for (const auto& g : result.garments)
        std::cout << "  " << recover::garment_choice_name(g.choice) << ": silhouette " << std::fixed
                  << std::setprecision(1) << g.silhouette_rms_px << " px RMS, bending x" << std::setprecision(2)
                  << g.material.bending_scale << " (nearest " << g.nearest_fabric << "), K " << g.mean_curvature_per_m
                  << " 1/m, drape " << (g.drape.usable ? "usable" : "NOT usable") << "\n";
    if (!s.usable(result)) throw CommandExit{1, "recover: a drape is not usable (see result.json)"};
}

}  // namespace

void add_recover_command(CLI::App& app) {
    auto args = std::make_shared<RecoverArgs>();
    CLI::App* cmd = app.add_subcommand(
        "recover", "Recover the body, each garment's sewing pattern, fabric and 3D drape from one photo; writes "
                   "DIR/result.json, garment_N.glb/.obj, pattern_N.svg/.dxf/.json, body.glb, mask.png");
    cmd->add_option("image", args->image, "the photo (JPEG/PNG)")->required();
    cmd->add_option("--joints", args->joints, "the 14 joints (JSON, as ../shared/data/photos/joints)")->required();
    cmd->add_option("--strokes", args->strokes, "user strokes (PNG: class ids, or colours with --palette); none = automatic");
    cmd->add_option("--palette", args->palette, "colour -> class table for colour-coded strokes");
    cmd->add_option("--garment", args->garment,
                    "auto, or skirt|pants|shorts|tshirt|tank|longsleeve|dress, or two joined by + (tshirt+pants)");
    cmd->add_option("--height", args->height_m, "the person's stature, metres");
    cmd->add_option("--gender", args->gender, "female|male");
    cmd->add_option("--quality", args->quality, "fast|default|fine");
    cmd->add_option("--threads", args->threads, "worker threads (default 2)");
    cmd->add_option("--seed", args->seed, "the particle swarm's seed (default 1)");
    cmd->add_option("--model", args->model, "a body model file (default: the built-in model)");
    cmd->add_option("--out", args->out, "output folder")->required();
    cmd->callback([args] { run_recover(*args); });
}

}  // namespace drape::app
