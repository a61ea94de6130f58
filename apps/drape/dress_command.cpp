// drape dress --garment skirt|pants|tshirt|dress --sizing G.json|auto --material NAME|PATH
//             [--materials DIR] [--body P.json] [--pose NAME|POSE.json] [--edge CM]
//             [--no-render] [--save-dressed] [--keep-arms] --out DIR
// drape eval-dress [--garments LIST] [--poses LIST] [--bodies LIST] [--edge CM] [--material NAME|PATH]
//             [--materials DIR] [--ansur N [--seed S] [--ansur-dir DIR]] [--docs FILE] --out DIR
//             (the templates x bodies x poses table; --ansur: bodies sampled from the ANSUR II records)
#include <drape/io/body_json.hpp>
#include "commands.hpp"
#include <drape/io/garment_json.hpp>
#include <drape/io/image_io.hpp>
#include <drape/io/json_io.hpp>
#include <drape/io/material_arg.hpp>

#include <drape/body/body_model.hpp>
#include <drape/body/pose.hpp>
#include <drape/body/shape_body.hpp>
#include <drape/cloth/material.hpp>
#include <drape/core/atomic_file.hpp>
#include <drape/core/errors.hpp>
#include <drape/garment/arm_clearance.hpp>
#include <drape/garment/drape_garment.hpp>
#include <drape/fixtures/ansur_records.hpp>
#include <drape/fixtures/eval_bodies.hpp>
#include <drape/garment/dress_outfit.hpp>
#include <drape/garment/garment_export.hpp>
#include <drape/garment/dressing.hpp>
#include <drape/garment/garment_mesh.hpp>
#include <drape/garment/pattern_dxf.hpp>
#include <drape/garment/pattern_json.hpp>
#include <drape/garment/pattern_svg.hpp>
#include <drape/garment/sizing_proposal.hpp>
#include <drape/render/preview.hpp>
#include <drape/render/renderer.hpp>

#include <CLI/CLI.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <array>
#include <atomic>
#include <mutex>
#include <thread>
#include <chrono>
#include <fstream>
#include <sstream>
#include <tuple>
#include <iomanip>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <memory>
#include <sstream>

