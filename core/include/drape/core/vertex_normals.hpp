// Per-vertex normals of a triangle mesh (libigl's per_vertex_normals, two weightings).
#pragma once

#include <Eigen/Core>

namespace drape::core {

/// How the faces around a vertex are weighted.
enum class NormalWeighting {
    /// Sum of the faces' unnormalised cross products (b − a) × (c − a): each face counts by
    /// twice its area. Smooth shading, skinning offsets.
    area,
    /// Sum of the faces' unit normals times the corner angle at the vertex: the angle-weighted
    /// pseudo-normal, whose sign against (x − vertex) is an inside/outside test of a closed
    /// mesh (Bærentzen and Aanæs 2005). Signed distances to an obstacle.
    angle,
};

/// Options of vertex_normals.
struct VertexNormalOptions {
    NormalWeighting weighting = NormalWeighting::area;  ///< default: area-weighted
    /// The normal given to a vertex whose summed normal is zero (no face, or faces that
    /// cancel). Default zero: such vertices keep a zero row.
    Eigen::Vector3d isolated = Eigen::Vector3d::Zero();
};

/// Unit vertex normals of a triangle mesh, outward for faces counter-clockwise seen from
/// outside. Faces are visited in order and their corners 0, 1, 2 in order, so the result is
/// deterministic to the bit.
///
/// \param V #V x 3 vertex positions (any frame; metres in Drape).
/// \param F #F x 3 vertex indices (rows of V).
/// \param options weighting and the normal of isolated vertices.
/// \return #V x 3, unit rows (or options.isolated where the sum is zero).
/// \pre every index of F is in [0, #V); triangles are not degenerate when weighting is angle
///      (a zero-length edge yields NaN). Not checked: the callers validate their meshes.
/// \throw nothing.
Eigen::MatrixXd vertex_normals(const Eigen::Ref<const Eigen::MatrixXd>& V,
                               const Eigen::Ref<const Eigen::MatrixXi>& F,
                               const VertexNormalOptions& options = {});

}  // namespace drape::core
