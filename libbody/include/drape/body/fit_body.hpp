// Fitting the body model to one photo (paper section 4.2, "Human Body Reconstruction"):
// 14 marked image joints plus the person's silhouette (and optionally the skin mask)
// determine pose theta, semantic shape z and a camera.
#pragma once

#include <drape/body/body_model.hpp>
#include <drape/body/camera.hpp>
#include <drape/body/pose.hpp>
#include <drape/core/joint_marks.hpp>

#include <Eigen/Core>

#include <functional>
#include <optional>
#include <string>

namespace drape::body {

struct FitInputs {
    /// In kImageJoints order, pixels in the camera.hpp frame: origin at the image's top-left
    /// corner, the centre of pixel (column i, row j) at (i + 0.5, j + 0.5). (Fashionista's
    /// 1-based MATLAB coordinates convert by subtracting 0.5; 0-based centres by adding 0.5.)
    /// Every joint must lie within [0, width] x [0, height] of the person mask.
    Eigen::Matrix<double, kImageJointCount, 2> joints_px;
    /// What the joints mark: people's marks (hand-marked offsets) or the model's joints.
    core::JointMarks marks = core::JointMarks::hand;
    Mask person;                    ///< person silhouette (garments included)
    Mask skin;                      ///< optional (width 0 = none): visible skin pixels
    std::optional<double> height_m;  ///< known stature
    std::optional<Gender> gender;    ///< known gender
};

enum class Termination { converged, max_iterations, failed, cancelled };

/// The longest offset ImageJointOffsets accepts, metres.
inline constexpr double kMaxImageJointOffsetM = 0.25;

/// Where the marked image joints lie relative to the model's joints. People marking a photo
/// put a "hip" on the side of the hips, not at the hip joint's centre deep inside the
/// pelvis, and a "shoulder" on the shoulder's outline; fitted as if they were the model's
/// joints, such marks make the body look wider and shorter-waisted than the model, and the
/// fit bends the trunk and legs towards the camera to match (docs/body-fitting.md, "Image
/// joints").
struct ImageJointOffsets {
    /// Row i (kImageJoints order): image joint i = model joint kImageJoints[i] + this offset
    /// in metres, given in the rest frame (x towards the body's left, y up, z forwards) of the
    /// bone that ends at that joint, and moved with that bone (the hips' with the pelvis,
    /// the shoulders' with the clavicles, a knee's with its thigh, ...).
    Eigen::Matrix<double, kImageJointCount, 3> offset_m = Eigen::Matrix<double, kImageJointCount, 3>::Zero();

    /// The model's joints themselves (no offset).
    static ImageJointOffsets none() { return {}; }
    /// The convention of hand-marked fashion photos (Fashionista's 14 joints), calibrated
    /// on the tuning part of the development photos by `drape_calibrate_image_joints`.
    static ImageJointOffsets hand_marked();
    /// hand_marked() for JointMarks::hand, none() for JointMarks::model.
    static ImageJointOffsets of(core::JointMarks marks);
    bool is_valid(std::string* why = nullptr) const;
};

/// The posed positions of the 14 image joints (kImageJoints order): each model joint plus
/// its offset, turned with the bone that ends at the joint.
Eigen::Matrix<double, kImageJointCount, 3> image_joint_positions(const PosedSkeleton& skeleton,
                                                                 const ImageJointOffsets& offsets);

struct FitOptions {
    CameraModel camera = CameraModel::weak_perspective;
    double focal_px = 0;              ///< required (> 0) for the pinhole camera
    int max_iterations = 100;         ///< per Ceres stage
    int threads = 2;
    /// Weights of the energy terms (docs/body-fitting.md). Image residuals are measured in
    /// percent of the person's pixel height, and each term is normalised so that weight 1
    /// makes "every joint 1 % off" (joints), "the body on average 1 % outside the person
    /// mask" (silhouette, counted twice) and "uncovered skin on average 1 % from the body"
    /// (skin) cost alike. Pose prior: 10 per radian outside JointLimits::standard() plus
    /// 0.3 per radian away from the rest pose; shape prior: the ANSUR Mahalanobis distance.
    double joint_weight = 1.0;        ///< > 0
    double silhouette_weight = 1.0;   ///< keep the body inside the person mask
    double skin_weight = 2.0;         ///< make the body cover the skin mask
    double pose_prior_weight = 1.0;
    /// Posture prior, per radian² of rotation of the trunk and legs (spine, chest, hips,
    /// knees) away from standing: how far a bone points towards or away from the camera is
    /// what one view cannot see, and without this term the fit bends the trunk and legs in
    /// depth to absorb the difference between the person's proportions and the model's
    /// (docs/body-fitting.md, "Posture"). 0 = off.
    double posture_weight = 100.0;
    /// Lean prior, per radian² of the whole body's tilt forwards, backwards or sideways (the
    /// root's rotation about the camera's x and z axes; the turn about the vertical stays
    /// free): gravity pulls the garments down the body as it stands. 0 = off.
    double lean_weight = 1000.0;
    double shape_prior_weight = 1.0;
    /// Which points of the body the image joints mark (see ImageJointOffsets); empty = as
    /// FitInputs::marks says (ImageJointOffsets::of).
    std::optional<ImageJointOffsets> image_joints;
    bool fit_shape = true;            ///< false: keep the prior mean shape (or height only)
    /// Called between stages/iterations with progress in [0,1]; return false to cancel.
    std::function<bool(double)> progress;