namespace drape::app {

using namespace io;

namespace {

namespace fs = std::filesystem;

struct DressArgs {
    std::string garment;
    std::string sizing;
    std::string material;
    std::string materials_dir;
    std::string body;
    std::string pose = "a_pose";
    std::string out;
    double edge_cm = 0;  // 0: kDefaultEdgeCm, kPantsEdgeCm for pants and outfits with pants
    bool no_render = false;
    bool save_dressed = false;
    bool keep_arms = false;
    double motion_s = garment::DrapeOptions{}.body_motion_s;
};

}  // namespace

body::Pose resolve_pose(const std::string& name) {
    if (name == "a_pose") return body::named_pose(body::NamedPose::a_pose);
    if (name == "arms_down") return body::named_pose(body::NamedPose::arms_down);
    if (name == "walking") return body::named_pose(body::NamedPose::walking);
    if (name == "t_pose") return body::named_pose(body::NamedPose::t_pose);
    if (fs::path(name).extension() == ".json") return pose_from_json(read_json_file(name), name);
    throw InvalidInput("--pose '" + name + "' is not a_pose, arms_down, walking, t_pose or a POSE.json file");
}

namespace {

/// Body and garments from the front-left, on a floor, studio light (render::preview_scene).
cv::Mat write_render(const fs::path& path, const Eigen::MatrixX3d& body_V, const Eigen::MatrixX3i& body_F,
                  const std::vector<const garment::GarmentMesh*>& meshes, const std::vector<Eigen::MatrixX3d>& Xs,
                  int width = 600, int height = 900) {
    std::vector<render::PreviewGarment> garments;
    for (size_t k = 0; k < meshes.size(); ++k) garments.push_back({Xs[k], meshes[k]->cloth.faces, meshes[k]->uv});
    const render::Scene scene = render::preview_scene(body_V, body_F, garments);
    const render::Camera camera = render::preview_camera(body_V, width, height);
    render::RenderImages images;
    const render::RenderSummary s =
        render::render(scene, camera, render::lighting_preset(render::LightingPreset::studio), {}, images);
    std::cerr << "drape dress: " << s.brief_report() << "\n";
    write_png(path, images.colour);
    return images.colour;
}

/// The summary.json keys common to a garment and an outfit.
nlohmann::json drape_report(const DressArgs& args, const std::string& material_source,
                            const garment::DrapeSummary& d) {
    nlohmann::json report = to_json(d);
    report["material"] = material_source;
    report["pose"] = args.pose;
    report["edge_cm"] = args.edge_cm;
    return report;
}

/// Progress on stderr every 50 steps.
bool print_progress(const garment::DrapeProgress& p) {
    if (p.step % 50 == 0)
        std::cerr << "drape dress: step " << p.step << ", seam gap " << 1000 * p.seam_gap_max_m
                  << " mm, kinetic energy " << p.kinetic_energy_j << " J\n";
    return true;
}

fs::path make_output_folder(const std::string& out) {
    const fs::path dir(out);
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) throw IoError("cannot create output folder '" + out + "': " + ec.message());
    return dir;
}

// The arm clearance's report on stderr, prefixed with `who`, when an arm had to move.
void print_arms(const std::string& who, const garment::ArmClearanceSummary& arms) {
    if (arms.crossings_before > 0) std::cerr << who << ": " << arms.brief_report() << "\n";
}

// The inputs both forms of `drape dress` read and check before the slow work.
struct DressInputs {
    body::Pose pose;
    cloth::Material material;
    std::string material_source;
    body::SemanticRequest body;
};

DressInputs read_dress_inputs(const DressArgs& args) {
    require(args.edge_cm > 0 && args.edge_cm <= 20, "--edge ", args.edge_cm, " must be in (0, 20] cm");
    DressInputs in;
    in.pose = resolve_pose(args.pose);
    in.material = load_material_arg(args.material, args.materials_dir, &in.material_source);
    in.body = args.body.empty() ? body::SemanticRequest{} : semantic_request_from_json(read_json_file(args.body), args.body);
    return in;
}

// The pipeline's options from `drape dress`'s flags.
garment::DressOutfitOptions dress_options(const DressArgs& args) {
    garment::DressOutfitOptions options;
    options.mesh.target_edge_cm = args.edge_cm;
    options.drape.on_progress = print_progress;
    options.drape.body_motion_s = args.motion_s;
    options.clear_arms = !args.keep_arms;
    return options;
}

// The body of --body (default: the mean female), shaped to its measurements.
body::ShapedBody shape_requested_body(const body::BodyModel& model, const body::SemanticRequest& request,
                                      const std::string& who) {
    body::ShapedBody shaped;
    const body::ShapeSummary shape = body::shape_body(model, model.prior.complete(request), body::ShapeOptions{}, shaped);
    if (!shape.usable()) throw std::runtime_error(who + ": body shaping failed: " + shape.brief_report());
    return shaped;
}

void run_dress_outfit(const DressArgs& args);

// Default mesh edge of `drape dress`. Pants get a coarser one: at 1.5 cm the dressing of
// their crotch (the push-out between the thighs) leaves crossings or vertices inside the
// body on 4 of the 5 evaluation bodies (all but the 5th-percentile woman), at 2.5 cm none
// (docs/dressing.md, Known problems).
constexpr double kDefaultEdgeCm = 1.5;
constexpr double kPantsEdgeCm = 2.5;

void run_dress(const DressArgs& requested) {
    DressArgs args = requested;
    if (args.edge_cm == 0)
        args.edge_cm = args.garment.find("pants") != std::string::npos ? kPantsEdgeCm : kDefaultEdgeCm;
    if (args.garment.find('+') != std::string::npos) return run_dress_outfit(args);
    const auto start = std::chrono::steady_clock::now();
    // Every input is read and checked before the slow work.
    const GarmentType type = garment_type_from_name(args.garment);
    const DressInputs in = read_dress_inputs(args);
    garment::GarmentRequest garment_request;
    garment_request.type = type;
    if (args.sizing != "auto") garment_request.sizing = sizing_from_json(type, read_json_file(args.sizing), args.sizing);
    garment_request.material = in.material;
    const garment::DressOutfitOptions options = dress_options(args);

    const body::BodyModel& model = body::BodyModel::default_model();
    const body::ShapedBody shaped = shape_requested_body(model, in.body, "drape dress");
    const fs::path dir = make_output_folder(args.out);
    // Dressed in the rest A-pose, sewn, then moved to the pose (garment::dress_outfit).
    garment::DressedOutfit out;
    const garment::DressOutfitSummary s = garment::dress_outfit(model, shaped, in.pose, {garment_request}, options, out);
    print_arms("drape dress", out.arms);
    const garment::Pattern& pattern = out.patterns[0];
    garment::write_pattern_svg(dir / "pattern.svg", pattern);
    garment::write_pattern_dxf(dir / "pattern.dxf", pattern);
    garment::write_pattern_json(dir / "pattern.json", pattern);
    if (s.termination != garment::DressOutfitTermination::draped) throw std::runtime_error("drape dress: " + s.message);
    const garment::GarmentMesh& mesh = out.meshes[0];
    std::cerr << "drape dress: " << out.meshing[0].brief_report() << "\n";
    if (args.save_dressed) {  // the initial state the simulation starts from
        Eigen::MatrixX3d D;
        body::Pose dressing_pose;
        garment::dress_for_drape(pattern, mesh, model, shaped, options.dressing, D, dressing_pose);
        garment::write_garment_obj(dir / "dressed.obj", pattern, mesh, D, "dressed garment (rest A-pose), world");
        if (!args.no_render)
            write_render(dir / "dressed.png", body::pose_body(model, shaped, dressing_pose).vertices, model.faces,
                         {&mesh}, {D});
    }
    const garment::DrapeSummary& draped = s.drape;
    std::cerr << "drape dress: " << out.dressing[0].brief_report() << "\n";
    std::cout << "drape dress: " << pattern.name << ", " << draped.brief_report() << "\n";

    const Eigen::MatrixX3d& X = out.positions[0];
    garment::write_garment_obj(dir / "garment.obj", pattern, mesh, X, "draped garment, world");
    garment::write_garment_glb(dir / "garment.glb", mesh, X);
    if (!args.no_render) write_render(dir / "render.png", out.body_vertices, model.faces, {&mesh}, {X});
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    nlohmann::json report = drape_report(args, in.material_source, draped);
    report["arms_raised_deg"] = {{"right", out.arms.right_degrees}, {"left", out.arms.left_degrees}};
    report["garment"] = garment_type_name(type);
    report["sizing"] = to_json(out.sizings[0]);
    report["faces"] = out.meshing[0].faces;
    report["dressing"] = out.dressing[0].brief_report();
    report["seconds_dress"] = out.dressing[0].seconds;
    report["seconds"] = seconds;
    write_json_file(dir / "summary.json", report);
    if (!draped.usable()) throw std::runtime_error("drape dress: draping not usable: " + draped.brief_report());
}

}  // namespace

