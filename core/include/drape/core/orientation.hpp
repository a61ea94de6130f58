// Orientation predicates in double precision (not exact: callers snap near-zero values).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace drape::core {

/// Six times the signed volume of the tetrahedron (a, b, c, d): positive when d lies below
/// the plane of a, b, c seen with a, b, c counter-clockwise. Any frame and unit.
inline double orient3d(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                       const Eigen::Vector3d& c, const Eigen::Vector3d& d) {
    return (a - d).dot((b - d).cross(c - d));
}

/// −1, 0 or +1.
inline int sign(double x) { return (x > 0) - (x < 0); }

}  // namespace drape::core
