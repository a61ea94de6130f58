// Camera, masks, distance transforms, the templated kinematics and residuals of fit_body
// (against pose.cpp and finite differences), Taylor's initialisation and synthetic fits.
#include "fit_distance_transform.hpp"
#include "fit_kinematics.hpp"
#include "fit_residuals.hpp"
#include "fit_taylor_init.hpp"

#include <drape/body/fit_body.hpp>
#include <drape/body/measurements.hpp>
#include <drape/body/shape_body.hpp>
#include <drape/core/errors.hpp>

#include <catch2/catch.hpp>

#include <ceres/ceres.h>

#include <cmath>
#include <random>

using namespace drape::body;
using Catch::Matchers::Contains;

namespace {

using JointsPx = Eigen::Matrix<double, kImageJointCount, 2>;

Mask make_mask(int w, int h, std::uint8_t value = 0) {
    Mask m;
    m.width = w;
    m.height = h;
    m.pixels.assign(static_cast<size_t>(w) * h, value);
    return m;
}

/// A synthetic photo of the default model: shape, pose and camera are known.
struct SyntheticPhoto {
    SemanticShape shape;
    ShapedBody shaped;
    Pose pose;
    Camera camera;
    FitInputs inputs;
    PosedBody posed;
};

// The image joints of a posed body as marked with `offsets`, projected.
JointsPx marked_joints(const ShapedBody& shaped, const Pose& pose, const Camera& camera,
                       const ImageJointOffsets& offsets) {
    const auto x = image_joint_positions(forward_kinematics(shaped.joints, pose), offsets);
    JointsPx out;
    for (int i = 0; i < kImageJointCount; ++i) out.row(i) = camera.project(x.row(i).transpose()).transpose();
    return out;
}

// Fit options without the posture and lean priors: the optimiser alone, which must
// reproduce an exact synthetic pose (bent in depth on purpose).
FitOptions unregularised() {
    FitOptions o;
    o.posture_weight = 0;
    o.lean_weight = 0;
    return o;
}

SyntheticPhoto synthetic_photo(double height_m) {
    const BodyModel& model = BodyModel::default_model();
    SyntheticPhoto s;
    SemanticRequest request;
    request.gender = Gender::female;
    request[Semantic::height_m] = height_m;
    s.shape = model.prior.complete(request);
    ShapeOptions so;
    so.match_measurements = false;  // the linear map: the subspace fit_body searches
    shape_body(model, s.shape, so, s.shaped);
    s.pose.rotations.row(index(Joint::pelvis)) << 0, 0.3, 0;
    s.pose.rotations.row(index(Joint::right_shoulder)) << 0.3, 0, 0.5;
    s.pose.rotations.row(index(Joint::left_shoulder)) << -0.2, 0, -0.4;
    s.pose.rotations.row(index(Joint::right_elbow)) = (JointLimits::standard(s.shaped.joints)
        .frames[index(Joint::right_elbow)] * Eigen::Vector3d(0.6, 0, 0)).transpose();
    s.pose.rotations.row(index(Joint::right_hip)) << -0.25, 0, 0.05;
    s.pose.rotations.row(index(Joint::right_knee)) << 0.35, 0, 0;
    s.pose.rotations.row(index(Joint::left_hip)) << 0.1, 0, -0.05;
    s.posed = pose_body(model, s.shaped, s.pose);
    s.camera.scale_px_per_m = 300.0;
    const double top = s.posed.vertices.col(1).maxCoeff();
    const double bottom = s.posed.vertices.col(1).minCoeff();
    s.camera.offset_px = Eigen::Vector2d(200.0, 300.0 + 300.0 * 0.5 * (top + bottom));
    // Marked as people mark photos (the fit's default convention).
    s.inputs.joints_px = marked_joints(s.shaped, s.pose, s.camera, ImageJointOffsets::hand_marked());
    s.inputs.person = render_silhouette(s.posed.vertices, model.faces, s.camera, 400, 600);
    s.inputs.skin = s.inputs.person;  // everything is "skin": the body must cover it all
    return s;
}

}  // namespace