namespace {

// `--garment top+bottom`: an outfit dressed and draped together (one fabric), the top over
// the bottom's waistband. Files per garment carry its name (garment_tshirt.obj, ...).
void run_dress_outfit(const DressArgs& args) {
    const auto start = std::chrono::steady_clock::now();
    const std::vector<GarmentType> types = outfit_from_spec(args.garment);  // inner (bottom) first
    const DressInputs in = read_dress_inputs(args);
    // --sizing auto, or one JSON object with a group per garment: {"tshirt": {...}, "pants": {...}}.
    nlohmann::json groups;
    if (args.sizing != "auto") {
        groups = read_json_file(args.sizing);
        require(groups.is_object(), args.sizing, ": an outfit's sizing must be an object with a group per garment");
        for (const auto& [key, value] : groups.items()) {
            const bool known = std::any_of(types.begin(), types.end(), [&](GarmentType t) { return garment_type_name(t) == key; });
            require(known, args.sizing, ": group '", key, "' is not a garment of the outfit '", args.garment, "'");
            require(value.is_object(), args.sizing, ": group '", key, "' must be an object");
        }
    }
    std::vector<garment::GarmentRequest> requests;
    for (GarmentType t : types) {
        const std::string name = garment_type_name(t);
        garment::GarmentRequest r;
        r.type = t;
        if (groups.contains(name)) r.sizing = sizing_from_json(t, groups[name], args.sizing + " (" + name + ")");
        r.material = in.material;
        requests.push_back(r);
    }
    const garment::DressOutfitOptions options = dress_options(args);

    const body::BodyModel& model = body::BodyModel::default_model();
    const body::ShapedBody shaped = shape_requested_body(model, in.body, "drape dress");
    const fs::path dir = make_output_folder(args.out);
    garment::DressedOutfit out;
    const garment::DressOutfitSummary s = garment::dress_outfit(model, shaped, in.pose, requests, options, out);
    print_arms("drape dress", out.arms);
    for (size_t g = 0; g < types.size(); ++g) {
        const std::string name = garment_type_name(types[g]);
        garment::write_pattern_svg(dir / ("pattern_" + name + ".svg"), out.patterns[g]);
        garment::write_pattern_dxf(dir / ("pattern_" + name + ".dxf"), out.patterns[g]);
        garment::write_pattern_json(dir / ("pattern_" + name + ".json"), out.patterns[g]);
    }
    if (s.termination != garment::DressOutfitTermination::draped) throw std::runtime_error("drape dress: " + s.message);
    const garment::DrapeSummary& draped = s.drape;
    std::cout << "drape dress: " << args.garment << ", " << draped.brief_report() << "\n";
    nlohmann::json garments = nlohmann::json::array();
    std::vector<const garment::GarmentMesh*> mesh_ptrs;
    for (size_t g = 0; g < types.size(); ++g) {
        const std::string name = garment_type_name(types[g]);
        garment::write_garment_obj(dir / ("garment_" + name + ".obj"), out.patterns[g], out.meshes[g], out.positions[g],
                          "draped " + name + ", world");
        garment::write_garment_glb(dir / ("garment_" + name + ".glb"), out.meshes[g], out.positions[g]);
        const garment::GarmentStateCheck& c = out.checks[g];
        garments.push_back({{"garment", name},
                            {"layer", g == 0 ? "inner" : "outer"},
                            {"sizing", to_json(out.sizings[g])},
                            {"vertices", out.meshes[g].cloth.vertex_count()},
                            {"seam_gap_max_m", c.max_seam_gap_m},
                            {"penetration_max_m", c.max_penetration_m},
                            {"self_intersections", c.self_intersections},
                            {"dressing", out.dressing[g].brief_report()}});
        mesh_ptrs.push_back(&out.meshes[g]);
    }
    if (!args.no_render) write_render(dir / "render.png", out.body_vertices, model.faces, mesh_ptrs, out.positions);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    nlohmann::json report = drape_report(args, in.material_source, draped);
    report["arms_raised_deg"] = {{"right", out.arms.right_degrees}, {"left", out.arms.left_degrees}};
    report["garment"] = args.garment;
    report["garments"] = garments;
    report["seconds"] = seconds;
    write_json_file(dir / "summary.json", report);
    if (!draped.usable()) throw std::runtime_error("drape dress: draping not usable: " + draped.brief_report());
}

}  // namespace

