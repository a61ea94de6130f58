// Point-in-closed-mesh queries (ray parity with a grid of faces), for garment-body
// interpenetration checks.
#pragma once

#include <Eigen/Core>

#include <memory>
#include <vector>

namespace drape::garment {

/// Inside test against a closed, 2-manifold triangle mesh (e.g. a posed body). Counts the
/// crossings of a ray from the point along +Y with the faces, which are binned on an (x, z)
/// grid so a query touches only the faces above it.
class MeshInsideTest {
public:
    /// \param V #V x 3 vertices (metres), \param F #F x 3 faces of a closed surface.
    /// \throw drape::InvalidInput if F is empty or indexes outside V.
    MeshInsideTest(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F);
    ~MeshInsideTest();
    MeshInsideTest(MeshInsideTest&&) noexcept;
    MeshInsideTest& operator=(MeshInsideTest&&) noexcept;

    bool inside(const Eigen::Vector3d& point) const;
    /// Per row of `points` (#P x 3).
    std::vector<bool> inside(const Eigen::MatrixX3d& points) const;

private:
    struct Grid;
    std::unique_ptr<Grid> grid_;
};

}  // namespace drape::garment