TEST_CASE("Camera projects weak-perspective and pinhole points", "[body][fit][camera]") {
    Camera c;
    c.scale_px_per_m = 100;
    c.offset_px = {50, 80};
    const Eigen::Vector2d p = c.project({1.0, 0.5, 7.0});
    CHECK(p.x() == Approx(150));
    CHECK(p.y() == Approx(30));  // +Y up is -v
    c.model = CameraModel::pinhole;
    c.focal_px = 500;
    c.distance_m = 4;
    const Eigen::Vector2d q = c.project({1.0, 0.5, 2.0});  // z_c = 2
    CHECK(q.x() == Approx(500 * 0.5 + 50));
    CHECK(q.y() == Approx(-500 * 0.25 + 80));
    std::string why;
    CHECK(c.is_valid(&why));
    c.focal_px = -1;
    CHECK_FALSE(c.is_valid(&why));
    CHECK_THAT(why, Contains("focal_px"));
    Camera w;
    w.scale_px_per_m = std::nan("");
    CHECK_FALSE(w.is_valid(&why));
    CHECK_THAT(why, Contains("scale_px_per_m"));
}

TEST_CASE("render_silhouette covers exactly the pixel centres inside the triangles",
          "[body][fit][camera]") {
    // A 4 x 3 px rectangle from corner (2, 1) to (6, 4) in the pixel frame.
    Camera c;
    c.scale_px_per_m = 1;
    c.offset_px = {0, 0};
    Eigen::MatrixXd V(4, 3);
    V << 2, -1, 0, 6, -1, 0, 6, -4, 0, 2, -4, 0;
    Eigen::MatrixXi F(2, 3);
    F << 0, 1, 2, 0, 3, 2;  // mixed winding on purpose
    const Mask m = render_silhouette(V, F, c, 10, 8);
    CHECK(m.count() == 12);
    CHECK(m.inside(2, 1));
    CHECK(m.inside(5, 3));
    CHECK_FALSE(m.inside(6, 3));
    CHECK_FALSE(m.inside(1, 1));
    CHECK_FALSE(m.inside(2, 4));
    CHECK_THROWS_AS(render_silhouette(V, F, c, -1, 8), drape::InvalidInput);
}

TEST_CASE("distance transform is the exact Euclidean distance", "[body][fit][distance]") {
    std::mt19937 rng(3);
    Mask m = make_mask(37, 23);
    for (auto& p : m.pixels) p = (rng() % 17 == 0) ? 1 : 0;
    m.pixels[100] = 1;
    const auto field = detail::distance_transform(m, true);
    for (int y = 0; y < m.height; ++y) {
        for (int x = 0; x < m.width; ++x) {
            double best = 1e9;
            for (int v = 0; v < m.height; ++v)
                for (int u = 0; u < m.width; ++u)
                    if (m.inside(u, v)) best = std::min(best, std::hypot(u - x, v - y));
            REQUIRE(field.at(x, y) == Approx(best).margin(1e-4));
        }
    }
    // Bilinear sampling at centres reproduces the grid and interpolates in between.
    CHECK(detail::sample_bilinear(field, 3.5, 4.5) == Approx(field.at(3, 4)));
    CHECK(detail::sample_bilinear(field, 4.0, 4.5) ==
          Approx(0.5 * (field.at(3, 4) + field.at(4, 4))));
    // Outside the image it keeps growing.
    CHECK(detail::sample_bilinear(field, -10.0, 4.5) == Approx(field.at(0, 4) + 10.5));
    // No target pixel: a large constant.
    const auto none = detail::distance_transform(make_mask(5, 4), true);
    CHECK(none.at(2, 2) == Approx(9));
}

