#include <drape/body/body_model.hpp>
#include <drape/body/measurements.hpp>
#include <drape/body/pose.hpp>
#include <drape/body/shape_body.hpp>
#include <drape/cloth/intersections.hpp>
#include <drape/cloth/obstacle.hpp>
#include <drape/garment/arm_clearance.hpp>
#include <drape/garment/circle_skirt.hpp>
#include <drape/garment/dress.hpp>
#include <drape/cloth/material.hpp>
#include <drape/core/errors.hpp>
#include <drape/garment/drape_garment.hpp>
#include <drape/garment/dressing.hpp>
#include <drape/garment/garment_sizing.hpp>
#include <drape/fixtures/eval_bodies.hpp>
#include <drape/core/point_in_mesh.hpp>
#include <drape/garment/pants.hpp>
#include <drape/garment/sizing_proposal.hpp>
#include <drape/garment/tshirt.hpp>

#include <catch2/catch.hpp>

// The sewn surface (stitched partners as one vertex) is private to libgarment.
#include "../../libgarment/src/dressing_internal.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <map>
#include <memory>
#include <string>

using namespace drape::garment;
namespace body = drape::body;

namespace {

// The default body (zero shape coefficients) in a named pose, with its measurements and an
// inside test on the posed mesh.
struct PosedDefaultBody {
    const body::BodyModel& model = body::BodyModel::default_model();
    body::ShapedBody shaped;
    body::BodyMeasurements m;
    body::Pose pose;
    body::PosedBody posed;
    std::unique_ptr<drape::core::ClosedMeshInside> inside;

    explicit PosedDefaultBody(body::NamedPose which) {
        shaped.coefficients = Eigen::VectorXd::Zero(model.shape_count());
        shaped.vertices = model.template_vertices;
        shaped.joints = model.template_joints;
        m = body::measure_body(model, shaped.vertices);
        pose = body::named_pose(which);
        posed = body::pose_body(model, shaped, pose);
        inside = std::make_unique<drape::core::ClosedMeshInside>(posed.vertices, model.faces);
    }
    /// Meshes `pattern` at 2.5 cm and dresses it on this body.
    DressingSummary dress(const Pattern& pattern, GarmentMesh& mesh, Eigen::MatrixX3d& X) const {
        MeshOptions mo;
        mo.target_edge_cm = 2.5;
        REQUIRE(mesh_pattern(pattern, mo, mesh).usable());
        return dress_garment(pattern, mesh, model, shaped, pose, DressingOptions{}, X);
    }
    int count_inside(const Eigen::MatrixX3d& X) const { return int(inside->inside_indices(X).size()); }
};

}  // namespace

TEST_CASE("rigid alignment recovers a rotation and translation", "[garment][dressing]") {
    Eigen::MatrixX3d q(4, 3);
    q << 0, 0, 0, 1, 0, 0, 0, 2, 0, 0, 0, 3;
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
    T.translation() = Eigen::Vector3d(0.3, -1, 2);
    const Eigen::MatrixX3d t = (T * q.transpose()).transpose();
    const Eigen::Isometry3d R = rigid_align(q, t);
    CHECK((R.matrix() - T.matrix()).norm() < 1e-12);
}

namespace {

// Dresses each garment on the default body in A-pose and checks it ends outside it.
void check_outside_default_body(const std::vector<std::pair<const char*, Pattern>>& garments) {
    const PosedDefaultBody b(body::NamedPose::a_pose);
    const auto& posed = b.posed;
    for (const auto& [name, pattern] : garments) {
        INFO(name);
        GarmentMesh mesh;
        Eigen::MatrixX3d X;
        const DressingSummary s = b.dress(pattern, mesh, X);
        WARN(name << ": " << s.brief_report());
        CHECK(s.alignment_rms_m < 1e-9);
        REQUIRE(X.rows() == mesh.cloth.vertex_count());
        CHECK(X.allFinite());
        CHECK(b.count_inside(X) == 0);
        CHECK(s.vertices_inside == 0);
        // Seam partners start together (the pants' crotch points sit a few cm apart on
        // the two leg tubes; the simulator closes that; sleeve caps start open, 4-15 cm
        // down the arm).
        if (std::string(name) != "tshirt" && std::string(name) != "dress")
            CHECK(s.max_seam_gap_m < (std::string(name) == "pants" ? 0.06 : 0.01));
        // The garment hangs on the body: within the body's bounding box grown by 40 cm.
        const Eigen::RowVector3d lo = posed.vertices.colwise().minCoeff(), hi = posed.vertices.colwise().maxCoeff();
        CHECK((X.rowwise() - lo).minCoeff() > -0.4);
        CHECK((X.rowwise() - hi).maxCoeff() < 0.4);
        // (The pants on this body still start with ~26 crossings at the crotch: docs/notes/dressing.md.)
        if (std::string(name) != "pants") CHECK(s.self_intersections == 0);
    }
}

}  // namespace

TEST_CASE("dressing: skirt and pants on the default body in A-pose are outside the body",
          "[garment][dressing]") {
    const PosedDefaultBody b(body::NamedPose::a_pose);
    check_outside_default_body({{"skirt", make_circle_skirt(propose_skirt_sizing(b.m))},
                                {"pants", make_pants(propose_pants_sizing(b.m))}});
}

// A flared circle skirt (side seams 107 degrees apart, waist arc 90 degrees: the middle of
// its hem lies farther from the waist centre than its corners) is wrapped as the cone its
// panels make. Sliced by the outline at each vertex's own radius, the hem's middle vertices
// got a sliver of the panel's width and were wrapped onto a tiny ring between the legs:
// edges up to 6x their pattern length, pushed out behind the thighs (a synthetic scene's
// heavy man, 51 mm left inside one thigh after the drape). Checked here: every edge of the
// wrapped skirt below the waist ring within 35 % of its pattern length (the waist ring,
// fitted to the body, within 50 %), the side seams closed, nothing pushed.
TEST_CASE("dressing: a flared circle skirt is wrapped as a cone, its hem rings whole",
          "[garment][dressing]") {
    const PosedDefaultBody b(body::NamedPose::a_pose);
    SkirtSizing g = propose_skirt_sizing(b.m);
    g.r1 = g.l1 / (0.5 * 3.14159265358979);  // waist arc of 90 degrees
    g.alpha = 107;
    g.r2 = 56;
    const Pattern pattern = make_circle_skirt(g);
    GarmentMesh mesh;
    Eigen::MatrixX3d X;
    const DressingSummary s = b.dress(pattern, mesh, X);
    INFO(s.brief_report());
    const drape::cloth::ClothMesh& M = mesh.cloth;
    double worst = 0, worst_waist = 0;
    for (Eigen::Index f = 0; f < M.faces.rows(); ++f)
        for (int c = 0; c < 3; ++c) {
            const double rest = (M.pattern.row(M.pattern_faces(f, c)) - M.pattern.row(M.pattern_faces(f, (c + 1) % 3))).norm();
            const double now = (X.row(M.faces(f, c)) - X.row(M.faces(f, (c + 1) % 3))).norm();
            const bool waist = mesh.boundary_edge(M.faces(f, c)) == 2 && mesh.boundary_edge(M.faces(f, (c + 1) % 3)) == 2;
            (waist ? worst_waist : worst) = std::max(waist ? worst_waist : worst, std::abs(now / rest - 1));
        }
    // The waist ring is the one part fitted to the body (placed where it fits, pushed out
    // radially over the belly); below it the wrap is the cone's.
    INFO("largest edge strain " << worst << ", along the waist " << worst_waist);
    CHECK(worst < 0.35);
    CHECK(worst_waist < 0.5);
    CHECK(s.max_seam_gap_m < 1e-3);
    CHECK(s.vertices_pushed == 0);
    CHECK(b.count_inside(X) == 0);
    // The hem hangs as the cone: its lowest point no lower than the skirt's length below
    // the waist, and every hem vertex well away from the body's axis (not between the legs).
    const Eigen::Vector3d pelvis = b.posed.joints.row(body::index(body::Joint::pelvis)).transpose();
    double nearest_hem = 1e9;
    for (int v = 0; v < M.vertex_count(); ++v)
        if (mesh.boundary_edge(v) == 0)
            nearest_hem = std::min(nearest_hem, std::hypot(X(v, 0) - pelvis.x(), X(v, 2) - pelvis.z()));
    INFO("hem vertex nearest the body axis: " << nearest_hem << " m");
    CHECK(nearest_hem > 0.25);
}

// On this zero-coefficient body the wrapped t-shirt's front panel folds onto itself at the
// neck and shoulders (9 crossing pairs, 1 vertex inside) and the dress crosses itself 4
// times; the untangling step of dress_garment separates them.
TEST_CASE("dressing: t-shirt and dress on the default body in A-pose are outside the body",
          "[garment][dressing]") {
    const PosedDefaultBody b(body::NamedPose::a_pose);
    check_outside_default_body({{"tshirt", make_tshirt(propose_tshirt_sizing(b.m))},
                                {"dress", make_dress(propose_dress_sizing(b.m))}});
}

