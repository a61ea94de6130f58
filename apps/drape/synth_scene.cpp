#include "synth_scene.hpp"

#include <drape/io/body_json.hpp>
#include <drape/io/garment_json.hpp>
#include <drape/io/image_io.hpp>
#include <drape/io/json_io.hpp>

#include <drape/body/camera.hpp>
#include <drape/core/errors.hpp>
#include <drape/garment/garment_type.hpp>
#include <drape/synth/print_check.hpp>

#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <optional>
#include <regex>
#include <system_error>
#include <vector>

namespace drape::app {

using namespace io;

namespace {

namespace fs = std::filesystem;
using garment::GarmentType;

body::NamedPose pose_of(const std::string& letter) {
    if (letter == "a") return body::NamedPose::a_pose;
    if (letter == "b") return body::NamedPose::arms_down;
    if (letter == "c") return body::NamedPose::walking;
    throw InvalidInput("--pose '" + letter + "' is not a (A-pose), b (arms down), c (walking) or random");
}

std::optional<render::PrintKind> print_of(const std::string& name) {
    if (name == "sampled") return std::nullopt;
    for (render::PrintKind k : synth::kPrintKinds)
        if (name == synth::print_name(k)) return k;
    throw InvalidInput("--print '" + name + "' is not none, stripes, checks, dots or sampled");
}

// Library messages carry wall times ("4017.18 ms (assembly ...)", "0.25 s"); scene files
// must not, so that they are the same bytes for a seed.
std::string without_timings(const std::string& message) {
    static const std::regex ms(R"(,? ?[0-9.eE+-]+ ms( \([^)]*\))?)"), s(R"(,? ?[0-9.eE+-]+ s\b)");
    return std::regex_replace(std::regex_replace(message, ms, ""), s, "");
}

nlohmann::json deepest_json(const synth::DeepestInside& d) {
    if (!d.found) return nullptr;
    return {{"panel", d.panel},
            {"position_m", {d.position_m.x(), d.position_m.y(), d.position_m.z()}},
            {"depth_m", d.depth_m},
            {"body_joint", d.body_joint}};
}

void write_scene_files(const fs::path& dir, const synth::SynthScene& scene, const synth::SynthOptions& options,
                       const synth::SynthResult& r) {
    write_png(dir / "image_midday.png", r.images.midday.colour);
    write_png(dir / "image_sunset.png", r.images.sunset.colour);
    write_png(dir / "labels.png", r.images.midday.labels);
    write_png(dir / "strokes.png", r.images.strokes);

    nlohmann::json pts = nlohmann::json::array();
    for (const Eigen::Vector2d& p : r.joints.px)
        // Written 1-based like ../shared/data/photos/joints (pixel (1, 1)'s centre is at 1).
        pts.push_back({p.x() + 0.5, p.y() + 0.5});
    write_json_file(dir / "joints.json",
                    {{"joints", pts},
                     {"joint_names", std::vector<std::string>(body::kImageJointNames.begin(), body::kImageJointNames.end())},
                     {"image_size", {scene.width_px, scene.height_px}},
                     {"pixel_origin", "one_based"},
                     {"marks", r.joints.marks == vision::JointMarks::model ? "model" : "hand"}});

    // Ground truth, in the schema `drape recover` writes as result.json.
    body::Pose truth_pose = scene.pose;
    truth_pose.translation += scene.placement;
    nlohmann::json truth_garments = nlohmann::json::array();
    for (std::size_t i = 0; i < scene.garments.size(); ++i) {
        const synth::SynthGarment& g = scene.garments[i];
        truth_garments.push_back({{"type", garment::garment_type_name(g.sizing.type)},
                                  {"sizing", to_json(g.sizing)},
                                  {"material", material_to_json(g.material, g.base_fabric)},
                                  {"mean_curvature_per_m", r.mean_curvature_per_m[i]},
                                  {"wrinkle_density_per_m2", r.wrinkles[i].summary.density_per_m2}});
    }
    write_json_file(dir / "truth.json",
                    {{"body", {{"params", to_json(scene.shape)}, {"pose", to_json(truth_pose)},
                               {"camera", to_json(scene.camera)}}},
                     {"garments", truth_garments}});

    const garment::DrapeSummary& d = r.drape.summary.drape;
    nlohmann::json garment_reports = nlohmann::json::array();
    std::vector<std::string> garment_names;
    for (std::size_t i = 0; i < scene.garments.size(); ++i) {
        const std::string type = garment::garment_type_name(scene.garments[i].sizing.type);
        garment_names.push_back(type);
        const garment::DressingSummary& ds = r.drape.outfit.dressing[i];
        const vision::WrinkleSummary& w = r.wrinkles[i].summary;
        garment_reports.push_back({{"type", type},
                                   {"vertices", r.drape.outfit.meshes[i].cloth.vertex_count()},
                                   {"faces", r.drape.outfit.meshing[i].faces},
                                   {"stitches", r.drape.outfit.meshes[i].stitches.size()},
                                   {"dressing", {{"vertices_inside", ds.vertices_inside},
                                                 {"vertices_pushed", ds.vertices_pushed},
                                                 {"iterations", ds.iterations},
                                                 {"max_seam_gap_m", ds.max_seam_gap_m},
                                                 {"alignment_rms_m", ds.alignment_rms_m}}},
                                   {"seam_gap_max_m", d.seam_gap_max_m},
                                   {"penetration_max_m", d.penetration_max_m},
                                   {"vertices_inside", d.vertices_inside},
                                   {"deepest_inside", deepest_json(r.deepest[i])},
                                   {"self_intersections", d.self_intersections},
                                   {"initial_self_intersections", d.initial_self_intersections},
                                   {"mean_drop_m", d.mean_drop_m},
                                   {"converged", d.converged},
                                   {"usable", d.usable()},
                                   {"steps", d.steps},
                                   {"message", without_timings(d.message)},
                                   {"wrinkles", {{"usable", w.usable()},
                                                 {"folds", w.folds},
                                                 {"fold_count", w.fold_count},
                                                 {"garment_area_m2", w.garment_area_m2},
                                                 {"visible_pixels", r.wrinkles[i].visible_pixels},
                                                 {"message", w.message}}},
                                   {"label", scene.garments[i].label}});
    }
    write_json_file(dir / "summary.json",
                    {{"seed", scene.seed},
                     {"garments", garment_names},
                     {"pose", scene.pose_name},
                     {"edge_cm", options.edge_cm},
                     {"max_steps", options.max_steps},
                     {"image_size", {scene.width_px, scene.height_px}},
                     {"samples_per_pixel", options.samples_per_pixel},
                     {"body_shaping", scene.shaping_report},
                     {"usable", r.summary.usable()},
                     {"drapes", garment_reports}});
}

}  // namespace

synth::SynthOptions with_choices(synth::SynthOptions base, const SynthChoices& choices) {
    base.garments = choices.garment == "random" ? std::vector<GarmentType>{} : outfit_from_spec(choices.garment);
    base.pose = choices.pose == "random" ? std::nullopt : std::optional<body::NamedPose>(pose_of(choices.pose));
    base.fabric = choices.material == "random" ? std::string() : choices.material;
    base.print = print_of(choices.print);
    return base;
}

synth::SynthSummary make_and_write_synth_scene(const synth::SynthOptions& options, const fs::path& dir) {
    const synth::SynthScene scene = synth::sample_synth_scene(options);
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) throw IoError("cannot create output folder '" + dir.string() + "': " + ec.message());
    const synth::SynthResult r = synth::make_synth_scene(scene, options);
    write_scene_files(dir, scene, options, r);
    return r.summary;
}