TEST_CASE("templated kinematics agree with pose.cpp and the affine shape map",
          "[body][fit][kinematics]") {
    const BodyModel& model = BodyModel::default_model();
    SemanticRequest request;
    request[Semantic::height_m] = 1.72;
    request.gender = Gender::male;
    const SemanticShape shape = model.prior.complete(request);
    std::vector<int> ids;
    for (int v = 0; v < model.vertex_count(); v += 97) ids.push_back(v);
    const detail::LinearRest rest = detail::make_linear_rest(model, Gender::male, ids);
    const ShapedBody shaped = shape_from_coefficients(
        model, detail::semantic_to_coefficients(model, Gender::male, shape.values));
    const Pose pose = named_pose(NamedPose::walking);
    const PosedBody posed = pose_body(model, shaped, pose);

    Eigen::Matrix<double, 3 * kJointCount, 1> joints;
    detail::rest_joints(rest, shape.values.data(), joints.data());
    Eigen::Matrix<double, kJointCount, 3, Eigen::RowMajor> rot = pose.rotations;
    detail::Frames<double> frames;
    detail::forward_kinematics_t(joints.data(), rot.data(), pose.translation.data(), frames);
    for (int j = 0; j < kJointCount; ++j) {
        CHECK((joints.segment<3>(3 * j) - shaped.joints.row(j).transpose()).norm() < 1e-9);
        CHECK((frames.position[j] - posed.joints.row(j).transpose()).norm() < 1e-9);
    }
    // The image joints with their offsets: the templated residual's and image_joint_positions.
    const ImageJointOffsets offsets = ImageJointOffsets::hand_marked();
    const auto marked = image_joint_positions(forward_kinematics(shaped.joints, pose), offsets);
    for (int i = 0; i < kImageJointCount; ++i) {
        CHECK((detail::image_joint_t(frames, offsets.offset_m, i) - marked.row(i).transpose()).norm() < 1e-9);
        CHECK((marked.row(i) - posed.joints.row(index(kImageJoints[static_cast<size_t>(i)]))).norm() ==
              Approx(offsets.offset_m.row(i).norm()).margin(1e-9));  // a rigid offset
    }
    for (int k = 0; k < rest.vertex_count(); ++k) {
        const Eigen::Vector3d x = detail::rest_vertex(rest, k, shape.values.data());
        CHECK((x - shaped.vertices.row(ids[k]).transpose()).norm() < 1e-9);
        const Eigen::Vector3d y = detail::skin_point(rest, k, x, frames);
        CHECK((y - posed.vertices.row(ids[k]).transpose()).norm() < 1e-9);
    }
}

namespace {

/// Compares the autodiff Jacobian of a 4-block residual with central differences.
template <class Functor, int Residuals>
void check_gradients(Functor* functor, int residuals, std::vector<double*> blocks) {
    using Cost = ceres::AutoDiffCostFunction<Functor, Residuals, detail::kRotationParams,
                                             detail::kTranslationParams, detail::kCameraParams,
                                             detail::kShapeParams>;
    std::unique_ptr<ceres::CostFunction> cost;
    if constexpr (Residuals == ceres::DYNAMIC)
        cost = std::make_unique<Cost>(functor, residuals);
    else
        cost = std::make_unique<Cost>(functor);
    const int sizes[4] = {detail::kRotationParams, 3, 3, detail::kShapeParams};
    std::vector<std::vector<double>> jac(4);
    std::vector<double*> jac_ptr(4);
    for (int b = 0; b < 4; ++b) {
        jac[b].resize(static_cast<size_t>(residuals * sizes[b]));
        jac_ptr[b] = jac[b].data();
    }
    std::vector<double> r(static_cast<size_t>(residuals)), rp(r.size()), rm(r.size());
    REQUIRE(cost->Evaluate(blocks.data(), r.data(), jac_ptr.data()));
    double worst = 0, scale = 0;
    for (int b = 0; b < 4; ++b) {
        for (int i = 0; i < sizes[b]; ++i) {
            double& x = blocks[b][i];
            const double saved = x, h = 1e-6 * std::max(1.0, std::abs(x));
            x = saved + h;
            REQUIRE(cost->Evaluate(blocks.data(), rp.data(), nullptr));
            x = saved - h;
            REQUIRE(cost->Evaluate(blocks.data(), rm.data(), nullptr));
            x = saved;
            for (int k = 0; k < residuals; ++k) {
                const double numeric = (rp[k] - rm[k]) / (2 * h);
                const double analytic = jac[b][static_cast<size_t>(k * sizes[b] + i)];
                worst = std::max(worst, std::abs(numeric - analytic));
                scale = std::max(scale, std::abs(analytic));
            }
        }
    }
    INFO("max |autodiff - finite difference| = " << worst << ", max |J| = " << scale);
    CHECK(worst <= 1e-5 * std::max(1.0, scale));
}

}  // namespace

