// Interpenetration removal of dress_garment (stages 4 and 5): vertices inside the posed body
// or too close to it are pushed out along the body normal, an as-rigid-as-possible
// deformation carrying their neighbours, and the crossings left are untangled.
#include "dressing_stages.hpp"

#include <drape/core/vertex_normals.hpp>

#include <Eigen/SVD>
#include <Eigen/SparseCholesky>

#include <algorithm>
#include <array>
#include <utility>
#include <vector>

namespace drape::garment::detail {

namespace {

using body::Joint;
using body::index;
constexpr double kStitchWeight = 20.0;  // ARAP weight of a stitch relative to a cloth edge

// As-rigid-as-possible deformation (uniform weights) from rest shape X0 towards soft
// positional targets; `iterations` local/global rounds starting from X.
void arap(const Eigen::MatrixX3d& X0, const std::vector<std::array<int, 2>>& edges,
          const std::vector<double>& edge_weight, const std::vector<bool>& zero_rest,
          const std::vector<int>& targets_index, const Eigen::MatrixX3d& targets, double weight,
          int iterations, Eigen::MatrixX3d& X) {
    const int n = static_cast<int>(X0.rows());
    struct Nbr {
        int j;
        double w;
        double rest;  // 1: rest edge from X0; 0: the edge's rest length is zero (a stitch)
    };
    std::vector<std::vector<Nbr>> nbr(n);
    for (size_t k = 0; k < edges.size(); ++k) {
        const double rest = zero_rest[k] ? 0.0 : 1.0;
        nbr[edges[k][0]].push_back({edges[k][1], edge_weight[k], rest});
        nbr[edges[k][1]].push_back({edges[k][0], edge_weight[k], rest});
    }
    std::vector<Eigen::Triplet<double>> trip;
    for (int i = 0; i < n; ++i)
        for (const Nbr& e : nbr[i]) {
            trip.emplace_back(i, i, e.w);
            trip.emplace_back(i, e.j, -e.w);
        }
    // A weak pull towards the starting positions keeps panels without targets in place
    // (the Laplacian alone leaves each panel's translation free).
    constexpr double kAnchor = 0.01;
    for (int i = 0; i < n; ++i) trip.emplace_back(i, i, kAnchor);
    for (int i : targets_index) trip.emplace_back(i, i, weight);
    Eigen::SparseMatrix<double> A(n, n);
    A.setFromTriplets(trip.begin(), trip.end());
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(A);
    if (solver.info() != Eigen::Success) return;
    const Eigen::MatrixX3d start = X;
    std::vector<Eigen::Matrix3d> R(n, Eigen::Matrix3d::Identity());
    for (int it = 0; it < iterations; ++it) {
        for (int i = 0; i < n; ++i) {
            Eigen::Matrix3d S = Eigen::Matrix3d::Zero();
            for (const Nbr& e : nbr[i])
                S += e.w * e.rest * (X0.row(i) - X0.row(e.j)).transpose() * (X.row(i) - X.row(e.j));
            Eigen::JacobiSVD<Eigen::Matrix3d> svd(S, Eigen::ComputeFullU | Eigen::ComputeFullV);
            Eigen::Matrix3d r = svd.matrixV() * svd.matrixU().transpose();
            if (r.determinant() < 0) {
                Eigen::Matrix3d v = svd.matrixV();
                v.col(2) *= -1;
                r = v * svd.matrixU().transpose();
            }
            R[i] = r;
        }
        Eigen::MatrixX3d b = kAnchor * start;
        for (int i = 0; i < n; ++i)
            for (const Nbr& e : nbr[i])
                b.row(i) += (0.5 * e.w * e.rest * (R[i] + R[e.j]) * (X0.row(i) - X0.row(e.j)).transpose()).transpose();
        for (size_t k = 0; k < targets_index.size(); ++k)
            b.row(targets_index[k]) += weight * targets.row(Eigen::Index(k));
        X = solver.solve(b);
    }
}
// Whether the body part of joint j is one a panel of this role must stay outside of: a
// forearm or hand resting on the hip (arms down) is not something pants go around, and
// torso panels only avoid the upper arm.
bool obstacle_for(Role role, int j) {
    if (role == Role::sleeve || role == Role::hint) return true;
    if (role == Role::torso)
        return !(j == index(Joint::left_elbow) || j == index(Joint::left_wrist) ||
                 j == index(Joint::right_elbow) || j == index(Joint::right_wrist));
    return !arm_joint(j);
}

}  // namespace

BodyOffenders::BodyOffenders(const Pattern& pattern, const GarmentMesh& mesh, const Eigen::MatrixXd& body_v,
                             const Eigen::MatrixXi& body_faces, const std::vector<int>& dominant,
                             double clearance_m)
    : pattern_(pattern), mesh_(mesh), body_v_(body_v),
      body_n_(core::vertex_normals(body_v, body_faces)),  // area-weighted
      dominant_(dominant), clearance_m_(clearance_m), inside_test_(body_v, body_faces),
      march_(size_t(mesh.cloth.vertex_count()), false) {}

std::vector<bool> BodyOffenders::inside_rows(const Eigen::MatrixX3d& P) const {
    std::vector<bool> in(size_t(P.rows()), false);
    for (int i : inside_test_.inside_indices(P)) in[size_t(i)] = true;
    return in;
}

void BodyOffenders::find(const Eigen::MatrixX3d& X, std::vector<int>* ids, Eigen::MatrixX3d* targets) {
    const int nv = mesh_.cloth.vertex_count();
    std::vector<std::pair<int, Eigen::Vector3d>> list;
    const std::vector<bool> in = inside_rows(X);
    for (int v = 0; v < nv; ++v) {
        const Eigen::Vector3d x = X.row(v).transpose();
        const int b = nearest_vertex(body_v_, x);
        if (!obstacle_for(role_of(pattern_, size_t(mesh_.panel_of_vertex(v))), dominant_[size_t(b)]))
            continue;
        const Eigen::Vector3d p = body_v_.row(b).transpose(), n = body_n_.row(b).transpose();
        const double d = (x - p).dot(n);
        if (in[size_t(v)] || d < 0.5 * clearance_m_) {
            // Inside the body but in front of the nearest surface: a fold (armpit, crotch)
            // or another body part; the target is on the nearest surface, no marching.
            const bool fold = in[size_t(v)] && d > 0;
            march_[size_t(v)] = !fold;
            list.emplace_back(v, fold ? Eigen::Vector3d(p + clearance_m_ * n)
                                      : Eigen::Vector3d(x + (clearance_m_ - d) * n));
        }
    }
    ids->clear();
    *targets = Eigen::MatrixX3d(Eigen::Index(list.size()), 3);
    for (size_t k = 0; k < list.size(); ++k) {
        ids->push_back(list[k].first);
        targets->row(Eigen::Index(k)) = list[k].second.transpose();
    }
}

PushOutResult push_out_of_body(const Pattern& pattern, const GarmentMesh& mesh, const DressingOptions& options,
                               BodyOffenders& offenders, Eigen::MatrixX3d& X) {
    PushOutResult result;
    const int nv = mesh.cloth.vertex_count();
    // Stitched vertex pairs join the ARAP graph, so seams that wrapping closed stay closed.
    // Stitch springs (rest length zero, stiffer than cloth edges: kStitchWeight) pull seams
    // that wrapping or skinning opened towards closing while the garment is pushed out.
    auto edges = mesh_edges(mesh.cloth.faces);
    std::vector<double> edge_weight(edges.size(), 1.0);
    std::vector<bool> zero_rest(edges.size(), false);
    const auto is_sleeve = [&](int v) {
        return role_of(pattern, size_t(mesh.panel_of_vertex(v))) == Role::sleeve;
    };
    for (const auto& st : mesh.stitches) {
        // Sleeve caps start open, down the arm (kSleeveOffsetM): the simulation sews them.
        // Pulled closed here they would drag the sleeve tube off the arm into a flap.
        if (is_sleeve(st[0]) != is_sleeve(st[1])) continue;
        edges.push_back({std::min(st[0], st[1]), std::max(st[0], st[1])});
        edge_weight.push_back(kStitchWeight);
        zero_rest.push_back(true);
    }
    const Eigen::MatrixX3d X0 = X;
    for (const auto& s : mesh.stitches)
        result.wrapped_seam_gap_m = std::max(result.wrapped_seam_gap_m, (X.row(s[0]) - X.row(s[1])).norm());
    std::vector<bool> ever(size_t(nv), false);
    std::vector<int> ids;
    Eigen::MatrixX3d targets;
    for (int it = 0; it < options.max_iterations; ++it) {
        offenders.find(X, &ids, &targets);
        result.iterations = it + 1;
        if (ids.empty()) break;
        for (int v : ids) ever[size_t(v)] = true;
        Eigen::MatrixX3d next = X;
        arap(X0, edges, edge_weight, zero_rest, ids, targets, options.constraint_weight, 2, next);
        guarded_moves(mesh, next, X);
    }
    // Whatever is still inside is projected onto its target (the hard constraint), marching
    // further along the normal where the nearest-vertex target is itself inside (folds of
    // the body such as an armpit).
    offenders.find(X, &ids, &targets);
    Eigen::MatrixX3d projected = X;
    for (size_t k = 0; k < ids.size(); ++k) {
        Eigen::Vector3d x = targets.row(Eigen::Index(k)).transpose();
        const Eigen::Vector3d step =
            0.005 * (x - Eigen::Vector3d(X.row(ids[k]).transpose())).normalized();
        for (int m = 0; m < 40 && offenders.march()[size_t(ids[k])] && offenders.inside_test().inside(x) &&
                        step.allFinite();
             ++m)
            x += step;
        projected.row(ids[k]) = x.transpose();
    }
    guarded_moves(mesh, projected, X);
    result.vertices_pushed = int(std::count(ever.begin(), ever.end(), true));
    return result;
}

// Crossings that wrapping and the push-out left (folds at the neck and shoulders, sleeves
// at the armpit) are separated, each side towards its own layer. Vertices the crossings
// held inside the body are then pushed out (guarded moves count crossings at a vertex's own
// position, not at its stitched group's, so a sleeve cap can cross again: a second
// untangling follows).
UntangleSummary untangle_and_push_out(const GarmentMesh& mesh, const Eigen::MatrixXd& body_v,
                                      const Eigen::MatrixXi& body_faces, const DressingOptions& options,
                                      BodyOffenders& offenders, Eigen::MatrixX3d& X) {
    UntangleSummary summary = untangle_garment(mesh, body_v, body_faces, options.untangle_options, X);
    std::vector<int> ids;
    Eigen::MatrixX3d targets;
    offenders.find(X, &ids, &targets);
    if (!ids.empty()) {
        Eigen::MatrixX3d out = X;
        for (size_t k = 0; k < ids.size(); ++k) out.row(ids[k]) = targets.row(Eigen::Index(k));
        guarded_moves(mesh, out, X);
        const UntangleSummary again = untangle_garment(mesh, body_v, body_faces, options.untangle_options, X);
        summary.self_intersections = again.self_intersections;
        summary.iterations += again.iterations;
        summary.seconds += again.seconds;
    }
    return summary;
}

}  // namespace drape::garment::detail
