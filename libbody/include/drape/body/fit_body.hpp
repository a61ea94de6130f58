// Fitting the body model to one photo (paper section 4.2, "Human Body Reconstruction"):
// 14 marked image joints plus the person's silhouette (and optionally the skin mask)
// determine pose theta, semantic shape z and a camera.
#pragma once

#include <drape/body/body_model.hpp>
#include <drape/body/camera.hpp>
#include <drape/body/pose.hpp>

#include <Eigen/Core>

#include <functional>
#include <optional>
#include <string>

namespace drape::body {

struct FitInputs {
    Eigen::Matrix<double, kImageJointCount, 2> joints_px;  ///< in kImageJoints order, pixels
    Mask person;                    ///< person silhouette (garments included)
    Mask skin;                      ///< optional (width 0 = none): visible skin pixels
    std::optional<double> height_m;  ///< known stature
    std::optional<Gender> gender;    ///< known gender
};

enum class Termination { converged, max_iterations, failed, cancelled };

struct FitOptions {
    CameraModel camera = CameraModel::weak_perspective;
    double focal_px = 0;              ///< required (> 0) for the pinhole camera
    int max_iterations = 100;         ///< per Ceres stage
    int threads = 2;
    double joint_weight = 1.0;        ///< weights of the energy terms (documented in docs/)
    double silhouette_weight = 1.0;
    double skin_weight = 1.0;
    double pose_prior_weight = 1.0;
    double shape_prior_weight = 1.0;
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
    Eigen::Matrix<double, kImageJointCount, 2> joints_2d;  ///< fitted joints projected, px
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

/// Fits pose, shape and camera. `fit` receives the result (also when not converged).
/// \throw drape::InvalidInput on bad inputs (NaN joints, joints outside the mask's image,
///        empty or mismatched masks, invalid options), naming the problem.
FitSummary fit_body(const BodyModel& model, const FitInputs& inputs, const FitOptions& options,
                    BodyFit& fit);

}  // namespace drape::body