TEST_CASE("fit residuals: autodiff Jacobians match finite differences", "[body][fit][gradient]") {
    const BodyModel& model = BodyModel::default_model();
    SemanticRequest request;
    request.gender = Gender::female;
    const SemanticShape shape = model.prior.complete(request);
    std::vector<int> ids;
    for (int v = 0; v < model.vertex_count(); v += 211) ids.push_back(v);
    const detail::LinearRest rest = detail::make_linear_rest(model, Gender::female, ids);

    Eigen::Matrix<double, detail::kRotationParams, 1> rot;
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> U(-0.4, 0.4);
    for (int i = 0; i < rot.size(); ++i) rot[i] = U(rng);
    Eigen::Vector3d trans(0.05, -0.9, 0.1), cam(300, 200, 300);
    Eigen::Matrix<double, kSemanticCount, 1> z = shape.values;
    std::vector<double*> blocks = {rot.data(), trans.data(), cam.data(), z.data()};

    for (CameraModel cm : {CameraModel::weak_perspective, CameraModel::pinhole}) {
        Camera fixed;
        fixed.model = cm;
        fixed.focal_px = 1500;
        fixed.distance_m = 5;
        fixed.offset_px = {200, 300};
        JointsPx target;
        for (int i = 0; i < kImageJointCount; ++i) target.row(i) << 150 + 7 * i, 100 + 25 * i;
        // With the hand-marked offsets: the image joints move with their bones' frames.
        check_gradients<detail::JointResidual, 2 * kImageJointCount>(
            new detail::JointResidual{&rest, fixed, target, ImageJointOffsets::hand_marked().offset_m, 1.3, 5.0},
            2 * kImageJointCount, blocks);

        // Distance field of a smooth blob, so that bilinear interpolation is differentiable
        // away from cell edges at the sampled points.
        Mask person = make_mask(400, 600);
        for (int y = 150; y < 450; ++y)
            for (int x = 170; x < 230; ++x) person.pixels[static_cast<size_t>(y) * 400 + x] = 1;
        const detail::DistanceField outside = detail::distance_transform(person, true);
        detail::VertexResidual vr;
        vr.rest = &rest;
        vr.fixed = fixed;
        vr.outside = &outside;
        vr.first = 0;
        vr.count = rest.vertex_count();
        vr.inside_weight = 0.7;
        vr.pulls = {{1, {100.3, 200.7}}, {5, {300.2, 410.9}}};
        vr.pull_weight = 0.9;
        vr.unit_px = 5;
        const int n = vr.residual_count();
        check_gradients<detail::VertexResidual, ceres::DYNAMIC>(new detail::VertexResidual(vr), n,
                                                                blocks);
    }
    Eigen::Matrix<double, kJointCount, 3> rj;
    for (int j = 0; j < kJointCount; ++j) rj.row(j) = model.template_joints.row(j);
    std::array<double, detail::kRotationParams> rest_weights{};
    for (size_t i = 0; i < rest_weights.size(); ++i) rest_weights[i] = 0.3 + 0.1 * double(i % 7);
    check_gradients<detail::PosePriorResidual, 2 * detail::kRotationParams>(
        new detail::PosePriorResidual{JointLimits::standard(rj), 10.0, rest_weights},
        2 * detail::kRotationParams, blocks);
    detail::ShapePriorResidual sp;
    sp.sqrt_information = model.prior.female.covariance.llt().matrixL().solve(
        Eigen::Matrix<double, kSemanticCount, kSemanticCount>::Identity());
    sp.mean = model.prior.female.mean;
    sp.height_m = 1.7;
    check_gradients<detail::ShapePriorResidual, kSemanticCount + 1>(
        new detail::ShapePriorResidual(sp), kSemanticCount + 1, blocks);
}

