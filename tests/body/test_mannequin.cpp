// The procedural mannequin: surface validity and quality, proportions, rig (joints,
// regressor, skinning, landmarks), conform_mannequin, and skinning under large bends.
#include "mannequin.hpp"

#include <drape/body/pose.hpp>
#include <drape/core/errors.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <numeric>
#include <set>
#include <unordered_map>

using namespace drape::body;
using namespace drape::body::detail;
using Eigen::Vector3d;

namespace {

constexpr double kPi = 3.14159265358979323846;

const MannequinMesh& mannequin() {
    static const MannequinMesh mesh = generate_mannequin();
    return mesh;
}

Vector3d vrow(const Eigen::MatrixXd& V, int i) { return V.row(i).transpose(); }
Vector3d joint(const MannequinMesh& m, Joint j) { return m.joints.row(index(j)).transpose(); }

double signed_volume(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
    double vol = 0.0;
    for (int f = 0; f < F.rows(); ++f)
        vol += vrow(V, F(f, 0)).dot(vrow(V, F(f, 1)).cross(vrow(V, F(f, 2)))) / 6.0;
    return vol;
}

// Generalised winding number (solid angles / 4 pi): ~1 inside, ~0 outside.
double winding_number(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const Vector3d& p) {
    double sum = 0.0;
    for (int f = 0; f < F.rows(); ++f) {
        const Vector3d a = vrow(V, F(f, 0)) - p, b = vrow(V, F(f, 1)) - p, c = vrow(V, F(f, 2)) - p;
        const double la = a.norm(), lb = b.norm(), lc = c.norm();
        const double num = a.dot(b.cross(c));
        const double den = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
        sum += 2.0 * std::atan2(num, den);
    }
    return sum / (4.0 * kPi);
}

double min_angle_deg(const Vector3d& a, const Vector3d& b, const Vector3d& c) {
    const Vector3d p[3] = {a, b, c};
    double best = 180.0;
    for (int k = 0; k < 3; ++k) {
        const Vector3d u = p[(k + 1) % 3] - p[k], v = p[(k + 2) % 3] - p[k];
        best = std::min(best, std::atan2(u.cross(v).norm(), u.dot(v)) * 180.0 / kPi);
    }
    return best;
}

struct Topology {
    int non_manifold_edges = 0;  // directed edge used twice or without its opposite
    long euler = 0;
    int components = 0;
};

Topology topology(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
    Topology t;
    std::map<std::pair<int, int>, int> directed;
    for (int f = 0; f < F.rows(); ++f)
        for (int k = 0; k < 3; ++k) ++directed[{F(f, k), F(f, (k + 1) % 3)}];
    for (const auto& [e, n] : directed)
        if (n != 1 || !directed.count({e.second, e.first})) ++t.non_manifold_edges;
    t.euler = static_cast<long>(V.rows()) - static_cast<long>(directed.size() / 2) +
              static_cast<long>(F.rows());
    std::vector<int> parent(static_cast<size_t>(V.rows()));
    std::iota(parent.begin(), parent.end(), 0);
    std::function<int(int)> find = [&](int x) {
        return parent[static_cast<size_t>(x)] == x ? x : parent[static_cast<size_t>(x)] = find(parent[static_cast<size_t>(x)]);
    };
    for (int f = 0; f < F.rows(); ++f)
        for (int k = 0; k < 3; ++k) parent[static_cast<size_t>(find(F(f, k)))] = find(F(f, (k + 1) % 3));
    std::set<int> roots;
    for (int v = 0; v < V.rows(); ++v) roots.insert(find(v));
    t.components = static_cast<int>(roots.size());
    return t;
}

// Segment pq crosses triangle abc (strictly inside both).
bool segment_hits_triangle(const Vector3d& p, const Vector3d& q, const Vector3d& a,
                           const Vector3d& b, const Vector3d& c) {
    const Vector3d d = q - p, e1 = b - a, e2 = c - a;
    const Vector3d h = d.cross(e2);
    const double det = e1.dot(h);
    if (std::abs(det) < 1e-18) return false;
    const Vector3d s = p - a;
    const double u = s.dot(h) / det;
    if (u <= 1e-9 || u >= 1 - 1e-9) return false;
    const Vector3d qv = s.cross(e1);
    const double v = d.dot(qv) / det;
    if (v <= 1e-9 || u + v >= 1 - 1e-9) return false;
    const double t = e2.dot(qv) / det;
    return t > 1e-9 && t < 1 - 1e-9;
}

// Number of intersecting pairs of triangles that share no vertex (uniform-grid broad phase).
int self_intersections(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
    const double cell = 0.02;
    std::unordered_map<long long, std::vector<int>> grid;
    auto key = [](long long i, long long j, long long k) { return (i * 4096 + j) * 4096 + k; };
    for (int f = 0; f < F.rows(); ++f) {
        Eigen::Vector3d lo = vrow(V, F(f, 0)), hi = lo;
        for (int k = 1; k < 3; ++k) {
            lo = lo.cwiseMin(vrow(V, F(f, k)));
            hi = hi.cwiseMax(vrow(V, F(f, k)));
        }
        const Eigen::Vector3i a = ((lo.array() + 2.0) / cell).floor().cast<int>();
        const Eigen::Vector3i b = ((hi.array() + 2.0) / cell).floor().cast<int>();
        for (int i = a.x(); i <= b.x(); ++i)
            for (int j = a.y(); j <= b.y(); ++j)
                for (int k = a.z(); k <= b.z(); ++k) grid[key(i, j, k)].push_back(f);
    }
    std::set<std::pair<int, int>> hits;
    for (const auto& [k, faces] : grid) {
        for (size_t x = 0; x < faces.size(); ++x)
            for (size_t y = x + 1; y < faces.size(); ++y) {
                const int f = faces[x], g = faces[y];
                bool shared = false;
                for (int i = 0; i < 3; ++i)
                    for (int j = 0; j < 3; ++j) shared = shared || F(f, i) == F(g, j);
                if (shared) continue;
                bool hit = false;
                for (int e = 0; e < 3 && !hit; ++e) {
                    hit = segment_hits_triangle(vrow(V, F(f, e)), vrow(V, F(f, (e + 1) % 3)),
                                                vrow(V, F(g, 0)), vrow(V, F(g, 1)), vrow(V, F(g, 2))) ||
                          segment_hits_triangle(vrow(V, F(g, e)), vrow(V, F(g, (e + 1) % 3)),
                                                vrow(V, F(f, 0)), vrow(V, F(f, 1)), vrow(V, F(f, 2)));
                }
                if (hit) hits.insert({std::min(f, g), std::max(f, g)});
            }
    }
    return static_cast<int>(hits.size());
}

BodyModel rig_only_model(const MannequinMesh& m) {
    BodyModel model;
    model.template_vertices = m.V;
    model.faces = m.F;
    model.template_joints = m.joints;
    model.joint_regressor = m.joint_regressor;
    model.skin_weights = m.skin_weights;
    return model;
}

// Distance from p to the polyline through `pts`.
double distance_to_polyline(const Vector3d& p, const std::vector<Vector3d>& pts) {
    double best = std::numeric_limits<double>::infinity();
    for (size_t i = 0; i + 1 < pts.size(); ++i) {
        const Vector3d d = pts[i + 1] - pts[i];
        const double t = std::clamp((p - pts[i]).dot(d) / d.squaredNorm(), 0.0, 1.0);
        best = std::min(best, (p - (pts[i] + t * d)).norm());
    }
    return best;
}

// Worst ratio (posed / rest) of the distance of vertices near `centre` to the bone polyline.
double worst_bone_distance_ratio(const MannequinMesh& m, const Eigen::MatrixXd& posed,
                                 const std::vector<Joint>& chain, const Eigen::MatrixXd& posed_joints,
                                 const Vector3d& centre, double radius) {
    std::vector<Vector3d> rest_line, posed_line;
    for (Joint j : chain) {
        rest_line.push_back(joint(m, j));
        posed_line.push_back(posed_joints.row(index(j)).transpose());
    }
    double worst = 1e9;
    for (int v = 0; v < m.V.rows(); ++v) {
        if ((vrow(m.V, v) - centre).norm() > radius) continue;
        const double r0 = distance_to_polyline(vrow(m.V, v), rest_line);
        if (r0 < 0.01) continue;
        worst = std::min(worst, distance_to_polyline(vrow(posed, v), posed_line) / r0);
    }
    return worst;
}

}  // namespace

