#include <drape/cloth/obstacle.hpp>

#include <drape/core/errors.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <utility>
#include <vector>

namespace drape::cloth {

namespace {

struct Box {
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
    Eigen::Vector3d hi = Eigen::Vector3d::Constant(-std::numeric_limits<double>::infinity());
    void extend(const Eigen::Vector3d& p) {
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
    }
    void extend(const Box& b) {
        lo = lo.cwiseMin(b.lo);
        hi = hi.cwiseMax(b.hi);
    }
    double squared_distance(const Eigen::Vector3d& p) const {
        const Eigen::Vector3d d = (lo - p).cwiseMax(p - hi).cwiseMax(0.0);
        return d.squaredNorm();
    }
};

// Leaves hold one triangle; internal nodes two children (first child at index + 1).
struct Node {
    Box box;
    int second = -1;  ///< index of the second child, -1 for a leaf
    int face = -1;    ///< leaf: the triangle
};

// Closest point on triangle (a, b, c) to p (Ericson, Real-Time Collision Detection §5.1.5).
// `feature` receives 0..2 = vertex a/b/c, 3..5 = edge ab/bc/ca, 6 = interior.
Eigen::Vector3d closest_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                    const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                                    int& feature) {
    const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
    const double d1 = ab.dot(ap), d2 = ac.dot(ap);
    if (d1 <= 0 && d2 <= 0) { feature = 0; return a; }
    const Eigen::Vector3d bp = p - b;
    const double d3 = ab.dot(bp), d4 = ac.dot(bp);
    if (d3 >= 0 && d4 <= d3) { feature = 1; return b; }
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) {
        feature = 3;
        return a + (d1 / (d1 - d3)) * ab;
    }
    const Eigen::Vector3d cp = p - c;
    const double d5 = ab.dot(cp), d6 = ac.dot(cp);
    if (d6 >= 0 && d5 <= d6) { feature = 2; return c; }
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) {
        feature = 5;
        return a + (d2 / (d2 - d6)) * ac;
    }
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
        feature = 4;
        return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
    }
    feature = 6;
    const double denom = 1 / (va + vb + vc);
    return a + ab * (vb * denom) + ac * (vc * denom);
}

}  // namespace

struct Obstacle::Impl {
    Eigen::MatrixX3d x;
    Eigen::MatrixX3i f;
    std::vector<Node> nodes;
    std::vector<Eigen::Vector3d> face_normals, vertex_normals;
    std::vector<std::array<int, 3>> face_edges;  // per face, edge (ab, bc, ca) index
    std::vector<std::array<int, 2>> edge_faces;  // per edge, its faces (-1 if boundary)
    std::vector<Eigen::Vector3d> edge_normals;

    Box face_box(int t) const {
        Box b;
        for (int c = 0; c < 3; ++c) b.extend(Eigen::Vector3d(x.row(f(t, c)).transpose()));
        return b;
    }

    int build(std::vector<int>& order, int begin, int end) {
        const int index = static_cast<int>(nodes.size());
        nodes.emplace_back();
        if (end - begin == 1) {
            nodes[static_cast<std::size_t>(index)].face = order[static_cast<std::size_t>(begin)];
            return index;
        }
        Box centroids;
        for (int i = begin; i < end; ++i)
            centroids.extend(Eigen::Vector3d(
                (x.row(f(order[static_cast<std::size_t>(i)], 0)) +
                 x.row(f(order[static_cast<std::size_t>(i)], 1)) +
                 x.row(f(order[static_cast<std::size_t>(i)], 2))).transpose() / 3));
        int axis = 0;
        (centroids.hi - centroids.lo).maxCoeff(&axis);
        const int mid = (begin + end) / 2;
        auto key = [&](int t) { return x(f(t, 0), axis) + x(f(t, 1), axis) + x(f(t, 2), axis); };
        std::nth_element(order.begin() + begin, order.begin() + mid, order.begin() + end,
                         [&](int a, int b) { return key(a) < key(b) || (key(a) == key(b) && a < b); });
        build(order, begin, mid);
        const int second = build(order, mid, end);
        nodes[static_cast<std::size_t>(index)].second = second;
        return index;
    }