// Hidden: OPEN (issue 4, docs/notes/dressing.md). Since the push-out no longer moves vertices
// through other panels, on this (zero-coefficient) body the crotch seam of the walking
// pants stays 3.4 cm open. Run it with: drape_garment_tests "[open]".
TEST_CASE("dressing: pants in a walking pose are outside the body with the crotch seam near",
          "[garment][dressing][.open]") {
    const PosedDefaultBody b(body::NamedPose::walking);
    GarmentMesh mesh;
    Eigen::MatrixX3d X;
    const DressingSummary s = b.dress(make_pants(propose_pants_sizing(b.m)), mesh, X);
    INFO("pants (walking): " << s.brief_report());
    CHECK(b.count_inside(X) == 0);
    CHECK(s.max_seam_gap_m < 0.03);
}

TEST_CASE("dressing: pants follow a walking pose", "[garment][dressing]") {
    // (A t-shirt in this pose keeps ~20 vertices in the armpit fold: see the docs.)
    const PosedDefaultBody b(body::NamedPose::walking);
    const Pattern pattern = make_pants(propose_pants_sizing(b.m));
    GarmentMesh mesh;
    Eigen::MatrixX3d X;
    const DressingSummary s = b.dress(pattern, mesh, X);
    INFO("pants (walking): " << s.brief_report());
    // The right knee is bent forward: the right pants leg's hem moves forward with it.
    double z_hem = -1e9;
    for (int v = 0; v < mesh.cloth.vertex_count(); ++v)
        if (pattern.panels[size_t(mesh.panel_of_vertex(v))].name == "front_right" &&
            mesh.boundary_edge(v) == 0)
            z_hem = std::max(z_hem, X(v, 2));
    CHECK(z_hem > b.posed.joints(body::index(body::Joint::right_hip), 2) + 0.1);
}

namespace {

// A mean ANSUR body of one gender (the shape prior's completion of a request that only
// names the gender) in a named pose.
struct MeanBody {
    const body::BodyModel& model = body::BodyModel::default_model();
    body::ShapedBody shaped;
    body::BodyMeasurements m;
    body::Pose pose;
    body::PosedBody posed;

    MeanBody(body::Gender gender, body::NamedPose which) {
        body::SemanticRequest request;
        request.gender = gender;
        REQUIRE(body::shape_body(model, model.prior.complete(request), body::ShapeOptions{}, shaped).usable());
        m = body::measure_body(model, shaped.vertices);
        pose = body::named_pose(which);
        posed = body::pose_body(model, shaped, pose);
    }
};

// The six templates sized for a body: skirt, pants, shorts, t-shirt, tank top, dress.
std::vector<std::pair<std::string, Pattern>> all_templates(const body::BodyMeasurements& m) {
    TShirtSizing tank = propose_tshirt_sizing(m);
    tank.l1 = 0;
    PantsSizing shorts = propose_pants_sizing(m);
    shorts.h1 = std::min(shorts.h1, shorts.h3 + 25.0);
    return {{"skirt", make_circle_skirt(propose_skirt_sizing(m))},
            {"pants", make_pants(propose_pants_sizing(m))},
            {"shorts", make_pants(shorts)},
            {"tshirt", make_tshirt(propose_tshirt_sizing(m))},
            {"tank_top", make_tshirt(tank)},
            {"dress", make_dress(propose_dress_sizing(m))}};
}

// Prints the crossing triangle pairs per pair of panels and the vertices inside the body
// (DRAPE_DRESS_DETAIL).
void print_crossings(const std::string& name, const Pattern& pattern, const GarmentMesh& mesh, const Eigen::MatrixX3d& X,
                     const Eigen::MatrixXd& body_V, const Eigen::MatrixXi& body_F) {
    const Eigen::MatrixX3i merged = detail::sewn_faces(mesh);
    std::vector<std::pair<int, int>> pairs;
    drape::cloth::count_self_intersections(X, merged, &pairs);
    std::map<std::string, std::pair<int, double>> hist;
    for (const auto& [f, g2] : pairs) {
        const auto& pa = pattern.panels[size_t(mesh.panel_of_vertex(mesh.cloth.faces(f, 0)))].name;
        const auto& pb = pattern.panels[size_t(mesh.panel_of_vertex(mesh.cloth.faces(g2, 0)))].name;
        auto& h = hist[pa + "-" + pb];
        ++h.first;
        h.second += X(mesh.cloth.faces(f, 0), 1);
    }
    const drape::cloth::Obstacle obst(body_V, body_F);
    std::map<std::string, std::vector<double>> inside;
    for (int v = 0; v < X.rows(); ++v) {
        const auto q = obst.closest(X.row(v).transpose(), 1e9);
        if (q.signed_distance_m < -0.001) inside[pattern.panels[size_t(mesh.panel_of_vertex(v))].name].push_back(X(v, 1));
    }
    for (const auto& [k, ys] : inside) std::printf("   %s: inside %s %zu (first y %.2f)\n", name.c_str(), k.c_str(), ys.size(), ys[0]);
    for (const auto& [k, h] : hist) std::printf("   %s: %s %d (mean y %.2f)\n", name.c_str(), k.c_str(), h.first, h.second / h.first);
}

struct DressedCase {
    std::string name;
    DressingSummary dressing;
    GarmentStateCheck check;
};

// Dresses every template at `edge_cm` on the mean female and male in the three poses.
std::vector<DressedCase> dress_all(double edge_cm) {
    std::vector<DressedCase> out;
    for (body::Gender g : {body::Gender::female, body::Gender::male})
        for (body::NamedPose p : {body::NamedPose::a_pose, body::NamedPose::arms_down, body::NamedPose::walking, body::NamedPose::t_pose}) {
            const MeanBody b(g, p);
            for (const auto& [name, pattern] : all_templates(b.m)) {
                MeshOptions mo;
                mo.target_edge_cm = edge_cm;
                GarmentMesh mesh;
                REQUIRE(mesh_pattern(pattern, mo, mesh).usable());
                Eigen::MatrixX3d X;
                DressedCase c;
                c.name = name + " / " + std::string(body::to_string(g)) + " / " +
                         (p == body::NamedPose::a_pose ? "a_pose" : p == body::NamedPose::arms_down ? "arms_down" : p == body::NamedPose::t_pose ? "t_pose" : "walking");
                c.dressing = dress_garment(pattern, mesh, b.model, b.shaped, b.pose, DressingOptions{}, X);
                c.check = check_garment_state(mesh, X, b.posed.vertices, b.model.faces);
                if (std::getenv("DRAPE_DRESS_DETAIL") && c.check.self_intersections > 0)
                    print_crossings(c.name, pattern, mesh, X, b.posed.vertices, b.model.faces);
                out.push_back(c);
            }
        }
    return out;
}

}  // namespace

TEST_CASE("dressing eval: every template on the mean bodies in three poses (table)", "[.eval][dressing]") {
    // Prints the docs/notes/dressing.md table; DRAPE_DRESS_EDGE_CM overrides the 4 cm edges.
    const double edge_cm = std::getenv("DRAPE_DRESS_EDGE_CM") ? std::atof(std::getenv("DRAPE_DRESS_EDGE_CM")) : 4.0;
    std::printf("| case | self-int. | penetration mm | min layer mm | close pairs | seam gap mm | s |\n");
    for (const DressedCase& c : dress_all(edge_cm)) {
        std::printf("| %-28s | %3d | %6.1f | %6.1f | %4d | %6.1f | %5.2f |\n", c.name.c_str(), c.check.self_intersections,
                    1000 * c.check.max_penetration_m, 1000 * c.check.min_layer_distance_m, c.check.close_pairs,
                    1000 * c.check.max_seam_gap_m, c.dressing.seconds);
        INFO(c.name);
        CHECK(c.check.self_intersections == 0);
        CHECK(c.check.max_penetration_m <= 0.001);
    }
}