TEST_CASE("mannequin: closed genus-0 manifold of the requested size", "[body][mannequin]") {
    const MannequinMesh& m = mannequin();
    CHECK(m.V.rows() >= 8000);
    CHECK(m.V.rows() <= 20000);
    CHECK(m.F.rows() == 2 * m.V.rows() - 4);
    CHECK(m.F.minCoeff() >= 0);
    CHECK(m.F.maxCoeff() < m.V.rows());
    const Topology t = topology(m.V, m.F);
    CHECK(t.non_manifold_edges == 0);
    CHECK(t.euler == 2);
    CHECK(t.components == 1);
    const double volume = signed_volume(m.V, m.F);
    CHECK(volume > 0.055);  // about 67 litres: a 68 kg adult
    CHECK(volume < 0.085);
    CHECK(self_intersections(m.V, m.F) == 0);
}

TEST_CASE("mannequin: triangle quality", "[body][mannequin]") {
    const MannequinMesh& m = mannequin();
    int below10 = 0, below2 = 0;
    for (int f = 0; f < m.F.rows(); ++f) {
        const double a = min_angle_deg(vrow(m.V, m.F(f, 0)), vrow(m.V, m.F(f, 1)), vrow(m.V, m.F(f, 2)));
        below10 += a < 10.0;
        below2 += a < 2.0;
    }
    CHECK(below10 <= m.F.rows() / 100);
    CHECK(below2 == 0);
}

