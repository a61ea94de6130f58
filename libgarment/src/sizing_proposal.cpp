#include <drape/garment/sizing_proposal.hpp>

#include <drape/body/skeleton.hpp>
#include <drape/core/errors.hpp>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace drape::garment {

namespace {

constexpr double kPi = 3.14159265358979323846;
// Stature ratios for lengths that BodyMeasurements does not measure (adult averages,
// ANSUR II order of magnitude): navel (waist) height, neck opening radius, armhole depth,
// short-sleeve length, knee-length skirt and sleeve-opening girth.
constexpr double kWaistHeightRatio = 0.60;
constexpr double kNeckRadiusRatio = 0.045;
constexpr double kArmholeDepthRatio = 0.125;
constexpr double kSleeveLengthRatio = 0.11;
constexpr double kSkirtLengthRatio = 0.30;
constexpr double kSleeveOpeningRatio = 0.20;
constexpr double kKneeToThighGirth = 0.65;
constexpr double kAnkleToKneeOpening = 0.88;

void check_measurements(const body::BodyMeasurements& m, const Ease& ease) {
    std::string why;
    require(ease.is_valid(&why), "garment sizing: ", why);
    const std::pair<const char*, double> values[] = {
        {"height_m", m.height_m},           {"chest_girth_m", m.chest_girth_m},
        {"waist_girth_m", m.waist_girth_m}, {"hip_girth_m", m.hip_girth_m},
        {"thigh_girth_m", m.thigh_girth_m}, {"shoulder_height_m", m.shoulder_height_m},
        {"crotch_height_m", m.crotch_height_m}};
    for (const auto& [name, v] : values)
        require(std::isfinite(v) && v > 0, "garment sizing: body measurement ", name, " = ", v,
                " must be positive");
}

double cm(double metres) { return 100.0 * metres; }

SkirtSizing skirt_for_waist(double waist_arc_cm, double height_cm) {
    SkirtSizing g;
    g.l1 = waist_arc_cm;
    g.r1 = waist_arc_cm / (kPi / 2);  // a quarter circle per panel: a half-circle skirt
    g.alpha = 90.0;
    g.r2 = kSkirtLengthRatio * height_cm;
    return g;
}

}  // namespace

bool Ease::is_valid(std::string* why) const {
    const std::pair<const char*, double> values[] = {
        {"waist_cm", waist_cm}, {"hip_cm", hip_cm}, {"chest_cm", chest_cm}, {"leg_cm", leg_cm}};
    for (const auto& [name, v] : values)
        if (!(std::isfinite(v) && v >= 0 && v <= 60)) {
            if (why) *why = std::string("Ease::") + name + " = " + std::to_string(v) +
                            " must be in [0, 60] cm";
            return false;
        }
    return true;
}

SkirtSizing propose_skirt_sizing(const body::BodyMeasurements& m, const Ease& ease) {
    check_measurements(m, ease);
    return skirt_for_waist((cm(m.waist_girth_m) + ease.waist_cm) / 2, cm(m.height_m));
}

namespace {
// Throws unless `shaped` is a shape of `model` (`caller` names the function).
void require_shape_of(const body::BodyModel& model, const body::ShapedBody& shaped, const char* caller) {
    require(shaped.vertices.rows() == model.vertex_count() && shaped.vertices.cols() == 3, caller,
            ": the shaped body does not fit the model");
}

// The horizontal trunk sections (body::section_girth) from the spine joint down to the pelvis
// joint, 1 cm apart, highest first: (height in the rest frame, girth), girth > 0.
std::vector<std::pair<double, double>> waist_sections(const body::BodyModel& model, const body::ShapedBody& shaped,
                                                      const char* caller) {
    require_shape_of(model, shaped, caller);
    const Eigen::Vector3d spine = shaped.joints.row(body::index(body::Joint::spine)).transpose();
    const Eigen::Vector3d pelvis = shaped.joints.row(body::index(body::Joint::pelvis)).transpose();
    const int steps = std::max(1, int(std::ceil((spine.y() - pelvis.y()) / 0.01)));
    std::vector<std::pair<double, double>> sections;
    for (int k = 0; k <= steps; ++k) {
        const Eigen::Vector3d p = spine + (pelvis - spine) * double(k) / steps;
        const double g = body::section_girth(shaped.vertices, model.faces, p, Eigen::Vector3d::UnitY());
        if (g > 0) sections.emplace_back(p.y(), g);
    }
    require(!sections.empty(), caller, ": no trunk section between the spine and pelvis joints");
    return sections;
}
}  // namespace

SkirtWaistband skirt_waistband(const body::BodyModel& model, const body::ShapedBody& shaped) {
    SkirtWaistband band;
    for (const auto& [y, g] : waist_sections(model, shaped, "skirt_waistband"))
        if (band.girth_m == 0 || g < band.girth_m) band.girth_m = g, band.height_m = y;
    return band;
}

