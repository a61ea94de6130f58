#include <drape/body/body_model.hpp>
#include <drape/body/measurements.hpp>
#include <drape/body/pose.hpp>
#include <drape/garment/dressing.hpp>
#include <drape/garment/mesh_inside.hpp>
#include <drape/garment/sizing_proposal.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
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
    std::unique_ptr<MeshInsideTest> inside;

    explicit PosedDefaultBody(body::NamedPose which) {
        shaped.coefficients = Eigen::VectorXd::Zero(model.shape_count());
        shaped.vertices = model.template_vertices;
        shaped.joints = model.template_joints;
        m = body::measure_body(model, shaped.vertices);
        pose = body::named_pose(which);
        posed = body::pose_body(model, shaped, pose);
        inside = std::make_unique<MeshInsideTest>(posed.vertices, model.faces);
    }
    /// Meshes `pattern` at 2.5 cm and dresses it on this body.
    DressingSummary dress(const Pattern& pattern, GarmentMesh& mesh, Eigen::MatrixX3d& X) const {
        MeshOptions mo;
        mo.target_edge_cm = 2.5;
        REQUIRE(mesh_pattern(pattern, mo, mesh).usable());
        return dress_garment(pattern, mesh, model, shaped, pose, DressingOptions{}, X);
    }
    int count_inside(const Eigen::MatrixX3d& X) const {
        int n = 0;
        for (bool b : inside->inside(X)) n += b;
        return n;
    }
};

}  // namespace

TEST_CASE("mesh inside test: points in and around a cube", "[garment][dressing]") {
    Eigen::MatrixXd V(8, 3);
    V << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1;
    Eigen::MatrixXi F(12, 3);
    F << 0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4, 2, 3, 7, 2, 7, 6, 1, 2, 6, 1, 6, 5,
        0, 4, 7, 0, 7, 3;
    const MeshInsideTest test(V, F);
    CHECK(test.inside(Eigen::Vector3d(0.5, 0.5, 0.5)));
    CHECK(test.inside(Eigen::Vector3d(0.01, 0.99, 0.5)));
    CHECK_FALSE(test.inside(Eigen::Vector3d(1.5, 0.5, 0.5)));
    CHECK_FALSE(test.inside(Eigen::Vector3d(0.5, 1.01, 0.5)));
    CHECK_FALSE(test.inside(Eigen::Vector3d(0.5, -0.01, 0.5)));
}

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

TEST_CASE("dressing: every template on the default body in A-pose is outside the body",
          "[garment][dressing]") {
    const PosedDefaultBody b(body::NamedPose::a_pose);
    const auto& m = b.m;
    const auto& posed = b.posed;
    const std::vector<std::pair<const char*, Pattern>> garments = {
        {"skirt", make_circle_skirt(propose_skirt_sizing(m))},
        {"pants", make_pants(propose_pants_sizing(m))},
        {"tshirt", make_tshirt(propose_tshirt_sizing(m))},
        {"dress", make_dress(propose_dress_sizing(m))}};
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
        // the two leg tubes; the simulator closes that).
        CHECK(s.max_seam_gap_m < (std::string(name) == "pants" ? 0.06 : 0.01));
        // The garment hangs on the body: within the body's bounding box grown by 40 cm.
        const Eigen::RowVector3d lo = posed.vertices.colwise().minCoeff(), hi = posed.vertices.colwise().maxCoeff();
        CHECK((X.rowwise() - lo).minCoeff() > -0.4);
        CHECK((X.rowwise() - hi).maxCoeff() < 0.4);
    }
}

TEST_CASE("dressing: pants follow a walking pose", "[garment][dressing]") {
    // (A t-shirt in this pose keeps ~20 vertices in the armpit fold: see the docs.)
    const PosedDefaultBody b(body::NamedPose::walking);
    const Pattern pattern = make_pants(propose_pants_sizing(b.m));
    GarmentMesh mesh;
    Eigen::MatrixX3d X;
    const DressingSummary s = b.dress(pattern, mesh, X);
    WARN("pants (walking): " << s.brief_report());
    CHECK(b.count_inside(X) == 0);
    CHECK(s.max_seam_gap_m < 0.03);
    // The right knee is bent forward: the right pants leg's hem moves forward with it.
    double z_hem = -1e9;
    for (int v = 0; v < mesh.cloth.vertex_count(); ++v)
        if (pattern.panels[size_t(mesh.panel_of_vertex(v))].name == "front_right" &&
            mesh.boundary_edge(v) == 0)
            z_hem = std::max(z_hem, X(v, 2));
    CHECK(z_hem > b.posed.joints(body::index(body::Joint::right_hip), 2) + 0.1);
}
