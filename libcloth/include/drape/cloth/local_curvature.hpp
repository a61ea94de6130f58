// The local curvature κ of the garment-recovery paper (section 5.3, after Wang et al. 2011
// and Bridson et al. 2003), which the material search matches to the wrinkle density.
//
// The paper writes κ = ‖sin(α/2) (h1 + h2)⁻¹ |e| x‖ "for each vertex x of the two triangles
// that share an edge e", α the supplementary angle of the dihedral angle (our θ: 0 when
// flat), h1, h2 the triangle heights over e. Its bending force k sin(α/2)(h1+h2)⁻¹|e| x is
// Bridson's F_i = k |e|²/(|N1|+|N2|) sin(θ/2) u_i, so "x" is read as Bridson's bending mode
// u_i, which equals ∂θ/∂x_i. Hence, per hinge and per hinge vertex i (units 1/m):
//     κ_i = |sin(θ/2)| |e| / (h1 + h2) · ‖∂θ/∂x_i‖.
// The paper does not say how the per-hinge values combine at a vertex; we take the mean
// over the hinges containing the vertex (an assumption, documented in docs/cloth.md).
#pragma once

#include <drape/cloth/cloth_mesh.hpp>

#include <Eigen/Core>

#include <vector>

namespace drape::cloth {

/// κ_i for the four vertices of one hinge (same vertex order as Hinge::v), in 1/m.
/// \param x 3 x 4 world positions (metres), columns x0..x3. Zero when flat.
/// \pre both faces non-degenerate (returns 0 for a degenerate hinge rather than NaN).
Eigen::Vector4d hinge_local_curvature(const Eigen::Matrix<double, 3, 4>& x);

/// Per-vertex κ: the mean of hinge_local_curvature over the hinges containing the vertex;
/// 0 for a vertex in no hinge.
/// \param positions #V x 3 world; \param hinges from build_hinges(mesh). \return #V, 1/m.
/// \throw drape::InvalidInput if positions has the wrong row count or is not finite.
Eigen::VectorXd vertex_local_curvature(const ClothMesh& mesh, const std::vector<Hinge>& hinges,
                                       const Eigen::MatrixX3d& positions);

/// Mean of `kappa` over `vertices` (the paper's average local curvature 𝒦 of a region).
/// \throw drape::InvalidInput if vertices is empty or an index is out of range.
double mean_local_curvature(const Eigen::VectorXd& kappa, const std::vector<int>& vertices);

}  // namespace drape::cloth