TEST_CASE("Taylor initialisation recovers a synthetic pose's joints", "[body][fit][taylor]") {
    const SyntheticPhoto s = synthetic_photo(1.65);
    const detail::TaylorInit init = detail::taylor_initialize(
        s.shaped.joints, s.inputs.joints_px, JointLimits::standard(s.shaped.joints));
    CHECK(init.sign_combinations == 16 * 16);
    CHECK(init.scale_px_per_m == Approx(300).epsilon(0.08));
    // Its 3D points reproject onto the image joints by construction; its pose puts the
    // model's joints near them (only the bone lengths of the image and model differ).
    Pose pose;
    pose.rotations = init.rotations;
    pose.translation = init.translation;
    const auto sk = forward_kinematics(s.shaped.joints, pose);
    Camera c;
    c.scale_px_per_m = init.scale_px_per_m;
    c.offset_px = init.offset_px;
    double error = 0;
    for (int i = 0; i < kImageJointCount; ++i)
        error += (c.project(sk.joints.row(index(kImageJoints[i])).transpose()) -
                  s.inputs.joints_px.row(i).transpose()).norm();
    error /= kImageJointCount;
    INFO("mean initial joint error " << error << " px");
    CHECK(error < 12.0);
    // The bent right knee bends the anatomical way (positive flexion about its frame x).
    const JointLimits L = JointLimits::standard(s.shaped.joints);
    const Eigen::Vector3d knee =
        L.frames[index(Joint::right_knee)].transpose() * init.rotations.row(index(Joint::right_knee)).transpose();
    CHECK(knee.x() > 0.1);
}

TEST_CASE("fit_body recovers a synthetic body's joints and height", "[body][fit][synthetic]") {
    const BodyModel& model = BodyModel::default_model();
    SyntheticPhoto s = synthetic_photo(1.70);
    s.inputs.height_m = 1.70;
    s.inputs.gender = Gender::female;
    BodyFit fit;
    const FitSummary summary = fit_body(model, s.inputs, unregularised(), fit);
    INFO(summary.brief_report());
    REQUIRE(summary.usable());
    CHECK(summary.mean_joint_error_px < 1.0);
    for (int i = 0; i < kImageJointCount; ++i)
        CHECK((fit.joints_2d.row(i) - s.inputs.joints_px.row(i)).norm() < 2.0);
    const double measured = measure_body(model, s.shaped.vertices).height_m;
    CHECK(fit.shape[Semantic::height_m] == Approx(measured).epsilon(0.02));
    // The recovered body covers its own silhouette (fit_quality, cross-checked by hand).
    const FitQuality q = fit_quality(model, s.inputs, fit, summary);
    const PosedBody posed = pose_body(model, shape_from_coefficients(model, fit.coefficients), fit.pose);
    const Mask m = render_silhouette(posed.vertices, model.faces, fit.camera, 400, 600);
    REQUIRE(q.silhouette.pixels == m.pixels);
    int inter = 0, uni = 0;
    for (size_t i = 0; i < m.pixels.size(); ++i) {
        inter += m.pixels[i] && s.inputs.person.pixels[i];
        uni += m.pixels[i] || s.inputs.person.pixels[i];
    }
    CHECK(double(inter) / uni > 0.9);
    CHECK(q.person_iou == Approx(double(inter) / uni));
    CHECK(q.skin_coverage > 0.9);  // the body covers its own visible skin
    CHECK(q.person_height_px > 300);
    CHECK(q.mean_joint_error_percent == Approx(100 * summary.mean_joint_error_px / q.person_height_px));
}

TEST_CASE("fit_body places hand-marked joints with their offsets", "[body][fit][synthetic]") {
    // The synthetic photo's joints are marked the hand-marked way: fitted as the model's own
    // joints (no offsets) they leave a larger error.
    const BodyModel& model = BodyModel::default_model();
    SyntheticPhoto s = synthetic_photo(1.70);
    s.inputs.height_m = 1.70;
    s.inputs.gender = Gender::female;
    FitOptions plain = unregularised();
    plain.image_joints = ImageJointOffsets::none();
    BodyFit with, without;
    const FitSummary a = fit_body(model, s.inputs, unregularised(), with);
    const FitSummary b = fit_body(model, s.inputs, plain, without);
    INFO(a.brief_report() << "\n" << b.brief_report());
    REQUIRE(a.usable());
    REQUIRE(b.usable());
    CHECK(a.mean_joint_error_px < 1.0);
    CHECK(b.mean_joint_error_px > 2.0 * a.mean_joint_error_px);
    // The calibrated convention: the hips marked on the side of the hips, the shoulders on
    // the shoulders' outline, the hands beyond the wrists (docs/body-fitting.md).
    const auto& o = ImageJointOffsets::hand_marked().offset_m;
    CHECK(o(3, 0) > 0.015);   // left hip, towards the left
    CHECK(o(2, 0) == -o(3, 0));  // mirrored on the right
    CHECK(o(9, 0) > 0.01);    // left shoulder
    CHECK(o(13, 1) > 0.0);    // head top above the model's
}