    // Recomputes boxes bottom-up (children follow their parent in `nodes`).
    void refit() {
        for (std::size_t i = nodes.size(); i-- > 0;) {
            Node& n = nodes[i];
            if (n.second < 0) {
                n.box = face_box(n.face);
            } else {
                n.box = nodes[i + 1].box;
                n.box.extend(nodes[static_cast<std::size_t>(n.second)].box);
            }
        }
    }

    void compute_normals() {
        const auto nf = static_cast<std::size_t>(f.rows());
        face_normals.resize(nf);
        vertex_normals.assign(static_cast<std::size_t>(x.rows()), Eigen::Vector3d::Zero());
        for (std::size_t t = 0; t < nf; ++t) {
            const Eigen::Index ti = static_cast<Eigen::Index>(t);
            const Eigen::Vector3d p[3] = {x.row(f(ti, 0)).transpose(), x.row(f(ti, 1)).transpose(),
                                          x.row(f(ti, 2)).transpose()};
            face_normals[t] = (p[1] - p[0]).cross(p[2] - p[0]).normalized();
            for (int c = 0; c < 3; ++c) {
                const Eigen::Vector3d e1 = (p[(c + 1) % 3] - p[c]).normalized();
                const Eigen::Vector3d e2 = (p[(c + 2) % 3] - p[c]).normalized();
                const double angle = std::acos(std::clamp(e1.dot(e2), -1.0, 1.0));
                vertex_normals[static_cast<std::size_t>(f(ti, c))] += angle * face_normals[t];
            }
        }
        for (Eigen::Vector3d& n : vertex_normals)
            if (n.norm() > 0) n.normalize();
        edge_normals.resize(edge_faces.size());
        for (std::size_t e = 0; e < edge_faces.size(); ++e) {
            Eigen::Vector3d n = face_normals[static_cast<std::size_t>(edge_faces[e][0])];
            if (edge_faces[e][1] >= 0) n += face_normals[static_cast<std::size_t>(edge_faces[e][1])];
            edge_normals[e] = n.norm() > 0 ? n.normalized() : face_normals[static_cast<std::size_t>(edge_faces[e][0])];
        }
    }

    void build_edges() {
        std::map<std::pair<int, int>, int> index;
        face_edges.assign(static_cast<std::size_t>(f.rows()), {-1, -1, -1});
        edge_faces.clear();
        for (Eigen::Index t = 0; t < f.rows(); ++t)
            for (int c = 0; c < 3; ++c) {
                const int a = f(t, c), b = f(t, (c + 1) % 3);
                const auto key = std::minmax(a, b);
                auto [it, inserted] = index.emplace(key, static_cast<int>(edge_faces.size()));
                if (inserted) edge_faces.push_back({static_cast<int>(t), -1});
                else edge_faces[static_cast<std::size_t>(it->second)][1] = static_cast<int>(t);
                face_edges[static_cast<std::size_t>(t)][static_cast<std::size_t>(c)] = it->second;
            }
    }

    void check_positions(const Eigen::MatrixX3d& p, const char* what) const {
        require(p.allFinite(), what, ": obstacle positions are not finite");
        for (Eigen::Index t = 0; t < f.rows(); ++t) {
            const Eigen::Vector3d a = p.row(f(t, 0)), b = p.row(f(t, 1)), c = p.row(f(t, 2));
            require((b - a).cross(c - a).norm() / 2 >= 1e-14, what, ": obstacle triangle ", t,
                    " is degenerate (area < 1e-14 m²)");
        }
    }
};

Obstacle::Obstacle(const Eigen::MatrixX3d& positions, const Eigen::MatrixX3i& faces)
    : impl_(std::make_unique<Impl>()) {
    require(positions.rows() > 0 && faces.rows() > 0, "Obstacle: the mesh is empty (",
            positions.rows(), " vertices, ", faces.rows(), " faces)");
    require(faces.minCoeff() >= 0 && faces.maxCoeff() < positions.rows(),
            "Obstacle: a face index is out of range [0, ", positions.rows(), ")");
    impl_->f = faces;
    impl_->check_positions(positions, "Obstacle");
    impl_->x = positions;
    std::vector<int> order(static_cast<std::size_t>(faces.rows()));
    std::iota(order.begin(), order.end(), 0);
    impl_->nodes.reserve(2 * order.size());
    impl_->build(order, 0, static_cast<int>(order.size()));
    impl_->refit();
    impl_->build_edges();
    impl_->compute_normals();
}

