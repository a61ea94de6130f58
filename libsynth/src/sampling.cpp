#include <drape/synth/sampling.hpp>

#include <drape/body/shape_body.hpp>
#include <drape/cloth/material.hpp>
#include <drape/core/errors.hpp>
#include <drape/garment/arm_clearance.hpp>
#include <drape/garment/sizing_proposal.hpp>

#include <Eigen/Cholesky>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace drape::synth {

namespace {

constexpr double kPi = 3.14159265358979323846;
using garment::GarmentSizing;
using garment::GarmentType;

template <class Sizing, class Table>
void clamp_to_table(Sizing& s, const Table& table) {
    for (const auto& p : table) s.*(p.field) = std::clamp(s.*(p.field), p.min, p.max);
}

void vary_skirt(Rng& rng, garment::SkirtSizing& s) {
    s.r2 *= rng.uniform(0.8, 1.15);
    s.alpha = rng.uniform(45.0, 150.0);
    clamp_to_table(s, garment::SkirtSizing::parameters());
}

const std::vector<Eigen::Vector3d>& garment_palette() {
    static const std::vector<Eigen::Vector3d> palette = {
        {0.62, 0.12, 0.14}, {0.13, 0.22, 0.45}, {0.16, 0.38, 0.27}, {0.85, 0.66, 0.18},
        {0.55, 0.55, 0.58}, {0.92, 0.90, 0.84}, {0.12, 0.12, 0.14}, {0.45, 0.23, 0.48},
        {0.80, 0.42, 0.30}, {0.30, 0.52, 0.72}, {0.70, 0.62, 0.48}, {0.86, 0.52, 0.62}};
    return palette;
}

}  // namespace

std::vector<std::string> measured_fabrics() {
    std::vector<std::string> names;
    for (const std::string& n : cloth::builtin_material_names())
        if (n != "paper" && n != "aluminium") names.push_back(n);
    return names;
}

std::vector<GarmentType> sample_garments(Rng& rng, const std::vector<GarmentType>& asked) {
    // Lower garment first: the upper one is draped over it (untucked).
    static const std::vector<std::vector<GarmentType>> all = {
        {GarmentType::skirt}, {GarmentType::pants}, {GarmentType::tshirt}, {GarmentType::dress},
        {GarmentType::pants, GarmentType::tshirt}, {GarmentType::skirt, GarmentType::tshirt}};
    return asked.empty() ? all[rng.index(all.size())] : asked;
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

std::string pose_name(body::NamedPose pose) {
    switch (pose) {
        case body::NamedPose::a_pose: return "a_pose";
        case body::NamedPose::arms_down: return "arms_down";
        case body::NamedPose::walking: return "walking";
        case body::NamedPose::t_pose: return "t_pose";
    }
    return "a_pose";
}

body::Pose sample_pose(Rng& rng, body::NamedPose which) {
    body::Pose pose = body::named_pose(which);
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
            garment::make_pattern(g);
            return g;
        } catch (const InvalidInput&) {
        }
    }
    return garment::proposed_sizing(type, m, skirt_waistband_girth_m);
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

int garment_label(GarmentType t) {
    switch (t) {
        case GarmentType::skirt: return 42;
        case GarmentType::pants: return 31;
        case GarmentType::tshirt: return 51;
        case GarmentType::dress: return 14;
    }
    return 0;
}

body::Camera sample_camera(Rng& rng, double h, int width_px, int height_px, Eigen::Vector3d& placement) {
    const double hc = rng.uniform(0.9, 1.25);
    placement = Eigen::Vector3d(rng.uniform(-0.05, 0.05), -hc, 0.0);
    body::Camera camera;
    camera.model = body::CameraModel::pinhole;
    camera.focal_px = 0.5 * height_px / std::tan(14.0 * kPi / 180.0);
    camera.distance_m = camera.focal_px * 1.25 * h / height_px;
    camera.offset_px =
        Eigen::Vector2d(0.5 * width_px, 0.5 * height_px + camera.focal_px * (0.5 * h - hc) / camera.distance_m);
    return camera;
}