TEST_CASE("mannequin: frame, stature and proportions", "[body][mannequin]") {
    const MannequinMesh& m = mannequin();
    CHECK(std::abs(m.V.col(1).minCoeff()) < 1e-6);
    const double stature = m.V.col(1).maxCoeff();
    CHECK(stature == Approx(1.70).margin(0.015));
    const Landmarks& L = m.landmarks;
    CHECK(m.V(L.crotch, 1) == Approx(0.80).margin(0.03));
    CHECK(m.V(L.right_acromion, 1) == Approx(1.39).margin(0.03));
    const double biacromial = m.V(L.left_acromion, 0) - m.V(L.right_acromion, 0);
    CHECK(biacromial == Approx(0.39).margin(0.04));
    // Symmetric about x = 0; faces +Z (nose and toes in front).
    CHECK(std::abs(m.V.col(0).maxCoeff() + m.V.col(0).minCoeff()) < 0.005);
    CHECK(m.V(L.navel, 2) > 0.08);
    CHECK(m.V(L.buttock, 2) < -0.08);
    // Legs apart: 3 cm below the crotch the inner thighs are more than 4 cm apart, and
    // stay apart when each thigh is widened by 20 % about its own centre.
    {
        const double y = m.V(L.crotch, 1) - 0.03;
        double inner = -1.0, outer = 0.0;
        for (int v = 0; v < m.V.rows(); ++v) {
            if (std::abs(m.V(v, 1) - y) > 0.006 || m.V(v, 0) >= 0.0 || m.V(v, 0) < -0.3) continue;
            inner = std::max(inner, m.V(v, 0));
            outer = std::min(outer, m.V(v, 0));
        }
        const double centre = 0.5 * (inner + outer), half = 0.5 * (inner - outer);
        CHECK(-2.0 * inner > 0.04);
        CHECK(-2.0 * (centre + 1.2 * half) > 0.005);
    }
    // A-pose: arms about 45 degrees down, legs apart.
    for (auto [s, e] : {std::pair{Joint::left_shoulder, Joint::left_elbow},
                        std::pair{Joint::right_shoulder, Joint::right_elbow}}) {
        const Vector3d d = joint(m, e) - joint(m, s);
        const double below = std::atan2(-d.y(), std::abs(d.x())) * 180.0 / kPi;
        CHECK(below > 38.0);
        CHECK(below < 47.0);
    }
}

