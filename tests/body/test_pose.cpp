// Forward kinematics, skinning and joint limits.
#include <drape/body/body_model.hpp>
#include <drape/body/pose.hpp>
#include <drape/core/errors.hpp>

#include <catch2/catch.hpp>

#include <cmath>

using namespace drape::body;

namespace {

constexpr double kPi = 3.14159265358979323846;

Eigen::Matrix<double, kJointCount, 3> rest_joints() { return BodyModel::default_model().template_joints; }

}  // namespace

TEST_CASE("the rest pose leaves joints and vertices in place", "[body][pose]") {
    const BodyModel& model = BodyModel::default_model();
    const ShapedBody shaped = shape_from_coefficients(model, Eigen::VectorXd::Zero(model.shape_count()));
    const PosedBody posed = pose_body(model, shaped, Pose::rest());
    CHECK((posed.vertices - model.template_vertices).cwiseAbs().maxCoeff() < 1e-12);
    CHECK((posed.joints - model.template_joints).cwiseAbs().maxCoeff() < 1e-12);
}

TEST_CASE("a root translation moves everything rigidly", "[body][pose]") {
    const BodyModel& model = BodyModel::default_model();
    const ShapedBody shaped = shape_from_coefficients(model, Eigen::VectorXd::Zero(model.shape_count()));
    Pose pose;
    pose.translation = Eigen::Vector3d(0.1, -0.2, 0.3);
    const PosedBody posed = pose_body(model, shaped, pose);
    const Eigen::MatrixXd d = posed.vertices - model.template_vertices;
    CHECK((d.rowwise() - pose.translation.transpose()).cwiseAbs().maxCoeff() < 1e-12);
}

TEST_CASE("rotating a joint swings its children rigidly about it", "[body][pose]") {
    const auto J = rest_joints();
    Pose pose;
    pose.rotations.row(index(Joint::right_elbow)) << 0.3, -0.5, 0.7;
    const PosedSkeleton sk = forward_kinematics(J, pose);
    // Distances from the elbow are preserved; joints above it do not move.
    const double rest_len = (J.row(index(Joint::right_wrist)) - J.row(index(Joint::right_elbow))).norm();
    const double posed_len =
        (sk.joints.row(index(Joint::right_wrist)) - sk.joints.row(index(Joint::right_elbow))).norm();
    CHECK(posed_len == Approx(rest_len).epsilon(1e-12));
    CHECK((sk.joints.row(index(Joint::right_shoulder)) - J.row(index(Joint::right_shoulder))).norm() < 1e-12);
    // The wrist moved by exactly the rotation of its offset.
    const Eigen::Vector3d aa(0.3, -0.5, 0.7);
    const Eigen::Vector3d expected =
        J.row(index(Joint::right_elbow)).transpose() +
        Eigen::AngleAxisd(aa.norm(), aa.normalized()) *
            (J.row(index(Joint::right_wrist)) - J.row(index(Joint::right_elbow))).transpose();
    CHECK((sk.joints.row(index(Joint::right_wrist)).transpose() - expected).norm() < 1e-12);
}

TEST_CASE("rotations compose down the chain", "[body][pose]") {
    const auto J = rest_joints();
    Pose pose;
    pose.rotations.row(index(Joint::pelvis)) << 0, kPi / 2, 0;  // turn the body 90 degrees left
    const PosedSkeleton sk = forward_kinematics(J, pose);
    // The body now faces +X: the right hip (at -X) moves to +Z... and the head stays above.
    const Eigen::Vector3d hip = sk.joints.row(index(Joint::right_hip)) - sk.joints.row(index(Joint::pelvis));
    CHECK(hip.z() > 0.05);
    CHECK(std::abs(hip.x()) < 0.02);
    CHECK(sk.joints(index(Joint::head_top), 1) == Approx(J(index(Joint::head_top), 1)).margin(1e-12));
}

