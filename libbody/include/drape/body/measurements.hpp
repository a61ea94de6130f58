// Tailor's-tape measurements on a body mesh at rest (ANSUR II landmark definitions; see
// docs/body-model.md for each definition and how it matches the survey's).
#pragma once

#include <drape/body/body_model.hpp>

#include <Eigen/Core>

namespace drape::body {

struct BodyMeasurements {
    double height_m = 0;           ///< stature: floor (lowest vertex) to highest vertex
    double weight_kg = 0;          ///< enclosed volume x density
    double chest_girth_m = 0;      ///< convex-hull perimeter of the torso section at bust points
    double waist_girth_m = 0;      ///< ... at the navel
    double hip_girth_m = 0;        ///< ... at the maximum buttock protrusion
    double thigh_girth_m = 0;      ///< right thigh, section normal to the femur below the furrow
    double calf_girth_m = 0;       ///< right calf, section normal to the tibia at maximum
    double shoulder_height_m = 0;  ///< floor to right acromion
    double crotch_height_m = 0;    ///< floor to crotch
    double volume_m3 = 0;

    /// The measured values in Semantic order (muscle is not measurable: NaN).
    Eigen::Matrix<double, kSemanticCount, 1> as_semantic() const;
};

/// Measures a rest-pose body (vertices #V x 3 with the model's topology and landmarks).
/// \throw drape::InvalidInput if sizes mismatch or the model has no landmarks.
BodyMeasurements measure_body(const BodyModel& model, const Eigen::MatrixXd& rest_vertices);

/// Perimeter (metres) of the convex hull of the planar cross-section of the closed mesh
/// (V #V x 3, F #F x 3) with the plane through `point` with normal `normal`, keeping only
/// the section loop nearest to `point` (so that one leg, not both, is measured).
/// Returns 0 if the plane misses the mesh.
double section_girth(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                     const Eigen::Vector3d& point, const Eigen::Vector3d& normal);

/// Enclosed volume (m^3) of a closed, outward-oriented triangle mesh.
double mesh_volume(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F);

}  // namespace drape::body