TEST_CASE("dressing: every template starts clean on the mean female in A-pose, skirt, pants, tank top on the male",
          "[garment][dressing]") {
    // The cases of the 36-case table (docs/notes/dressing.md) that are clean: no self-intersection
    // (seam partners as one vertex) and nothing deeper than 1 mm inside the body.
    struct Case {
        body::Gender gender;
        body::NamedPose pose;
        std::vector<std::string> garments;
    };
    const std::vector<Case> cases = {
        {body::Gender::female, body::NamedPose::a_pose, {"skirt", "pants", "shorts", "tshirt", "tank_top", "dress"}},
        {body::Gender::male, body::NamedPose::a_pose, {"skirt", "pants", "tank_top"}}};
    for (const Case& k : cases) {
        const MeanBody b(k.gender, k.pose);
        for (const auto& [name, pattern] : all_templates(b.m)) {
            if (std::find(k.garments.begin(), k.garments.end(), name) == k.garments.end()) continue;
            INFO(name << " on the mean " << body::to_string(k.gender) << ", pose " << int(k.pose));
            MeshOptions mo;
            mo.target_edge_cm = 4.0;
            GarmentMesh mesh;
            REQUIRE(mesh_pattern(pattern, mo, mesh).usable());
            Eigen::MatrixX3d X;
            const DressingSummary s = dress_garment(pattern, mesh, b.model, b.shaped, b.pose, DressingOptions{}, X);
            const GarmentStateCheck c = check_garment_state(mesh, X, b.posed.vertices, b.model.faces);
            INFO(c.brief_report());
            CHECK(c.self_intersections == 0);
            CHECK(c.max_penetration_m <= 0.001);
            // (Sleeve caps start open, 4-15 cm down the arm: the simulation sews them.)
            if (name != "tshirt" && name != "dress") CHECK(c.max_seam_gap_m < 0.005);
            CHECK(s.self_intersections == c.self_intersections);
            CHECK(s.max_penetration_m == Approx(c.max_penetration_m).margin(1e-12));
        }
    }
}

namespace {

// `pattern` meshed at 4 cm edges.
GarmentMesh mesh_at_4cm(const Pattern& pattern) {
    MeshOptions mo;
    mo.target_edge_cm = 4.0;
    GarmentMesh mesh;
    REQUIRE(mesh_pattern(pattern, mo, mesh).usable());
    return mesh;
}

// Largest angle allowed between the ends of a sleeve-cap stitch in the dressed state.
constexpr double kMaxCapStitchAngleDeg = 30.0;

// The largest angle (degrees) about the posed upper-arm axis (shoulder -> elbow joint)
// between the two ends of a sleeve-cap stitch (a sleeve vertex and its armhole vertex):
// near 0 when the armhole loops around the arm root as the cap does; near 180 when a cap
// point in front of the arm is to be sewn to an armhole point behind it (the seam then
// closes through the arm root).
double max_cap_stitch_angle_deg(const Pattern& pattern, const GarmentMesh& mesh, const Eigen::MatrixX3d& X,
                                const body::PosedSkeleton& skel) {
    const auto is_sleeve = [&](int v) {
        return pattern.placements[size_t(mesh.panel_of_vertex(v))].body_part == BodyPart::left_sleeve ||
               pattern.placements[size_t(mesh.panel_of_vertex(v))].body_part == BodyPart::right_sleeve;
    };
    double worst = 0;
    for (const auto& st : mesh.stitches) {
        if (is_sleeve(st[0]) == is_sleeve(st[1])) continue;
        const int sv = is_sleeve(st[0]) ? st[0] : st[1], tv = is_sleeve(st[0]) ? st[1] : st[0];
        const bool left = pattern.placements[size_t(mesh.panel_of_vertex(sv))].body_part == BodyPart::left_sleeve;
        const Eigen::Vector3d c = skel.joints.row(body::index(left ? body::Joint::left_shoulder : body::Joint::right_shoulder));
        const Eigen::Vector3d e = skel.joints.row(body::index(left ? body::Joint::left_elbow : body::Joint::right_elbow));
        const Eigen::Vector3d a = (e - c).normalized();
        const auto radial = [&](int v) {
            const Eigen::Vector3d d = X.row(v).transpose() - c;
            return Eigen::Vector3d((d - d.dot(a) * a).normalized());
        };
        worst = std::max(worst, std::acos(std::clamp(radial(sv).dot(radial(tv)), -1.0, 1.0)) * 45.0 / std::atan(1.0));
    }
    return worst;
}

struct ShapedAnsurBody {
    const body::BodyModel& model = body::BodyModel::default_model();
    body::ShapedBody shaped;
    body::BodyMeasurements m;
    body::Pose pose = body::named_pose(body::NamedPose::a_pose);
    body::PosedBody posed;

    explicit ShapedAnsurBody(const EvalBody& a) {
        body::SemanticRequest request;
        request.gender = a.gender;
        request[body::Semantic::height_m] = a.height_m;
        request[body::Semantic::weight_kg] = a.weight_kg;
        shape(request);
    }
    explicit ShapedAnsurBody(const body::SemanticRequest& request) { shape(request); }
    void shape(const body::SemanticRequest& request) {
        REQUIRE(body::shape_body(model, model.prior.complete(request), body::ShapeOptions{}, shaped).usable());
        m = body::measure_body(model, shaped.vertices);
        posed = body::pose_body(model, shaped, pose);
    }
    GarmentStateCheck dress(const Pattern& pattern, DressingSummary* s, const DressingOptions& o = {},
                            double* cap_angle_deg = nullptr) const {
        const GarmentMesh mesh = mesh_at_4cm(pattern);
        Eigen::MatrixX3d X;
        *s = dress_garment(pattern, mesh, model, shaped, pose, o, X);
        if (cap_angle_deg)
            *cap_angle_deg = max_cap_stitch_angle_deg(pattern, mesh, X, body::forward_kinematics(shaped.joints, pose));
        const GarmentStateCheck c = check_garment_state(mesh, X, posed.vertices, model.faces);
        if (std::getenv("DRAPE_DRESS_DETAIL") && c.self_intersections > 0)
            print_crossings(pattern.name, pattern, mesh, X, posed.vertices, model.faces);
        return c;
    }
};

}  // namespace

TEST_CASE("dressing eval: every template on the five ANSUR bodies in A-pose (table)", "[.eval][dressing]") {
    std::printf("| case | before untangling | self-int. | penetration mm | min layer mm | close pairs | s |\n");
    for (const EvalBody& a : kEvalBodies) {
        const ShapedAnsurBody b(a);
        for (const auto& [name, proposed] : all_templates(b.m)) {
            if (name == "shorts" || name == "tank_top") continue;
            const Pattern pattern = name == "skirt" ? make_circle_skirt(propose_skirt_sizing(
                                                          b.m, skirt_waistband(b.model, b.shaped).girth_m))
                                                    : proposed;
            DressingSummary s;
            DressingOptions o;
            o.untangle = std::getenv("DRAPE_DRESS_NO_UNTANGLE") == nullptr;
            const GarmentStateCheck c = b.dress(pattern, &s, o);
            std::printf("| %-8s / %-10s | %3d | %3d | %6.1f | %6.1f | %4d | %5.2f |\n", name.c_str(), a.name,
                        s.untangle.initial_self_intersections, c.self_intersections, 1000 * c.max_penetration_m,
                        1000 * c.min_layer_distance_m, c.close_pairs, s.seconds);
            std::fflush(stdout);
        }
    }
}

TEST_CASE("dressing: t-shirt and dress start without crossings or penetration on the five ANSUR bodies in A-pose",
          "[garment][dressing]") {
    // Before the untangling step (2026-11-23) the dress crossed itself on 4 of these bodies
    // (2-29 pairs) and the t-shirt on 3 (1-7): docs/notes/dressing.md.
    int untangled = 0;
    for (const EvalBody& a : kEvalBodies) {
        const ShapedAnsurBody b(a);
        for (const auto& [name, pattern] : {std::pair<std::string, Pattern>{"tshirt", make_tshirt(propose_tshirt_sizing(b.m))},
                                            {"dress", make_dress(propose_dress_sizing(b.m))}}) {
            DressingSummary s;
            double cap_angle = 0;
            const GarmentStateCheck c = b.dress(pattern, &s, DressingOptions{}, &cap_angle);
            INFO(name << " on " << a.name << ": " << s.brief_report() << "; " << c.brief_report()
                      << "; cap stitches up to " << cap_angle << " degrees apart about the arm");
            CHECK(c.self_intersections == 0);
            // Armhole and sleeve cap on the same side of the arm root (docs/notes/dressing.md: on
            // the 5th-percentile man the right cap was to be sewn to armhole points up to
            // 175 degrees away, and the seam closed through his shoulder).
            CHECK(cap_angle < kMaxCapStitchAngleDeg);
            CHECK(c.max_penetration_m <= 0.001);
            CHECK(s.self_intersections == c.self_intersections);
            CHECK(s.untangle.self_intersections == 0);
            untangled += s.untangle.initial_self_intersections > 0 ? 1 : 0;
        }
    }
    // Since the armholes are opened around the arm roots (2026-11-24) the dressed state is
    // clean before untangling on all ten; before, 7 of them started with 1-29 crossing
    // pairs that the untangling step removed (that step is still tested on a folded skirt).
    CHECK(untangled == 0);
}