TEST_CASE("mannequin: generation is deterministic and fast enough", "[body][mannequin]") {
    const auto t0 = std::chrono::steady_clock::now();
    const MannequinMesh again = generate_mannequin();
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    WARN("generate_mannequin took " << seconds << " s for " << again.V.rows() << " vertices");
    REQUIRE(again.V.rows() == mannequin().V.rows());
    CHECK(again.F == mannequin().F);
    CHECK((again.V - mannequin().V).cwiseAbs().maxCoeff() == 0.0);
}

TEST_CASE("mannequin: joints lie inside the body at anatomical places", "[body][mannequin]") {
    const MannequinMesh& m = mannequin();
    for (int j = 0; j < kJointCount; ++j) {
        if (j == index(Joint::head_top)) continue;
        INFO("joint " << kJointNames[static_cast<size_t>(j)]);
        CHECK(winding_number(m.V, m.F, m.joints.row(j).transpose()) > 0.99);
    }
    // head_top: the top of the skull, on the surface.
    CHECK((joint(m, Joint::head_top) - vrow(m.V, m.landmarks.head_top)).norm() < 1e-12);
    CHECK(joint(m, Joint::head_top).y() == Approx(m.V.col(1).maxCoeff()));
    // Hips inside the pelvis, 8-9.5 cm from the midline; pelvis between them.
    for (Joint hip : {Joint::left_hip, Joint::right_hip}) {
        CHECK(std::abs(joint(m, hip).x()) > 0.075);
        CHECK(std::abs(joint(m, hip).x()) < 0.095);
        CHECK(joint(m, hip).y() > m.V(m.landmarks.crotch, 1));
    }
    CHECK(std::abs(joint(m, Joint::pelvis).x()) < 1e-3);
    CHECK(joint(m, Joint::spine).y() == Approx(m.V(m.landmarks.navel, 1)).margin(0.06));
    CHECK(joint(m, Joint::chest).y() == Approx(m.V(m.landmarks.right_bust, 1)).margin(0.05));
    CHECK(joint(m, Joint::neck).y() > m.V(m.landmarks.right_acromion, 1));
    CHECK(joint(m, Joint::head).y() > joint(m, Joint::neck).y() + 0.05);
    // Limb joints in order along the limbs; toes in front of the ankles.
    CHECK(joint(m, Joint::left_elbow).x() > joint(m, Joint::left_shoulder).x() + 0.15);
    CHECK(joint(m, Joint::left_wrist).x() > joint(m, Joint::left_elbow).x() + 0.12);
    CHECK(joint(m, Joint::right_knee).y() == Approx(0.48).margin(0.04));
    CHECK(joint(m, Joint::right_ankle).y() == Approx(0.08).margin(0.03));
    CHECK(joint(m, Joint::right_toe).z() > joint(m, Joint::right_ankle).z() + 0.08);
}

