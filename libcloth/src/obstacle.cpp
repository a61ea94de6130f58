#include <drape/cloth/obstacle.hpp>

#include <drape/core/bvh.hpp>
#include <drape/core/closest_point_triangle.hpp>
#include <drape/core/errors.hpp>
#include <drape/core/vertex_normals.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <utility>
#include <vector>

namespace drape::cloth {

struct Obstacle::Impl {
    Eigen::MatrixX3d x;
    Eigen::MatrixX3i f;
    core::Bvh bvh;  // one triangle per leaf, split at the centroids of the first positions
    std::vector<Eigen::Vector3d> face_normals;
    Eigen::MatrixXd vertex_normals;  // angle-weighted pseudo-normals, #V x 3
    std::vector<std::array<int, 3>> face_edges;  // per face, edge (ab, bc, ca) index
    std::vector<std::array<int, 2>> edge_faces;  // per edge, its faces (-1 if boundary)
    std::vector<Eigen::Vector3d> edge_normals;

    void build_tree() {
        std::vector<Eigen::Vector3d> centroids(static_cast<std::size_t>(f.rows()));
        for (Eigen::Index t = 0; t < f.rows(); ++t)
            centroids[static_cast<std::size_t>(t)] =
                (x.row(f(t, 0)) + x.row(f(t, 1)) + x.row(f(t, 2))).transpose() / 3;
        bvh = core::Bvh(core::Bvh::triangle_boxes(x, f), centroids, 1);
    }

    void compute_normals() {
        const auto nf = static_cast<std::size_t>(f.rows());
        face_normals.resize(nf);
        for (std::size_t t = 0; t < nf; ++t) {
            const Eigen::Index ti = static_cast<Eigen::Index>(t);
            const Eigen::Vector3d p[3] = {x.row(f(ti, 0)).transpose(), x.row(f(ti, 1)).transpose(),
                                          x.row(f(ti, 2)).transpose()};
            face_normals[t] = (p[1] - p[0]).cross(p[2] - p[0]).normalized();
        }
        core::VertexNormalOptions angle;
        angle.weighting = core::NormalWeighting::angle;
        vertex_normals = core::vertex_normals(x, f, angle);
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
    impl_->build_tree();
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
    impl_->bvh.refit(core::Bvh::triangle_boxes(impl_->x, impl_->f));
    impl_->compute_normals();
}

ObstacleQuery Obstacle::closest(const Eigen::Vector3d& p, double max_distance_m) const {
    const Impl& m = *impl_;
    ObstacleQuery q;
    double best = max_distance_m * max_distance_m;
    if (!(best > 0)) return q;
    int best_feature = -1;
    m.bvh.nearest(p, best, [&](int t, double& best_d2) {
        core::TriangleFeature feature = core::TriangleFeature::vertex_a;
        Eigen::Vector3d weights;
        const Eigen::Vector3d c = core::closest_point_on_triangle(
            p, m.x.row(m.f(t, 0)).transpose(), m.x.row(m.f(t, 1)).transpose(),
            m.x.row(m.f(t, 2)).transpose(), &feature, &weights);
        const double d2 = (p - c).squaredNorm();
        if (d2 < best_d2) {
            best_d2 = d2;
            q.found = true;
            q.face = t;
            q.point = c;
            q.weights = weights;
            best_feature = static_cast<int>(feature);
        }
    });
    if (!q.found) return q;
    const auto t = static_cast<std::size_t>(q.face);
    if (best_feature < 3)
        q.normal = m.vertex_normals.row(m.f(q.face, best_feature)).transpose();
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
