#include <drape/cloth/intersections.hpp>

#include <drape/core/errors.hpp>

#include <Eigen/Geometry>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

namespace drape::cloth {

namespace {

using Vec3 = Eigen::Vector3d;
using Box = Eigen::AlignedBox3d;

// Sign of the volume of (a, b, c, d): positive when d lies below the plane of a, b, c seen
// with a, b, c counter-clockwise.
double orient3d(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
    return (a - d).dot((b - d).cross(c - d));
}

double orient2d(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
    return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

int sign(double x) { return (x > 0) - (x < 0); }

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

// A bounding-volume hierarchy over boxes: median split on the longest centroid axis.
class Bvh {
public:
    explicit Bvh(std::vector<Box> boxes) : boxes_(std::move(boxes)) {
        order_.resize(boxes_.size());
        for (std::size_t i = 0; i < order_.size(); ++i) order_[i] = static_cast<int>(i);
        if (!boxes_.empty()) build(0, static_cast<int>(order_.size()));
    }

    /// Calls visit(id) for every leaf box for which overlaps(box) holds.
    template <class Overlaps, class Visit>
    void traverse(Overlaps&& overlaps, Visit&& visit) const {
        if (nodes_.empty()) return;
        int stack[128];
        int top = 0;
        stack[top++] = 0;
        while (top > 0) {
            const Node& node = nodes_[stack[--top]];
            if (!overlaps(node.box)) continue;
            if (node.left < 0) {
                for (int i = node.begin; i < node.end; ++i)
                    if (overlaps(boxes_[order_[i]])) visit(order_[i]);
            } else {
                stack[top++] = node.left;
                stack[top++] = node.right;
            }
        }
    }

private:
    struct Node {
        Box box;
        int left = -1, right = -1, begin = 0, end = 0;
    };
    static constexpr int kLeafSize = 4;

    int build(int begin, int end) {
        const int index = static_cast<int>(nodes_.size());
        nodes_.emplace_back();
        Box box, centroids;
        for (int i = begin; i < end; ++i) {
            box.extend(boxes_[order_[i]]);
            centroids.extend(boxes_[order_[i]].center());
        }
        nodes_[index].box = box;
        nodes_[index].begin = begin;
        nodes_[index].end = end;
        if (end - begin <= kLeafSize) return index;
        int axis = 0;
        centroids.sizes().maxCoeff(&axis);
        const int mid = begin + (end - begin) / 2;
        std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end,
                         [&](int a, int b) {
                             const double ca = boxes_[a].center()(axis),
                                          cb = boxes_[b].center()(axis);
                             return ca < cb || (ca == cb && a < b);
                         });
        const int left = build(begin, mid);
        const int right = build(mid, end);
        nodes_[index].left = left;
        nodes_[index].right = right;
        return index;
    }

    std::vector<Box> boxes_;
    std::vector<int> order_;
    std::vector<Node> nodes_;
};

Bvh triangle_bvh(const Eigen::MatrixX3d& positions, const Eigen::MatrixX3i& faces) {
    std::vector<Box> boxes(faces.rows());
    for (int f = 0; f < faces.rows(); ++f) boxes[f] = triangle_box(corners(positions, faces, f));
    return Bvh(std::move(boxes));
}

constexpr int kChunk = 256;

// Runs body(i, out) for i in [0, n) on threads; the per-chunk outputs are concatenated in
// index order, so the result does not depend on the schedule.
template <class T, class Body>
std::vector<T> parallel_collect(int n, Body&& body) {
    const int chunks = (n + kChunk - 1) / kChunk;
    std::vector<std::vector<T>> parts(chunks);
    tbb::parallel_for(0, chunks, [&](int c) {
        for (int i = c * kChunk; i < std::min(n, (c + 1) * kChunk); ++i) body(i, parts[c]);
    });
    std::vector<T> all;
    for (auto& part : parts) all.insert(all.end(), part.begin(), part.end());
    return all;
}

using Pairs = std::vector<std::pair<int, int>>;

int finish(Pairs found, Pairs* pairs) {
    std::sort(found.begin(), found.end());
    const int count = static_cast<int>(found.size());
    if (pairs) *pairs = std::move(found);
    return count;
}

// ---- ray parity -------------------------------------------------------------------------

enum class Crossing { none, crosses, ambiguous };

struct Ray {
    Vec3 p, q;  // the segment from the query point to beyond the mesh
    Box box;
};

Ray make_ray(const Vec3& point, const Box& mesh_box, const Vec3& direction) {
    const double length = 2 * (mesh_box.diagonal().norm() + (point - mesh_box.center()).norm()) + 1;
    Ray ray{point, point + length * direction, Box(point)};
    ray.box.extend(ray.q);
    return ray;
}

// Canonical orientation of the ray against edge (i, j): evaluated with the smaller vertex
// index first, so the two faces of an edge see exactly opposite signs.
double edge_side(const Ray& ray, const Eigen::MatrixX3d& x, int i, int j) {
    return i < j ? orient3d(ray.p, ray.q, x.row(i).transpose(), x.row(j).transpose())
                 : -orient3d(ray.p, ray.q, x.row(j).transpose(), x.row(i).transpose());
}

Crossing ray_crossing(const Ray& ray, const Eigen::MatrixX3d& x, const Eigen::MatrixX3i& faces,
                      int f) {
    const int a = faces(f, 0), b = faces(f, 1), c = faces(f, 2);
    const int s1 = sign(edge_side(ray, x, a, b)), s2 = sign(edge_side(ray, x, b, c)),
              s3 = sign(edge_side(ray, x, c, a));
    const bool all_pos = s1 >= 0 && s2 >= 0 && s3 >= 0, all_neg = s1 <= 0 && s2 <= 0 && s3 <= 0;
    if (!all_pos && !all_neg) return Crossing::none;
    const Vec3 xa = x.row(a).transpose(), xb = x.row(b).transpose(), xc = x.row(c).transpose();
    const int o1 = sign(orient3d(xa, xb, xc, ray.p)), o2 = sign(orient3d(xa, xb, xc, ray.q));
    if (o1 * o2 > 0) return Crossing::none;
    // Through an edge or vertex (a zero edge side), along the plane, or starting on it.
    if (s1 == 0 || s2 == 0 || s3 == 0 || o1 == 0 || o2 == 0) return Crossing::ambiguous;
    return Crossing::crosses;
}

// Irrational-looking directions so that a ray rarely meets an edge or vertex exactly.
const Vec3 kDirections[] = {Vec3(0.5773502691896257, 0.5773502691896258, 0.5773502691896257)
                                .cwiseProduct(Vec3(0.8314696123, 1.0, 1.2247448714))
                                .normalized(),
                            Vec3(-0.2672612419, 0.8017837257, -0.5345224838).normalized(),
                            Vec3(0.7071067812, -0.3141592654, 0.6324555320).normalized(),
                            Vec3(-0.9110886, -0.2718281828, 0.3090169944).normalized()};

// Parity with retries; `candidates(ray, visit)` enumerates faces the ray may cross.
template <class Candidates>
bool inside_by_parity(const Vec3& point, const Box& mesh_box, const Eigen::MatrixX3d& x,
                      const Eigen::MatrixX3i& faces, Candidates&& candidates) {
    if (!mesh_box.contains(point)) return false;
    for (const Vec3& direction : kDirections) {
        const Ray ray = make_ray(point, mesh_box, direction);
        int crossings = 0;
        bool ambiguous = false;
        candidates(ray, [&](int f) {
            const Crossing c = ray_crossing(ray, x, faces, f);
            if (c == Crossing::crosses) ++crossings;
            if (c == Crossing::ambiguous) ambiguous = true;
        });
        if (!ambiguous) return crossings % 2 == 1;
    }
    return false;  // on the surface (every direction was ambiguous)
}

// Segment–box overlap by slabs.
bool segment_overlaps_box(const Ray& ray, const Box& box) {
    if (!ray.box.intersects(box)) return false;
    double t0 = 0, t1 = 1;
    const Vec3 d = ray.q - ray.p;
    for (int a = 0; a < 3; ++a) {
        if (d(a) == 0) {
            if (ray.p(a) < box.min()(a) || ray.p(a) > box.max()(a)) return false;
            continue;
        }
        double ta = (box.min()(a) - ray.p(a)) / d(a), tb = (box.max()(a) - ray.p(a)) / d(a);
        if (ta > tb) std::swap(ta, tb);
        t0 = std::max(t0, ta);
        t1 = std::min(t1, tb);
        if (t0 > t1) return false;
    }
    return true;
}

Box mesh_box(const Eigen::MatrixX3d& positions) {
    Box box;
    for (int i = 0; i < positions.rows(); ++i) box.extend(positions.row(i).transpose());
    return box;
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
    const Bvh bvh = triangle_bvh(positions_b, faces_b);
    const int nf = static_cast<int>(faces_a.rows());
    return parallel_collect<std::pair<int, int>>(nf, [&](int f, Pairs& out) {
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
    validate_mesh(positions, faces, "point_inside_closed_mesh");
    require(point.allFinite(), "point_inside_closed_mesh: point is not finite");
    const int nf = static_cast<int>(faces.rows());
    return inside_by_parity(point, mesh_box(positions), positions, faces,
                            [&](const Ray&, auto&& visit) {
                                for (int f = 0; f < nf; ++f) visit(f);
                            });
}

int count_points_inside_closed_mesh(const Eigen::MatrixX3d& points,
                                    const Eigen::MatrixX3d& positions,
                                    const Eigen::MatrixX3i& faces, std::vector<int>* inside) {
    validate_mesh(positions, faces, "count_points_inside_closed_mesh");
    require(points.allFinite(), "count_points_inside_closed_mesh: points are not finite");
    const Bvh bvh = triangle_bvh(positions, faces);
    const Box box = mesh_box(positions);
    std::vector<int> found = parallel_collect<int>(
        static_cast<int>(points.rows()), [&](int i, std::vector<int>& out) {
            const bool in = inside_by_parity(
                points.row(i).transpose(), box, positions, faces,
                [&](const Ray& ray, auto&& visit) {
                    bvh.traverse([&](const Box& b) { return segment_overlaps_box(ray, b); },
                                 visit);
                });
            if (in) out.push_back(i);
        });
    const int count = static_cast<int>(found.size());
    if (inside) *inside = std::move(found);
    return count;
}

}  // namespace drape::cloth
