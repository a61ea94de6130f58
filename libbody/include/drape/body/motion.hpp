// Body motion: a sequence of poses at a frame rate. Made by the built-in walk cycle or by
// retargeting a BVH motion capture onto the 22-joint skeleton (docs/animation.md, "Joint
// map"), and resampled to the frame rate an animation needs.
//
// Frame: world, metres, +Y up, the body faces +Z, the person's left is +X (skeleton.hpp).
#pragma once

#include <drape/body/pose.hpp>
#include <drape/body/skeleton.hpp>

#include <Eigen/Core>

#include <array>
#include <filesystem>
#include <string>
#include <vector>

namespace drape::body {

/// Poses sampled at a constant rate: frame k is the pose at time k / fps seconds.
struct Motion {
    double fps = 30;            ///< frames per second, > 0
    std::vector<Pose> frames;   ///< >= 1, each valid

    /// Time of the last frame, (frames - 1) / fps (s).
    double duration_s() const { return frames.empty() ? 0.0 : double(frames.size() - 1) / fps; }
    /// fps > 0 and finite, at least one frame, every frame valid; explains the first failure.
    bool is_valid(std::string* why = nullptr) const;
    /// The pose at time t (s): the two nearest frames interpolated (interpolate_pose), t
    /// clamped to [0, duration_s()]. \throw drape::InvalidInput if the motion is invalid or t
    /// is not finite.
    Pose at(double t_s) const;
};

/// `motion` sampled at `fps` over `seconds` (frame k at k / fps, k = 0 .. round(seconds *
/// fps)); seconds <= 0 means the motion's whole duration. Times past the motion's end hold
/// its last pose (Motion::at clamps).
/// \throw drape::InvalidInput if the motion is invalid or fps is not > 0 and finite (naming it).
Motion resample_motion(const Motion& motion, double fps, double seconds = 0);

/// The built-in walk cycle (docs/animation.md, "Walk cycle"): a designed periodic gait.
struct WalkOptions {
    double period_s = 1.1;           ///< one full cycle (two steps), > 0
    double hip_swing_rad = 0.38;     ///< hip flexion amplitude (±), in [0, 1]
    double knee_swing_rad = 0.65;    ///< largest knee flexion in swing, in [0, 1.5]
    double arm_swing_rad = 0.3;      ///< shoulder swing amplitude (±), in [0, 1]
    /// Arms lowered from the rest A-pose towards the sides, rad. 0.25 keeps the armpit open
    /// on the median body through the swing: arm and trunk surfaces that are 3 cm apart at
    /// rest stay 16 mm apart (0.42, as NamedPose::arms_down, closed them to 6 mm, less than
    /// a sleeve and a side panel with their contact layers need; docs/animation.md).
    double arm_lowering_rad = 0.25;
    double bob_m = 0.012;            ///< vertical bounce of the pelvis (peak to peak / 2), >= 0
    /// The body moves forward (+Z) at the speed of the stance foot relative to the hip: the
    /// hips swing at a nearly steady rate through each half cycle (reversing smoothly at the
    /// ends), so the stance foot stays nearly still on the ground (a sinusoidal swing made it
    /// skate 0.9 m/s). false: walks in place.
    bool forward = true;
    bool is_valid(std::string* why = nullptr) const;
};

/// The walk cycle for a body with rest joints `rest_joints` (ShapedBody::joints, for the
/// leg length that sets the forward speed): `seconds` long (> 0) at `fps`. Periodic: the
/// joint rotations of frames k and k + period_s * fps agree, and the translation advances
/// by the stride each period. It starts from a pose near the rest A-pose (phase 0: legs
/// together) so a garment draped at rest can follow it.
/// \throw drape::InvalidInput if options, fps or seconds are invalid (naming them).
Motion walk_cycle(const Eigen::Matrix<double, kJointCount, 3>& rest_joints, double seconds, double fps,
                  const WalkOptions& options = {});

/// Which joint of a BVH file drives each joint of the skeleton. For joint j, the first name
/// of candidates[j] that the file has is used; an empty list leaves j unmapped (it keeps
/// its parent's orientation). `required` joints must find a name, else the map does not
/// fit the file.
struct BvhJointMap {
    std::array<std::vector<std::string>, kJointCount> candidates;
    std::array<bool, kJointCount> required{};
    /// Names of the CMU motion-capture database (Hips, LowerBack, Spine1, LeftUpLeg, LeftLeg,
    /// LeftArm, ...) and of the Biovision/MotionBuilder convention (Hips, Ab, Chest,
    /// LeftHip, LeftKnee, LeftShoulder, LeftElbow, ...), the table in docs/animation.md.
    static BvhJointMap standard();
};

/// A BVH file's motion retargeted onto the skeleton with rest joints `rest_joints`.
struct BvhRetargetSummary {
    int file_joints = 0;           ///< joints of the BVH hierarchy (end sites excluded)
    int file_frames = 0;           ///< frames in the file
    double file_fps = 0;           ///< its frame rate
    int mapped_joints = 0;         ///< joints of ours driven by a BVH joint
    std::array<std::string, kJointCount> source;  ///< per joint of ours, its BVH joint ("" unmapped)
    double root_scale = 0;         ///< our leg length / the file's (root motion is scaled by it)
};

struct BvhLoadOptions {
    /// Parse and retarget in a forked child process (core::run_isolated): only the motion
    /// comes back, decoded and checked as untrusted bytes. assimp 5.2's BVH importer leaks a
    /// node on every malformed hierarchy (docs/hardening.md): isolated, the leak (and any
    /// crash) stays in the child, so a service reading users' files does not grow. Off: in
    /// this process (the fuzzer, for coverage of the retargeting).
    bool isolate = true;
    double isolation_timeout_s = 60.0;  ///< with `isolate`: the child is killed after this
};

/// Reads a BVH motion through assimp and retargets it (docs/animation.md, "Joint map"):
/// each mapped joint's world orientation follows its BVH joint's, composed with the rotation
/// that takes our rest bone direction onto the file's rest bone direction (our rest is an
/// A-pose, a BVH's usually a T-pose); the file's facing is turned to +Z (its left hip to +X);
/// the root translation relative to frame 0 is scaled by the leg length ratio, so the body
/// starts at the origin. Frames keep the file's rate (resample_motion to change it).
/// \throw drape::IoError if the file cannot be read or does not parse as BVH (assimp's
///        reason); drape::InvalidInput if it has no animation, or the joint map does not fit
///        (naming the joint, the candidate names and the file's joints).
///        IoError also if the isolated child crashed or hung on it.
Motion load_bvh_motion(const std::filesystem::path& path, const Eigen::Matrix<double, kJointCount, 3>& rest_joints,
                       const BvhJointMap& map = BvhJointMap::standard(), BvhRetargetSummary* summary = nullptr,
                       const BvhLoadOptions& options = {});

}  // namespace drape::body
