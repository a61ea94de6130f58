#include <drape/io/recovery_files.hpp>

#include <drape/io/body_json.hpp>
#include <drape/io/garment_json.hpp>
#include <drape/io/image_io.hpp>
#include <drape/io/json_io.hpp>
#include <drape/io/vision_json.hpp>

#include "staging.hpp"

#include <drape/body/model_io.hpp>
#include <drape/core/errors.hpp>
#include <drape/recover/outfit_glb.hpp>
#include <drape/recover/overlay.hpp>
#include <drape/recover/recovery_report.hpp>
#include <drape/vision/image_io.hpp>
#include <drape/vision/strokes.hpp>

#include "staging.hpp"

#include <sstream>

namespace drape::io {

namespace fs = std::filesystem;

nlohmann::json drape_json(const recover::DrapeState& d) {
    return {{"usable", d.usable},
            {"converged", d.converged},
            {"penetration_max_m", d.penetration_max_m},
            {"seam_gap_max_m", d.seam_gap_max_m},
            {"self_intersections", d.self_intersections},
            {"mesh", d.source == recover::DrapeState::Source::search ? "search" : "output"},
            {"edge_cm", d.edge_cm},
            {"message", d.message}};
}

namespace {

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

// How the draping pose (body.pose) differs from the fit's (body.fit_pose), per arm.
nlohmann::json arms_json(const recover::RecoveryResult& r) {
    const garment::ArmLoweringSummary& l = r.arms_lowered;
    const garment::ArmClearanceSummary& c = r.arms_cleared;
    auto arm = [](double lowered, double elevation, double outward, double depth) {
        return nlohmann::json{{"elevation_deg", elevation},
                              {"lowered_deg", lowered},
                              {"turned_out_deg", outward},
                              {"swung_in_depth_deg", depth}};
    };
    return {{"right", arm(l.right_lowered_degrees, l.right_elevation_degrees, c.right_degrees, c.right_depth_degrees)},
            {"left", arm(l.left_lowered_degrees, l.left_elevation_degrees, c.left_degrees, c.left_depth_degrees)},
            {"trunk_crossings_before", c.crossings_before},
            {"trunk_crossings_after", c.crossings_after},
            {"image_shift_m", c.image_shift_m}};
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
            {"objective_history",
             {{"sizing_px2", g.sizing_history},
              {"material_relative2", g.material_history},
              {"joint_pose_material", g.joint_history}}},
            {"seconds", {{"sizing", g.seconds_sizing}, {"material", g.seconds_material}}}};
}

using detail::Staging;

}  // namespace

void check_output_folder(const fs::path& out) {
    const Staging probe(out);  // made and removed
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
            {"material_target", recover::material_target_name(options.material_target)},
            {"joint_pose_material", options.joint_pose_material},
            {"base_fabric", options.base_fabric},
            {"max_arm_elevation_degrees", options.max_arm_elevation_degrees},
            {"min_ease_cm", options.min_ease_cm},
            {"output_drape", recover::output_drape_name(options.output_drape)},
            {"body",
             {{"params", to_json(result.fit.shape)},
              {"pose", to_json(result.pose)},
              {"fit_pose", to_json(result.fit.pose)},
              {"arms", arms_json(result)},
              {"camera", to_json(result.fit.camera)}}},
            {"garments", garments},
            {"summary", summary_json(s)}};
}

bool write_recovery(const fs::path& out, const std::string& image, const body::BodyModel& model,
                    const recover::RecoverInputs& in, const recover::RecoverOptions& options,
                    const recover::RecoveryResult& result, const recover::RecoverSummary& s,
                    const std::function<bool()>& keep_going) {
    Staging staging(out);
    for (size_t i = 0; i < result.garments.size(); ++i) {
        const recover::RecoveredGarment& g = result.garments[i];
        staging.write_garment(i, g.pattern, g.mesh, g.positions,
                              "drape recover: " + garment::garment_type_name(g.type) + " from " + image);
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
    if (keep_going && !keep_going()) return false;
    staging.commit();
    return true;
}


namespace {

const nlohmann::json& field(const nlohmann::json& j, const std::string& key, const std::string& file,
                            const std::string& where) {
    if (!j.is_object() || !j.contains(key))
        throw InvalidInput(file + ": " + where + " has no field '" + key + "'");
    return j.at(key);
}

}  // namespace

SavedRecovery read_recovery_folder(const std::string& spec) {
    SavedRecovery saved;
    std::string dir = spec;
    int only = -1;
    const size_t colon = spec.rfind(':');
    if (colon != std::string::npos && colon + 1 < spec.size() &&
        spec.find_first_not_of("0123456789", colon + 1) == std::string::npos) {
        dir = spec.substr(0, colon);
        try {
            only = std::stoi(spec.substr(colon + 1));
        } catch (const std::exception&) {
            throw InvalidInput("garment '" + spec + "': the garment number after ':' is out of range");
        }
    }
    saved.folder = dir;
    std::error_code ec;
    if (!fs::is_directory(saved.folder, ec)) throw IoError("result folder '" + dir + "' does not exist");
    fs::path file = saved.folder / "result.json";
    if (!fs::exists(file, ec)) file = saved.folder / "truth.json";
    if (!fs::exists(file, ec))
        throw IoError("result folder '" + dir + "' holds neither result.json nor truth.json");
    const std::string name = file.string();
    const nlohmann::json j = read_json_file(file);
    const nlohmann::json& b = field(j, "body", name, "the file");
    saved.body = semantic_request_from_json(field(b, "params", name, "'body'"), name);
    if (b.contains("pose")) saved.pose = pose_from_json(b.at("pose"), name);
    const nlohmann::json& gs = field(j, "garments", name, "the file");
    if (!gs.is_array()) throw InvalidInput(name + ": field 'garments' must be an array, got " + gs.dump());
    if (gs.empty()) throw InvalidInput(name + ": the result holds no garment");
    if (only >= static_cast<int>(gs.size()))
        throw InvalidInput("garment '" + spec + "': " + name + " holds " + std::to_string(gs.size()) +
                           " garment(s), numbered from 0");
    for (size_t i = 0; i < gs.size(); ++i) {
        if (only >= 0 && static_cast<int>(i) != only) continue;
        const nlohmann::json& g = gs[i];
        const std::string where = "garment " + std::to_string(i);
        SavedGarment sg;
        sg.index = static_cast<int>(i);
        const nlohmann::json& type = field(g, "type", name, where);
        if (!type.is_string()) throw InvalidInput(name + ": " + where + " field 'type' must be a string, got " + type.dump());
        try {
            sg.type = garment::garment_type_from_name(type.get<std::string>());
        } catch (const InvalidInput& e) {
            throw InvalidInput(name + ": " + where + " field 'type': " + e.what());
        }
        sg.garment = g.contains("garment") && g.at("garment").is_string() ? g.at("garment").get<std::string>()
                                                                          : type.get<std::string>();
        if (g.contains("supported") && g.at("supported").is_boolean()) sg.supported = g.at("supported").get<bool>();
        sg.sizing = sizing_from_json(sg.type, field(g, "sizing", name, where), name + ": " + where);
        sg.material = material_from_json(field(g, "material", name, where), name + ": " + where, &sg.base_fabric);
        saved.garments.push_back(std::move(sg));
    }
    return saved;
}

}  // namespace drape::io