TEST_CASE("mannequin: joint regressor is local, convex and exact", "[body][mannequin]") {
    const MannequinMesh& m = mannequin();
    const auto& R = m.joint_regressor;
    REQUIRE(R.rows() == kJointCount);
    REQUIRE(R.cols() == m.V.rows());
    const Eigen::MatrixXd J = R * m.V;
    CHECK((J - m.joints).cwiseAbs().maxCoeff() < 1e-9);
    const Eigen::VectorXd sums = R * Eigen::VectorXd::Ones(m.V.rows());
    for (int j = 0; j < kJointCount; ++j) CHECK(sums(j) == Approx(1.0).margin(1e-12));
    Eigen::SparseMatrix<double, Eigen::RowMajor> Rr = R;
    for (int j = 0; j < kJointCount; ++j) {
        int nnz = 0;
        double reach = 0.0;
        for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(Rr, j); it; ++it) {
            CHECK(it.value() >= 0.0);
            ++nnz;
            reach = std::max(reach, (vrow(m.V, static_cast<int>(it.col())) - m.joints.row(j).transpose()).norm());
        }
        INFO("joint " << kJointNames[static_cast<size_t>(j)]);
        CHECK(nnz >= 1);
        CHECK(nnz <= 250);
        CHECK(reach < 0.30);
    }
}

TEST_CASE("mannequin: skinning weights are convex, sparse and skip end sites", "[body][mannequin]") {
    const MannequinMesh& m = mannequin();
    const auto& W = m.skin_weights;
    REQUIRE(W.rows() == m.V.rows());
    REQUIRE(W.cols() == kJointCount);
    Eigen::SparseMatrix<double, Eigen::RowMajor> Wr = W;
    int worst_nnz = 0;
    double worst_sum = 0.0, min_value = 1.0;
    for (int v = 0; v < Wr.rows(); ++v) {
        int nnz = 0;
        double sum = 0.0;
        for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(Wr, v); it; ++it) {
            ++nnz;
            sum += it.value();
            min_value = std::min(min_value, it.value());
        }
        worst_nnz = std::max(worst_nnz, nnz);
        worst_sum = std::max(worst_sum, std::abs(sum - 1.0));
    }
    CHECK(worst_nnz <= 4);
    CHECK(worst_sum < 1e-12);
    CHECK(min_value >= 0.0);
    for (Joint end : {Joint::head_top, Joint::left_toe, Joint::right_toe})
        CHECK(W.col(index(end)).norm() == 0.0);
    // Every other joint drives some vertices; hands belong to the wrists, the skull to
    // the head.
    for (int j = 0; j < kJointCount; ++j) {
        if (j == index(Joint::head_top) || j == index(Joint::left_toe) || j == index(Joint::right_toe)) continue;
        CHECK(W.col(j).sum() > 20.0);
    }
    const Eigen::MatrixXd Wd = Eigen::MatrixXd(W);
    CHECK(Wd(m.landmarks.head_top, index(Joint::head)) > 0.99);
}

TEST_CASE("mannequin: landmarks are placed on the right anatomy", "[body][mannequin]") {
    const MannequinMesh& m = mannequin();
    const Landmarks& L = m.landmarks;
    for (int v : {L.head_top, L.right_acromion, L.left_acromion, L.crotch, L.right_bust, L.left_bust,
                  L.navel, L.buttock, L.right_thigh, L.right_calf}) {
        REQUIRE(v >= 0);
        REQUIRE(v < m.V.rows());
    }
    const Eigen::MatrixXd& V = m.V;
    CHECK(V(L.head_top, 1) == V.col(1).maxCoeff());
    CHECK(V(L.right_acromion, 0) < -0.15);
    CHECK(V(L.left_acromion, 0) > 0.15);
    CHECK(std::abs(V(L.crotch, 0)) < 0.015);
    CHECK(V(L.right_bust, 0) < -0.04);
    CHECK(V(L.left_bust, 0) > 0.04);
    CHECK(V(L.right_bust, 2) > joint(m, Joint::chest).z() + 0.10);
    CHECK(std::abs(V(L.navel, 0)) < 0.02);
    CHECK(V(L.navel, 1) < joint(m, Joint::spine).y());
    CHECK(V(L.navel, 1) > joint(m, Joint::spine).y() - 0.06);
    CHECK(std::abs(V(L.buttock, 0)) < 0.02);
    CHECK(V(L.buttock, 1) > V(L.crotch, 1));
    CHECK(V(L.buttock, 1) < joint(m, Joint::pelvis).y() + 0.02);
    CHECK(V(L.right_thigh, 0) < -0.04);
    CHECK(V(L.right_thigh, 1) < V(L.crotch, 1));
    CHECK(V(L.right_thigh, 1) > V(L.crotch, 1) - 0.06);
    CHECK(V(L.right_calf, 0) < -0.05);
    CHECK(V(L.right_calf, 2) < joint(m, Joint::right_knee).z() - 0.05);
    CHECK(V(L.right_calf, 1) < joint(m, Joint::right_knee).y() - 0.08);
    CHECK(V(L.right_calf, 1) > joint(m, Joint::right_ankle).y() + 0.15);
}

