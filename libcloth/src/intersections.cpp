#include <drape/cloth/intersections.hpp>

#include <drape/core/bvh.hpp>
#include <drape/core/errors.hpp>
#include <drape/core/orientation.hpp>
#include <drape/core/parallel_for.hpp>
#include <drape/core/point_in_mesh.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

namespace drape::cloth {

namespace {

using Vec3 = Eigen::Vector3d;
using Box = core::Box3;
using core::orient3d;
using core::sign;

double orient2d(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
    return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

// Closed 2D segment intersection.
bool segments_intersect_2d(const Eigen::Vector2d& p, const Eigen::Vector2d& q,
                           const Eigen::Vector2d& r, const Eigen::Vector2d& s) {
    const int o1 = sign(orient2d(p, q, r)), o2 = sign(orient2d(p, q, s));
    const int o3 = sign(orient2d(r, s, p)), o4 = sign(orient2d(r, s, q));
    if (o1 * o2 < 0 && o3 * o4 < 0) return true;
    auto on_segment = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                         const Eigen::Vector2d& c) {  // c collinear with a–b
        return std::min(a.x(), b.x()) <= c.x() && c.x() <= std::max(a.x(), b.x()) &&
               std::min(a.y(), b.y()) <= c.y() && c.y() <= std::max(a.y(), b.y());
    };
    return (o1 == 0 && on_segment(p, q, r)) || (o2 == 0 && on_segment(p, q, s)) ||
           (o3 == 0 && on_segment(r, s, p)) || (o4 == 0 && on_segment(r, s, q));
}

// Closed point-in-triangle in 2D (either orientation).
bool point_in_triangle_2d(const Eigen::Vector2d& p, const std::array<Eigen::Vector2d, 3>& t) {
    const double o0 = orient2d(t[0], t[1], p), o1 = orient2d(t[1], t[2], p),
                 o2 = orient2d(t[2], t[0], p);
    return (o0 >= 0 && o1 >= 0 && o2 >= 0) || (o0 <= 0 && o1 <= 0 && o2 <= 0);
}

// Projects coplanar geometry onto the coordinate plane most orthogonal to `normal`.
struct Projector {
    int u = 0, v = 1;
    explicit Projector(const Vec3& normal) {
        int drop = 0;
        normal.cwiseAbs().maxCoeff(&drop);
        u = (drop + 1) % 3;
        v = (drop + 2) % 3;
    }
    Eigen::Vector2d operator()(const Vec3& x) const { return {x(u), x(v)}; }
};

// Coplanar triangles a, b (columns are corners): 2D overlap.
bool coplanar_triangles_intersect(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
    const Vec3 n = (a.col(1) - a.col(0)).cross(a.col(2) - a.col(0));
    const Vec3 m = (b.col(1) - b.col(0)).cross(b.col(2) - b.col(0));
    const Projector proj(n.squaredNorm() >= m.squaredNorm() ? n : m);
    std::array<Eigen::Vector2d, 3> ta, tb;
    for (int k = 0; k < 3; ++k) {
        ta[k] = proj(a.col(k));
        tb[k] = proj(b.col(k));
    }
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            if (segments_intersect_2d(ta[i], ta[(i + 1) % 3], tb[j], tb[(j + 1) % 3]))
                return true;
    return point_in_triangle_2d(ta[0], tb) || point_in_triangle_2d(tb[0], ta);
}

// Sign of orient3d with values within rounding noise of 0 snapped to 0: a relative
// tolerance of 1e-10 of the product of the three edge lengths from d. Without it, nearly
// coplanar triangles (a sheet's triangles translated along a ruling) get random signs and
// count as crossing.
int orient3d_sign(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
    const double v = orient3d(a, b, c, d);
    const double scale = (a - d).norm() * (b - d).norm() * (c - d).norm();
    return std::abs(v) <= 1e-10 * scale ? 0 : sign(v);
}

// Closed segment p–q against triangle t (columns), not coplanar with it, when p and q are
// not strictly on one side of t's plane: the line through p, q meets t.
bool segment_crosses_triangle(const Vec3& p, const Vec3& q, const Eigen::Matrix3d& t) {
    const int s1 = orient3d_sign(p, q, t.col(0), t.col(1));
    const int s2 = orient3d_sign(p, q, t.col(1), t.col(2));
    const int s3 = orient3d_sign(p, q, t.col(2), t.col(0));
    return (s1 >= 0 && s2 >= 0 && s3 >= 0) || (s1 <= 0 && s2 <= 0 && s3 <= 0);
}

// Closed segment p–q lying in the plane of triangle t: 2D test.
bool coplanar_segment_meets_triangle(const Vec3& p, const Vec3& q, const Eigen::Matrix3d& t) {
    const Projector proj((t.col(1) - t.col(0)).cross(t.col(2) - t.col(0)));
    const std::array<Eigen::Vector2d, 3> t2 = {proj(t.col(0)), proj(t.col(1)), proj(t.col(2))};
    const Eigen::Vector2d p2 = proj(p), q2 = proj(q);
    for (int i = 0; i < 3; ++i)
        if (segments_intersect_2d(p2, q2, t2[i], t2[(i + 1) % 3])) return true;
    return point_in_triangle_2d(p2, t2);
}

void validate_mesh(const Eigen::MatrixX3d& positions, const Eigen::MatrixX3i& faces,
                   const char* what) {
    require(positions.allFinite(), what, ": positions are not finite");
    const int n = static_cast<int>(positions.rows());
    for (int f = 0; f < faces.rows(); ++f)
        for (int c = 0; c < 3; ++c)
            require(faces(f, c) >= 0 && faces(f, c) < n, what, ": faces(", f, ", ", c,
                    ") = ", faces(f, c), " is out of range [0, ", n, ")");
}

Eigen::Matrix3d corners(const Eigen::MatrixX3d& positions, const Eigen::MatrixX3i& faces,
                        int f) {
    Eigen::Matrix3d t;
    for (int c = 0; c < 3; ++c) t.col(c) = positions.row(faces(f, c)).transpose();
    return t;
}

Box triangle_box(const Eigen::Matrix3d& t) {
    Box b(t.col(0));
    b.extend(t.col(1));
    b.extend(t.col(2));
    return b;
}

core::Bvh triangle_bvh(const Eigen::MatrixX3d& positions, const Eigen::MatrixX3i& faces) {
    return core::Bvh(core::Bvh::triangle_boxes(positions, faces));
}

constexpr int kChunk = 256;

using Pairs = std::vector<std::pair<int, int>>;

int finish(Pairs found, Pairs* pairs) {
    std::sort(found.begin(), found.end());
    const int count = static_cast<int>(found.size());
    if (pairs) *pairs = std::move(found);
    return count;
}

}  // namespace

bool triangles_intersect(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
    int sb[3], sa[3];
    for (int k = 0; k < 3; ++k) {
        sb[k] = orient3d_sign(a.col(0), a.col(1), a.col(2), b.col(k));
        sa[k] = orient3d_sign(b.col(0), b.col(1), b.col(2), a.col(k));
    }
    auto one_side = [](const int* s) {
        return (s[0] > 0 && s[1] > 0 && s[2] > 0) || (s[0] < 0 && s[1] < 0 && s[2] < 0);
    };
    if (one_side(sb) || one_side(sa)) return false;
    if ((sb[0] == 0 && sb[1] == 0 && sb[2] == 0) || (sa[0] == 0 && sa[1] == 0 && sa[2] == 0))
        return coplanar_triangles_intersect(a, b);
    // Not coplanar: the intersection, if any, is a segment whose ends lie on edges of a or
    // b, so some edge of one triangle meets the other. An edge lying in the other's plane
    // is tested in 2D.
    auto edges_meet = [](const Eigen::Matrix3d& t, const int* side, const Eigen::Matrix3d& u) {
        for (int i = 0; i < 3; ++i) {
            const int j = (i + 1) % 3;
            if (side[i] * side[j] > 0) continue;
            if (side[i] == 0 && side[j] == 0) {
                if (coplanar_segment_meets_triangle(t.col(i), t.col(j), u)) return true;
                continue;
            }
            if (segment_crosses_triangle(t.col(i), t.col(j), u)) return true;
        }
        return false;
    };
    return edges_meet(b, sb, a) || edges_meet(a, sa, b);
}

namespace {

// Pairs (face f of A, face g of B) that intersect, skip(f, g) aside; BVH over B.
template <class Skip>
Pairs intersecting_pairs(const Eigen::MatrixX3d& positions_a, const Eigen::MatrixX3i& faces_a,
                         const Eigen::MatrixX3d& positions_b, const Eigen::MatrixX3i& faces_b,
                         Skip&& skip) {
    const core::Bvh bvh = triangle_bvh(positions_b, faces_b);
    const int nf = static_cast<int>(faces_a.rows());
    return core::parallel_collect<std::pair<int, int>>(nf, kChunk, [&](int f, Pairs& out) {
        const Eigen::Matrix3d t = corners(positions_a, faces_a, f);
        const Box box = triangle_box(t);
        bvh.traverse([&](const Box& b) { return b.intersects(box); },
                     [&](int g) {
                         if (!skip(f, g) &&
                             triangles_intersect(t, corners(positions_b, faces_b, g)))
                             out.push_back({f, g});
                     });
    });
}

}  // namespace

int count_self_intersections(const Eigen::MatrixX3d& positions, const Eigen::MatrixX3i& faces,
                             std::vector<std::pair<int, int>>* pairs) {
    validate_mesh(positions, faces, "count_self_intersections");
    auto adjacent_or_seen = [&](int f, int g) {
        if (g <= f) return true;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                if (faces(f, i) == faces(g, j)) return true;
        return false;
    };
    return finish(intersecting_pairs(positions, faces, positions, faces, adjacent_or_seen),
                  pairs);
}

int count_intersections(const Eigen::MatrixX3d& positions_a, const Eigen::MatrixX3i& faces_a,
                        const Eigen::MatrixX3d& positions_b, const Eigen::MatrixX3i& faces_b,
                        std::vector<std::pair<int, int>>* pairs) {
    validate_mesh(positions_a, faces_a, "count_intersections (mesh A)");
    validate_mesh(positions_b, faces_b, "count_intersections (mesh B)");
    return finish(intersecting_pairs(positions_a, faces_a, positions_b, faces_b,
                                     [](int, int) { return false; }),
                  pairs);
}

bool point_inside_closed_mesh(const Eigen::Vector3d& point, const Eigen::MatrixX3d& positions,
                              const Eigen::MatrixX3i& faces) {
    return core::point_inside_closed_mesh(point, positions, faces);
}

int count_points_inside_closed_mesh(const Eigen::MatrixX3d& points,
                                    const Eigen::MatrixX3d& positions,
                                    const Eigen::MatrixX3i& faces, std::vector<int>* inside) {
    validate_mesh(positions, faces, "count_points_inside_closed_mesh");
    require(points.allFinite(), "count_points_inside_closed_mesh: points are not finite");
    std::vector<int> found = core::ClosedMeshInside(positions, faces).inside_indices(points);
    const int count = static_cast<int>(found.size());
    if (inside) *inside = std::move(found);
    return count;
}

}  // namespace drape::cloth