TEST_CASE("fit_body keeps a standing body upright where its legs look short", "[body][fit][synthetic][posture]") {
    // A standing body seen from the front whose legs are marked 15 % shorter than the
    // model's (the proportions of a photo rarely match the model's): without the posture
    // and lean priors the fit tilts the trunk and legs towards the camera to shorten them in
    // the image; with them it keeps them upright and leaves a small joint error instead.
    const BodyModel& model = BodyModel::default_model();
    SemanticRequest request;
    request.gender = Gender::female;
    ShapedBody shaped;
    ShapeOptions so;
    so.match_measurements = false;
    shape_body(model, model.prior.complete(request), so, shaped);
    Pose pose;
    pose.rotations.row(index(Joint::right_shoulder)) << 0, 0, 0.6;  // arms down a little
    pose.rotations.row(index(Joint::left_shoulder)) << 0, 0, -0.6;
    const PosedBody posed = pose_body(model, shaped, pose);
    Camera camera;
    camera.scale_px_per_m = 300.0;
    camera.offset_px = Eigen::Vector2d(200.0, 300.0 + 300.0 * 0.5 * (posed.vertices.col(1).maxCoeff() + posed.vertices.col(1).minCoeff()));
    FitInputs in;
    in.joints_px = marked_joints(shaped, pose, camera, ImageJointOffsets::hand_marked());
    // Shorten both legs towards their hips in the image.
    for (const auto& [hip, knee, ankle] : {std::array<int, 3>{2, 1, 0}, std::array<int, 3>{3, 4, 5}}) {
        const Eigen::RowVector2d h = in.joints_px.row(hip);
        in.joints_px.row(knee) = h + 0.85 * (in.joints_px.row(knee) - h);
        in.joints_px.row(ankle) = h + 0.85 * (in.joints_px.row(ankle) - h);
    }
    in.person = render_silhouette(posed.vertices, model.faces, camera, 400, 600);
    in.gender = Gender::female;
    BodyFit free_fit, upright_fit;
    const FitSummary free_summary = fit_body(model, in, unregularised(), free_fit);
    const FitSummary upright_summary = fit_body(model, in, FitOptions{}, upright_fit);
    REQUIRE(free_summary.usable());
    REQUIRE(upright_summary.usable());
    const FitQuality free_q = fit_quality(model, in, free_fit, free_summary);
    const FitQuality upright_q = fit_quality(model, in, upright_fit, upright_summary);
    INFO("without the priors: trunk " << free_q.trunk_out_of_plane_deg << " deg, legs " << free_q.leg_out_of_plane_deg
         << " deg, knees " << free_q.knee_bend_deg << " deg, joints " << free_q.mean_joint_error_percent
         << " %; with them: trunk " << upright_q.trunk_out_of_plane_deg << ", legs " << upright_q.leg_out_of_plane_deg
         << ", knees " << upright_q.knee_bend_deg << ", joints " << upright_q.mean_joint_error_percent << " %");
    CHECK(free_q.leg_out_of_plane_deg > 20.0);
    CHECK(upright_q.leg_out_of_plane_deg < 0.6 * free_q.leg_out_of_plane_deg);  // 15.5 against 31.7 deg
    CHECK(upright_q.trunk_out_of_plane_deg < 5.0);
    CHECK(upright_q.knee_bend_deg < 15.0);  // 8.5 against 63 deg
    CHECK(upright_q.mean_joint_error_percent < 2.5);  // docs/body-fitting.md's acceptance
}