TEST_CASE("mannequin: conform_mannequin lands every design on its surface", "[body][mannequin]") {
    const MannequinMesh& m = mannequin();
    const Eigen::MatrixXd N0 = mannequin_vertex_normals(m.V, m.F);
    const std::vector<MannequinDesign> designs = {
        {0.0, 0.0, 0.0}, {1.0, 0.0, 0.0}, {0.5, 1.0, 0.0},  {0.5, -1.0, 0.0},
        {0.5, 0.0, 1.0}, {0.5, 0.0, -1.0}, {1.0, 1.0, 1.0}, {0.0, -1.0, -1.0}};
    for (const MannequinDesign& d : designs) {
        INFO("design " << d.femininity << " " << d.fat << " " << d.muscle);
        const Eigen::MatrixXd V = conform_mannequin(m, d);
        REQUIRE(V.rows() == m.V.rows());
        const MannequinImplicit body(d);
        double worst = 0.0;
        for (int v = 0; v < V.rows(); ++v) worst = std::max(worst, std::abs(body.value(vrow(V, v))));
        CHECK(worst < 1e-3);
        int flipped = 0, slivers = 0;
        for (int f = 0; f < m.F.rows(); ++f) {
            const Vector3d a = vrow(V, m.F(f, 0)), b = vrow(V, m.F(f, 1)), c = vrow(V, m.F(f, 2));
            const Vector3d n = (b - a).cross(c - a);
            const Vector3d n0 = N0.row(m.F(f, 0)) + N0.row(m.F(f, 1)) + N0.row(m.F(f, 2));
            flipped += n.dot(n0) <= 0.0;
            slivers += min_angle_deg(a, b, c) < 2.0;
        }
        CHECK(flipped == 0);
        CHECK(slivers == 0);
        CHECK(signed_volume(V, m.F) > 0.04);
    }
    // The default design maps onto itself.
    CHECK((conform_mannequin(m, MannequinDesign{}) - m.V).cwiseAbs().maxCoeff() < 1e-6);
}

TEST_CASE("mannequin: femininity grows the bust, fat the belly, muscle the arms", "[body][mannequin]") {
    const MannequinMesh& m = mannequin();
    const Landmarks& L = m.landmarks;
    const Eigen::MatrixXd male = conform_mannequin(m, {0.0, 0.0, 0.0});
    const Eigen::MatrixXd female = conform_mannequin(m, {1.0, 0.0, 0.0});
    const double bust = female(L.right_bust, 2) - male(L.right_bust, 2);
    CHECK(bust > 0.02);
    CHECK(bust < 0.08);
    const double shoulders = (male(L.left_acromion, 0) - male(L.right_acromion, 0)) -
                             (female(L.left_acromion, 0) - female(L.right_acromion, 0));
    CHECK(shoulders > 0.02);
    const Eigen::MatrixXd fat = conform_mannequin(m, {0.5, 1.0, 0.0});
    const Eigen::MatrixXd lean = conform_mannequin(m, {0.5, -1.0, 0.0});
    const double belly = fat(L.navel, 2) - lean(L.navel, 2);
    CHECK(belly > 0.04);
    CHECK(belly < 0.15);
    const double volume_gain = signed_volume(fat, m.F) / signed_volume(lean, m.F);
    CHECK(volume_gain > 1.15);
    CHECK(volume_gain < 1.8);
    const Eigen::MatrixXd strong = conform_mannequin(m, {0.5, 0.0, 1.0});
    const Eigen::MatrixXd weak = conform_mannequin(m, {0.5, 0.0, -1.0});
    CHECK(signed_volume(strong, m.F) > signed_volume(weak, m.F));
}