namespace {

nlohmann::json wrinkles_json(const synth::GarmentWrinkles& w) {
    return {{"P_per_m2", w.summary.density_per_m2},
            {"fold_count", w.summary.fold_count},
            {"usable", w.summary.usable()},
            {"message", w.summary.message}};
}

nlohmann::json print_check_json(const synth::SynthScene& scene, const std::vector<synth::PrintComparison>& garments) {
    nlohmann::json out = nlohmann::json::array();
    for (const synth::PrintComparison& g : garments) {
        nlohmann::json per = nlohmann::json::object(), ratios = nlohmann::json::object();
        for (std::size_t k = 0; k < synth::kPrintKinds.size(); ++k) {
            per[synth::print_name(synth::kPrintKinds[k])] = wrinkles_json(g.wrinkles[k]);
            if (k > 0) ratios[synth::print_name(synth::kPrintKinds[k])] = g.ratio(k);
        }
        out.push_back({{"type", g.type}, {"label", g.label}, {"sampled_print", synth::print_name(g.sampled_print)},
                       {"bending_scale", scene.garments[&g - garments.data()].material.bending_scale},
                       {"prints", per}, {"ratio_to_plain", ratios}});
    }
    return {{"seed", scene.seed}, {"garments", out}};
}

fs::path print_image_path(const fs::path& dir, render::PrintKind k) {
    return dir / (std::string("print_") + synth::print_name(k) + ".png");
}

}  // namespace

nlohmann::json make_and_write_print_check(const synth::SynthOptions& options, const fs::path& dir, bool reuse,
                                          synth::SynthSummary* summary, const vision::WrinkleOptions& detector) {
    if (options.print)
        throw InvalidInput("drape synth --print-check renders every print itself: leave --print out");
    const synth::SynthScene scene = synth::sample_synth_scene(options);
    bool have = reuse && fs::exists(dir / "labels.png");
    for (render::PrintKind k : synth::kPrintKinds) have = have && fs::exists(print_image_path(dir, k));
    std::vector<synth::PrintComparison> garments;
    if (have) {
        std::array<cv::Mat, 4> midday;
        for (std::size_t k = 0; k < midday.size(); ++k) midday[k] = read_photo(print_image_path(dir, synth::kPrintKinds[k]));
        const cv::Mat labels = cv::imread((dir / "labels.png").string(), cv::IMREAD_UNCHANGED);
        if (labels.empty()) throw IoError("cannot read '" + (dir / "labels.png").string() + "'");
        garments = synth::compare_prints(scene, midday, labels, detector);
    } else {
        std::error_code ec;
        fs::create_directories(dir, ec);
        if (ec) throw IoError("cannot create output folder '" + dir.string() + "': " + ec.message());
        const synth::SynthResult r = synth::make_synth_scene(scene, options);
        write_scene_files(dir, scene, options, r);
        const synth::PrintCheck c = synth::check_prints(scene, r, options, detector);
        for (std::size_t k = 0; k < c.midday.size(); ++k) write_png(print_image_path(dir, synth::kPrintKinds[k]), c.midday[k]);
        garments = c.garments;
        if (summary) *summary = r.summary;
    }
    const nlohmann::json j = print_check_json(scene, garments);
    write_json_file(dir / "print_check.json", j);
    return j;
}

}  // namespace drape::app