TEST_CASE("named poses are valid and do what they say", "[body][pose]") {
    const auto J = rest_joints();
    for (NamedPose p : {NamedPose::a_pose, NamedPose::arms_down, NamedPose::walking, NamedPose::t_pose}) {
        std::string why;
        CHECK(named_pose(p).is_valid(&why));
    }
    const PosedSkeleton down = forward_kinematics(J, named_pose(NamedPose::arms_down));
    const Eigen::Vector3d arm =
        (down.joints.row(index(Joint::right_wrist)) - down.joints.row(index(Joint::right_shoulder))).transpose();
    CHECK(std::acos(-arm.normalized().y()) < 0.25);  // within ~14 degrees of vertical
    const PosedSkeleton t = forward_kinematics(J, named_pose(NamedPose::t_pose));
    const Eigen::Vector3d t_arm =
        (t.joints.row(index(Joint::right_wrist)) - t.joints.row(index(Joint::right_shoulder))).transpose();
    CHECK(std::abs(t_arm.normalized().y()) < 0.2);  // about horizontal
    const PosedSkeleton walk = forward_kinematics(J, named_pose(NamedPose::walking));
    CHECK(walk.joints(index(Joint::right_ankle), 2) > walk.joints(index(Joint::left_ankle), 2) + 0.2);
}

TEST_CASE("interpolate_pose turns every joint along the short arc", "[body][pose]") {
    const Pose a = named_pose(NamedPose::walking), b = named_pose(NamedPose::t_pose);
    CHECK((interpolate_pose(a, b, 0.0).rotations - a.rotations).cwiseAbs().maxCoeff() < 1e-12);
    CHECK((interpolate_pose(a, b, 1.0).rotations - b.rotations).cwiseAbs().maxCoeff() < 1e-12);
    // From rest, half way is half the angle about the same axis.
    Pose one;
    one.rotations.row(index(Joint::left_elbow)) << 0.3, -1.2, 0.4;
    one.translation << 0.2, 0.0, -0.4;
    const Pose half = interpolate_pose(Pose::rest(), one, 0.5);
    CHECK((half.rotations.row(index(Joint::left_elbow)) - 0.5 * one.rotations.row(index(Joint::left_elbow))).norm() < 1e-12);
    CHECK((half.translation - Eigen::Vector3d(0.1, 0.0, -0.2)).norm() < 1e-15);
    // Two rotations of 170 degrees about opposite axes are 20 degrees apart: the path turns
    // through pi (the short way), not through zero.
    Pose p, q;
    p.rotations.row(index(Joint::spine)) << 0, 170 * M_PI / 180, 0;
    q.rotations.row(index(Joint::spine)) << 0, -170 * M_PI / 180, 0;
    const Eigen::Vector3d mid = interpolate_pose(p, q, 0.5).rotations.row(index(Joint::spine)).transpose();
    CHECK(mid.norm() == Approx(M_PI).epsilon(1e-9));
    CHECK_THROWS_AS(interpolate_pose(p, q, 1.5), drape::InvalidInput);
}

TEST_CASE("invalid poses are rejected with a message", "[body][pose]") {
    Pose pose;
    pose.rotations(index(Joint::left_knee), 0) = std::nan("");
    CHECK_THROWS_WITH(forward_kinematics(rest_joints(), pose), Catch::Contains("left_knee"));
    pose = Pose{};
    pose.rotations(index(Joint::spine), 1) = 4.0;
    CHECK_THROWS_AS(forward_kinematics(rest_joints(), pose), drape::InvalidInput);
}

TEST_CASE("joint limits: rest is inside, hyper-extended knee and elbow are not", "[body][pose]") {
    const JointLimits limits = JointLimits::standard(rest_joints());
    CHECK(limits.violation(Pose::rest()) == 0.0);
    for (NamedPose p : {NamedPose::arms_down, NamedPose::walking})
        CHECK(limits.violation(named_pose(p)) == 0.0);
    // Knee flexion (shank backwards) is positive about the knee frame's x axis.
    Pose bent;
    bent.rotations.row(index(Joint::right_knee)) = (limits.frames[index(Joint::right_knee)].col(0) * 1.2).transpose();
    CHECK(limits.violation(bent) == 0.0);
    const PosedSkeleton sk = forward_kinematics(rest_joints(), bent);
    CHECK(sk.joints(index(Joint::right_ankle), 2) < rest_joints()(index(Joint::right_ankle), 2) - 0.2);
    Pose hyper;
    hyper.rotations.row(index(Joint::right_knee)) = (limits.frames[index(Joint::right_knee)].col(0) * -0.5).transpose();
    CHECK(limits.violation(hyper) == Approx(0.25).epsilon(1e-9));
    // Elbow flexion swings the forearm forwards.
    Pose elbow;
    elbow.rotations.row(index(Joint::left_elbow)) = (limits.frames[index(Joint::left_elbow)].col(0) * 1.5).transpose();
    const PosedSkeleton ske = forward_kinematics(rest_joints(), elbow);
    CHECK(ske.joints(index(Joint::left_wrist), 2) > rest_joints()(index(Joint::left_wrist), 2) + 0.15);
}