SkirtWaistband skirt_waist_fit(const body::BodyModel& model, const body::ShapedBody& shaped, double waist_girth_m) {
    require(std::isfinite(waist_girth_m) && waist_girth_m > 0, "skirt_waist_fit: waist girth ", waist_girth_m,
            " m must be positive");
    SkirtWaistband narrowest;
    for (const auto& [y, g] : waist_sections(model, shaped, "skirt_waist_fit")) {
        if (g <= waist_girth_m) return {g, y};
        if (narrowest.girth_m == 0 || g < narrowest.girth_m) narrowest = {g, y};
    }
    return narrowest;
}

namespace {
// The faces of the right upper arm: every corner skinned mainly to the right shoulder or
// elbow joint (body::dominant_joints). A section of the whole body normal to the humerus
// runs through the armpit into the trunk wherever the arm touches it (a heavy body in the
// rest A-pose: 176-188 cm "arm" girths at the prior's heavy corners); a section of these
// faces alone is the arm's.
Eigen::MatrixXi right_upper_arm_faces(const body::BodyModel& model) {
    const std::vector<int> dominant = body::dominant_joints(model);
    const auto on_arm = [&](int v) {
        const int j = dominant[size_t(v)];
        return j == body::index(body::Joint::right_shoulder) || j == body::index(body::Joint::right_elbow);
    };
    std::vector<int> kept;
    for (Eigen::Index f = 0; f < model.faces.rows(); ++f)
        if (on_arm(model.faces(f, 0)) && on_arm(model.faces(f, 1)) && on_arm(model.faces(f, 2))) kept.push_back(int(f));
    Eigen::MatrixXi F(Eigen::Index(kept.size()), 3);
    for (size_t k = 0; k < kept.size(); ++k) F.row(Eigen::Index(k)) = model.faces.row(kept[k]);
    return F;
}
}  // namespace

double upper_arm_girth(const body::BodyModel& model, const body::ShapedBody& shaped, double sleeve_length_cm) {
    require_shape_of(model, shaped, "upper_arm_girth");
    require(std::isfinite(sleeve_length_cm) && sleeve_length_cm > 0, "upper_arm_girth: sleeve length ",
            sleeve_length_cm, " cm must be positive");
    const Eigen::Vector3d shoulder = shaped.joints.row(body::index(body::Joint::right_shoulder)).transpose();
    const Eigen::Vector3d elbow = shaped.joints.row(body::index(body::Joint::right_elbow)).transpose();
    const Eigen::Vector3d axis = elbow - shoulder;
    const double length = axis.norm();
    require(length > 0, "upper_arm_girth: the shoulder and elbow joints coincide");
    const Eigen::MatrixXi arm_faces = right_upper_arm_faces(model);
    require(arm_faces.rows() > 0, "upper_arm_girth: the model has no faces skinned to the right upper arm");
    const double t_end = std::clamp(0.01 * sleeve_length_cm / length, 0.35, 0.95);
    double girth = 0;
    for (double t = 0.35; t <= t_end + 1e-9; t += 0.05)
        girth = std::max(girth, body::section_girth(shaped.vertices, arm_faces, shoulder + t * axis, axis));
    require(girth > 0, "upper_arm_girth: no section of the right upper arm");
    return girth;
}

namespace {
// Throws unless the girth is positive and the ease in [0, 60] cm (`what` names the caller).
void check_girth_and_ease(const char* what, double girth_m, double ease_cm) {
    require(std::isfinite(girth_m) && girth_m > 0, what, ": girth ", girth_m, " m must be positive");
    require(std::isfinite(ease_cm) && ease_cm >= 0 && ease_cm <= 60, what, ": ease ", ease_cm,
            " cm must be in [0, 60]");
}
}  // namespace

TShirtSizing fit_sleeves(TShirtSizing g, double arm_girth_m, double ease_cm) {
    check_girth_and_ease("fit_sleeves", arm_girth_m, ease_cm);
    if (g.l1 > 0) g.w1 = std::max(g.w1, cm(arm_girth_m) + ease_cm);
    return g;
}

double neck_girth(const body::BodyModel& model, const body::ShapedBody& shaped) {
    require_shape_of(model, shaped, "neck_girth");
    const Eigen::Vector3d neck = shaped.joints.row(body::index(body::Joint::neck)).transpose();
    const Eigen::Vector3d head = shaped.joints.row(body::index(body::Joint::head)).transpose();
    require((head - neck).norm() > 0, "neck_girth: the neck and head joints coincide");
    const double g = body::section_girth(shaped.vertices, model.faces, neck + 0.3 * (head - neck), head - neck);
    require(g > 0, "neck_girth: no section of the neck");
    return g;
}