TEST_CASE("drape: the 5th-percentile man's t-shirt in A-pose sews its sleeve caps around the arms",
          "[garment][drape][dressing]") {
    // Before the armholes were opened around the arm roots (2026-11-24) the right cap seam
    // closed through his shoulder: 47 mm of cloth inside the body after the drape.
    const ShapedAnsurBody b(kEvalBodies[3]);
    REQUIRE(std::string(kEvalBodies[3].name) == "male_p5");
    const Pattern pattern = make_tshirt(propose_tshirt_sizing(b.m));
    const GarmentMesh mesh = mesh_at_4cm(pattern);
    Eigen::MatrixX3d X;
    const DressingSummary dressed = dress_garment(pattern, mesh, b.model, b.shaped, b.pose, DressingOptions{}, X);
    const double cap_angle = max_cap_stitch_angle_deg(pattern, mesh, X, body::forward_kinematics(b.shaped.joints, b.pose));
    INFO(dressed.brief_report() << "; cap stitches up to " << cap_angle << " degrees apart about the arm");
    CHECK(cap_angle < kMaxCapStitchAngleDeg);
    CHECK(dressed.self_intersections == 0);
    const DrapeSummary s = dress_and_drape(pattern, mesh, b.model, b.shaped, b.pose,
                                           drape::cloth::builtin_material("gray-interlock"), DressingOptions{},
                                           DrapeOptions{}, X);
    const GarmentStateCheck c = check_garment_state(mesh, X, b.posed.vertices, b.model.faces);
    INFO(s.brief_report() << "; " << c.brief_report());
    CHECK(s.usable());
    CHECK(s.welded);
    CHECK(c.self_intersections == 0);
    CHECK(c.max_penetration_m <= 0.001);
    CHECK(c.max_seam_gap_m < 0.001);
}

TEST_CASE("dressing: placement passes are validated, a clean skirt keeps the single pass",
          "[garment][dressing]") {
    DressingOptions d;
    std::string why;
    for (int bad : {-1, 9}) {
        d.placement_passes = bad;
        CHECK_FALSE(d.is_valid(&why));
        CHECK(why.find("placement_passes") != std::string::npos);
    }
    d.placement_passes = 4;
    CHECK(d.is_valid(&why));
    // Automatic: a skirt (no sleeves) whose one-pass placement leaves no crossing is dressed
    // exactly as with one pass, not with four.
    const MeanBody b(body::Gender::female, body::NamedPose::a_pose);
    const Pattern pattern = make_circle_skirt(propose_skirt_sizing(b.m));
    const GarmentMesh mesh = mesh_at_4cm(pattern);
    Eigen::MatrixX3d automatic, one, four;
    const DressingSummary sa = dress_garment(pattern, mesh, b.model, b.shaped, b.pose, DressingOptions{}, automatic);
    REQUIRE(sa.self_intersections == 0);
    DressingOptions o1, o4;
    o1.placement_passes = 1;
    o4.placement_passes = 4;
    dress_garment(pattern, mesh, b.model, b.shaped, b.pose, o1, one);
    dress_garment(pattern, mesh, b.model, b.shaped, b.pose, o4, four);
    CHECK((automatic - one).cwiseAbs().maxCoeff() == 0.0);
    INFO("four passes move the dressed skirt by up to " << (four - one).rowwise().norm().maxCoeff() << " m");
    CHECK(four.allFinite());
}

TEST_CASE("dressing: pants whose one-pass placement leaves the crotch seam open get the 4-pass placement",
          "[garment][dressing]") {
    // ANSUR II record 28192 (a man of 1.806 m and 69.0 kg; the record's own girths and
    // heights, as drape eval-dress --ansur shapes him): with one pass the push-out and the
    // untangling left a stitch at the crotch point 19 mm open and on the far side of the
    // other leg's panel; the drape then needed 360-555 steps to close it and ended with 8-12
    // crossings in every pose (docs/dressing.md).
    const body::BodyModel& model = body::BodyModel::default_model();
    body::SemanticRequest r;
    r.gender = body::Gender::male;
    r[body::Semantic::height_m] = 1.806;
    r[body::Semantic::weight_kg] = 69.0;
    r[body::Semantic::chest_girth_m] = 0.938;
    r[body::Semantic::waist_girth_m] = 0.780;
    r[body::Semantic::hip_girth_m] = 0.937;
    r[body::Semantic::thigh_girth_m] = 0.559;
    r[body::Semantic::calf_girth_m] = 0.344;
    r[body::Semantic::shoulder_height_m] = 1.465;
    r[body::Semantic::crotch_height_m] = 0.880;
    body::ShapedBody shaped;
    REQUIRE(body::shape_body(model, model.prior.complete(r), body::ShapeOptions{}, shaped).usable());
    const body::BodyMeasurements m = body::measure_body(model, shaped.vertices);
    const GarmentSizing g = proposed_sizing(GarmentType::pants, model, shaped, m);
    const Pattern pattern = make_pants(g.pants);
    const GarmentMesh mesh = mesh_at_4cm(pattern);
    Eigen::MatrixX3d automatic, one;
    body::Pose dressing_pose;
    const DressingSummary sa = dress_for_drape(pattern, mesh, model, shaped, DressingOptions{}, automatic, dressing_pose);
    DressingOptions o1;
    o1.placement_passes = 1;
    const DressingSummary s1 = dress_for_drape(pattern, mesh, model, shaped, o1, one, dressing_pose);
    INFO("one pass: " << s1.brief_report() << "; automatic: " << sa.brief_report());
    CHECK(sa.usable());
    CHECK(sa.self_intersections == 0);
    CHECK(sa.max_seam_gap_m <= kMaxSewnDressingSeamGapM);
    // The automatic choice did not keep a worse state than one pass.
    CHECK(sa.max_seam_gap_m <= s1.max_seam_gap_m);
}

TEST_CASE("untangle: options are validated and a clean state is left alone", "[garment][dressing]") {
    UntangleOptions o;
    std::string why;
    CHECK(o.is_valid(&why));
    o.max_iterations = 0;
    CHECK_FALSE(o.is_valid(&why));
    CHECK(why.find("max_iterations") != std::string::npos);
    o = UntangleOptions{};
    o.step_m = 0;
    CHECK_FALSE(o.is_valid(&why));
    CHECK(why.find("step_m") != std::string::npos);
    DressingOptions d;
    d.untangle_options.clearance_m = -1;
    CHECK_FALSE(d.is_valid(&why));
    CHECK(why.find("clearance_m") != std::string::npos);

    const MeanBody b(body::Gender::female, body::NamedPose::a_pose);
    const Pattern pattern = make_circle_skirt(propose_skirt_sizing(b.m));
    const GarmentMesh mesh = mesh_at_4cm(pattern);
    Eigen::MatrixX3d X;
    REQUIRE(dress_garment(pattern, mesh, b.model, b.shaped, b.pose, DressingOptions{}, X).self_intersections == 0);
    const Eigen::MatrixX3d before = X;
    const UntangleSummary s = untangle_garment(mesh, b.posed.vertices, b.model.faces, UntangleOptions{}, X);
    CHECK(s.initial_self_intersections == 0);
    CHECK(s.usable());
    CHECK(s.vertices_moved == 0);
    CHECK(X == before);
    Eigen::MatrixX3d wrong = X.topRows(3);
    CHECK_THROWS_AS(untangle_garment(mesh, b.posed.vertices, b.model.faces, UntangleOptions{}, wrong), drape::InvalidInput);
}

TEST_CASE("untangle: a skirt folded through itself is separated", "[garment][dressing]") {
    // The dressed skirt with a band of its hem pushed through the panel above it.
    const MeanBody b(body::Gender::female, body::NamedPose::a_pose);
    const Pattern pattern = make_circle_skirt(propose_skirt_sizing(b.m));
    const GarmentMesh mesh = mesh_at_4cm(pattern);
    Eigen::MatrixX3d X;
    dress_garment(pattern, mesh, b.model, b.shaped, b.pose, DressingOptions{}, X);
    const double y_top = X.col(1).maxCoeff(), y_low = X.col(1).minCoeff();
    const Eigen::RowVector3d centre = X.colwise().mean();
    // Front hem band (z > centre) folded up and pulled in, through the skirt above it.
    for (int v = 0; v < X.rows(); ++v) {
        if (X(v, 2) <= centre.z() + 0.05 || X(v, 1) > y_low + 0.1 * (y_top - y_low)) continue;
        X(v, 1) += 0.05;
        X(v, 2) -= 0.03;
    }
    const GarmentStateCheck folded = check_garment_state(mesh, X, b.posed.vertices, b.model.faces);
    REQUIRE(folded.self_intersections > 0);
    const UntangleSummary s = untangle_garment(mesh, b.posed.vertices, b.model.faces, UntangleOptions{}, X);
    const GarmentStateCheck c = check_garment_state(mesh, X, b.posed.vertices, b.model.faces);
    INFO(s.brief_report() << "; " << c.brief_report());
    CHECK(s.initial_self_intersections == folded.self_intersections);
    CHECK(c.self_intersections == 0);
    CHECK(s.self_intersections == 0);
    CHECK(c.max_penetration_m <= std::max(folded.max_penetration_m, 0.001));
}