struct EvalDressArgs {
    std::vector<std::string> garments = {"skirt", "pants", "tshirt", "dress"};
    std::vector<std::string> poses = {"a_pose", "arms_down", "walking"};
    std::vector<std::string> bodies;  // empty: all of kEvalBodies (or of the ANSUR sample)
    std::string material = "gray-interlock";
    std::string materials_dir;
    double edge_cm = 4.0;
    bool outfit = true;
    int ansur = 0;             // > 0: this many bodies sampled from the ANSUR II records
    std::uint64_t seed = 1;    // of the ANSUR sampling
    std::string ansur_dir = "../shared/data/anthropometry";
    int jobs = 1;              // cases run at once (threads)
    std::string docs;  // a Markdown file whose eval-dress block is replaced (see kDocsBegin)
    std::string out;
};

using garment::EvalBody;
using garment::kEvalBodies;

// `--docs FILE`: the lines between these markers are replaced by the run's table and its
// summary line, and the contact sheet goes to images/dress_eval.jpg beside FILE. A run with
// --ansur has its own markers, so both tables live in one file.
constexpr const char* kDocsBegin = "<!-- drape eval-dress: table begin -->";
constexpr const char* kDocsEnd = "<!-- drape eval-dress: table end -->";
constexpr const char* kDocsAnsurBegin = "<!-- drape eval-dress --ansur: table begin -->";
constexpr const char* kDocsAnsurEnd = "<!-- drape eval-dress --ansur: table end -->";

// The text of `path` and where its eval-dress block's content starts and ends.
// \throw IoError if unreadable, InvalidInput naming the file if a marker is missing.
std::tuple<std::string, size_t, size_t> docs_block(const fs::path& path, const std::string& begin_marker,
                                                   const std::string& end_marker) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw IoError("drape eval-dress: --docs " + path.string() + ": cannot read the file");
    std::ostringstream text;
    text << in.rdbuf();
    const std::string s = text.str();
    const size_t b = s.find(begin_marker), e = s.find(end_marker);
    require(b != std::string::npos && e != std::string::npos && b < e, "drape eval-dress: --docs ", path.string(),
            ": needs the lines '", begin_marker, "' and then '", end_marker, "' around the table to replace");
    return {s, b + begin_marker.size(), e};
}

// A body of the evaluation: a fixed one (kEvalBodies) or an ANSUR II record.
struct EvalCaseBody {
    std::string name;                 // female_p50, or f10037 / m20512 (gender, subject id)
    body::SemanticRequest request;
    int subject_id = 0;               // ANSUR: the record's id
    std::string stratum;              // ANSUR: why it was sampled ("height p1", "random", ...)
    body::Gender gender = body::Gender::female;
    double height_m = 0, weight_kg = 0, chest_m = 0, waist_m = 0, hip_m = 0;  // as requested
};

std::vector<EvalCaseBody> eval_bodies(const EvalDressArgs& args) {
    std::vector<EvalCaseBody> bodies;
    if (args.ansur == 0) {
        for (const EvalBody& eb : kEvalBodies) {
            EvalCaseBody b;
            b.name = eb.name;
            b.gender = eb.gender;
            b.height_m = eb.height_m;
            b.weight_kg = eb.weight_kg;
            b.request.gender = eb.gender;
            b.request[body::Semantic::height_m] = eb.height_m;
            b.request[body::Semantic::weight_kg] = eb.weight_kg;
            bodies.push_back(b);
        }
        return bodies;
    }
    // The record's measurements, as `drape dress --body P.json` with them: stature, mass,
    // chest, waist, hip, thigh and calf girths, shoulder and crotch heights; the muscle
    // proxy (not a measurement) is left to the prior.
    for (const test::AnsurSampledRecord& s :
         test::sample_ansur_bodies(test::load_ansur_all(args.ansur_dir), args.ansur, args.seed)) {
        EvalCaseBody b;
        b.gender = s.record.gender;
        b.name = std::string(b.gender == body::Gender::female ? "f" : "m") + std::to_string(s.record.subject_id);
        b.subject_id = s.record.subject_id;
        b.stratum = s.stratum;
        b.request.gender = b.gender;
        for (int k = 0; k < body::kSemanticCount; ++k)
            if (k != int(body::Semantic::muscle)) b.request.values[size_t(k)] = s.record.values[k];
        const auto value = [&](body::Semantic v) { return s.record.values[int(v)]; };
        b.height_m = value(body::Semantic::height_m);
        b.weight_kg = value(body::Semantic::weight_kg);
        b.chest_m = value(body::Semantic::chest_girth_m);
        b.waist_m = value(body::Semantic::waist_girth_m);
        b.hip_m = value(body::Semantic::hip_girth_m);
        bodies.push_back(b);
    }
    return bodies;
}

// One case's result.
struct EvalCase {
    std::string garment, body, pose;
    bool usable = false;
    int vertices = 0, self_intersections = 0, steps = 0;
    double seam_gap_m = 0, penetration_m = 0, drop_m = 0, seconds = 0;
    bool converged = false;
    std::string why;  // the drape's report, or the error that stopped the case
};

