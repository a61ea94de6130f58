// Construction of the built-in body model from the procedural mannequin (private).
#pragma once

#include <drape/body/body_model.hpp>

namespace drape::body::detail {

/// Shape-basis column indices of the built-in model (documented in docs/body-model.md).
enum class Basis : int {
    femininity = 0,      ///< male (-0.5) .. female (+0.5) build, from the mannequin's design
    fat = 1,             ///< soft tissue: belly, arms, neck, thighs (per unit: fat -1 -> +1 / 2)
    muscle = 2,          ///< muscle definition (per unit: muscle -1 -> +1 / 2)
    crotch_height = 3,   ///< metres added to the leg length (floor to crotch)
    torso_length = 4,    ///< metres added between crotch and acromion
    head_neck = 5,       ///< metres added between acromion and vertex
    arm_scale = 6,       ///< relative scale of both arms about the shoulder joints
    shoulder_breadth = 7,///< metres each shoulder and arm moves outwards
    chest_girth = 8,     ///< relative radial scale of the torso around bust level
    waist_girth = 9,     ///< ... around navel level
    hip_girth = 10,      ///< ... around buttock level (torso and tops of the thighs)
    thigh_girth = 11,    ///< relative radial scale of both thighs about the femur axis
    calf_girth = 12,     ///< relative radial scale of both calves about the tibia axis
    head_scale = 13,     ///< relative scale of the head about the head joint
};
inline constexpr int kBasisCount = 14;

/// The columns whose coefficients shape_body() refines to match measurements, in the
/// order of the matched measurements (height, shoulder, crotch, chest, waist, hip, thigh, calf).
inline constexpr int kMatchedCount = 8;

BodyModel build_default_model();

/// Measurements (height, shoulder, crotch, chest, waist, hip, thigh, calf, weight) of the
/// template and their Jacobian w.r.t. the shape coefficients.
struct LinearRule {
    Eigen::Matrix<double, kMatchedCount + 1, 1> m0;
    Eigen::MatrixXd jacobian;  ///< (kMatchedCount + 1) x K
};
LinearRule linear_rule(const BodyModel& model);

/// Linear semantic map of the built-in model: coefficients for v = [female, values...].
Eigen::VectorXd default_linear_coefficients(const LinearRule& rule,
                                            const Eigen::Matrix<double, 1 + kSemanticCount, 1>& v);

}  // namespace drape::body::detail
