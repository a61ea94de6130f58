// Private to librecover: the joint material-pose search of paper section 6.2 (Algorithm 2),
// "Joint Pose-Material Parameter Identification". It alternates a particle swarm over the pose
// angles of the joints under a garment (material fixed) with the L-BFGS bending search (pose
// fixed) on the curvature objective, E = ((K − K_target) / K_target)² plus a small prior that
// keeps the pose near the photo fit's (the paper has none: its joints are free, and a pose
// that strays far from the photo's would change the silhouette the sizing was fitted to).
#pragma once

#include <drape/body/pose.hpp>
#include <drape/body/skeleton.hpp>
#include <drape/recover/recover.hpp>

#include <functional>
#include <vector>

namespace drape::recover {

/// Thrown by a progress callback to unwind a cancelled recovery (caught in recover()).
struct Cancelled {};

/// The joints under a garment whose angles the search moves: a skirt's or shorts' hips,
/// pants' hips and knees, a top's chest and shoulders (and elbows under long sleeves), a
/// dress's hips and shoulders.
std::vector<body::Joint> joints_under(GarmentChoice choice);

/// `pose` with, for joint k of `joints`, a rotation by degrees[3k], degrees[3k+1],
/// degrees[3k+2] about the x, y and z axes of the joint's parent frame applied after the
/// pose's own rotation of that joint. \throw drape::InvalidInput if degrees has not 3 values
/// per joint.
body::Pose perturbed_pose(const body::Pose& pose, const std::vector<body::Joint>& joints,
                          const std::vector<double>& degrees);

/// K of the garment's drape at a bending scale on the body posed in a pose, by worker `worker`.
using CurvatureOfPose = std::function<double(double bending_scale, const body::Pose& pose, int worker)>;

struct JointSearchResult {
    body::Pose pose;                 ///< the best pose (the start's when nothing improved)
    double bending_scale = 1;        ///< the best bending scale
    double k_per_m = 0;              ///< K there
    std::vector<double> history;     ///< E at the start, after the pose step, after the material step
    bool improved = false;           ///< E fell below the start's
    long evaluations = 0;
};

/// One garment's search from `pose` and `bending_scale` towards `k_target_per_m`; the pose
/// swarm uses options.pose_particles, pose_generations, pose_max_degrees, pose_prior_weight,
/// threads and seed; the bending search the quality's iteration budget. `keep_going` is asked
/// after every swarm generation and bending iterate: false stops (the best so far is returned).
JointSearchResult joint_pose_material(GarmentChoice choice, const body::Pose& pose, double bending_scale,
                                      double k_target_per_m, const CurvatureOfPose& curvature,
                                      const RecoverOptions& options, const std::function<bool()>& keep_going);

}  // namespace drape::recover