TEST_CASE("mannequin: elbow and knee bends of +-90 degrees do not collapse", "[body][mannequin][pose]") {
    const MannequinMesh& m = mannequin();
    const double rest_volume = signed_volume(m.V, m.F);
    struct Case {
        Joint joint, parent, child;
        Vector3d axis;
    };
    const Vector3d re = joint(m, Joint::right_elbow), rs = joint(m, Joint::right_shoulder);
    const Vector3d elbow_axis = (re - rs).normalized().cross(Vector3d::UnitZ()).normalized();
    const std::vector<Case> cases = {
        {Joint::right_elbow, Joint::right_shoulder, Joint::right_wrist, elbow_axis},
        {Joint::right_knee, Joint::right_hip, Joint::right_ankle, Vector3d::UnitX()},
    };
    for (const Case& c : cases) {
        for (double angle : {-kPi / 2, kPi / 2}) {
            INFO(kJointNames[static_cast<size_t>(index(c.joint))] << " bent by " << angle);
            Pose pose;
            pose.rotations.row(index(c.joint)) = (angle * c.axis).transpose();
            const PosedSkeleton sk = forward_kinematics(m.joints, pose);
            const Eigen::MatrixXd P = skin_vertices(rig_only_model(m), m.V, sk);
            const double ratio = worst_bone_distance_ratio(m, P, {c.parent, c.joint, c.child}, sk.joints,
                                                           joint(m, c.joint), 0.12);
            const double volume_ratio = signed_volume(P, m.F) / rest_volume;
            WARN(kJointNames[static_cast<size_t>(index(c.joint))] << " bent by " << angle
                 << " rad: worst bone-distance ratio " << ratio << ", volume ratio " << volume_ratio);
            CHECK(ratio > 0.30);
            CHECK(volume_ratio > 0.97);
            double stretch = 0.0;
            for (int f = 0; f < m.F.rows(); ++f)
                for (int k = 0; k < 3; ++k) {
                    const int a = m.F(f, k), b = m.F(f, (k + 1) % 3);
                    stretch = std::max(stretch, (vrow(P, a) - vrow(P, b)).norm() / (vrow(m.V, a) - vrow(m.V, b)).norm());
                }
            CHECK(stretch < 3.0);
        }
    }
}

TEST_CASE("mannequin: 90 degree shoulder abduction keeps the shoulder", "[body][mannequin][pose]") {
    const MannequinMesh& m = mannequin();
    Pose pose;
    // Raise the right arm by 90 degrees in the frontal plane (to 45 degrees above horizontal).
    pose.rotations.row(index(Joint::right_shoulder)) = Eigen::RowVector3d(0, 0, -kPi / 2);
    const PosedSkeleton sk = forward_kinematics(m.joints, pose);
    const Eigen::MatrixXd P = skin_vertices(rig_only_model(m), m.V, sk);
    CHECK(sk.joints(index(Joint::right_elbow), 1) > joint(m, Joint::right_shoulder).y() + 0.15);
    const double ratio = worst_bone_distance_ratio(
        m, P, {Joint::right_clavicle, Joint::right_shoulder, Joint::right_elbow}, sk.joints,
        joint(m, Joint::right_shoulder), 0.10);
    // Linear blend skinning folds the top of the shoulder (clavicle / shoulder weights
    // about 50/50) in towards the joint: about 0.25 of its rest distance.
    WARN("shoulder abduction: worst bone-distance ratio " << ratio);
    CHECK(ratio > 0.20);
    CHECK(signed_volume(P, m.F) / signed_volume(m.V, m.F) > 0.96);
}

