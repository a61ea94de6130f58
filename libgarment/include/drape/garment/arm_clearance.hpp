// Arms clear of the trunk: a pose whose arms do not pass into the torso, for draping.
#pragma once

#include <drape/body/body_model.hpp>
#include <drape/body/pose.hpp>
#include <drape/body/shape_body.hpp>

#include <string>

namespace drape::garment {

struct ArmClearanceOptions {
    double step_degrees = 1.0;  ///< abduction added per trial, (0, 10]
    /// At most this much per arm, [0, 60]. 20 was enough for the five evaluation bodies;
    /// the heaviest ANSUR II people need more (a woman of 97 kg: 26-27 deg, a man of 124 kg:
    /// 28 deg, arms down; at 20 deg 57-60 arm/trunk pairs still crossed).
    double max_degrees = 45.0;
    /// From the body towards the viewer (world, any length; zero = not given). When
    /// given, each arm is cleared by the turn at the shoulder that changes its look from
    /// there least: a swing in depth (about the axis across the upper arm and the view,
    /// which moves elbow and wrist along the view and their image only by foreshortening),
    /// an outward turn in the image plane, or both, chosen on a grid of depth_step_degrees x
    /// step_degrees by the image displacement of the elbow and wrist (the turns leaving it
    /// smallest are tried first; at most max_trials). A photo's camera is on +Z
    /// (body::Camera), so a recovery asks for (0, 0, 1): an arm held in front of the trunk
    /// then moves in front of it instead of out to the side, where the mask would show a
    /// sleeve that is not in the photo.
    Eigen::Vector3d view_direction = Eigen::Vector3d::Zero();
    double depth_step_degrees = 5.0;  ///< depth swing grid step, (0, 30]
    double max_depth_degrees = 45.0;  ///< the depth swing at most this much either way, [0, 90]
    int max_trials = 200;             ///< posed bodies checked per arm with a view direction, [1, 10000]
    bool is_valid(std::string* why = nullptr) const;
};

struct ArmClearanceSummary {
    int crossings_before = 0;     ///< crossing triangle pairs arm / trunk of the given pose
    int crossings_after = 0;      ///< the same in the returned pose (0 unless max_degrees ran out)
    double right_degrees = 0;     ///< abduction added to the right shoulder
    double left_degrees = 0;      ///< abduction added to the left shoulder (with a view direction: the outward turn in the image plane)
    double right_depth_degrees = 0;  ///< with a view direction: the right arm's swing in depth (+ towards the viewer)
    double left_depth_degrees = 0;
    double image_shift_m = 0;     ///< with a view direction: the image displacement of both elbows and wrists, summed (m)
    int trials = 0;               ///< posed bodies checked
    bool clear() const { return crossings_after == 0; }
    std::string brief_report() const;
};

/// `pose` with the right arm raised sideways by `right_degrees` and the left by
/// `left_degrees` (about each shoulder's parent-frame z, the body's front axis; negative
/// lowers). \throw drape::InvalidInput on an invalid pose or non-finite angles.
body::Pose raise_arms(const body::Pose& pose, double right_degrees, double left_degrees);

/// Linear blend skinning lets a thick arm held close to the body pass into the torso at the
/// armpit (arms down or swinging, on most bodies but the slimmest): a garment vertex caught
/// between the two surfaces there cannot be outside both. This returns `pose` with each
/// arm raised sideways (about the shoulder's parent-frame z, the body's front axis) by the
/// smallest multiple of step_degrees after which no triangle of that arm (faces skinned
/// mainly to the shoulder, elbow or wrist) crosses a triangle of the trunk (pelvis, spine,
/// chest), at most max_degrees. Arms that are clear are not changed; the pose is otherwise
/// unchanged. With `options.view_direction` the turn is the one that changes each arm's look
/// along that direction least (ArmClearanceOptions). \throw drape::InvalidInput on
/// invalid options, pose or a body that does not fit the model.
body::Pose clear_arms_from_trunk(const body::BodyModel& model, const body::ShapedBody& shaped,
                                 const body::Pose& pose, const ArmClearanceOptions& options = {},
                                 ArmClearanceSummary* summary = nullptr);

/// What lower_raised_arms did.
struct ArmLoweringSummary {
    double right_elevation_degrees = 0;  ///< the right upper arm's elevation before (0 = hanging, 180 = up)
    double left_elevation_degrees = 0;
    double right_lowered_degrees = 0;    ///< how far it was lowered (0 if at most the limit)
    double left_lowered_degrees = 0;
};

/// `pose` with each upper arm raised more than `max_elevation_degrees` above hanging (the
/// angle between shoulder -> elbow and neck -> pelvis, posed) lowered to that elevation, in
/// the plane of the arm and the trunk; the forearm follows. A top dressed on a body whose
/// hands rest on its head is dragged up and out by its armholes: draped with the arms at
/// most at the limit, it hangs as it does on the person (docs/recovery.md). Arms at or below
/// the limit are not changed. \throw drape::InvalidInput on an invalid pose, a limit outside
/// [0, 180] or a body that does not fit the model.
body::Pose lower_raised_arms(const body::BodyModel& model, const body::ShapedBody& shaped, const body::Pose& pose,
                             double max_elevation_degrees, ArmLoweringSummary* summary = nullptr);

}  // namespace drape::garment
