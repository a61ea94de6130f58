#include "synth_scene.hpp"

#include "body_json.hpp"
#include "image_io.hpp"
#include "json_io.hpp"

#include <drape/body/body_model.hpp>
#include <drape/body/shape_body.hpp>
#include <drape/cloth/cloth_mesh.hpp>
#include <drape/cloth/local_curvature.hpp>
#include <drape/cloth/obstacle.hpp>
#include <drape/core/errors.hpp>
#include <drape/garment/arm_clearance.hpp>
#include <drape/garment/drape_garment.hpp>
#include <drape/garment/dressing.hpp>
#include <drape/garment/garment_mesh.hpp>
#include <drape/garment/sizing_proposal.hpp>
#include <drape/render/renderer.hpp>
#include <drape/vision/joints.hpp>
#include <drape/vision/strokes.hpp>
#include <drape/vision/wrinkle_density.hpp>

#include <opencv2/imgproc.hpp>

#include <Eigen/Cholesky>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <regex>
#include <sstream>

namespace drape::app {

namespace {

namespace fs = std::filesystem;
constexpr double kPi = 3.14159265358979323846;

// splitmix64 (Steele, Lea, Flood 2014): a fully specified 64-bit generator, so scenes do
// not depend on the standard library's distributions.
class Rng {
public:
    Rng(std::uint64_t seed, std::uint64_t stream) : state_(seed ^ (0x9E3779B97F4A7C15ull * (stream + 1))) {
        next();
    }
    std::uint64_t next() {
        std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    double uniform() { return double(next() >> 11) * (1.0 / 9007199254740992.0); }  // [0, 1)
    double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
    std::size_t index(std::size_t n) { return std::size_t(uniform() * double(n)) % n; }
    double normal() {  // Box-Muller
        const double u1 = 1.0 - uniform(), u2 = uniform();
        return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * kPi * u2);
    }
    double truncated_normal(double limit) {
        for (;;) {
            const double z = normal();
            if (std::abs(z) <= limit) return z;
        }
    }

private:
    std::uint64_t state_;
};

// Independent streams, so that e.g. choosing another pose leaves body and sizing unchanged.
enum Stream : std::uint64_t { body_stream = 1, pose_stream, garment_stream, sizing_stream,
                              material_stream, look_stream, camera_stream };

// The ten fabrics measured by Wang et al. 2011 (paper and aluminium are not cloth).
std::vector<std::string> measured_fabrics() {
    std::vector<std::string> names;
    for (const std::string& n : cloth::builtin_material_names())
        if (n != "paper" && n != "aluminium") names.push_back(n);
    return names;
}

std::vector<GarmentType> garments_of(const std::string& spec, Rng& rng) {
    static const std::vector<std::string> all = {"skirt", "pants", "tshirt", "dress", "tshirt+pants",
                                                 "tshirt+skirt"};
    const std::string s = spec == "random" ? all[rng.index(all.size())] : spec;
    std::vector<GarmentType> out;
    std::size_t start = 0;
    for (;;) {
        const std::size_t plus = s.find('+', start);
        out.push_back(garment_type_from_name(s.substr(start, plus - start)));
        if (plus == std::string::npos) break;
        start = plus + 1;
    }
    require(out.size() <= 2, "--garment '", spec, "': at most two garments (an upper and a lower one)");
    if (out.size() == 2) {
        // Lower garment first: the upper one is draped over it (untucked).
        std::sort(out.begin(), out.end(), [](GarmentType a, GarmentType b) {
            return (a == GarmentType::tshirt) < (b == GarmentType::tshirt);
        });
        require(out[0] != GarmentType::tshirt && out[0] != GarmentType::dress && out[1] == GarmentType::tshirt,
                "--garment '", spec, "': an outfit is a t-shirt with pants or a skirt (tshirt+pants, tshirt+skirt)");
    }
    return out;
}

body::SemanticShape sample_body(Rng& rng, const body::ShapePrior& prior) {
    body::SemanticShape shape;
    shape.gender = rng.uniform() < 0.5 ? body::Gender::female : body::Gender::male;
    const body::GaussianPrior& p = prior.of(shape.gender);
    const Eigen::Matrix<double, body::kSemanticCount, body::kSemanticCount> L = p.covariance.llt().matrixL();
    const int muscle = static_cast<int>(body::Semantic::muscle);
    for (int attempt = 0; attempt < 200; ++attempt) {
        Eigen::Matrix<double, body::kSemanticCount, 1> z;
        for (int k = 0; k < body::kSemanticCount; ++k) z[k] = rng.truncated_normal(2.0);
        shape.values = p.mean + L * z;
        shape.values[muscle] = std::clamp(shape.values[muscle], 0.0, 1.0);
        bool inside = true;
        for (int k = 0; k < body::kSemanticCount; ++k)
            inside = inside && (k == muscle || (shape.values[k] >= p.min[k] && shape.values[k] <= p.max[k]));
        if (inside && shape.is_valid()) return shape;
    }
    shape.values = p.mean;  // not reached in practice: 2-sigma draws lie in the survey's range
    return shape;
}

const char* pose_preset_name(const std::string& letter) {
    if (letter == "a") return "a_pose";
    if (letter == "b") return "arms_down";
    if (letter == "c") return "walking";
    throw InvalidInput("--pose '" + letter + "' is not a (A-pose), b (arms down), c (walking) or random");
}

body::Pose sample_pose(Rng& rng, const std::string& name) {
    body::Pose pose = body::named_pose(name == "a_pose"      ? body::NamedPose::a_pose
                                       : name == "arms_down" ? body::NamedPose::arms_down
                                                             : body::NamedPose::walking);
    // Small natural variation (about 1 degree) on the joints a standing person moves; no
    // root tilt, so the feet stay on the floor.
    using body::Joint;
    for (Joint j : {Joint::spine, Joint::chest, Joint::neck, Joint::head, Joint::right_shoulder,
                    Joint::left_shoulder, Joint::right_elbow, Joint::left_elbow, Joint::right_hip,
                    Joint::left_hip, Joint::right_knee, Joint::left_knee})
        for (int c = 0; c < 3; ++c) pose.rotations(body::index(j), c) += 0.02 * rng.truncated_normal(2.0);
    // The body turns up to 20 degrees left or right of the camera.
    pose.rotations(body::index(Joint::pelvis), 1) += rng.uniform(-20.0, 20.0) * kPi / 180.0;
    return pose;
}

template <class Sizing, class Table>
void clamp_to_table(Sizing& s, const Table& table) {
    for (const auto& p : table) s.*(p.field) = std::clamp(s.*(p.field), p.min, p.max);
}

void vary_skirt(Rng& rng, garment::SkirtSizing& s) {
    s.r2 *= rng.uniform(0.8, 1.15);
    s.alpha = rng.uniform(45.0, 150.0);
    clamp_to_table(s, garment::SkirtSizing::parameters());
}

// The template's proposal for the body with seeded ease, then seeded length and flare
// changes; a variation the template rejects is redrawn (the proposal after 20 tries).
GarmentSizing sample_sizing(Rng& rng, GarmentType type, const body::BodyMeasurements& m,
                            double skirt_waistband_girth_m) {
    for (int attempt = 0; attempt < 20; ++attempt) {
        garment::Ease ease;
        ease.waist_cm = rng.uniform(2.0, 8.0);
        ease.hip_cm = rng.uniform(4.0, 14.0);
        ease.chest_cm = rng.uniform(6.0, 18.0);
        ease.leg_cm = rng.uniform(4.0, 14.0);
        GarmentSizing g;
        g.type = type;
        switch (type) {
            case GarmentType::skirt:
                // The waist where a waistband holds (garment::skirt_waistband) with 1-3 cm
                // of ease (the seeded waist ease mapped from [2, 8] cm, so the random
                // streams stay as they were): sized from the navel girth, skirts slid off
                // bodies whose belly is wider than their hips.
                g.skirt = garment::propose_skirt_sizing(m, skirt_waistband_girth_m,
                                                        1.0 + (ease.waist_cm - 2.0) / 3.0);
                vary_skirt(rng, g.skirt);
                break;
            case GarmentType::pants:
                g.pants = garment::propose_pants_sizing(m, ease);
                g.pants.h1 *= rng.uniform(0.93, 1.0);
                clamp_to_table(g.pants, garment::PantsSizing::parameters());
                break;
            case GarmentType::tshirt: {
                g.tshirt = garment::propose_tshirt_sizing(m, ease);
                g.tshirt.l1 *= rng.uniform(0.6, 1.4);
                const double dh = rng.uniform(-6.0, 4.0);  // longer or shorter, same armhole
                g.tshirt.h1 += dh;
                g.tshirt.h2 += dh;
                clamp_to_table(g.tshirt, garment::TShirtSizing::parameters());
                break;
            }
            case GarmentType::dress:
                g.dress = garment::propose_dress_sizing(m, ease);
                g.dress.bodice.l1 *= rng.uniform(0.6, 1.4);
                clamp_to_table(g.dress.bodice, garment::TShirtSizing::parameters());
                vary_skirt(rng, g.dress.skirt);
                g.dress.skirt.l1 = g.dress.bodice.w2;  // the waist seam joins them
                break;
        }
        try {
            make_pattern(g);
            return g;
        } catch (const InvalidInput&) {
        }
    }
    return proposed_sizing(type, m, skirt_waistband_girth_m);
}

const std::vector<Eigen::Vector3d>& garment_palette() {
    static const std::vector<Eigen::Vector3d> palette = {
        {0.62, 0.12, 0.14}, {0.13, 0.22, 0.45}, {0.16, 0.38, 0.27}, {0.85, 0.66, 0.18},
        {0.55, 0.55, 0.58}, {0.92, 0.90, 0.84}, {0.12, 0.12, 0.14}, {0.45, 0.23, 0.48},
        {0.80, 0.42, 0.30}, {0.30, 0.52, 0.72}, {0.70, 0.62, 0.48}, {0.86, 0.52, 0.62}};
    return palette;
}

render::Material sample_look(Rng& rng) {
    const auto& palette = garment_palette();
    render::Material m;
    const std::size_t base = rng.index(palette.size());
    m.colour_srgb = palette[base];
    m.roughness = rng.uniform(0.7, 0.92);
    const double r = rng.uniform();
    m.print.kind = r < 0.4 ? render::PrintKind::solid
                 : r < 0.6 ? render::PrintKind::stripes
                 : r < 0.8 ? render::PrintKind::checks
                           : render::PrintKind::dots;
    std::size_t second = rng.index(palette.size() - 1);
    if (second >= base) ++second;
    m.print.second_colour_srgb = palette[second];
    m.print.period = rng.uniform(0.03, 0.08);  // metres of pattern space
    m.print.angle_rad = rng.uniform() < 0.5 ? 0.0 : kPi / 2;
    m.print.dot_radius = rng.uniform(0.15, 0.3);
    return m;
}

int label_of(GarmentType t) {  // labels.txt ids
    switch (t) {
        case GarmentType::skirt: return 42;
        case GarmentType::pants: return 31;
        case GarmentType::tshirt: return 51;
        case GarmentType::dress: return 14;
    }
    return 0;
}

nlohmann::json camera_to_json(const body::Camera& c) {  // the `drape fit-body` camera object
    return {{"model", "pinhole"},
            {"focal_px", c.focal_px},
            {"distance_m", c.distance_m},
            {"offset_px", {c.offset_px.x(), c.offset_px.y()}},
            {"pixel_frame", "origin at the top-left corner of the image, pixel centres at +0.5"}};
}

template <class Table>
nlohmann::json table_json(const Table& t) {
    nlohmann::json j = nlohmann::json::array();
    for (const auto& row : t) j.push_back(std::vector<double>(row.begin(), row.end()));
    return j;
}

nlohmann::json material_json(const SynthGarment& g) {
    return {{"bending_scale", g.material.bending_scale},
            {"stretching_scale", g.material.stretching_scale},
            {"base_fabric", g.base_fabric},
            {"stretching", table_json(g.material.stretching_n_per_m)},
            {"bending", table_json(g.material.bending_n_m)},
            {"density", g.material.density_kg_per_m2}};
}

// Library messages carry wall times ("4017.18 ms (assembly ...)", "0.25 s"); scene files
// must not, so that they are the same bytes for a seed.
std::string without_timings(const std::string& message) {
    static const std::regex ms(R"(,? ?[0-9.eE+-]+ ms( \([^)]*\))?)"), s(R"(,? ?[0-9.eE+-]+ s\b)");
    return std::regex_replace(std::regex_replace(message, ms, ""), s, "");
}

double seconds_since(std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace

bool SynthOptions::is_valid(std::string* why) const {
    auto fail = [&](const std::string& m) {
        if (why) *why = m;
        return false;
    };
    if (!(edge_cm > 0 && edge_cm <= 20)) return fail("edge " + std::to_string(edge_cm) + " cm must be in (0, 20]");
    if (max_steps < 20) return fail("max_steps " + std::to_string(max_steps) + " must be >= 20");
    if (width_px < 64 || width_px > 8192) return fail("width " + std::to_string(width_px) + " px must be in [64, 8192]");
    if (height_px < 600 || height_px > 8192)
        return fail("height " + std::to_string(height_px) + " px must be in [600, 8192]");
    if (samples_per_pixel < 1 || samples_per_pixel > 4096)
        return fail("samples " + std::to_string(samples_per_pixel) + " must be in [1, 4096]");
    if (threads < 0) return fail("threads must be >= 0");
    if (!std::isfinite(bending_scale) || bending_scale > 1e4)
        return fail("bending scale " + std::to_string(bending_scale) + " must be finite and <= 1e4");
    return true;
}

SynthScene sample_synth_scene(const SynthOptions& options) {
    std::string why;
    if (!options.is_valid(&why)) throw InvalidInput("drape synth: " + why);
    const body::BodyModel& model = body::BodyModel::default_model();
    SynthScene s;
    s.seed = options.seed;
    s.width_px = options.width_px;
    s.height_px = options.height_px;

    Rng garment_rng(options.seed, garment_stream);
    const std::vector<GarmentType> types = garments_of(options.garment, garment_rng);
    Rng pose_rng(options.seed, pose_stream);
    static const std::array<const char*, 3> letters = {"a", "b", "c"};
    const std::string letter = options.pose == "random" ? letters[pose_rng.index(3)] : options.pose;
    s.pose_name = pose_preset_name(letter);
    const std::vector<std::string> fabrics = measured_fabrics();
    if (options.material != "random") cloth::builtin_material(options.material);  // unknown name -> InvalidInput

    Rng body_rng(options.seed, body_stream);
    s.shape = sample_body(body_rng, model.prior);
    s.pose = sample_pose(pose_rng, s.pose_name);

    // Sizing needs the body's measurements.
    const body::ShapeSummary shaping = body::shape_body(model, s.shape, body::ShapeOptions{}, s.shaped);
    if (!shaping.usable()) throw std::runtime_error("drape synth: body shaping failed: " + shaping.brief_report());
    s.shaping_report = shaping.brief_report();
    // Arms held down pass into a thick torso under skinning: raised just clear of it
    // (garment::clear_arms_from_trunk), as in drape eval-dress.
    s.pose = garment::clear_arms_from_trunk(model, s.shaped, s.pose);
    Rng sizing_rng(options.seed, sizing_stream), material_rng(options.seed, material_stream),
        look_rng(options.seed, look_stream);
    // Only a skirt's sizing needs it (the dress's skirt is sized from its bodice).
    const bool has_skirt = std::find(types.begin(), types.end(), GarmentType::skirt) != types.end();
    const double waistband_girth_m = has_skirt ? garment::skirt_waistband(model, s.shaped).girth_m : 0.0;
    for (GarmentType t : types) {
        SynthGarment g;
        // Sleeves and neckline at least the arm's and neck's girth + ease (stature ratios
        // alone made them too small for heavy bodies).
        g.sizing = fit_top_to_body(sample_sizing(sizing_rng, t, shaping.measured, waistband_girth_m), model, s.shaped);
        g.base_fabric = options.material == "random" ? fabrics[material_rng.index(fabrics.size())] : options.material;
        g.material = cloth::builtin_material(g.base_fabric);
        const double log_scale = material_rng.uniform(0.0, 2.0);  // drawn always: streams stay aligned
        g.material.bending_scale = options.bending_scale > 0 ? options.bending_scale
                                   : options.material == "random" ? std::pow(10.0, log_scale)
                                                                  : 1.0;
        g.look = sample_look(look_rng);
        g.label = label_of(t);
        s.garments.push_back(g);
    }
    static const std::vector<Eigen::Vector3d> skins = {
        {0.80, 0.74, 0.67}, {0.86, 0.82, 0.76}, {0.62, 0.50, 0.42}, {0.93, 0.91, 0.88}};
    s.skin_srgb = skins[look_rng.index(skins.size())];

    // A pinhole camera (the fit-body convention: centre (0, 0, d), looking down -Z) with a
    // 28-degree vertical view; the body is lowered so the camera stands at hc above its
    // floor, and framed with its full height plus 25 %.
    Rng camera_rng(options.seed, camera_stream);
    const double h = s.shape[body::Semantic::height_m];
    const double hc = camera_rng.uniform(0.9, 1.25);
    s.placement = Eigen::Vector3d(camera_rng.uniform(-0.05, 0.05), -hc, 0.0);
    s.camera.model = body::CameraModel::pinhole;
    s.camera.focal_px = 0.5 * s.height_px / std::tan(14.0 * kPi / 180.0);
    s.camera.distance_m = s.camera.focal_px * 1.25 * h / s.height_px;
    s.camera.offset_px = Eigen::Vector2d(0.5 * s.width_px,
                                         0.5 * s.height_px + s.camera.focal_px * (0.5 * h - hc) / s.camera.distance_m);
    return s;
}

bool SynthSummary::usable() const {
    return std::all_of(garments.begin(), garments.end(), [](const SynthGarmentResult& g) { return g.usable; });
}

std::string SynthSummary::brief_report() const {
    std::ostringstream os;
    os << (usable() ? "usable" : "NOT usable") << ": ";
    for (const auto& g : garments) os << g.type << " (" << g.drape_report << ", " << g.seconds << " s); ";
    os << "drape " << seconds_drape << " s, render " << seconds_render << " s, total " << seconds << " s";
    return os.str();
}

SynthSummary make_synth_scene(const SynthScene& scene, const SynthOptions& options, const fs::path& dir) {
    const auto start = std::chrono::steady_clock::now();
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) throw IoError("cannot create output folder '" + dir.string() + "': " + ec.message());

    const body::BodyModel& model = body::BodyModel::default_model();
    const body::ShapedBody& shaped = scene.shaped;
    require(shaped.vertices.rows() == model.vertex_count(), "drape synth: the scene has no shaped body");
    const body::PosedBody posed = body::pose_body(model, shaped, scene.pose);
    const Eigen::MatrixX3d body_V = posed.vertices;
    const Eigen::MatrixX3i body_F = model.faces;

    // A single garment is dressed in the rest A-pose and moved to the scene's pose with the
    // body (garment::dress_and_drape: starts without crossings); the garments of an outfit
    // are dressed and draped together the same way (garment::dress_and_drape_outfit, lower
    // garment first, each in its own fabric).
    SynthSummary summary;
    nlohmann::json garment_reports = nlohmann::json::array();
    const std::size_t n = scene.garments.size();
    std::vector<garment::Pattern> patterns;
    std::vector<garment::GarmentMesh> meshes(n);
    std::vector<garment::MeshSummary> meshed(n);
    std::vector<cloth::Material> materials;
    for (std::size_t i = 0; i < n; ++i) {
        patterns.push_back(make_pattern(scene.garments[i].sizing));
        materials.push_back(scene.garments[i].material);
        garment::MeshOptions mesh_options;
        mesh_options.target_edge_cm = options.edge_cm;
        meshed[i] = garment::mesh_pattern(patterns[i], mesh_options, meshes[i]);
        if (!meshed[i].usable()) throw std::runtime_error("drape synth: meshing failed: " + meshed[i].brief_report());
    }
    garment::DrapeOptions drape_options;
    drape_options.max_steps = options.max_steps;
    // Untangling and the fallback after a failed static solve get at most a third each.
    drape_options.max_untangle_steps = std::min(drape_options.max_untangle_steps, options.max_steps / 3);
    drape_options.fallback_steps = std::min(drape_options.fallback_steps, options.max_steps / 3);
    drape_options.min_steps = std::min(drape_options.min_steps, options.max_steps);
    std::vector<Eigen::MatrixX3d> draped(n);
    std::vector<garment::DressingSummary> dressed(n);
    const auto t0 = std::chrono::steady_clock::now();
    // An outfit has one drape (one simulation): its summary is every garment's report.
    const garment::DrapeSummary d =
        n == 1 ? garment::dress_and_drape(patterns[0], meshes[0], model, shaped, scene.pose, materials[0],
                                          garment::DressingOptions{}, drape_options, draped[0], &dressed[0])
               : garment::dress_and_drape_outfit(patterns, meshes, model, shaped, scene.pose, materials,
                                                 garment::DressingOptions{}, drape_options, draped, &dressed);
    const double drape_seconds = seconds_since(t0);
    // Where each garment is deepest inside the body (for the summary: which panel, where,
    // and the body joint that mainly moves the face it is under).
    const cloth::Obstacle body_obstacle(body_V, body_F);
    const std::vector<int> joint_of = body::dominant_joints(model);
    const auto deepest_inside = [&](std::size_t i) {
        nlohmann::json out = nullptr;
        double depth = 0;
        for (Eigen::Index v = 0; v < draped[i].rows(); ++v) {
            const cloth::ObstacleQuery q = body_obstacle.closest(draped[i].row(v).transpose(), 0.1);
            if (!q.found || -q.signed_distance_m <= depth) continue;
            depth = -q.signed_distance_m;
            const int joint = joint_of[size_t(body_F(q.face, 0))];
            out = {{"panel", patterns[i].panels[size_t(meshes[i].panel_of_vertex(v))].name},
                   {"position_m", {draped[i](v, 0), draped[i](v, 1), draped[i](v, 2)}},
                   {"depth_m", depth},
                   {"body_joint", joint >= 0 ? std::string(body::kJointNames[size_t(joint)]) : std::string()}};
        }
        return out;
    };
    std::vector<double> mean_curvature(n);
    for (std::size_t i = 0; i < n; ++i) {
        const std::vector<cloth::Hinge> hinges = cloth::build_hinges(meshes[i].cloth);
        mean_curvature[i] = cloth::vertex_local_curvature(meshes[i].cloth, hinges, draped[i]).mean();
        SynthGarmentResult r;
        r.type = garment_type_name(scene.garments[i].sizing.type);
        r.usable = d.usable();
        r.drape_report = d.brief_report();
        r.seconds = drape_seconds;
        summary.garments.push_back(r);
        const garment::DressingSummary& ds = dressed[i];
        garment_reports.push_back({{"type", r.type},
                                   {"vertices", meshes[i].cloth.vertex_count()},
                                   {"faces", meshed[i].faces},
                                   {"stitches", meshes[i].stitches.size()},
                                   {"dressing", {{"vertices_inside", ds.vertices_inside},
                                                 {"vertices_pushed", ds.vertices_pushed},
                                                 {"iterations", ds.iterations},
                                                 {"max_seam_gap_m", ds.max_seam_gap_m},
                                                 {"alignment_rms_m", ds.alignment_rms_m}}},
                                   {"seam_gap_max_m", d.seam_gap_max_m},
                                   {"penetration_max_m", d.penetration_max_m},
                                   {"vertices_inside", d.vertices_inside},
                                   {"deepest_inside", deepest_inside(i)},
                                   {"self_intersections", d.self_intersections},
                                   {"initial_self_intersections", d.initial_self_intersections},
                                   {"mean_drop_m", d.mean_drop_m},
                                   {"converged", d.converged},
                                   {"usable", d.usable()},
                                   {"steps", d.steps},
                                   {"message", without_timings(d.message)}});
    }
    summary.seconds_drape = seconds_since(start);

    // The render: the body lowered so the camera is at its height, on a studio cove.
    const auto t_render = std::chrono::steady_clock::now();
    const Eigen::RowVector3d shift = scene.placement.transpose();
    render::Scene rs;
    render::Mesh b;
    b.name = "body";
    b.V = body_V.rowwise() + shift;
    b.F = body_F;
    b.material.colour_srgb = scene.skin_srgb;
    b.material.roughness = 0.6;
    b.label = 41;  // labels.txt "skin"
    double floor_y = b.V.col(1).minCoeff();
    rs.meshes.push_back(std::move(b));
    for (std::size_t i = 0; i < scene.garments.size(); ++i) {
        render::Mesh g;
        g.name = garment_type_name(scene.garments[i].sizing.type);
        g.V = draped[i].rowwise() + shift;
        g.F = meshes[i].cloth.faces;
        // Pattern coordinates in metres, so print periods are real sizes on the cloth.
        g.UV = meshes[i].cloth.pattern.rows() == g.V.rows() ? Eigen::MatrixXd(meshes[i].cloth.pattern)
                                                            : Eigen::MatrixXd(meshes[i].uv);
        g.material = scene.garments[i].look;
        g.label = scene.garments[i].label;
        // Drawn on its Phong-tessellated surface: the simulated mesh's flat triangles cut
        // chords through the body (drape::render::phong_tessellate).
        g.smooth_subdivisions = render::kSimulatedGarmentSubdivisions;
        floor_y = std::min(floor_y, g.V.col(1).minCoeff());
        rs.meshes.push_back(std::move(g));
    }
    rs.floor.enabled = true;
    rs.floor.height_m = floor_y;
    rs.backdrop.enabled = true;
    rs.backdrop.distance_m = 1.6;
    const render::Renderer renderer(rs);
    const render::Camera camera = render::Camera::from_body(scene.camera, scene.width_px, scene.height_px);
    render::RenderOptions ro;
    ro.samples_per_pixel = options.samples_per_pixel;
    ro.threads = options.threads;
    render::RenderImages midday, sunset;
    renderer.render(camera, render::lighting_preset(render::LightingPreset::midday), ro, midday);
    renderer.render(camera, render::lighting_preset(render::LightingPreset::sunset), ro, sunset);
    write_png(dir / "image_midday.png", midday.colour);
    write_png(dir / "image_sunset.png", sunset.colour);
    write_png(dir / "labels.png", midday.labels);
    write_png(dir / "strokes.png", vision::simulate_strokes(midday.labels));
    summary.seconds_render = seconds_since(t_render);

    // The 14 image joints, projected from the posed 3D skeleton.
    vision::Joints joints;
    nlohmann::json pts = nlohmann::json::array();
    for (int k = 0; k < body::kImageJointCount; ++k) {
        const Eigen::Vector3d X =
            posed.joints.row(body::index(body::kImageJoints[std::size_t(k)])).transpose() + scene.placement;
        joints.px[std::size_t(k)] = scene.camera.project(X);
        // Written 1-based like ../shared/data/photos/joints (pixel (1, 1)'s centre is at 1).
        pts.push_back({joints.px[std::size_t(k)].x() + 0.5, joints.px[std::size_t(k)].y() + 0.5});
    }
    write_json_file(dir / "joints.json",
                    {{"joints", pts},
                     {"joint_names", std::vector<std::string>(body::kImageJointNames.begin(), body::kImageJointNames.end())},
                     {"image_size", {scene.width_px, scene.height_px}},
                     {"pixel_origin", "one_based"}});

    // Ground truth, in the schema `drape recover` writes as result.json.
    body::Pose truth_pose = scene.pose;
    truth_pose.translation += scene.placement;
    nlohmann::json truth_garments = nlohmann::json::array();
    nlohmann::json wrinkle_reports = nlohmann::json::array();
    for (std::size_t i = 0; i < scene.garments.size(); ++i) {
        const SynthGarment& g = scene.garments[i];
        cv::Mat mask;
        cv::compare(midday.labels, g.label, mask, cv::CMP_EQ);
        vision::WrinkleOptions wo;
        wo.person_height_m = scene.shape[body::Semantic::height_m];
        vision::WrinkleSummary w;
        w.message = "garment not visible";
        if (cv::countNonZero(mask) > 0) {
            try {
                w = vision::detect_wrinkles(midday.colour, mask, cv::Mat(), joints, wo, nullptr);
            } catch (const InvalidInput& e) {  // e.g. a joint outside the frame: P stays 0, said in summary.json
                w.message = e.what();
            }
        }
        truth_garments.push_back({{"type", garment_type_name(g.sizing.type)},
                                  {"sizing", to_json(g.sizing)},
                                  {"material", material_json(g)},
                                  {"mean_curvature_per_m", mean_curvature[i]},
                                  {"wrinkle_density_per_m2", w.density_per_m2}});
        wrinkle_reports.push_back({{"usable", w.usable()},
                                   {"folds", w.folds},
                                   {"fold_count", w.fold_count},
                                   {"garment_area_m2", w.garment_area_m2},
                                   {"visible_pixels", cv::countNonZero(mask)},
                                   {"message", w.message}});
    }
    write_json_file(dir / "truth.json",
                    {{"body", {{"params", to_json(scene.shape)}, {"pose", to_json(truth_pose)},
                               {"camera", camera_to_json(scene.camera)}}},
                     {"garments", truth_garments}});

    std::vector<std::string> garment_names;
    for (const auto& g : scene.garments) garment_names.push_back(garment_type_name(g.sizing.type));
    for (std::size_t i = 0; i < garment_reports.size(); ++i) {
        garment_reports[i]["wrinkles"] = wrinkle_reports[i];
        garment_reports[i]["label"] = scene.garments[i].label;
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
                     {"usable", summary.usable()},
                     {"drapes", garment_reports}});
    summary.seconds = seconds_since(start);
    return summary;
}

}  // namespace drape::app
