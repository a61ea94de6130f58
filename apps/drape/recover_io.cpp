#include "recover_io.hpp"

#include "body_json.hpp"
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
#include <drape/recover/outfit_glb.hpp>
#include <drape/recover/overlay.hpp>
#include <drape/recover/recovery_report.hpp>
#include <drape/vision/image_io.hpp>
#include <drape/vision/strokes.hpp>

#include <chrono>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>
#include <unistd.h>

namespace drape::app {

namespace {

namespace fs = std::filesystem;

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

}  // namespace

recover::RecoverOptions recover_options(const RecoverFlags& f, const std::string& prefix) {
    install_interrupt_handlers();
    recover::RecoverOptions options;
    options.quality = recover::quality_from_name(f.quality);
    recover::apply_quality(options);
    options.threads = f.threads;
    options.seed = f.seed;
    if (f.particles) options.particles = *f.particles;
    if (f.generations) options.generations = *f.generations;
    if (f.rounds) options.rounds = *f.rounds;
    options.estimate_material = !f.no_material;
    struct Printer {
        std::string last_stage;
        std::chrono::steady_clock::time_point last_print = std::chrono::steady_clock::now() - std::chrono::seconds(10);
    };
    auto state = std::make_shared<Printer>();
    options.on_progress = [state, prefix](const recover::RecoverProgress& p) {
        const std::string stage = recover::stage_name(p.stage);
        const auto now = std::chrono::steady_clock::now();
        if (stage != state->last_stage || now - state->last_print > std::chrono::seconds(2)) {
            std::ostringstream line;
            line << std::fixed << std::setprecision(1) << prefix << ": [" << p.seconds << " s] " << stage;
            if (p.garment >= 0) line << ", garment " << p.garment;
            if (p.round > 0) line << ", round " << p.round;
            line << ", " << p.evaluations << " drapes";
            if (p.stage == recover::Stage::sizing) line << ", best " << std::setprecision(2) << p.best_objective << " px²";
            if (p.eta_seconds >= 0) line << std::setprecision(0) << ", ETA " << p.eta_seconds << " s";
            std::cerr << line.str() << "\n";
            state->last_stage = stage;
            state->last_print = now;
        }
        return !interrupted();
    };
    return options;
}

recover::RecoverInputs read_recover_inputs(const fs::path& image, const fs::path& joints, const std::string& strokes,
                                           const std::string& palette, const std::string& garments) {
    recover::RecoverInputs in;
    in.image_bgr = vision::load_image(image);
    in.joints = read_vision_joints(joints, in.image_bgr.cols, in.image_bgr.rows);
    if (!palette.empty() && strokes.empty())
        throw InvalidInput("--palette is for colour-coded --strokes; no --strokes given");
    if (!strokes.empty()) {
        const vision::StrokePalette p = read_stroke_palette(palette, vision::LabelTable::fashionista());
        in.strokes = vision::load_strokes(strokes, p);
        if (in.strokes.size() != in.image_bgr.size())
            throw InvalidInput("strokes '" + strokes + "' are " + std::to_string(in.strokes.cols) + " x " +
                               std::to_string(in.strokes.rows) + " pixels but the photo '" + image.string() + "' is " +
                               std::to_string(in.image_bgr.cols) + " x " + std::to_string(in.image_bgr.rows));
    }
    if (garments != "auto") {
        std::stringstream ss(garments);
        std::string part;
        while (std::getline(ss, part, '+')) in.garments.push_back(recover::garment_choice_from_name(part));
    }
    return in;
}

nlohmann::json recovery_json(const std::string& image, const recover::RecoverInputs& in,
                             const recover::RecoverOptions& options, const recover::RecoveryResult& result,
                             const recover::RecoverSummary& s) {
    nlohmann::json garments = nlohmann::json::array();
    for (const auto& g : result.garments) garments.push_back(garment_result_json(g));
    return {{"format", "drape.recovery"},
            {"version", 1},
            {"image", {{"file", image}, {"width", in.image_bgr.cols}, {"height", in.image_bgr.rows}}},
            {"mode", in.strokes.empty() ? "auto" : "strokes"},
            {"quality", recover::quality_name(options.quality)},
            {"body", {{"params", to_json(result.fit.shape)}, {"pose", to_json(result.pose)}, {"camera", to_json(result.fit.camera)}}},
            {"garments", garments},
            {"summary", summary_json(s)}};
}

void write_recovery(const fs::path& out, const std::string& image, const body::BodyModel& model,
                    const recover::RecoverInputs& in, const recover::RecoverOptions& options,
                    const recover::RecoveryResult& result, const recover::RecoverSummary& s) {
    Staging staging(out);
    for (size_t i = 0; i < result.garments.size(); ++i) {
        const recover::RecoveredGarment& g = result.garments[i];
        const std::string n = std::to_string(i);
        garment::write_garment_glb(staging / ("garment_" + n + ".glb"), g.mesh, g.positions);
        garment::write_garment_obj(staging / ("garment_" + n + ".obj"), g.pattern, g.mesh, g.positions,
                                   "drape recover: " + garment::garment_type_name(g.type) + " from " + image);
        garment::write_pattern_svg(staging / ("pattern_" + n + ".svg"), g.pattern);
        garment::write_pattern_dxf(staging / ("pattern_" + n + ".dxf"), g.pattern);
        garment::write_pattern_json(staging / ("pattern_" + n + ".json"), g.pattern);
    }
    body::export_glb(staging / "body.glb", model, result.shaped, result.pose);
    write_png(staging / "mask.png", result.mask);
    write_png(staging / "segmentation.png", vision::draw_segmentation(in.image_bgr, result.segmentation.labels));
    const recover::OutfitMeshes outfit = recover::outfit_meshes(model, result);
    recover::write_outfit_glb(staging / "outfit.glb", outfit);
    recover::OverlayOptions overlay_options;
    overlay_options.threads = options.threads;
    const cv::Mat overlay = recover::render_overlay(in.image_bgr, outfit, result.fit.camera, overlay_options);
    write_png(staging / "overlay.png", overlay);
    recover::write_report_html(staging / "report.html",
                               recover::recovery_report(in.image_bgr, result, s, overlay, "Drape recovery of " + image));
    write_json_file(staging / "result.json", recovery_json(image, in, options, result, s));
    if (interrupted()) throw CommandExit{130, "recover: cancelled; '" + out.string() + "' is unchanged"};
    staging.commit();
}

}  // namespace drape::app
