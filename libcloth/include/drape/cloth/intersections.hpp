// Intersection checks between triangle meshes: self-intersections of a cloth, crossings
// between two meshes (garment layers, garment and body), and points inside a closed mesh.
// Used to verify simulation results (the anchor scene must end with no self-intersection
// and no cloth vertex inside the body). See docs/self-contact.md.
#pragma once

#include <Eigen/Core>

#include <utility>
#include <vector>

namespace drape::cloth {

/// Whether two triangles intersect (closed sets: touching counts), by orientation tests in
/// double precision (exact up to rounding; coplanar triangles are tested in 2D).
/// \param a 3 x 3, column k is corner k; \param b likewise. Degenerate (zero-area)
/// triangles are tested as the segments or points they are only approximately.
/// Orientations within 1e-10 (relative) of zero count as zero, so nearly coplanar
/// triangles are tested in 2D and near-touching ones count as touching.
bool triangles_intersect(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b);

/// Number of pairs of triangles of one mesh that share no vertex and intersect.
/// Adjacent triangles (sharing a vertex) are never counted. Uses a BVH and threads.
/// \param positions #V x 3 (metres); \param faces #F x 3 rows of positions.
/// \param pairs if not null, receives the pairs (f, g), f < g, sorted.
/// \throw drape::InvalidInput if an index is out of range or a position is not finite.
int count_self_intersections(const Eigen::MatrixX3d& positions, const Eigen::MatrixX3i& faces,
                             std::vector<std::pair<int, int>>* pairs = nullptr);

/// Number of intersecting pairs (triangle of A, triangle of B) between two meshes.
/// \param pairs if not null, receives (face of A, face of B), sorted.
/// \throw drape::InvalidInput as count_self_intersections, naming the mesh.
int count_intersections(const Eigen::MatrixX3d& positions_a, const Eigen::MatrixX3i& faces_a,
                        const Eigen::MatrixX3d& positions_b, const Eigen::MatrixX3i& faces_b,
                        std::vector<std::pair<int, int>>* pairs = nullptr);

/// Whether `point` lies inside a closed (watertight) triangle mesh, by ray parity. The
/// crossing test evaluates each edge's orientation in a canonical vertex order, so a ray
/// through a shared edge is counted once; a ray through a vertex or along the surface is
/// retried in another direction. Orientation of the faces does not matter. O(#F).
/// Points on the surface may be reported either way.
/// \throw drape::InvalidInput if an index is out of range or a value is not finite.
bool point_inside_closed_mesh(const Eigen::Vector3d& point, const Eigen::MatrixX3d& positions,
                              const Eigen::MatrixX3i& faces);

/// Number of `points` (#P x 3) inside a closed mesh (see point_inside_closed_mesh), with a
/// BVH built once: use it to count cloth vertices inside a body.
/// \param inside if not null, receives the indices of the inside points, increasing.
int count_points_inside_closed_mesh(const Eigen::MatrixX3d& points,
                                    const Eigen::MatrixX3d& positions,
                                    const Eigen::MatrixX3i& faces,
                                    std::vector<int>* inside = nullptr);

}  // namespace drape::cloth
