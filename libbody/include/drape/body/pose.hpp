// Body pose theta: a root translation plus one parent-relative rotation per joint,
// relative to the model's rest A-pose, and the forward kinematics / skinning that apply it.
#pragma once

#include <drape/body/body_model.hpp>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <array>
#include <string>

namespace drape::body {

struct Pose {
    Eigen::Vector3d translation = Eigen::Vector3d::Zero();  ///< of the root, world, metres
    /// Row j: axis-angle rotation (radians) of joint j in its parent's frame, applied about
    /// the joint's rest position. Rows of end sites (head_top, toes) only turn
    /// their own frame: they move no vertex or joint position.
    Eigen::Matrix<double, kJointCount, 3> rotations =
        Eigen::Matrix<double, kJointCount, 3>::Zero();

    static Pose rest() { return Pose{}; }
    /// Finite values and rotation angles below pi; explains the first failure in `why`.
    bool is_valid(std::string* why = nullptr) const;
};

/// The pose a fraction s of the way from a to b: every joint turned along the shortest arc
/// (quaternion slerp of its parent-relative rotation), the root translated linearly. s = 0
/// gives a, s = 1 gives b. For moving a dressed body from the pose it was dressed in to
/// another one. \throw drape::InvalidInput if s is outside [0, 1] or a pose is invalid.
Pose interpolate_pose(const Pose& a, const Pose& b, double s);

/// Named poses used by tests, the demo and later issues.
enum class NamedPose { a_pose, arms_down, walking, t_pose };
Pose named_pose(NamedPose which);

/// Anatomical joint limits, used as a soft prior by fitting (table in docs/body-model.md).
/// A joint's axis-angle rotation a (parent frame) is expressed in the joint's limit frame,
/// a_local = frames[j]^T a, whose axes are: x = flexion axis (positive = flexion: the child
/// bone swings forward, or backward for the knee), y = the rest bone direction (twist),
/// z = x cross y (ab/adduction). The box [lower, upper] bounds a_local.
struct JointLimits {
    Eigen::Matrix<double, kJointCount, 3> lower;
    Eigen::Matrix<double, kJointCount, 3> upper;
    std::array<Eigen::Matrix3d, kJointCount> frames;  ///< columns: x, y, z axes (parent frame)
    /// Limits for a skeleton with these rest joint positions (the frames depend on them).
    static JointLimits standard(const Eigen::Matrix<double, kJointCount, 3>& rest_joints);
    /// Sum of squared violations (radians^2) of a pose's joint rotations; 0 inside the box.
    double violation(const Pose& pose) const;
};

/// World transforms of every joint (rigid, 4x4 affine) and the posed joint positions.
struct PosedSkeleton {
    std::array<Eigen::Isometry3d, kJointCount> global;     ///< joint frame -> world
    std::array<Eigen::Isometry3d, kJointCount> skinning;   ///< rest world -> posed world
    Eigen::Matrix<double, kJointCount, 3> joints;          ///< posed joint positions
};

/// Forward kinematics. \param rest_joints kJointCount x 3 rest positions (ShapedBody::joints).
PosedSkeleton forward_kinematics(const Eigen::Matrix<double, kJointCount, 3>& rest_joints,
                                 const Pose& pose);

/// A joint's parent-relative axis-angle rotation after turning the joint (and so its
/// subtree) by `world_rotation` about its own origin, in the world frame:
/// R' = G^T world_rotation G R, G the parent's world rotation (PosedSkeleton::global of
/// the parent; identity for the root).
Eigen::Vector3d rotated_in_world(const Eigen::Vector3d& local_axis_angle, const Eigen::Matrix3d& parent_world_rotation,
                                 const Eigen::Matrix3d& world_rotation);

/// Linear blend skinning of rest vertices (#V x 3) with the model's weights.
/// \throw drape::InvalidInput on size mismatch or an invalid pose.
Eigen::MatrixXd skin_vertices(const BodyModel& model, const Eigen::MatrixXd& rest_vertices,
                              const PosedSkeleton& skeleton);

/// Convenience: shaped + posed vertices (#V x 3) and joints.
struct PosedBody {
    Eigen::MatrixXd vertices;
    Eigen::Matrix<double, kJointCount, 3> joints;
};
PosedBody pose_body(const BodyModel& model, const ShapedBody& shaped, const Pose& pose);

}  // namespace drape::body