// Sized from the navel girth + 4 cm ease (propose_skirt_sizing(m)) this skirt fell 61-113
// cm; his belly is wider than his hips. Sized from the narrowest section above his pelvis +
// 1.5 cm it still fell (97-101 cm): the knit waist stretched 16 % over his hips. With the
// waistband (DrapeOptions::waistband_width_cm, 2026-11-24) it stays up (drop 15 cm; it
// fell 105 cm, so the check is far from both).
TEST_CASE("drape: the 95th-percentile man's skirt, sized where its waistband sits, stays up",
          "[garment][drape]") {
    const ShapedAnsurBody b(kEvalBodies[4]);
    const double girth = skirt_waistband(b.model, b.shaped).girth_m;
    CHECK(girth < b.m.waist_girth_m);
    const SkirtSizing g = propose_skirt_sizing(b.m, girth);
    CHECK(2 * g.l1 == Approx(100 * girth + kSkirtWaistEaseCm));
    const Pattern pattern = make_circle_skirt(g);
    const GarmentMesh mesh = mesh_at_4cm(pattern);
    Eigen::MatrixX3d X;
    DressingSummary dressed;
    const DrapeSummary s = dress_and_drape(pattern, mesh, b.model, b.shaped, b.pose,
                                           drape::cloth::builtin_material("gray-interlock"), DressingOptions{},
                                           DrapeOptions{}, X, &dressed);
    INFO(dressed.brief_report() << "; " << s.brief_report());
    // His belly at the spine joint is wider than the skirt: its waist is placed lower, at the
    // highest section it fits (at most down to the narrowest, skirt_waistband's height).
    const double spine_y = b.shaped.joints(body::index(body::Joint::spine), 1);
    const double narrowest_drop = spine_y - skirt_waistband(b.model, b.shaped).height_m;
    CHECK(dressed.skirt_waist_drop_m > 0.02);
    CHECK(dressed.skirt_waist_drop_m <= narrowest_drop + 1e-9);
    CHECK(dressed.skirt_waist_drop_m == Approx(spine_y - skirt_waist_fit(b.model, b.shaped, 0.01 * 2 * g.l1).height_m));
    // A waist wider than every section sits at the spine joint, one narrower than all at the
    // narrowest section.
    CHECK(skirt_waist_fit(b.model, b.shaped, 10.0).height_m == Approx(spine_y));
    CHECK(skirt_waist_fit(b.model, b.shaped, 0.1).height_m == Approx(spine_y - narrowest_drop));
    CHECK_THROWS_AS(skirt_waist_fit(b.model, b.shaped, -1.0), drape::InvalidInput);
    CHECK(s.usable());
    CHECK(s.mean_drop_m < 0.20);  // 15 cm: the band settles from the spine joint to his narrowest section
    const GarmentStateCheck c = check_garment_state(mesh, X, b.posed.vertices, b.model.faces);
    CHECK(c.self_intersections == 0);
    CHECK(c.max_penetration_m <= 0.001);
}

TEST_CASE("drape: the median woman's pants through a walking step stay free of crossings",
          "[garment][drape]") {
    // Case of the 60-case table (docs/dressing.md). Until the self-contact rest filter
    // compared a welded seam's vertices in each panel's own pattern (2026-11-24), the pants
    // crossed themselves at the back of the crotch during the step (4 pairs from step 170 on).
    const drape::cloth::Material material = drape::cloth::builtin_material("gray-interlock");
    const ShapedAnsurBody b(kEvalBodies[1]);  // female_p50
    const body::BodyModel& model = b.model;
    const body::ShapedBody& shaped = b.shaped;
    const body::Pose pose = clear_arms_from_trunk(model, shaped, body::named_pose(body::NamedPose::walking));
    const Pattern pattern = make_pants(propose_pants_sizing(b.m));
    const GarmentMesh mesh = mesh_at_4cm(pattern);
    const Eigen::MatrixX3i sewn = detail::sewn_faces(mesh);
    int most_crossings = 0, checked = 0;
    DrapeOptions options;
    options.on_progress = [&](const DrapeProgress& p) {
        if (p.step % 10 == 0 && p.positions) {
            most_crossings = std::max(most_crossings, drape::cloth::count_self_intersections(*p.positions, sewn));
            ++checked;
        }
        return true;
    };
    Eigen::MatrixX3d X;
    DressingSummary dressed;
    const DrapeSummary s = dress_and_drape(pattern, mesh, model, shaped, pose, material, DressingOptions{}, options, X, &dressed);
    INFO(dressed.brief_report() << "; " << s.brief_report());
    CHECK(s.usable());
    CHECK(s.welded);
    CHECK(checked > 15);
    CHECK(most_crossings == 0);  // at every 10th step, not only at the end
    const GarmentStateCheck c = check_garment_state(mesh, X, body::pose_body(model, shaped, pose).vertices, model.faces);
    CHECK(c.self_intersections == 0);
    CHECK(c.max_penetration_m <= 1e-3);
}

TEST_CASE("drape: the 5th-percentile woman's t-shirt through a walking step comes to rest",
          "[garment][drape]") {
    // Case of the 60-case table (docs/dressing.md). With the stretching stiffness frozen
    // afresh at every step's start, an underarm vertex of this t-shirt alternated between
    // two places 1.7 mm apart for 400 steps (every step's Newton converged; the strain of
    // its faces sat where the table changes fast): not at rest after 600 steps. The
    // simulator now under-relaxes the stiffness across steps (docs/cloth.md).
    const drape::cloth::Material material = drape::cloth::builtin_material("gray-interlock");
    const ShapedAnsurBody b(kEvalBodies[0]);  // female_p5
    REQUIRE(std::string(kEvalBodies[0].name) == "female_p5");
    const body::BodyModel& model = b.model;
    const body::ShapedBody& shaped = b.shaped;
    const body::Pose pose = clear_arms_from_trunk(model, shaped, body::named_pose(body::NamedPose::walking));
    TShirtSizing g = propose_tshirt_sizing(b.m);  // as drape eval-dress: fitted to arms and neck
    g = fit_neckline(fit_sleeves(g, upper_arm_girth(model, shaped, g.l1)), neck_girth(model, shaped));
    const Pattern pattern = make_tshirt(g);
    const GarmentMesh mesh = mesh_at_4cm(pattern);
    Eigen::MatrixX3d X;
    DressingSummary dressed;
    const DrapeSummary s =
        dress_and_drape(pattern, mesh, model, shaped, pose, material, DressingOptions{}, DrapeOptions{}, X, &dressed);
    INFO(dressed.brief_report() << "; " << s.brief_report());
    CHECK(s.converged);
    CHECK(s.usable());
    CHECK(s.steps < 450);
}

// The body of a diagnostic: an evaluation body by name (female_p50, ...), or a record's
// measurements "female|male,height,weight,chest,waist,hip,thigh,calf,shoulder,crotch" (SI).
ShapedAnsurBody diag_body(const std::string& spec) {
    for (const EvalBody& e : kEvalBodies)
        if (spec == e.name) return ShapedAnsurBody(e);
    std::vector<std::string> fields;
    std::string field;
    for (const char c : spec + ",") {
        if (c == ',') fields.push_back(field), field.clear();
        else field += c;
    }
    REQUIRE(fields.size() == 10);
    body::SemanticRequest request;
    request.gender = body::parse_gender(fields[0]);
    const body::Semantic order[] = {body::Semantic::height_m, body::Semantic::weight_kg, body::Semantic::chest_girth_m,
                                    body::Semantic::waist_girth_m, body::Semantic::hip_girth_m, body::Semantic::thigh_girth_m,
                                    body::Semantic::calf_girth_m, body::Semantic::shoulder_height_m,
                                    body::Semantic::crotch_height_m};
    for (size_t k = 0; k < 9; ++k) request[order[k]] = std::stod(fields[k + 1]);
    return ShapedAnsurBody(request);
}