Obstacle::~Obstacle() = default;
Obstacle::Obstacle(const Obstacle& o) : impl_(std::make_unique<Impl>(*o.impl_)) {}
Obstacle& Obstacle::operator=(const Obstacle& o) {
    if (this != &o) impl_ = std::make_unique<Impl>(*o.impl_);
    return *this;
}
Obstacle::Obstacle(Obstacle&&) noexcept = default;
Obstacle& Obstacle::operator=(Obstacle&&) noexcept = default;

void Obstacle::set_positions(const Eigen::MatrixX3d& positions) {
    require(positions.rows() == impl_->x.rows(), "Obstacle::set_positions: ", positions.rows(),
            " rows, expected ", impl_->x.rows());
    impl_->check_positions(positions, "Obstacle::set_positions");
    impl_->x = positions;
    impl_->refit();
    impl_->compute_normals();
}

ObstacleQuery Obstacle::closest(const Eigen::Vector3d& p, double max_distance_m) const {
    const Impl& m = *impl_;
    ObstacleQuery q;
    double best = max_distance_m * max_distance_m;
    if (!(best > 0)) return q;
    int best_feature = -1;
    // Depth-first, nearer child first; the stack never exceeds the tree depth + 1 per level.
    std::array<int, 128> stack{};
    int top = 0;
    stack[static_cast<std::size_t>(top++)] = 0;
    while (top > 0) {
        const Node& n = m.nodes[static_cast<std::size_t>(stack[static_cast<std::size_t>(--top)])];
        if (n.box.squared_distance(p) >= best) continue;
        if (n.second < 0) {
            const int t = n.face;
            int feature = 0;
            const Eigen::Vector3d c = closest_on_triangle(
                p, m.x.row(m.f(t, 0)).transpose(), m.x.row(m.f(t, 1)).transpose(),
                m.x.row(m.f(t, 2)).transpose(), feature);
            const double d2 = (p - c).squaredNorm();
            if (d2 < best) {
                best = d2;
                q.found = true;
                q.face = t;
                q.point = c;
                best_feature = feature;
            }
            continue;
        }
        const int first = static_cast<int>(&n - m.nodes.data()) + 1;
        const double d_first = m.nodes[static_cast<std::size_t>(first)].box.squared_distance(p);
        const double d_second = m.nodes[static_cast<std::size_t>(n.second)].box.squared_distance(p);
        if (top + 2 > static_cast<int>(stack.size())) continue;  // cannot happen for < 2^64 faces
        if (d_first < d_second) {
            stack[static_cast<std::size_t>(top++)] = n.second;
            stack[static_cast<std::size_t>(top++)] = first;
        } else {
            stack[static_cast<std::size_t>(top++)] = first;
            stack[static_cast<std::size_t>(top++)] = n.second;
        }
    }
    if (!q.found) return q;
    const auto t = static_cast<std::size_t>(q.face);
    if (best_feature < 3)
        q.normal = m.vertex_normals[static_cast<std::size_t>(m.f(q.face, best_feature))];
    else if (best_feature < 6)
        q.normal = m.edge_normals[static_cast<std::size_t>(m.face_edges[t][static_cast<std::size_t>(best_feature - 3)])];
    else
        q.normal = m.face_normals[t];
    const double distance = std::sqrt(best);
    q.signed_distance_m = (p - q.point).dot(q.normal) < 0 ? -distance : distance;
    return q;
}

const Eigen::MatrixX3d& Obstacle::positions() const { return impl_->x; }
const Eigen::MatrixX3i& Obstacle::faces() const { return impl_->f; }

}  // namespace drape::cloth
