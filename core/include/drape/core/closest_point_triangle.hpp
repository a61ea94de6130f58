// Closest point on a triangle to a point (Ericson, Real-Time Collision Detection, 5.1.5).
#pragma once

#include <Eigen/Core>

namespace drape::core {

/// The feature of a triangle (a, b, c) that holds a closest point. The numbering is stable
/// (0..6) so that callers may index per-feature tables with it.
enum class TriangleFeature {
    vertex_a = 0,
    vertex_b = 1,
    vertex_c = 2,
    edge_ab = 3,
    edge_bc = 4,
    edge_ca = 5,
    interior = 6,
};

/// Closest point on the closed triangle (a, b, c) to `p`, by the Voronoi regions of the
/// triangle's vertices, edges and face. Any frame and unit, as long as all four points share
/// it (metres, world frame in Drape's callers).
///
/// \param p the query point; \param a, b, c the triangle's corners.
/// \param feature if not null, receives the feature the closest point lies on.
/// \param weights if not null, receives the closest point's barycentric weights (wa, wb, wc):
///        each >= 0, summing to 1, point = wa a + wb b + wc c.
/// \return the closest point, in the frame of the inputs.
/// \pre the triangle is not degenerate (zero area); a degenerate triangle returns a point of
///      it whenever a vertex or edge region applies, but the interior formula divides by 0.
/// \throw nothing.
Eigen::Vector3d closest_point_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                          const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                                          TriangleFeature* feature = nullptr,
                                          Eigen::Vector3d* weights = nullptr);

}  // namespace drape::core
