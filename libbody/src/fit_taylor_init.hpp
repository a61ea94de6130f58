// Private to libbody: the initial pose and weak-perspective camera of a body fit, after
// C. J. Taylor, "Reconstruction of articulated objects from point correspondences in a
// single uncalibrated image", CVIU 80(3), 2000.
#pragma once

#include <drape/body/pose.hpp>
#include <drape/body/skeleton.hpp>

#include <Eigen/Core>

namespace drape::body::detail {

struct TaylorInit {
    Eigen::Matrix<double, kJointCount, 3> rotations = Eigen::Matrix<double, kJointCount, 3>::Zero();
    /// Root translation that puts the posed hip midpoint at the world origin.
    Eigen::Vector3d translation = Eigen::Vector3d::Zero();
    double scale_px_per_m = 0;     ///< weak-perspective s
    Eigen::Vector2d offset_px;     ///< (tx, ty): the image point of the world origin
    /// 3D image-joint positions (world, metres, hip midpoint at the origin) of the chosen
    /// depth-sign combination, in kImageJoints order.
    Eigen::Matrix<double, kImageJointCount, 3> joints_3d;
    double plausibility_cost = 0;  ///< joint-limit violation (rad^2) of the chosen signs
    int sign_combinations = 0;     ///< how many were evaluated
};

/// Taylor's reconstruction: the scale s is the largest ratio of projected to model length
/// over the torso and leg bones (the least foreshortened in a standing photo), each bone
/// gets a relative depth dZ = +-sqrt(l^2 - d^2 / s^2) (0 when the bone looks longer than
/// it is), and the sign of each dZ is chosen so that the joint rotations that reproduce
/// the 3D points violate JointLimits least (a knee or elbow bent the wrong way, a hip
/// twisted backwards). The rotations come from aligning the model's rest bones (and the
/// knee/elbow flexion planes) with the reconstructed ones.
/// \param rest_joints rest joint positions (kJointCount x 3, metres) of the shaped body.
/// \param joints_px image joints (kImageJoints order), pixel frame of camera.hpp.
TaylorInit taylor_initialize(const Eigen::Matrix<double, kJointCount, 3>& rest_joints,
                             const Eigen::Matrix<double, kImageJointCount, 2>& joints_px,
                             const JointLimits& limits);

/// Squared violation of `limits` by the rotations of `joints` (rad^2).
double limit_violation(const Eigen::Matrix<double, kJointCount, 3>& rotations,
                       const JointLimits& limits, std::initializer_list<int> joints);

}  // namespace drape::body::detail
