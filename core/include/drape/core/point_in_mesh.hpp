// Whether points lie inside a closed triangle mesh (ray parity with retries).
#pragma once

#include <drape/core/bvh.hpp>

#include <Eigen/Core>

#include <vector>

namespace drape::core {

/// Whether `point` lies inside a closed (watertight) triangle mesh, by ray parity. The
/// crossing test evaluates each edge's orientation in a canonical vertex order, so a ray
/// through a shared edge is counted once; a ray through a vertex or along the surface is
/// retried in another direction. Orientation of the faces does not matter. O(#F): for many
/// points build a ClosedMeshInside once.
/// Points on the surface may be reported either way.
///
/// \param point any frame, the mesh's; \param V #V x 3; \param F #F x 3 rows of V.
/// \throw drape::InvalidInput if an index is out of range or a value is not finite.
bool point_inside_closed_mesh(const Eigen::Vector3d& point,
                              const Eigen::Ref<const Eigen::MatrixXd>& V,
                              const Eigen::Ref<const Eigen::MatrixXi>& F);

/// The same test against one mesh for many points, with a Bvh over the triangles built once
/// (rays only test the faces whose boxes they cross). Answers are those of
/// point_inside_closed_mesh, to the bit.
class ClosedMeshInside {
public:
    /// Copies the mesh. \param V #V x 3; \param F #F x 3 rows of V.
    /// \throw drape::InvalidInput if an index is out of range or a value is not finite.
    ClosedMeshInside(const Eigen::Ref<const Eigen::MatrixXd>& V,
                     const Eigen::Ref<const Eigen::MatrixXi>& F);

    /// Whether `point` is inside. \throw drape::InvalidInput if it is not finite.
    bool inside(const Eigen::Vector3d& point) const;

    /// Indices of the rows of `points` (#P x 3) that are inside, increasing; in parallel.
    /// \throw drape::InvalidInput if a point is not finite.
    std::vector<int> inside_indices(const Eigen::Ref<const Eigen::MatrixXd>& points) const;

private:
    Eigen::MatrixXd V_;
    Eigen::MatrixXi F_;
    Box3 box_;
    Bvh bvh_;
};

}  // namespace drape::core