std::string fixed(double v, int digits) {
    std::ostringstream s;
    s << std::fixed << std::setprecision(digits) << v;
    return s.str();
}

// The --ansur tables: bodies with their usable cases per template, usable counts per
// template and pose, and every failure.
std::string ansur_tables(const std::vector<EvalCaseBody>& bodies, const std::vector<std::string>& garments,
                         const std::vector<std::string>& poses, const std::vector<EvalCase>& cases) {
    std::ostringstream t;
    t << "| body | subject | gender | sampled as | stature m | mass kg | chest / waist / hip m |";
    for (const std::string& g : garments) t << " " << g << " |";
    t << "\n|---|---|---|---|---|---|---|";
    for (size_t k = 0; k < garments.size(); ++k) t << "---|";
    t << "\n";
    const auto count = [&](const std::string& g, const std::string& b, const std::string& p, bool only_usable) {
        return std::count_if(cases.begin(), cases.end(), [&](const EvalCase& c) {
            return (g.empty() || c.garment == g) && (b.empty() || c.body == b) && (p.empty() || c.pose == p) &&
                   (!only_usable || c.usable);
        });
    };
    for (const EvalCaseBody& b : bodies) {
        t << "| " << b.name << " | " << b.subject_id << " | " << body::to_string(b.gender) << " | " << b.stratum
          << " | " << fixed(b.height_m, 3) << " | " << fixed(b.weight_kg, 1) << " | " << fixed(b.chest_m, 2) << " / "
          << fixed(b.waist_m, 2) << " / " << fixed(b.hip_m, 2) << " |";
        for (const std::string& g : garments) t << " " << count(g, b.name, "", true) << "/" << count(g, b.name, "", false) << " |";
        t << "\n";
    }
    t << "\nUsable per template and pose (all bodies):\n\n| template |";
    for (const std::string& p : poses) t << " " << p << " |";
    t << " all |\n|---|";
    for (size_t k = 0; k <= poses.size(); ++k) t << "---|";
    t << "\n";
    for (const std::string& g : garments) {
        t << "| " << g << " |";
        for (const std::string& p : poses) t << " " << count(g, "", p, true) << "/" << count(g, "", p, false) << " |";
        t << " " << count(g, "", "", true) << "/" << count(g, "", "", false) << " |\n";
    }
    t << "\nFailures:\n\n";
    bool any = false;
    for (const EvalCase& c : cases)
        if (!c.usable) {
            any = true;
            t << "- " << c.garment << " / " << c.body << " / " << c.pose << ": seam gap " << fixed(1000 * c.seam_gap_m, 2)
              << " mm, penetration " << fixed(1000 * c.penetration_m, 2) << " mm, " << c.self_intersections
              << " crossings, " << (c.converged ? "converged" : "not converged") << " (" << c.why << ")\n";
        }
    if (!any) t << "- none\n";
    return t.str();
}