// Diagnostic (hidden): the crossings of a garment of the 60-case table over the drape,
// every 5 steps, with where they are (panels, centre of the first face). DRAPE_DIAG_BODY
// (female_p50), DRAPE_DIAG_GARMENT (pants|skirt|tshirt), DRAPE_DIAG_POSE
// (walking|arms_down|a_pose).
TEST_CASE("drape diag: crossings over the drape of one case of the 60-case table", "[.diag]") {
    const drape::cloth::Material material = drape::cloth::builtin_material("gray-interlock");
    const auto env = [](const char* k, const char* d) { const char* v = std::getenv(k); return std::string(v ? v : d); };
    const std::string garment = env("DRAPE_DIAG_GARMENT", "pants"), pose_name = env("DRAPE_DIAG_POSE", "walking");
    const ShapedAnsurBody b = diag_body(env("DRAPE_DIAG_BODY", "female_p50"));
    const body::BodyModel& model = b.model;
    const body::ShapedBody& shaped = b.shaped;
    const body::NamedPose np = pose_name == "walking" ? body::NamedPose::walking
                               : pose_name == "arms_down" ? body::NamedPose::arms_down : body::NamedPose::a_pose;
    const body::Pose pose = clear_arms_from_trunk(model, shaped, body::named_pose(np));
    Pattern pattern;
    if (garment == "pants") pattern = make_pants(propose_pants_sizing(b.m));
    else if (garment == "skirt") pattern = make_circle_skirt(propose_skirt_sizing(b.m, skirt_waistband(model, shaped).girth_m));
    else {  // as drape eval-dress: the sleeves and neckline fitted to the body
        TShirtSizing g = propose_tshirt_sizing(b.m);
        g = fit_neckline(fit_sleeves(g, upper_arm_girth(model, shaped, g.l1)), neck_girth(model, shaped));
        pattern = make_tshirt(g);
    }
    const GarmentMesh mesh = mesh_at_4cm(pattern);
    const Eigen::MatrixX3i sewn = detail::sewn_faces(mesh);
    const drape::cloth::Obstacle final_body(body::pose_body(model, shaped, pose).vertices, model.faces);
    DrapeOptions options;
    options.on_progress = [&](const DrapeProgress& p) {
        if (p.step % 5 != 0 || !p.positions) return true;
        std::vector<std::pair<int, int>> pairs;
        const int n = drape::cloth::count_self_intersections(*p.positions, sewn, &pairs);
        // The top ring: boundary vertices within 2 cm of the highest at the first report,
        // its mean height and its length taken in order of angle about the vertical.
        static std::vector<int> ring;
        if (ring.empty()) {
            const double ymax = p.positions->col(1).maxCoeff();
            for (int v = 0; v < p.positions->rows(); ++v)
                if (mesh.boundary_edge(v) >= 0 && (*p.positions)(v, 1) > ymax - 0.02) ring.push_back(v);
        }
        Eigen::Vector3d c = Eigen::Vector3d::Zero();
        for (int v : ring) c += p.positions->row(v).transpose() / double(ring.size());
        std::vector<std::pair<double, int>> by_angle;
        for (int v : ring) by_angle.push_back({std::atan2((*p.positions)(v, 2) - c.z(), (*p.positions)(v, 0) - c.x()), v});
        std::sort(by_angle.begin(), by_angle.end());
        double top_len = 0;
        for (size_t k = 0; k < by_angle.size(); ++k)
            top_len += (p.positions->row(by_angle[k].second) - p.positions->row(by_angle[(k + 1) % by_angle.size()].second)).norm();
        const double top_y = c.y();
        // The deepest vertex inside the body in `pose` (meaningful once the body got there).
        double deepest = 0;
        int deepest_vertex = -1;
        for (int v = 0; v < p.positions->rows(); ++v) {
            const auto q = final_body.closest(p.positions->row(v).transpose(), 0.05);
            if (q.found && -q.signed_distance_m > deepest) deepest = -q.signed_distance_m, deepest_vertex = v;
        }
        // The vertex that moved most since the last report (a chatter that keeps the cloth
        // from coming to rest shows here).
        static Eigen::MatrixX3d last;
        int fastest = -1;
        double moved = 0;
        if (last.rows() == p.positions->rows())
            moved = (*p.positions - last).rowwise().norm().maxCoeff(&fastest);
        last = *p.positions;
        std::printf("step %d phase %d ke %.3g top loop y %.3f length %.3f deepest %.2f mm (vertex %d) crossings %d",
                    p.step, int(p.phase), p.kinetic_energy_j, top_y, top_len, 1000 * deepest, deepest_vertex, n);
        if (fastest >= 0)
            std::printf(" moved most: vertex %d (%s) %.2f mm at %.3f %.3f %.3f", fastest,
                        pattern.panels[size_t(mesh.panel_of_vertex(fastest))].name.c_str(), 1000 * moved,
                        (*p.positions)(fastest, 0), (*p.positions)(fastest, 1), (*p.positions)(fastest, 2));
        for (size_t k = 0; k < std::min<size_t>(pairs.size(), 6); ++k) {
            const int f = pairs[k].first, g = pairs[k].second;
            const Eigen::RowVector3d cf = (p.positions->row(mesh.cloth.faces(f, 0)) + p.positions->row(mesh.cloth.faces(f, 1)) +
                                           p.positions->row(mesh.cloth.faces(f, 2))) / 3;
            std::printf(" [%s/%s at %.3f %.3f %.3f]", pattern.panels[size_t(mesh.panel_of_vertex(mesh.cloth.faces(f, 0)))].name.c_str(),
                        pattern.panels[size_t(mesh.panel_of_vertex(mesh.cloth.faces(g, 0)))].name.c_str(), cf.x(), cf.y(), cf.z());
        }
        std::printf("\n");
        std::fflush(stdout);
        return true;
    };
    Eigen::MatrixX3d X;
    DressingSummary dressed;
    const DrapeSummary s = dress_and_drape(pattern, mesh, model, shaped, pose, material, DressingOptions{}, options, X, &dressed);
    std::printf("%s\n%s\n", dressed.brief_report().c_str(), s.brief_report().c_str());
    // The garment vertices inside the posed body: where, how deep, and the joint that
    // mainly moves the body face they are under (a vertex between two crossing body parts
    // cannot be outside both).
    const drape::cloth::Obstacle& obstacle = final_body;
    const std::vector<int> joint_of = body::dominant_joints(model);
    for (int v = 0; v < X.rows(); ++v) {
        const auto q = obstacle.closest(X.row(v).transpose(), 1e9);
        if (q.signed_distance_m >= 0) continue;
        const int joint = joint_of[size_t(model.faces(q.face, 0))];
        std::printf("inside: vertex %d (%s) at %.3f %.3f %.3f, %.2f mm deep, under a face of joint %s\n", v,
                    pattern.panels[size_t(mesh.panel_of_vertex(v))].name.c_str(), X(v, 0), X(v, 1), X(v, 2),
                    -1000 * q.signed_distance_m, joint >= 0 ? std::string(body::kJointNames[size_t(joint)]).c_str() : "?");
    }
}

// Diagnostic (hidden): the dressed state of one garment (DRAPE_DIAG_BODY, female_p50;
// DRAPE_DIAG_GARMENT, pants|skirt|tshirt|dress; DRAPE_DIAG_POSE, a_pose; DRAPE_DIAG_EDGE in cm,
// 1.5): the dressing report, then each crossing pair's panels and place.
TEST_CASE("dressing diag: crossings of one dressed state", "[.diag]") {
    const auto env = [](const char* k, const char* d) { const char* v = std::getenv(k); return std::string(v ? v : d); };
    const std::string garment = env("DRAPE_DIAG_GARMENT", "pants"), pose_name = env("DRAPE_DIAG_POSE", "a_pose");
    const double edge_cm = std::stod(env("DRAPE_DIAG_EDGE", "1.5"));
    const ShapedAnsurBody b = diag_body(env("DRAPE_DIAG_BODY", "female_p50"));
    const body::NamedPose np = pose_name == "walking" ? body::NamedPose::walking
                               : pose_name == "arms_down" ? body::NamedPose::arms_down : body::NamedPose::a_pose;
    const body::Pose pose = clear_arms_from_trunk(b.model, b.shaped, body::named_pose(np));
    const Pattern pattern = garment == "skirt"    ? make_circle_skirt(propose_skirt_sizing(b.m))
                            : garment == "tshirt" ? make_tshirt(propose_tshirt_sizing(b.m))
                            : garment == "dress"  ? make_dress(propose_dress_sizing(b.m))
                                                  : make_pants(propose_pants_sizing(b.m));
    MeshOptions mo;
    mo.target_edge_cm = edge_cm;
    GarmentMesh mesh;
    REQUIRE(mesh_pattern(pattern, mo, mesh).usable());
    Eigen::MatrixX3d X;
    const DressingSummary d = dress_garment(pattern, mesh, b.model, b.shaped, pose, DressingOptions{}, X);
    std::printf("%s\n", d.brief_report().c_str());
    std::vector<std::pair<int, int>> pairs;
    drape::cloth::count_self_intersections(X, detail::sewn_faces(mesh), &pairs);
    for (const auto& [f, g] : pairs) {
        const Eigen::RowVector3d c = (X.row(mesh.cloth.faces(f, 0)) + X.row(mesh.cloth.faces(f, 1)) + X.row(mesh.cloth.faces(f, 2))) / 3;
        std::printf("crossing %s / %s at %.3f %.3f %.3f\n", pattern.panels[size_t(mesh.panel_of_vertex(mesh.cloth.faces(f, 0)))].name.c_str(),
                    pattern.panels[size_t(mesh.panel_of_vertex(mesh.cloth.faces(g, 0)))].name.c_str(), c.x(), c.y(), c.z());
    }
}