SynthScene sample_synth_scene(const SynthOptions& options) {
    std::string why;
    if (!options.is_valid(&why)) throw InvalidInput("drape synth: " + why);
    const body::BodyModel& model = body::BodyModel::default_model();
    SynthScene s;
    s.seed = options.seed;
    s.width_px = options.width_px;
    s.height_px = options.height_px;

    Rng garment_rng(options.seed, Stream::garment);
    const std::vector<GarmentType> types = sample_garments(garment_rng, options.garments);
    Rng pose_rng(options.seed, Stream::pose);
    static const std::array<body::NamedPose, 3> poses = {body::NamedPose::a_pose, body::NamedPose::arms_down,
                                                         body::NamedPose::walking};
    const body::NamedPose pose = options.pose ? *options.pose : poses[pose_rng.index(3)];
    s.pose_name = pose_name(pose);
    const std::vector<std::string> fabrics = measured_fabrics();
    const bool random_fabric = options.fabric.empty();
    if (!random_fabric) cloth::builtin_material(options.fabric);  // unknown name -> InvalidInput

    Rng body_rng(options.seed, Stream::body);
    s.shape = sample_body(body_rng, model.prior);
    s.pose = sample_pose(pose_rng, pose);

    // Sizing needs the body's measurements.
    const body::ShapeSummary shaping = body::shape_body(model, s.shape, body::ShapeOptions{}, s.shaped);
    if (!shaping.usable()) throw std::runtime_error("drape synth: body shaping failed: " + shaping.brief_report());
    s.shaping_report = shaping.brief_report();
    // Arms held down pass into a thick torso under skinning: raised just clear of it
    // (garment::clear_arms_from_trunk), as in drape eval-dress.
    s.pose = garment::clear_arms_from_trunk(model, s.shaped, s.pose);
    Rng sizing_rng(options.seed, Stream::sizing), material_rng(options.seed, Stream::material),
        look_rng(options.seed, Stream::look);
    // Only a skirt's sizing needs it (the dress's skirt is sized from its bodice).
    const bool has_skirt = std::find(types.begin(), types.end(), GarmentType::skirt) != types.end();
    const double waistband_girth_m = has_skirt ? garment::skirt_waistband(model, s.shaped).girth_m : 0.0;
    for (GarmentType t : types) {
        SynthGarment g;
        // Sleeves and neckline at least the arm's and neck's girth + ease (stature ratios
        // alone made them too small for heavy bodies).
        g.sizing = garment::fit_top_to_body(sample_sizing(sizing_rng, t, shaping.measured, waistband_girth_m),
                                            model, s.shaped);
        g.base_fabric = random_fabric ? fabrics[material_rng.index(fabrics.size())] : options.fabric;
        g.material = cloth::builtin_material(g.base_fabric);
        const double log_scale = material_rng.uniform(0.0, 2.0);  // drawn always: streams stay aligned
        g.material.bending_scale = options.bending_scale > 0 ? options.bending_scale
                                   : random_fabric           ? std::pow(10.0, log_scale)
                                                             : 1.0;
        g.look = sample_look(look_rng);  // drawn always: the streams stay aligned
        if (options.print) g.look.print.kind = *options.print;
        g.label = garment_label(t);
        s.garments.push_back(g);
    }
    static const std::vector<Eigen::Vector3d> skins = {
        {0.80, 0.74, 0.67}, {0.86, 0.82, 0.76}, {0.62, 0.50, 0.42}, {0.93, 0.91, 0.88}};
    s.skin_srgb = skins[look_rng.index(skins.size())];

    Rng camera_rng(options.seed, Stream::camera);
    s.camera = sample_camera(camera_rng, s.shape[body::Semantic::height_m], s.width_px, s.height_px, s.placement);
    return s;
}

}  // namespace drape::synth