void run_eval_dress(const EvalDressArgs& args) {
    require(args.edge_cm > 0 && args.edge_cm <= 20, "--edge ", args.edge_cm, " must be in (0, 20] cm");
    require(args.ansur >= 0, "--ansur ", args.ansur, " must be >= 0 (0: the five fixed bodies)");
    require(args.jobs >= 1 && args.jobs <= 64, "--jobs ", args.jobs, " must be in [1, 64]");
    const bool ansur = args.ansur > 0;
    const std::string docs_begin = ansur ? kDocsAnsurBegin : kDocsBegin, docs_end = ansur ? kDocsAnsurEnd : kDocsEnd;
    // Checked before the long run, used after it.
    if (!args.docs.empty()) docs_block(args.docs, docs_begin, docs_end);
    const std::vector<EvalCaseBody> all_bodies = eval_bodies(args);
    const auto selected = [&](const EvalCaseBody& eb) {
        return args.bodies.empty() || std::find(args.bodies.begin(), args.bodies.end(), eb.name) != args.bodies.end();
    };
    for (const std::string& b : args.bodies) {
        std::string names;
        for (const EvalCaseBody& eb : all_bodies) names += (names.empty() ? "" : ", ") + eb.name;
        require(std::any_of(all_bodies.begin(), all_bodies.end(), [&](const EvalCaseBody& eb) { return b == eb.name; }),
                "--bodies: unknown body '", b, "' (", names, ")");
    }
    std::vector<EvalCaseBody> bodies;
    for (const EvalCaseBody& eb : all_bodies)
        if (selected(eb)) bodies.push_back(eb);
    std::vector<GarmentType> types;
    for (const std::string& g : args.garments) types.push_back(garment_type_from_name(g));
    std::vector<body::Pose> poses;
    for (const std::string& p : args.poses) poses.push_back(resolve_pose(p));
    std::string material_source;
    const cloth::Material material = load_material_arg(args.material, args.materials_dir, &material_source);
    const fs::path dir = make_output_folder(args.out);

    garment::DressOutfitOptions options;  // default dressing and draping, arms cleared
    options.mesh.target_edge_cm = args.edge_cm;

    const body::BodyModel& model = body::BodyModel::default_model();
    std::ostringstream table;
    table << "| garment | body | pose | vertices | seam gap mm | penetration mm | self-int. | drop cm | converged | usable | steps | s |\n"
          << "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    // One case: the garments (inner first) on a body in pose k. An exception (a body that
    // cannot be shaped, a proposed sizing the template refuses) is that case's failure, not
    // the run's. Cases run on --jobs threads; results are kept in case order.
    struct CaseSpec {
        size_t body = 0;
        std::string name;
        std::vector<garment::GarmentRequest> requests;
        size_t pose = 0;
        bool render = false;
    };
    std::vector<body::ShapedBody> shaped_bodies(bodies.size());
    std::vector<std::string> shape_errors(bodies.size());
    std::vector<CaseSpec> specs;
    for (size_t i = 0; i < bodies.size(); ++i) {
        const EvalCaseBody& eb = bodies[i];
        try {
            shaped_bodies[i] = shape_requested_body(model, eb.request, "drape eval-dress: " + eb.name);
        } catch (const std::exception& e) {
            if (!ansur) throw;  // the fixed bodies always shape
            shape_errors[i] = e.what();
        }
        for (size_t t = 0; t < types.size(); ++t) {
            garment::GarmentRequest garment_request;
            garment_request.type = types[t];
            garment_request.material = material;
            // One render per template and pose, on the median woman.
            for (size_t k = 0; k < poses.size(); ++k)
                specs.push_back({i, args.garments[t], {garment_request}, k, eb.name == "female_p50"});
        }
        // The outfit (t-shirt over pants): on the median woman of the fixed bodies, on every
        // sampled ANSUR body. Its row reports the joint simulation (crossings between the
        // garments included) and each garment's own check.
        if (args.outfit && (ansur || eb.name == "female_p50")) {
            std::vector<garment::GarmentRequest> requests(2);
            requests[0].type = GarmentType::pants;
            requests[1].type = GarmentType::tshirt;
            for (garment::GarmentRequest& r : requests) r.material = material;
            for (size_t k = 0; k < poses.size(); ++k) specs.push_back({i, "tshirt+pants", requests, k, !ansur});
        }
    }
    std::vector<EvalCase> cases(specs.size());
    std::vector<nlohmann::json> case_json(specs.size());
    std::vector<cv::Mat> renders(specs.size());
    std::mutex print_mutex;
    int done = 0;
    const auto run_case = [&](size_t index) {
        const CaseSpec& spec = specs[index];
        const EvalCaseBody& eb = bodies[spec.body];
        EvalCase c;
        c.garment = spec.name;
        c.body = eb.name;
        c.pose = args.poses[spec.pose];
        nlohmann::json sizings = nlohmann::json::array();
        std::string arms;
        try {
            if (!shape_errors[spec.body].empty()) throw std::runtime_error(shape_errors[spec.body]);
            garment::DressedOutfit out;
            const garment::DressOutfitSummary s = garment::dress_outfit(model, shaped_bodies[spec.body],
                                                                        poses[spec.pose], spec.requests, options, out);
            if (out.arms.crossings_before > 0) arms = out.arms.brief_report();
            if (s.termination != garment::DressOutfitTermination::draped) throw std::runtime_error(s.message);
            const garment::DrapeSummary& d = s.drape;
            // Usable by the simulator's own report and by the independent checks of each draped garment.
            c.usable = s.usable() && s.checks_pass(out);
            c.vertices = d.vertices;
            c.seam_gap_m = d.seam_gap_max_m;
            c.penetration_m = d.penetration_max_m;
            c.self_intersections = d.self_intersections;
            for (const garment::GarmentStateCheck& check : out.checks) {
                c.seam_gap_m = std::max(c.seam_gap_m, check.max_seam_gap_m);
                c.penetration_m = std::max(c.penetration_m, check.max_penetration_m);
                c.self_intersections = std::max(c.self_intersections, check.self_intersections);
            }
            c.drop_m = d.mean_drop_m;
            c.converged = d.converged;
            c.steps = d.steps;
            c.seconds = s.seconds_dress + d.seconds;
            c.why = d.brief_report();
            for (size_t g = 0; g < out.dressing.size(); ++g)
                c.why += "; dressing " + garment_type_name(spec.requests[g].type) + ": " + out.dressing[g].brief_report();
            for (const garment::GarmentSizing& z : out.sizings) sizings.push_back(to_json(z));
            if (spec.render) {
                std::vector<const garment::GarmentMesh*> meshes;
                for (const garment::GarmentMesh& m : out.meshes) meshes.push_back(&m);
                renders[index] = write_render(dir / (spec.name + "_" + c.pose + ".png"), out.body_vertices,
                                              model.faces, meshes, out.positions, 300, 450);
            }
        } catch (const std::exception& e) {
            c.usable = false;
            c.why = std::string("refused: ") + e.what();
        }
        case_json[index] = {{"garment", c.garment},
                            {"body", eb.name},
                            {"subject_id", eb.subject_id},
                            {"pose", c.pose},
                            {"sizing", sizings},
                            {"vertices", c.vertices},
                            {"seam_gap_max_m", c.seam_gap_m},
                            {"penetration_max_m", c.penetration_m},
                            {"self_intersections", c.self_intersections},
                            {"mean_drop_m", c.drop_m},
                            {"converged", c.converged},
                            {"usable", c.usable},
                            {"steps", c.steps},
                            {"report", c.why},
                            {"seconds", c.seconds}};
        const std::lock_guard<std::mutex> lock(print_mutex);
        if (!arms.empty()) std::cerr << "drape eval-dress: " << eb.name << " / " << c.pose << ": " << arms << "\n";
        std::cout << "drape eval-dress: " << ++done << "/" << specs.size() << ": " << c.garment << " / " << eb.name
                  << " / " << c.pose << ": " << (c.usable ? "usable" : "NOT usable") << ", " << c.why << std::endl;
        cases[index] = std::move(c);
    };
    {
        std::atomic<size_t> next{0};
        const auto worker = [&] {
            for (size_t i = next++; i < specs.size(); i = next++) run_case(i);
        };
        std::vector<std::thread> threads;
        for (int j = 1; j < args.jobs; ++j) threads.emplace_back(worker);
        worker();
        for (std::thread& t : threads) t.join();
    }
    std::vector<std::string> table_garments = args.garments;
    if (args.outfit) table_garments.push_back("tshirt+pants");
    int usable = 0, total = 0;
    double seconds_sum = 0;
    nlohmann::json cases_json = nlohmann::json::array();
    std::vector<std::pair<std::string, cv::Mat>> sheet_cells;
    for (size_t i = 0; i < specs.size(); ++i) {
        const EvalCase& c = cases[i];
        usable += c.usable ? 1 : 0;
        ++total;
        seconds_sum += c.seconds;
        table << "| " << c.garment << " | " << c.body << " | " << c.pose << " | " << c.vertices << " | "
              << fixed(1000 * c.seam_gap_m, 2) << " | " << fixed(1000 * c.penetration_m, 2) << " | "
              << c.self_intersections << " | " << fixed(100 * c.drop_m, 1) << " | " << (c.converged ? "yes" : "no")
              << " | " << (c.usable ? "**yes**" : "no") << " | " << c.steps << " | " << fixed(c.seconds, 1) << " |\n";
        cases_json.push_back(case_json[i]);
        if (specs[i].render) sheet_cells.push_back({c.garment + ", " + c.pose, renders[i]});
    }
    // Contact sheet: a row per garment (and the outfit), a column per pose.
    std::string contact_sheet_jpeg;
    if (!sheet_cells.empty()) {
        const int columns = int(poses.size()), w = 300, h = 450, caption = 24;
        const int rows = (int(sheet_cells.size()) + columns - 1) / columns;
        cv::Mat sheet(rows * (h + caption), columns * w, CV_8UC3, cv::Scalar(255, 255, 255));
        for (size_t i = 0; i < sheet_cells.size(); ++i) {
            const int x0 = int(i % size_t(columns)) * w, y0 = int(i / size_t(columns)) * (h + caption);
            const cv::Mat& im = sheet_cells[i].second;
            if (im.rows == h && im.cols == w && im.type() == CV_8UC3) im.copyTo(sheet(cv::Rect(x0, y0, w, h)));
            cv::putText(sheet, sheet_cells[i].first, cv::Point(x0 + 6, y0 + h + 17), cv::FONT_HERSHEY_SIMPLEX, 0.5,
                        cv::Scalar(30, 30, 30), 1, cv::LINE_AA);
        }
        std::vector<unsigned char> jpeg;
        cv::imencode(".jpg", sheet, jpeg, {cv::IMWRITE_JPEG_QUALITY, 80});
        contact_sheet_jpeg.assign(jpeg.begin(), jpeg.end());
        write_text_atomically(dir / "contact_sheet.jpg", contact_sheet_jpeg);
    }
    std::ostringstream summary;
    summary << usable << " of " << total << " cases usable (" << fixed(100.0 * usable / std::max(total, 1), 1)
            << " %); " << fixed(seconds_sum / std::max(total, 1), 1) << " s per case on average (dress + drape).\n";
    table << "\n" << summary.str();
    write_text_atomically(dir / "table.md", table.str());
    const std::string docs_table =
        ansur ? ansur_tables(bodies, table_garments, args.poses, cases) + "\n" + summary.str() : table.str();
    if (ansur) write_text_atomically(dir / "bodies.md", docs_table);
    if (!args.docs.empty()) {
        const auto [text, begin, end] = docs_block(args.docs, docs_begin, docs_end);
        write_text_atomically(args.docs, text.substr(0, begin) + "\n" + docs_table + text.substr(end));
        if (!contact_sheet_jpeg.empty()) {
            const fs::path images = fs::path(args.docs).parent_path() / "images";
            fs::create_directories(images);
            write_text_atomically(images / "dress_eval.jpg", contact_sheet_jpeg);
        }
        std::cout << "drape eval-dress: wrote the table into " << args.docs << "\n";
    }
    nlohmann::json results = {{"edge_cm", args.edge_cm}, {"material", material_source}, {"usable", usable},
                              {"total", total}, {"cases", cases_json}};
    if (ansur) results["ansur"] = {{"count", args.ansur}, {"seed", args.seed}, {"dir", args.ansur_dir}};
    write_json_file(dir / "results.json", results);
    std::cout << (ansur ? docs_table : table.str());
}