TEST_CASE("sizing: sleeves and neckline fitted to the arms and neck of the five ANSUR bodies", "[garment][dressing]") {
    double slim_arm = 0, heavy_arm = 0, slim_neck = 0, heavy_neck = 0;
    for (const EvalBody& eb : kEvalBodies) {
        const ShapedAnsurBody b(eb);
        const TShirtSizing proposed = propose_tshirt_sizing(b.m);
        const double arm = upper_arm_girth(b.model, b.shaped, proposed.l1);
        const double neck = neck_girth(b.model, b.shaped);
        INFO(eb.name << ": upper arm " << 100 * arm << " cm, neck " << 100 * neck << " cm, thigh "
                     << 100 * b.m.thigh_girth_m << " cm");
        // Adult girths (ANSUR II, ../shared/data/anthropometry, 5th-95th percentiles: biceps
        // flexed 25.9-36.0 cm women, 30.3-41.8 men; neck base 34.0-40.5 women, 39.5-47.9 men;
        // measured here: arm 24-41, neck 36-49 cm), and an arm thinner than the thigh.
        CHECK(arm > 0.22);
        CHECK(arm < 0.45);
        CHECK(arm < b.m.thigh_girth_m);
        CHECK(neck > 0.30);
        CHECK(neck < 0.55);
        if (std::string(eb.name) == "female_p5") slim_arm = arm, slim_neck = neck;
        if (std::string(eb.name) == "male_p95") heavy_arm = arm, heavy_neck = neck;
        // The fitted top: the sleeve opening and the neckline at least the girth + ease.
        const TShirtSizing sleeves = fit_sleeves(proposed, arm);
        CHECK(sleeves.w1 >= 100 * arm + kSleeveEaseCm - 1e-9);
        CHECK(sleeves.w1 >= proposed.w1);
        const TShirtSizing fitted = fit_neckline(sleeves, neck);
        const Pattern tee = make_tshirt(fitted);
        const double neckline = tee.panels[0].edges[4].length() + tee.panels[1].edges[4].length();
        CHECK((neckline >= 100 * neck + kNecklineEaseCm - 1e-6 || 2 * fitted.r >= fitted.w2 - 10.0 - 1e-9));
        CHECK(fitted.r >= proposed.r);
        // A tank top keeps its (absent) sleeves.
        TShirtSizing tank = proposed;
        tank.l1 = 0;
        CHECK(fit_sleeves(tank, arm).w1 == tank.w1);
    }
    // The heavy man's arm and neck are thicker than the slim woman's; his neckline from the
    // stature ratio alone was too small (the bodice cut into his neck).
    CHECK(heavy_arm > slim_arm + 0.05);
    CHECK(heavy_neck > slim_neck + 0.04);
    {
        const ShapedAnsurBody b(kEvalBodies[4]);
        const TShirtSizing proposed = propose_tshirt_sizing(b.m);
        CHECK(fit_neckline(proposed, neck_girth(b.model, b.shaped)).r > proposed.r + 1.0);
        CHECK_THROWS_AS(fit_sleeves(proposed, -0.3), drape::InvalidInput);
        CHECK_THROWS_AS(fit_neckline(proposed, 0.4, -1.0), drape::InvalidInput);
        CHECK_THROWS_AS(upper_arm_girth(b.model, b.shaped, 0.0), drape::InvalidInput);
    }
}

namespace {

// An eval body shaped by the prior from its gender, stature and mass (as drape eval-dress).
body::ShapedBody shaped_eval_body(const body::BodyModel& model, const EvalBody& eb) {
    body::SemanticRequest request;
    request.gender = eb.gender;
    request[body::Semantic::height_m] = eb.height_m;
    request[body::Semantic::weight_kg] = eb.weight_kg;
    body::ShapedBody shaped;
    REQUIRE(body::shape_body(model, model.prior.complete(request), body::ShapeOptions{}, shaped).usable());
    return shaped;
}

}  // namespace

TEST_CASE("dressing eval: the posed eval bodies' own surface overlaps (armpits, thighs)",
          "[garment][dressing][.eval]") {
    // Linear blend skinning lets touching body parts pass into each other (the arm into
    // the torso at the armpit with the arms down, the thighs of heavy bodies): a garment
    // vertex caught there cannot be outside both. Prints, per eval body and pose, the
    // crossing triangle pairs of the body mesh, those between an arm and the trunk, and
    // what clear_arms_from_trunk makes of them.
    const body::BodyModel& model = body::BodyModel::default_model();
    for (const EvalBody& eb : kEvalBodies) {
        const body::ShapedBody shaped = shaped_eval_body(model, eb);
        for (const auto pose : {body::NamedPose::a_pose, body::NamedPose::arms_down, body::NamedPose::walking}) {
            const Eigen::MatrixX3d P = body::pose_body(model, shaped, body::named_pose(pose)).vertices;
            ArmClearanceSummary arms;
            clear_arms_from_trunk(model, shaped, body::named_pose(pose), {}, &arms);
            std::printf("%s pose %d: %d crossing triangle pairs of the body surface, %s\n", eb.name,
                        static_cast<int>(pose), drape::cloth::count_self_intersections(P, model.faces),
                        arms.brief_report().c_str());
        }
    }
}

TEST_CASE("arms are raised just clear of the trunk, and only where they cross it", "[garment][dressing][pose]") {
    const body::BodyModel& model = body::BodyModel::default_model();
    // The median woman's arms held down pass into her torso (119 crossing triangle pairs):
    // a few degrees clear them, and one step less does not.
    const body::ShapedBody median = shaped_eval_body(model, kEvalBodies[1]);
    const body::Pose down = body::named_pose(body::NamedPose::arms_down);
    ArmClearanceSummary s;
    const body::Pose cleared = clear_arms_from_trunk(model, median, down, {}, &s);
    INFO(s.brief_report());
    CHECK(s.crossings_before > 50);
    CHECK(s.clear());
    CHECK(s.right_degrees > 0);
    CHECK(s.left_degrees > 0);
    CHECK(s.right_degrees <= 10);
    CHECK(s.left_degrees <= 10);
    const Eigen::MatrixX3d X = body::pose_body(model, median, cleared).vertices;
    CHECK(drape::cloth::count_self_intersections(X, model.faces) == 0);
    // Only the shoulders turned, both outward (the hands farther from the body's axis).
    for (int j = 0; j < body::kJointCount; ++j)
        if (j != body::index(body::Joint::right_shoulder) && j != body::index(body::Joint::left_shoulder))
            CHECK(cleared.rotations.row(j) == down.rotations.row(j));
    const Eigen::MatrixX3d J0 = body::pose_body(model, median, down).joints, J1 = body::pose_body(model, median, cleared).joints;
    for (body::Joint w : {body::Joint::right_wrist, body::Joint::left_wrist}) {
        const int j = body::index(w), pelvis = body::index(body::Joint::pelvis);
        CHECK(std::abs(J1(j, 0) - J1(pelvis, 0)) > std::abs(J0(j, 0) - J0(pelvis, 0)));
    }
    // A step less leaves crossings (the smallest multiple of the step is taken).
    ArmClearanceOptions capped;
    capped.max_degrees = std::max(s.right_degrees, s.left_degrees) - 1;
    ArmClearanceSummary c;
    clear_arms_from_trunk(model, median, down, capped, &c);
    CHECK_FALSE(c.clear());
    // The 5th-percentile woman's arms do not touch her torso: the pose is returned as is.
    const body::ShapedBody slim = shaped_eval_body(model, kEvalBodies[0]);
    ArmClearanceSummary t;
    const body::Pose same = clear_arms_from_trunk(model, slim, down, {}, &t);
    CHECK(t.crossings_before == 0);
    CHECK(same.rotations == down.rotations);
    // Bad options.
    ArmClearanceOptions bad;
    bad.step_degrees = 0;
    CHECK_THROWS_AS(clear_arms_from_trunk(model, slim, down, bad), drape::InvalidInput);
    bad = ArmClearanceOptions{};
    bad.max_degrees = 90;
    CHECK_THROWS_AS(clear_arms_from_trunk(model, slim, down, bad), drape::InvalidInput);
}