TEST_CASE("fit_body with a pinhole camera fits the joints", "[body][fit][synthetic]") {
    const BodyModel& model = BodyModel::default_model();
    const SyntheticPhoto s = synthetic_photo(1.62);
    FitOptions options = unregularised();
    options.camera = CameraModel::pinhole;
    options.focal_px = 3000;  // a long lens: close to the weak-perspective photo
    BodyFit fit;
    const FitSummary summary = fit_body(model, s.inputs, options, fit);
    INFO(summary.brief_report());
    REQUIRE(summary.usable());
    CHECK(fit.camera.model == CameraModel::pinhole);
    CHECK(summary.mean_joint_error_px < 2.0);
}

TEST_CASE("fit_body rejects bad inputs with messages naming them", "[body][fit][errors]") {
    const BodyModel& model = BodyModel::default_model();
    FitInputs good;
    good.person = make_mask(40, 60, 1);
    for (int i = 0; i < kImageJointCount; ++i) good.joints_px.row(i) << 20, 5 + 3 * i;
    BodyFit fit;
    auto fails_with = [&](const FitInputs& in, const FitOptions& o, const std::string& text) {
        try {
            fit_body(model, in, o, fit);
            FAIL("no exception; expected one mentioning '" << text << "'");
        } catch (const drape::InvalidInput& e) {
            CHECK_THAT(std::string(e.what()), Contains(text));
        }
    };
    FitInputs in = good;
    in.joints_px(3, 1) = std::nan("");
    fails_with(in, {}, "left_hip");
    in = good;
    in.joints_px(13, 0) = 41;
    fails_with(in, {}, "outside");
    in = good;
    in.person = Mask{};
    fails_with(in, {}, "person mask is empty");
    in = good;
    in.person = make_mask(40, 60, 0);
    fails_with(in, {}, "no pixel set");
    in = good;
    in.skin = make_mask(41, 60, 1);
    fails_with(in, {}, "skin mask is 41 x 60");
    in = good;
    in.person.pixels.pop_back();
    fails_with(in, {}, "person mask has 2399 pixels");
    in = good;
    in.height_m = -3;
    fails_with(in, {}, "height_m");
    FitOptions o;
    o.camera = CameraModel::pinhole;
    fails_with(good, o, "focal_px");
    o = {};
    o.silhouette_weight = -1;
    fails_with(good, o, "silhouette_weight");
    o = {};
    o.posture_weight = std::nan("");
    fails_with(good, o, "posture_weight");
    o = {};
    o.lean_weight = -2;
    fails_with(good, o, "lean_weight");
    o = {};
    o.image_joints = ImageJointOffsets::hand_marked();
    o.image_joints->offset_m(8, 1) = std::nan("");
    fails_with(good, o, "image_joints: offset_m of image joint 'right_shoulder'");
    o.image_joints = ImageJointOffsets::none();
    o.image_joints->offset_m(13, 1) = 0.3;
    fails_with(good, o, "'head' is 0.3 m long");
    std::string why;
    CHECK(FitOptions{}.is_valid(&why));
}

TEST_CASE("fit_body survives degenerate joints", "[body][fit][errors]") {
    FitInputs in;
    in.person = make_mask(40, 60, 1);
    for (int i = 0; i < kImageJointCount; ++i) in.joints_px.row(i) << 20, 30;  // all at one pixel
    BodyFit fit;
    FitOptions o;
    o.max_iterations = 10;
    const FitSummary summary = fit_body(BodyModel::default_model(), in, o, fit);
    INFO(summary.brief_report());
    CHECK(fit.pose.is_valid());
    CHECK(fit.camera.is_valid());
    CHECK(std::isfinite(summary.mean_joint_error_px));
}

TEST_CASE("fit_body can be cancelled", "[body][fit]") {
    const SyntheticPhoto s = synthetic_photo(1.65);
    FitOptions o;
    int calls = 0;
    o.progress = [&](double) { return ++calls < 3; };
    BodyFit fit;
    const FitSummary summary = fit_body(BodyModel::default_model(), s.inputs, o, fit);
    CHECK(summary.termination == Termination::cancelled);
    CHECK_FALSE(summary.usable());
    CHECK_THAT(summary.brief_report(), Contains("cancelled"));
}