void add_eval_dress_command(CLI::App& app) {
    auto args = std::make_shared<EvalDressArgs>();
    CLI::App* cmd = app.add_subcommand(
        "eval-dress", "Dress and drape every template on five ANSUR bodies (or --ansur N bodies sampled from the "
                      "ANSUR II records) in three poses; writes table.md, results.json and one render per template "
                      "and pose (the median woman)");
    cmd->add_option("--garments", args->garments, "templates (default: skirt pants tshirt dress)");
    cmd->add_option("--poses", args->poses, "poses (default: a_pose arms_down walking)");
    cmd->add_option("--bodies", args->bodies,
                    "evaluation bodies (default: female_p5 female_p50 female_p95 male_p5 male_p95; the outfit only "
                    "with female_p50); with --ansur, names of the sample (f<subject id>, m<subject id>)");
    cmd->add_option("--ansur", args->ansur,
                    "instead of the five fixed bodies, N >= 8 real records of the ANSUR II survey: per gender the "
                    "1st and 99th percentiles of stature and of body mass, the rest drawn at random (--seed); each "
                    "body shaped to the record's stature, mass, girths and heights; the outfit on every body; "
                    "bodies.md gets the per-body table");
    cmd->add_option("--seed", args->seed, "seed of the --ansur sampling (default 1)");
    cmd->add_option("--ansur-dir", args->ansur_dir,
                    "folder of ANSUR_II_FEMALE_Public.csv and ANSUR_II_MALE_Public.csv (default "
                    "../shared/data/anthropometry)");
    cmd->add_option("--jobs", args->jobs, "cases run at once, on threads (default 1)");
    cmd->add_option("--edge", args->edge_cm, "mesh target edge length, cm (default 4)");
    cmd->add_option("--material", args->material, "fabric name or file (default gray-interlock)");
    cmd->add_flag("!--no-outfit", args->outfit, "skip the outfit (t-shirt over pants)");
    cmd->add_option("--materials", args->materials_dir, "folder of fabric JSON files");
    cmd->add_option("--docs", args->docs,
                    "also replace the table between the lines '<!-- drape eval-dress: table begin -->' and "
                    "'<!-- drape eval-dress: table end -->' (with --ansur: '<!-- drape eval-dress --ansur: table "
                    "begin -->' ... 'end -->') of this Markdown file (e.g. docs/dressing.md) and write the contact "
                    "sheet to images/dress_eval.jpg beside it");
    cmd->add_option("--out", args->out, "output folder")->required();
    cmd->callback([args] { run_eval_dress(*args); });
}