TShirtSizing fit_neckline(TShirtSizing g, double neck_girth_m, double ease_cm) {
    check_girth_and_ease("fit_neckline", neck_girth_m, ease_cm);
    // The neckline's arcs scale with r (their depths are fixed fractions of it).
    const Pattern p = make_tshirt(g);
    const double neckline = p.panels[0].edges[4].length() + p.panels[1].edges[4].length();
    const double wanted = cm(neck_girth_m) + ease_cm;
    if (neckline >= wanted) return g;
    double r_max = 0.5 * (g.w2 - 10.0);
    for (const auto& spec : TShirtSizing::parameters())
        if (std::string(spec.name) == "r") r_max = std::min(r_max, spec.max);
    g.r = std::max(g.r, std::min(r_max, g.r * wanted / neckline));
    return g;
}

SkirtSizing propose_skirt_sizing(const body::BodyMeasurements& m, double waistband_girth_m, double ease_cm) {
    Ease ease;
    ease.waist_cm = ease_cm;
    check_measurements(m, ease);
    require(std::isfinite(waistband_girth_m) && waistband_girth_m > 0, "propose_skirt_sizing: waistband_girth_m = ",
            waistband_girth_m, " must be positive");
    return skirt_for_waist((cm(waistband_girth_m) + ease_cm) / 2, cm(m.height_m));
}

PantsSizing propose_pants_sizing(const body::BodyMeasurements& m, const Ease& ease) {
    check_measurements(m, ease);
    const double waist_height = kWaistHeightRatio * cm(m.height_m);
    PantsSizing g;
    g.w1 = cm(m.waist_girth_m) + ease.waist_cm;
    g.w2 = std::max(cm(m.hip_girth_m) + ease.hip_cm, g.w1);
    g.w3 = kKneeToThighGirth * cm(m.thigh_girth_m) + ease.leg_cm;
    g.w4 = kAnkleToKneeOpening * g.w3;
    g.h1 = waist_height - 3.0;  // hem 3 cm above the floor
    g.h3 = waist_height - cm(m.crotch_height_m) + 2.0;
    g.h2 = g.h3 + 5.0;
    return g;
}

TShirtSizing propose_tshirt_sizing(const body::BodyMeasurements& m, const Ease& ease) {
    check_measurements(m, ease);
    const double height = cm(m.height_m);
    TShirtSizing g;
    g.r = kNeckRadiusRatio * height;
    g.w1 = kSleeveOpeningRatio * height;
    g.w2 = (cm(m.chest_girth_m) + ease.chest_cm) / 2;
    g.h2 = cm(m.shoulder_height_m) + 4.0 - (cm(m.crotch_height_m) + 2.0);  // hem near the crotch
    g.h1 = g.h2 - kTShirtShoulderDrop - kArmholeDepthRatio * height;
    g.l1 = kSleeveLengthRatio * height;
    return g;
}

DressSizing propose_dress_sizing(const body::BodyMeasurements& m, const Ease& ease) {
    DressSizing g;
    g.bodice = propose_tshirt_sizing(m, ease);
    const double height = cm(m.height_m);
    g.bodice.h2 = cm(m.shoulder_height_m) + 4.0 - kWaistHeightRatio * height;
    g.bodice.h1 = g.bodice.h2 - kTShirtShoulderDrop - kArmholeDepthRatio * height;
    g.skirt = skirt_for_waist(g.bodice.w2, height);
    return g;
}

GarmentSizing proposed_sizing(GarmentType type, const body::BodyMeasurements& measured) {
    GarmentSizing g;
    g.type = type;
    switch (type) {
        case GarmentType::skirt: g.skirt = propose_skirt_sizing(measured); break;
        case GarmentType::pants: g.pants = propose_pants_sizing(measured); break;
        case GarmentType::tshirt: g.tshirt = propose_tshirt_sizing(measured); break;
        case GarmentType::dress: g.dress = propose_dress_sizing(measured); break;
    }
    return g;
}

GarmentSizing proposed_sizing(GarmentType type, const body::BodyMeasurements& measured,
                              double skirt_waistband_girth_m) {
    GarmentSizing g = proposed_sizing(type, measured);
    if (type == GarmentType::skirt) g.skirt = propose_skirt_sizing(measured, skirt_waistband_girth_m);
    return g;
}

GarmentSizing proposed_sizing(GarmentType type, const body::BodyModel& model, const body::ShapedBody& shaped,
                              const body::BodyMeasurements& measured) {
    if (type == GarmentType::skirt) return proposed_sizing(type, measured, skirt_waistband(model, shaped).girth_m);
    return fit_top_to_body(proposed_sizing(type, measured), model, shaped);
}

GarmentSizing fit_top_to_body(GarmentSizing g, const body::BodyModel& model, const body::ShapedBody& shaped) {
    if (g.type != GarmentType::tshirt && g.type != GarmentType::dress) return g;
    TShirtSizing& top = g.type == GarmentType::tshirt ? g.tshirt : g.dress.bodice;
    if (top.l1 > 0) top = fit_sleeves(top, upper_arm_girth(model, shaped, top.l1));
    top = fit_neckline(top, neck_girth(model, shaped));
    return g;
}

}  // namespace drape::garment
