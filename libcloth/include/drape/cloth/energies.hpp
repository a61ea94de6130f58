// The elastic and external energies of the cloth, per element, with analytic gradients and
// Hessians for a Newton solver. Stretching stiffness is an argument (frozen during a Newton
// iteration): the table depends on the strain through eigen-directions, and ArcSim, like
// us, drops ∂k/∂G. Bending stiffness depends on the curvature only, so its dependence is
// integrated into a true energy (BendingCurve): the force equals ArcSim's exactly. Every
// function below is an exact energy whose gradient and Hessian are its true derivatives.
#pragma once

#include <drape/cloth/cloth_mesh.hpp>
#include <drape/cloth/material.hpp>

#include <Eigen/Core>

#include <array>

namespace drape::cloth {

using Vector9d = Eigen::Matrix<double, 9, 1>;
using Matrix9d = Eigen::Matrix<double, 9, 9>;
using Vector12d = Eigen::Matrix<double, 12, 1>;
using Matrix12d = Eigen::Matrix<double, 12, 12>;

/// What Hessian an energy function returns.
enum class HessianMode {
    exact,          ///< the true second derivative (may be indefinite)
    projected_psd,  ///< the true Hessian with negative eigenvalues clamped to 0 (for Newton)
    /// A cheaper PSD approximation where the energy has one (bending: 2c ∇θ∇θᵀ, dropping
    /// the (θ−θ̄)∇²θ term, which is small near the rest angle; stretching: the material
    /// part plus the geometric part with the stress's negative eigenvalues clamped to 0,
    /// when the stiffness is convex, else the projected Hessian); energies without one
    /// return the projected Hessian.
    gauss_newton,
};

// ---- stretching -------------------------------------------------------------------------

/// Rest data of one triangle, from its pattern coordinates.
struct TriangleRest {
    Eigen::Matrix2d dm_inverse = Eigen::Matrix2d::Identity();  ///< inverse of [u1-u0, u2-u0]
    double area_m2 = 0;                                         ///< rest (pattern) area
};

/// Rest data from the three pattern corners (pattern frame, metres), counter-clockwise.
/// \throw drape::InvalidInput if the signed area is <= 1e-12 m² or a coordinate is not finite.
TriangleRest triangle_rest(const Eigen::Vector2d& u0, const Eigen::Vector2d& u1,
                           const Eigen::Vector2d& u2);

/// Green strain G = ½(FᵀF − I), F = [x1−x0, x2−x0] · dm_inverse (3 x 2).
/// \param x 3 x 3, column k is world vertex k (metres). \return 2 x 2, pattern frame.
Eigen::Matrix2d green_strain(const Eigen::Matrix3d& x, const TriangleRest& rest);

/// Stretching energy of one triangle in joules: A · ψ(G) with
/// ψ = ½ k_uu G_uu² + k_uv G_uu G_vv + ½ k_vv G_vv² + k_shear G_uv² (StretchingStiffness).
/// \param x 3 x 3, column k is world vertex k.
/// \param gradient if not null, receives ∂E/∂x (9: vertex 0 xyz, vertex 1 xyz, vertex 2 xyz).
/// \param hessian if not null, receives the 9 x 9 Hessian (see HessianMode).
double stretching_energy(const Eigen::Matrix3d& x, const TriangleRest& rest,
                         const StretchingStiffness& k, Vector9d* gradient = nullptr,
                         Matrix9d* hessian = nullptr,
                         HessianMode mode = HessianMode::projected_psd);

// ---- bending ----------------------------------------------------------------------------

/// Signed dihedral angle (radians, in (−π, π]) of a hinge with edge x0–x1, face 0 =
/// (x0, x1, x2) and face 1 = (x1, x0, x3): 0 when flat, positive when x3 lies on the
/// negative side of face 0's plane (normal (x1−x0)×(x2−x0)), negative on the positive side.
/// Computed as atan2(((n0×n1)·e), |e| n0·n1) with n0 = e×(x2−x0), n1 = (x3−x0)×e, e = x1−x0.
/// \param x 3 x 4, columns x0..x3.
double dihedral_angle(const Eigen::Matrix<double, 3, 4>& x);

/// Gradient of dihedral_angle (closed form: ∂θ/∂x2 = −|e| n0/|n0|², ∂θ/∂x3 = −|e| n1/|n1|²,
/// and x0, x1 by the lever rule along the edge). \return 12 (x0 xyz, x1, x2, x3).
/// \pre both faces non-degenerate.
Vector12d dihedral_angle_gradient(const Eigen::Matrix<double, 3, 4>& x);

/// Rest data of one hinge.
struct HingeRest {
    double rest_angle_rad = 0;     ///< θ̄: 0 for a flat pattern
    double rest_length_m = 0;      ///< l̄: rest length of the hinge edge (pattern)
    double rest_area_sum_m2 = 0;   ///< A0 + A1, rest areas of the two faces
    double direction_rad[2] = {0, 0};  ///< angle of the edge from the pattern u axis, per side
};

/// Rest data of `hinge` from the mesh's pattern; θ̄ = 0 (flat pattern).
HingeRest hinge_rest(const ClothMesh& mesh, const Hinge& hinge);

/// Hinge curvature θ l̄ / (A0 + A1) in 1/m (ArcSim's definition, with the rest length).
double hinge_curvature(double angle_rad, const HingeRest& rest);

/// A hinge's bending rigidity as a function of |curvature| (N·m against 1/m): piecewise
/// linear through `knot_count` knots, the first at 0, constant beyond the last.
struct BendingCurve {
    int knot_count = 1;
    std::array<double, 12> curvature_per_m{};  ///< increasing, [0] = 0
    std::array<double, 12> stiffness_n_m{};    ///< >= 0
    /// Rigidity at |curvature| `kappa` (N·m) and, if slope is not null, its derivative.
    double at(double kappa_abs, double* slope = nullptr) const;
};

/// A curvature-independent rigidity `stiffness_n_m`.
BendingCurve constant_bending_curve(double stiffness_n_m);

/// The hinge's curve from the material: knots at the table's 0, 10, 20, 30, 40 1/m, each
/// value the min over the two sides' directions (ArcSim), plus a knot wherever the two
/// sides' lines cross. Sign-symmetric in the curvature (ArcSim extrapolates for θ < 0).
BendingCurve bending_curve(const Material& material, const HingeRest& rest);

/// Bending energy with curvature-dependent rigidity k(κ), κ = |θ−θ̄| l̄/(A0+A1):
/// E = l̄²/(8(A0+A1)) ∫₀^{|θ−θ̄|} 2 s k(κ(s)) ds, so that the force is exactly ArcSim's
/// −k(κ) l̄²/(4(A0+A1)) (θ−θ̄) ∇θ and the model stays conservative (Newton with a line
/// search on a true energy). With a constant curve this equals the other overload.
/// \param gradient 12; \param hessian 12 x 12; gauss_newton gives max(E'', 0) ∇θ∇θᵀ.
double bending_energy(const Eigen::Matrix<double, 3, 4>& x, const HingeRest& rest,
                      const BendingCurve& curve, Vector12d* gradient = nullptr,
                      Matrix12d* hessian = nullptr,
                      HessianMode mode = HessianMode::projected_psd);

/// Bending energy of one hinge in joules, E = k l̄² / (8 (A0 + A1)) · (θ − θ̄)² with
/// k the bending rigidity in N·m (ArcSim's ke l²/(2(A0+A1)) (θ−θ̄)²/4, with the rest length
/// l̄ as in ArcSim 0.2.1, so that the energy is exactly differentiable).
/// \param x 3 x 4, columns x0..x3 (the Hinge's vertex order).
/// \param gradient 12; \param hessian 12 x 12 (see HessianMode).
double bending_energy(const Eigen::Matrix<double, 3, 4>& x, const HingeRest& rest,
                      double stiffness_n_m, Vector12d* gradient = nullptr,
                      Matrix12d* hessian = nullptr,
                      HessianMode mode = HessianMode::projected_psd);

// ---- mass and gravity -------------------------------------------------------------------

/// Lumped vertex masses in kg: each face gives ρ · A_rest / 3 to each of its corners.
/// \return #V. \throw drape::InvalidInput if the material is invalid (mesh is validated).
Eigen::VectorXd vertex_masses(const ClothMesh& mesh, const Material& material);

/// Gravitational potential −Σ m_i g·x_i in joules.
/// \param positions #V x 3 world; \param masses #V kg; \param gravity m/s² (e.g. (0,0,−9.8)).
/// \param gradient if not null, receives #V x 3, row i = −m_i g (the Hessian is zero).
double gravity_energy(const Eigen::MatrixX3d& positions, const Eigen::VectorXd& masses,
                      const Eigen::Vector3d& gravity, Eigen::MatrixX3d* gradient = nullptr);

}  // namespace drape::cloth