TEST_CASE("mannequin: a 90 degree wrist or forearm twist keeps 70 % of the cross-section", "[body][mannequin][pose]") {
    const MannequinMesh& m = mannequin();
    const Vector3d elbow = joint(m, Joint::left_elbow), wrist = joint(m, Joint::left_wrist);
    const Vector3d axis = (wrist - elbow).normalized();
    for (Joint twisted : {Joint::left_wrist, Joint::left_elbow}) {
        INFO("twisting " << kJointNames[static_cast<size_t>(index(twisted))]);
        Pose pose;
        pose.rotations.row(index(twisted)) = (kPi / 2 * axis).transpose();
        const PosedSkeleton sk = forward_kinematics(m.joints, pose);
        const Eigen::MatrixXd P = skin_vertices(rig_only_model(m), m.V, sk);
        // RMS distance to the forearm axis per 1 cm slice, posed over rest.
        const Vector3d centre = joint(m, twisted);
        double worst = 1e9;
        for (double s = -0.07; s <= 0.05; s += 0.01) {
            double rest2 = 0.0, posed2 = 0.0;
            int n = 0;
            for (int v = 0; v < m.V.rows(); ++v) {
                const Vector3d d = vrow(m.V, v) - centre;
                const double along = d.dot(axis);
                if (std::abs(along - s) > 0.005 || (d - along * axis).norm() > 0.06) continue;
                const Vector3d dp = vrow(P, v) - centre;
                rest2 += (d - along * axis).squaredNorm();
                posed2 += (dp - dp.dot(axis) * axis).squaredNorm();
                ++n;
            }
            if (n >= 6) worst = std::min(worst, std::sqrt(posed2 / rest2));
        }
        WARN("worst cross-section radius ratio under a 90 degree twist: " << worst);
        CHECK(worst > 0.69);
    }
}

TEST_CASE("mannequin: dominant_joints names the joint of each vertex's largest skin weight", "[body][mannequin]") {
    const BodyModel& model = BodyModel::default_model();
    const std::vector<int> dominant = dominant_joints(model);
    REQUIRE(int(dominant.size()) == model.vertex_count());
    const Eigen::SparseMatrix<double, Eigen::RowMajor> W = model.skin_weights;
    int checked = 0;
    for (int v = 0; v < model.vertex_count(); v += 37) {
        REQUIRE(dominant[size_t(v)] >= 0);
        const double w = W.coeff(v, dominant[size_t(v)]);
        for (int j = 0; j < kJointCount; ++j) CHECK(W.coeff(v, j) <= w);
        ++checked;
    }
    CHECK(checked > 100);
    // The vertex nearest each wrist and knee joint is moved by that limb (the joint itself
    // its parent or a child).
    for (const auto& [joint, parent] : {std::pair{Joint::right_wrist, Joint::right_elbow},
                                        std::pair{Joint::left_knee, Joint::left_hip}}) {
        Eigen::Index nearest = 0;
        (model.template_vertices.rowwise() - model.template_joints.row(index(joint))).rowwise().squaredNorm().minCoeff(&nearest);
        const int d = dominant[size_t(nearest)];
        INFO(kJointNames[size_t(index(joint))] << ": nearest vertex moved by " << kJointNames[size_t(d)]);
        CHECK((d == index(joint) || d == index(parent) || (d >= 0 && kJointParents[size_t(d)] == index(joint))));
    }
}