void add_dress_command(CLI::App& app) {
    auto args = std::make_shared<DressArgs>();
    CLI::App* cmd = app.add_subcommand(
        "dress", "Dress a body in a garment: pattern from sizing G, wrapped on the body, seams sewn and "
                 "draped with the cloth simulator (garment.obj/glb, pattern.svg/dxf/json, render.png, "
                 "summary.json)");
    cmd->add_option("--garment", args->garment,
                    "skirt, pants, tshirt or dress, or an outfit tshirt+pants / tshirt+skirt (dressed and "
                    "draped together, one fabric, the top over the waistband; files per garment)")
        ->required();
    cmd->add_option("--sizing", args->sizing,
                    "G.json with the paper's parameter names (cm, degrees), or 'auto' to derive G from "
                    "the body's measurements")
        ->required();
    cmd->add_option("--material", args->material,
                    "a measured fabric name (e.g. gray-interlock: NAME.json in --materials if there, else "
                    "the built-in fabric) or a material file (ours or ArcSim's)")
        ->required();
    cmd->add_option("--materials", args->materials_dir, "folder of fabric JSON files");
    cmd->add_option("--body", args->body,
                    "body P.json (semantic measurements, as `drape body --params`); default: the mean female");
    cmd->add_option("--pose", args->pose, "a_pose (default), arms_down, walking, t_pose, or a POSE.json");
    cmd->add_option("--edge", args->edge_cm,
                    "mesh target edge length, cm (default 1.5; 2.5 for pants and outfits with pants, whose "
                    "crotch does not dress cleanly at 1.5 cm on every body)");
    cmd->add_flag("--no-render", args->no_render, "skip render.png");
    cmd->add_flag("--keep-arms", args->keep_arms,
                  "keep the pose's arms as given (default: each arm is raised just clear of the trunk where it passes into it)");
    cmd->add_option("--motion-seconds", args->motion_s,
                    "time over which the body moves from the A-pose to --pose after sewing (default 0.6; longer "
                    "if a body vertex would move more than half the contact thickness per step)");
    cmd->add_flag("--save-dressed", args->save_dressed,
                  "also write the dressed state the simulation starts from (dressed.obj, dressed.png)");
    cmd->add_option("--out", args->out, "output folder")->required();
    cmd->callback([args] { run_dress(*args); });
}

}  // namespace drape::app
