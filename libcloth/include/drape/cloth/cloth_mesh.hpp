// A cloth triangle mesh: world positions, faces and the 2D sewing-pattern coordinates that
// define each triangle's rest shape and its warp/weft axes.
#pragma once

#include <Eigen/Core>

#include <array>
#include <vector>

namespace drape::cloth {

/// Cloth mesh. Pattern coordinates are indexed per face corner through `pattern_faces`, so
/// that one world vertex may sit on two pattern pieces (a seam); for a single-piece cloth
/// use from_vertex_pattern(), which sets `pattern_faces = faces`.
///
/// Frames: `positions` in the world frame, metres; `pattern` in the pattern frame, metres,
/// u (column 0) is the weft / 0-degree axis of the material tables, v (column 1) the warp /
/// 90-degree axis. Faces are counter-clockwise in the pattern (positive pattern area).
struct ClothMesh {
    Eigen::MatrixX3d positions;      ///< #V x 3, world, metres
    Eigen::MatrixX3i faces;          ///< #F x 3, rows of `positions`
    Eigen::MatrixX2d pattern;        ///< #P x 2, pattern frame, metres
    Eigen::MatrixX3i pattern_faces;  ///< #F x 3, rows of `pattern` (corner k of face f)

    int vertex_count() const { return static_cast<int>(positions.rows()); }
    int face_count() const { return static_cast<int>(faces.rows()); }

    /// Checks the mesh; throws on the first problem found.
    /// \throw drape::InvalidInput naming the element if: a position or pattern coordinate
    ///        is not finite; shapes disagree; an index is out of range; a face repeats a
    ///        vertex; a pattern triangle has area <= 1e-12 m² or is clockwise (degenerate);
    ///        a pattern point is a corner of two different vertices;
    ///        an edge has more than two faces (non-manifold); or two faces traverse a
    ///        shared edge in the same direction (inconsistent orientation).
    void validate() const;

    /// A mesh whose pattern coordinates are given per vertex.
    /// \param positions #V x 3 world positions; \param faces #F x 3;
    /// \param pattern #V x 2 pattern coordinates. Does not validate.
    static ClothMesh from_vertex_pattern(const Eigen::MatrixX3d& positions,
                                         const Eigen::MatrixX3i& faces,
                                         const Eigen::MatrixX2d& pattern);
};

/// An interior edge with its two faces, for bending. Face `faces[0]` is
/// (v[0], v[1], v[2]) in counter-clockwise order and `faces[1]` is (v[1], v[0], v[3]);
/// `corners[s]` gives, for side s, the corner numbers (0..2) of v[0] and v[1] in that face
/// so the pattern coordinates of the edge can be looked up on each side.
struct Hinge {
    std::array<int, 4> v{};
    std::array<int, 2> faces{};
    std::array<std::array<int, 2>, 2> corners{};
};

/// All interior edges of a validated mesh, in a deterministic order.
/// \throw drape::InvalidInput as ClothMesh::validate (it is called first).
std::vector<Hinge> build_hinges(const ClothMesh& mesh);

/// A regular grid of (n+1)² vertices over the pattern square [0, size]², with alternating
/// diagonals, placed in the world by (u, v) -> origin + u * axis_u + v * axis_v. For tests
/// and the anchor scene. \pre n >= 1, size > 0. \throw drape::InvalidInput otherwise.
ClothMesh make_square_grid(int n, double size_m, const Eigen::Vector3d& origin,
                           const Eigen::Vector3d& axis_u, const Eigen::Vector3d& axis_v);

}  // namespace drape::cloth
