#include <drape/core/point_in_mesh.hpp>

#include <drape/core/errors.hpp>
#include <drape/core/orientation.hpp>
#include <drape/core/parallel_for.hpp>

#include <algorithm>
#include <utility>

namespace drape::core {

namespace {

using Vec3 = Eigen::Vector3d;

void validate_mesh(const Eigen::Ref<const Eigen::MatrixXd>& V,
                   const Eigen::Ref<const Eigen::MatrixXi>& F, const char* what) {
    require(V.cols() == 3 && F.cols() == 3, what, ": V is #V x ", V.cols(), " and F #F x ",
            F.cols(), ", expected 3 columns each");
    require(V.allFinite(), what, ": positions are not finite");
    const int n = static_cast<int>(V.rows());
    for (int f = 0; f < F.rows(); ++f)
        for (int c = 0; c < 3; ++c)
            require(F(f, c) >= 0 && F(f, c) < n, what, ": faces(", f, ", ", c, ") = ", F(f, c),
                    " is out of range [0, ", n, ")");
}

Box3 mesh_box(const Eigen::Ref<const Eigen::MatrixXd>& V) {
    Box3 box;
    for (int i = 0; i < V.rows(); ++i) box.extend(Vec3(V.row(i).transpose()));
    return box;
}

enum class Crossing { none, crosses, ambiguous };

struct Ray {
    Vec3 p, q;  // the segment from the query point to beyond the mesh
    Box3 box;
};

Ray make_ray(const Vec3& point, const Box3& mesh_box, const Vec3& direction) {
    const double length = 2 * (mesh_box.diagonal().norm() + (point - mesh_box.center()).norm()) + 1;
    Ray ray{point, point + length * direction, Box3(point)};
    ray.box.extend(ray.q);
    return ray;
}

// Canonical orientation of the ray against edge (i, j): evaluated with the smaller vertex
// index first, so the two faces of an edge see exactly opposite signs.
double edge_side(const Ray& ray, const Eigen::Ref<const Eigen::MatrixXd>& x, int i, int j) {
    return i < j ? orient3d(ray.p, ray.q, x.row(i).transpose(), x.row(j).transpose())
                 : -orient3d(ray.p, ray.q, x.row(j).transpose(), x.row(i).transpose());
}

Crossing ray_crossing(const Ray& ray, const Eigen::Ref<const Eigen::MatrixXd>& x,
                      const Eigen::Ref<const Eigen::MatrixXi>& faces, int f) {
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

// Parity with retries; `candidates(ray, visit)` enumerates faces the ray may cross. The
// count and the ambiguity flag do not depend on the order the faces come in.
template <class Candidates>
bool inside_by_parity(const Vec3& point, const Box3& mesh_box,
                      const Eigen::Ref<const Eigen::MatrixXd>& x,
                      const Eigen::Ref<const Eigen::MatrixXi>& faces, Candidates&& candidates) {
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
bool segment_overlaps_box(const Ray& ray, const Box3& box) {
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

constexpr int kChunk = 256;

}  // namespace

bool point_inside_closed_mesh(const Eigen::Vector3d& point,
                              const Eigen::Ref<const Eigen::MatrixXd>& V,
                              const Eigen::Ref<const Eigen::MatrixXi>& F) {
    validate_mesh(V, F, "point_inside_closed_mesh");
    require(point.allFinite(), "point_inside_closed_mesh: point is not finite");
    const int nf = static_cast<int>(F.rows());
    return inside_by_parity(point, mesh_box(V), V, F, [&](const Ray&, auto&& visit) {
        for (int f = 0; f < nf; ++f) visit(f);
    });
}

ClosedMeshInside::ClosedMeshInside(const Eigen::Ref<const Eigen::MatrixXd>& V,
                                   const Eigen::Ref<const Eigen::MatrixXi>& F) {
    validate_mesh(V, F, "ClosedMeshInside");
    V_ = V;
    F_ = F;
    box_ = mesh_box(V_);
    bvh_ = Bvh(Bvh::triangle_boxes(V_, F_));
}

bool ClosedMeshInside::inside(const Eigen::Vector3d& point) const {
    require(point.allFinite(), "ClosedMeshInside::inside: point is not finite");
    return inside_by_parity(point, box_, V_, F_, [&](const Ray& ray, auto&& visit) {
        bvh_.traverse([&](const Box3& b) { return segment_overlaps_box(ray, b); }, visit);
    });
}

std::vector<int> ClosedMeshInside::inside_indices(const Eigen::Ref<const Eigen::MatrixXd>& points) const {
    require(points.cols() == 3, "ClosedMeshInside::inside_indices: points are #P x ",
            points.cols(), ", expected 3 columns");
    require(points.allFinite(), "ClosedMeshInside::inside_indices: points are not finite");
    return parallel_collect<int>(static_cast<int>(points.rows()), kChunk,
                                 [&](int i, std::vector<int>& out) {
                                     if (inside(points.row(i).transpose())) out.push_back(i);
                                 });
}

}  // namespace drape::core
