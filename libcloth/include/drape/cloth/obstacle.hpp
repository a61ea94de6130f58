// A collision obstacle for the cloth (the body): a triangle mesh with a bounding-volume
// hierarchy for closest-point and signed-distance queries. It may move between simulation
// steps (same triangles, new vertex positions).
#pragma once

#include <Eigen/Core>

#include <memory>

namespace drape::cloth {

/// Result of a closest-point query.
struct ObstacleQuery {
    bool found = false;              ///< false when nothing lies within the search radius
    int face = -1;                   ///< closest triangle
    Eigen::Vector3d point = Eigen::Vector3d::Zero();   ///< closest point on the surface, world
    /// The closest point's barycentric weights on `face` (its corners in order; >= 0, sum 1).
    Eigen::Vector3d weights = Eigen::Vector3d::Zero();
    /// Outward unit normal at the closest feature (angle-weighted pseudo-normal on edges and
    /// vertices, so that the sign of (x − point)·normal is the inside/outside test of a
    /// closed, consistently oriented mesh).
    Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
    double signed_distance_m = 0;    ///< > 0 outside, < 0 inside (closed meshes)
};

/// A triangle mesh obstacle. Faces are counter-clockwise seen from outside (outward normals).
/// Open meshes are allowed; the sign is then only meaningful near the surface.
class Obstacle {
public:
    /// \param positions #V x 3 world, metres; \param faces #F x 3 rows of positions.
    /// \throw drape::InvalidInput if empty, an index is out of range, a value is not finite
    ///        or a triangle is degenerate (area < 1e-14 m²).
    Obstacle(const Eigen::MatrixX3d& positions, const Eigen::MatrixX3i& faces);
    ~Obstacle();
    Obstacle(const Obstacle&);
    Obstacle& operator=(const Obstacle&);
    Obstacle(Obstacle&&) noexcept;
    Obstacle& operator=(Obstacle&&) noexcept;

    /// Moves the vertices (same faces) and refits the hierarchy.
    /// \throw drape::InvalidInput on a shape mismatch or non-finite value.
    void set_positions(const Eigen::MatrixX3d& positions);

    /// Closest surface point to `x` within `max_distance_m` (pass infinity for no limit).
    ObstacleQuery closest(const Eigen::Vector3d& x, double max_distance_m) const;

    const Eigen::MatrixX3d& positions() const;
    const Eigen::MatrixX3i& faces() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace drape::cloth