    bool is_valid(std::string* why = nullptr) const;
};

struct BodyFit {
    SemanticShape shape;              ///< the fitted semantic parameters (measured on the mesh)
    Eigen::VectorXd coefficients;     ///< shape coefficients
    Pose pose;
    Camera camera;
    /// The fitted image joints (model joints + their offsets, image_joint_positions) projected, px.
    Eigen::Matrix<double, kImageJointCount, 2> joints_2d;
};

struct FitSummary {
    Termination termination = Termination::failed;
    std::string message;
    int iterations = 0;
    double initial_cost = 0;
    double final_cost = 0;
    double mean_joint_error_px = 0;
    double seconds = 0;

    bool usable() const { return termination == Termination::converged ||
                                 termination == Termination::max_iterations; }
    std::string brief_report() const;
};

/// Fits pose, shape and camera (docs/body-fitting.md): Taylor's (2000) initialisation from
/// the joints, then Ceres least squares in stages (camera + global rotation; + joint
/// rotations; + semantic shape z with the silhouette, skin and shape-prior terms, three
/// rounds that re-render the body to find the uncovered skin). Only the 10 continuous
/// semantic values move; the gender is the given one or the prior's choice.
/// `fit` receives the result (also when not converged; for a failed solve, the last finite
/// parameters). Never aborts: numerical trouble is reported in the summary.
/// \throw drape::InvalidInput on bad inputs (NaN joints, joints outside the mask's image,
///        empty or mismatched masks, invalid options), naming the problem.
FitSummary fit_body(const BodyModel& model, const FitInputs& inputs, const FitOptions& options,
                    BodyFit& fit);

/// How well a fitted body matches the photo it was fitted to (the quality figures of
/// docs/body-fitting.md, measured on the fitted body's silhouette).
struct FitQuality {
    double person_iou = 0;        ///< IoU of the body's silhouette and inputs.person
    /// Fraction of inputs.skin's pixels the body covers; -1 when there is no skin mask (or
    /// it is empty).
    double skin_coverage = -1;
    double person_height_px = 0;  ///< head-top joint to the lower ankle, pixels
    /// FitSummary::mean_joint_error_px as a percentage of person_height_px (>= 1 px).
    double mean_joint_error_percent = 0;
    Mask silhouette;              ///< the fitted body rendered with the fitted camera
    /// Posture in depth (what the photo cannot show directly), degrees: the largest angle
    /// out of the image plane of the trunk (pelvis to neck), the thighs and the shins, and
    /// the larger knee bend (angle between thigh and shin). A person standing to the camera
    /// has all three near 0.
    double trunk_out_of_plane_deg = 0;
    double leg_out_of_plane_deg = 0;
    double knee_bend_deg = 0;
};

/// Renders the fitted body (`fit`: coefficients, pose, camera) into the person mask's image
/// and measures it against `inputs` (as given to fit_body) and `summary` (its result).
/// \throw drape::InvalidInput if the fit's coefficients do not match the model or the
///        skin mask's size differs from the person mask's.
FitQuality fit_quality(const BodyModel& model, const FitInputs& inputs, const BodyFit& fit,
                       const FitSummary& summary);

}  // namespace drape::body