TEST_CASE("arms are cleared of the trunk with the least change seen from the viewer", "[garment][dressing][pose]") {
    const body::BodyModel& model = body::BodyModel::default_model();
    const body::ShapedBody median = shaped_eval_body(model, kEvalBodies[1]);
    using body::Joint;
    // Arms down, and a forearm held across the belly (the elbow bent 100 degrees, the hand
    // in the trunk): seen from the front (+Z), each is cleared; the joints' image (x, y)
    // moves less than with the plain sideways raise, and no arm crosses the trunk.
    body::Pose across = body::named_pose(body::NamedPose::arms_down);
    const double deg = 3.14159265358979 / 180;
    across.rotations.row(body::index(Joint::right_elbow)) = Eigen::RowVector3d(-100 * deg, 0, 0);
    {
        const int sj = body::index(Joint::right_shoulder);
        const Eigen::Matrix3d G = body::forward_kinematics(median.joints, across).global[size_t(body::kJointParents[size_t(sj)])].linear();
        across.rotations.row(sj) = body::rotated_in_world(across.rotations.row(sj).transpose(), G,
                                                          Eigen::AngleAxisd(70 * deg, Eigen::Vector3d::UnitY()).toRotationMatrix())
                                       .transpose();
    }
    for (const body::Pose& pose : {body::named_pose(body::NamedPose::arms_down), across}) {
        ArmClearanceSummary plain, seen;
        const body::Pose raised = clear_arms_from_trunk(model, median, pose, {}, &plain);
        ArmClearanceOptions o;
        o.view_direction = Eigen::Vector3d(0, 0, 2);
        const body::Pose cleared = clear_arms_from_trunk(model, median, pose, o, &seen);
        INFO(plain.brief_report());
        INFO(seen.brief_report());
        CHECK(seen.crossings_before == plain.crossings_before);
        CHECK(seen.crossings_before > 0);
        CHECK(seen.clear());
        const Eigen::MatrixX3d X = body::pose_body(model, median, cleared).vertices;
        std::vector<std::pair<int, int>> pairs;
        drape::cloth::count_self_intersections(X, model.faces, &pairs);
        const Eigen::MatrixX3d J0 = body::pose_body(model, median, pose).joints;
        auto image_shift = [&](const body::Pose& p) {
            const Eigen::MatrixX3d J = body::pose_body(model, median, p).joints;
            double d = 0;
            for (Joint j : {Joint::right_elbow, Joint::right_wrist, Joint::left_elbow, Joint::left_wrist})
                d += (J.row(body::index(j)).head<2>() - J0.row(body::index(j)).head<2>()).norm();
            return d;
        };
        CHECK(image_shift(cleared) == Approx(seen.image_shift_m).margin(1e-9));
        CHECK(image_shift(cleared) < image_shift(raised));
        std::printf("view clearance: %s | plain: %s | image shift %.3f m -> %.3f m\n", seen.brief_report().c_str(),
                    plain.brief_report().c_str(), image_shift(raised), image_shift(cleared));
        for (int j = 0; j < body::kJointCount; ++j)
            if (j != body::index(Joint::right_shoulder) && j != body::index(Joint::left_shoulder))
                CHECK(cleared.rotations.row(j) == pose.rotations.row(j));
    }
    ArmClearanceOptions bad;
    bad.view_direction = Eigen::Vector3d(0, std::nan(""), 1);
    CHECK_THROWS_AS(clear_arms_from_trunk(model, median, body::named_pose(body::NamedPose::arms_down), bad), drape::InvalidInput);
    bad = ArmClearanceOptions{};
    bad.max_trials = 0;
    CHECK_THROWS_AS(clear_arms_from_trunk(model, median, body::named_pose(body::NamedPose::arms_down), bad), drape::InvalidInput);
}

TEST_CASE("raised arms are lowered to the elevation limit, in the plane of arm and trunk", "[garment][dressing][pose]") {
    const body::BodyModel& model = body::BodyModel::default_model();
    const body::ShapedBody median = shaped_eval_body(model, kEvalBodies[1]);
    const body::Pose a = body::named_pose(body::NamedPose::a_pose);
    // Elevation of an upper arm, measured here from the posed joints (0 = hanging).
    auto elevation = [&](const body::Pose& p, body::Joint shoulder, body::Joint elbow) {
        const Eigen::MatrixX3d J = body::pose_body(model, median, p).joints;
        const Eigen::Vector3d down = (J.row(body::index(body::Joint::pelvis)) - J.row(body::index(body::Joint::neck)))
                                         .transpose()
                                         .normalized();
        const Eigen::Vector3d u = (J.row(body::index(elbow)) - J.row(body::index(shoulder))).transpose().normalized();
        return std::acos(std::clamp(u.dot(down), -1.0, 1.0)) * 180 / 3.14159265358979323846;
    };
    const double a_right = elevation(a, body::Joint::right_shoulder, body::Joint::right_elbow);
    // The right arm raised well above the head, the left one left in the A-pose.
    const body::Pose up = raise_arms(a, 110, 0);
    const double up_right = elevation(up, body::Joint::right_shoulder, body::Joint::right_elbow);
    REQUIRE(up_right > 120);
    ArmLoweringSummary s;
    const body::Pose lowered = lower_raised_arms(model, median, up, 90, &s);
    CHECK(s.right_elevation_degrees == Approx(up_right).margin(1e-6));
    CHECK(s.right_lowered_degrees == Approx(up_right - 90).margin(1e-6));
    CHECK(elevation(lowered, body::Joint::right_shoulder, body::Joint::right_elbow) == Approx(90).margin(0.5));
    // In the plane of the arm and the trunk: the lowered upper arm lies in the plane of the
    // raised one and the neck -> pelvis line (both poses share the trunk).
    const Eigen::MatrixX3d J0 = body::pose_body(model, median, up).joints, J1 = body::pose_body(model, median, lowered).joints;
    const int re = body::index(body::Joint::right_elbow), rs = body::index(body::Joint::right_shoulder);
    const Eigen::Vector3d down =
        (J0.row(body::index(body::Joint::pelvis)) - J0.row(body::index(body::Joint::neck))).transpose().normalized();
    const Eigen::Vector3d u0 = (J0.row(re) - J0.row(rs)).transpose().normalized();
    const Eigen::Vector3d u1 = (J1.row(re) - J1.row(rs)).transpose().normalized();
    CHECK(std::abs(u1.dot(u0.cross(down).normalized())) < 1e-6);
    CHECK((J1.row(rs) - J0.row(rs)).norm() < 1e-9);
    // An arm below the limit and every other joint are unchanged.
    CHECK(s.left_lowered_degrees == 0);
    CHECK(s.left_elevation_degrees < 90);
    for (int j = 0; j < body::kJointCount; ++j)
        if (j != rs) CHECK(lowered.rotations.row(j) == up.rotations.row(j));
    CHECK(lower_raised_arms(model, median, a, 90).rotations == a.rotations);
    CHECK(a_right < 90);
    // Bad limits.
    CHECK_THROWS_AS(lower_raised_arms(model, median, a, -1), drape::InvalidInput);
    CHECK_THROWS_AS(lower_raised_arms(model, median, a, std::nan("")), drape::InvalidInput);
}

// Diagnostic (hidden): how far down the arms the sleeve caps of the proposed t-shirt and
// dress start in the rest A-pose, on the five evaluation bodies and on the bodies of
// DRAPE_DIAG_BODIES (semicolon-separated diag_body specs).
TEST_CASE("dressing diag: sleeve cap offsets", "[.diag]") {
    std::vector<std::string> specs;
    for (const EvalBody& e : kEvalBodies) specs.push_back(e.name);
    if (const char* extra = std::getenv("DRAPE_DIAG_BODIES")) {
        std::string spec;
        for (const char c : std::string(extra) + ";") {
            if (c == ';') specs.push_back(spec), spec.clear();
            else spec += c;
        }
    }
    for (const std::string& spec : specs) {
        const ShapedAnsurBody b = diag_body(spec);
        for (const GarmentType type : {GarmentType::tshirt, GarmentType::dress}) {
            const Pattern pattern = make_pattern(proposed_sizing(type, b.model, b.shaped, b.m));
            const GarmentMesh mesh = mesh_at_4cm(pattern);
            Eigen::MatrixX3d X;
            const char* raise = std::getenv("DRAPE_DIAG_RAISE");
            const double deg = raise ? std::atof(raise) : 0.0;
            const DressingSummary s = dress_garment(pattern, mesh, b.model, b.shaped, raise_arms(body::Pose::rest(), deg, deg),
                                                    DressingOptions{}, X);
            std::printf("%s %s: sleeve caps %.0f cm down, seam gap %.1f cm, %d crossings\n", spec.substr(0, 24).c_str(),
                        garment_type_name(type).c_str(), 100 * s.sleeve_cap_offset_m, 100 * s.max_seam_gap_m,
                        s.self_intersections);
        }
    }
}
