#include <drape/body/measurements.hpp>

#include <drape/core/errors.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>
#include <vector>

namespace drape::body {

namespace {

using Vec2 = Eigen::Vector2d;

double cross2(const Vec2& o, const Vec2& a, const Vec2& b) {
    return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
}

// Perimeter of the convex hull of 2D points (Andrew's monotone chain).
double hull_perimeter(std::vector<Vec2> pts) {
    if (pts.size() < 2) return 0;
    std::sort(pts.begin(), pts.end(), [](const Vec2& a, const Vec2& b) {
        return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
    });
    std::vector<Vec2> hull(2 * pts.size());
    size_t k = 0;
    for (const auto& p : pts) {
        while (k >= 2 && cross2(hull[k - 2], hull[k - 1], p) <= 0) --k;
        hull[k++] = p;
    }
    for (size_t i = pts.size() - 1, t = k + 1; i-- > 0;) {
        while (k >= t && cross2(hull[k - 2], hull[k - 1], pts[i]) <= 0) --k;
        hull[k++] = pts[i];
    }
    hull.resize(k - 1);
    double perimeter = 0;
    for (size_t i = 0; i < hull.size(); ++i) perimeter += (hull[(i + 1) % hull.size()] - hull[i]).norm();
    return perimeter;
}

struct EdgeKey {
    int a, b;
    bool operator==(const EdgeKey& o) const { return a == o.a && b == o.b; }
};
struct EdgeHash {
    size_t operator()(const EdgeKey& k) const {
        return std::hash<long long>()((static_cast<long long>(k.a) << 32) ^ static_cast<unsigned>(k.b));
    }
};

Eigen::Vector3d vertex(const Eigen::MatrixXd& V, int i) { return V.row(i).transpose(); }

}  // namespace

double section_girth(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                     const Eigen::Vector3d& point, const Eigen::Vector3d& normal_in) {
    require(V.cols() == 3 && F.cols() == 3, "section_girth: V and F must have 3 columns");
    require(normal_in.allFinite() && normal_in.norm() > 0, "section_girth: normal must be non-zero");
    const Eigen::Vector3d n = normal_in.normalized();
    // Signed distances, nudged off zero so that every crossing is a proper edge crossing.
    Eigen::VectorXd d(V.rows());
    for (int i = 0; i < V.rows(); ++i) {
        d[i] = n.dot(vertex(V, i) - point);
        if (std::abs(d[i]) < 1e-12) d[i] = 1e-12;
    }
    // Each crossed triangle contributes a segment joining two crossed edges; segments
    // sharing an edge belong to the same loop (union-find over crossed edges).
    std::unordered_map<EdgeKey, int, EdgeHash> edge_id;
    std::vector<Eigen::Vector3d> points;
    std::vector<int> parent;
    auto find = [&](int x) {
        while (parent[x] != x) x = parent[x] = parent[parent[x]];
        return x;
    };
    auto crossing = [&](int a, int b) {
        EdgeKey key{std::min(a, b), std::max(a, b)};
        auto it = edge_id.find(key);
        if (it != edge_id.end()) return it->second;
        const double t = d[a] / (d[a] - d[b]);
        points.push_back((1 - t) * vertex(V, a) + t * vertex(V, b));
        parent.push_back(static_cast<int>(parent.size()));
        const int id = static_cast<int>(points.size()) - 1;
        edge_id.emplace(key, id);
        return id;
    };
    for (int f = 0; f < F.rows(); ++f) {
        int crossed[2];
        int count = 0;
        for (int e = 0; e < 3; ++e) {
            const int a = F(f, e), b = F(f, (e + 1) % 3);
            if ((d[a] > 0) != (d[b] > 0) && count < 2) crossed[count++] = crossing(a, b);
        }
        if (count == 2) {
            const int ra = find(crossed[0]), rb = find(crossed[1]);
            if (ra != rb) parent[ra] = rb;
        }
    }
    if (points.empty()) return 0;
    // The loop nearest to `point`.
    int best_root = -1;
    double best = std::numeric_limits<double>::infinity();
    for (size_t i = 0; i < points.size(); ++i) {
        const double dist = (points[i] - point).squaredNorm();
        if (dist < best) {
            best = dist;
            best_root = find(static_cast<int>(i));
        }
    }
    // Project that loop's points to 2D plane coordinates and take the hull perimeter.
    Eigen::Vector3d u = n.unitOrthogonal();
    Eigen::Vector3d v = n.cross(u);
    std::vector<Vec2> loop;
    for (size_t i = 0; i < points.size(); ++i)
        if (find(static_cast<int>(i)) == best_root) loop.emplace_back(u.dot(points[i]), v.dot(points[i]));
    return hull_perimeter(std::move(loop));
}

double mesh_volume(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
    double six_v = 0;
    for (int f = 0; f < F.rows(); ++f)
        six_v += vertex(V, F(f, 0)).dot(vertex(V, F(f, 1)).cross(vertex(V, F(f, 2))));
    return six_v / 6.0;
}

Eigen::Matrix<double, kSemanticCount, 1> BodyMeasurements::as_semantic() const {
    Eigen::Matrix<double, kSemanticCount, 1> v;
    v << height_m, weight_kg, std::numeric_limits<double>::quiet_NaN(), chest_girth_m,
        waist_girth_m, hip_girth_m, thigh_girth_m, calf_girth_m, shoulder_height_m, crotch_height_m;
    return v;
}

BodyMeasurements measure_body(const BodyModel& model, const Eigen::MatrixXd& V) {
    require(V.rows() == model.vertex_count() && V.cols() == 3, "measure_body: vertices are ",
            V.rows(), " x ", V.cols(), ", expected ", model.vertex_count(), " x 3");
    require(V.allFinite(), "measure_body: vertices are not finite");
    const Landmarks& L = model.landmarks;
    for (int idx : {L.head_top, L.right_acromion, L.crotch, L.right_bust, L.left_bust, L.navel,
                    L.buttock, L.right_thigh, L.right_calf})
        require(idx >= 0 && idx < V.rows(),
                "measure_body: the model lacks a landmark needed for measuring (index ", idx, ")");
    const auto& F = model.faces;
    const double floor_y = V.col(1).minCoeff();
    const Eigen::Vector3d up(0, 1, 0);
    auto at = [&](int i) -> Eigen::Vector3d { return V.row(i).transpose(); };
    // Joints of this shape, for the limb axes.
    const Eigen::Matrix<double, kJointCount, 3> J = model.joint_regressor * V;
    auto joint = [&](Joint j) -> Eigen::Vector3d { return J.row(index(j)).transpose(); };

    BodyMeasurements m;
    m.height_m = V.col(1).maxCoeff() - floor_y;
    m.shoulder_height_m = at(L.right_acromion).y() - floor_y;
    m.crotch_height_m = at(L.crotch).y() - floor_y;
    // Chest: horizontal plane through the bust points, measured at the midline in front
    // of them so that the torso loop (not an arm) is taken.
    const Eigen::Vector3d bust = 0.5 * (at(L.right_bust) + at(L.left_bust));
    m.chest_girth_m = section_girth(V, F, bust, up);
    m.waist_girth_m = section_girth(V, F, at(L.navel), up);
    m.hip_girth_m = section_girth(V, F, at(L.buttock), up);
    m.thigh_girth_m = section_girth(V, F, at(L.right_thigh),
                                    joint(Joint::right_knee) - joint(Joint::right_hip));
    m.calf_girth_m = section_girth(V, F, at(L.right_calf),
                                   joint(Joint::right_ankle) - joint(Joint::right_knee));
    m.volume_m3 = mesh_volume(V, F);
    m.weight_kg = m.volume_m3 * model.density_kg_m3;
    return m;
}

}  // namespace drape::body
