// Initial garment registration: rigid alignment, skinning and interpenetration removal.
#include <drape/garment/dressing.hpp>
#include <drape/garment/mesh_inside.hpp>

#include "dressing_internal.hpp"

#include <drape/core/errors.hpp>

#include <Eigen/SVD>
#include <Eigen/SparseCholesky>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <set>
#include <sstream>

namespace drape::garment {

namespace {

using body::Joint;
using body::index;
constexpr double kStitchWeight = 20.0;  // ARAP weight of a stitch relative to a cloth edge

// Nearest body vertex (brute force over the body, parallel-free and exact).
int nearest_vertex(const Eigen::MatrixXd& V, const Eigen::Vector3d& p) {
    int best = 0;
    double d = 1e300;
    for (Eigen::Index i = 0; i < V.rows(); ++i) {
        const double e = (V.row(i).transpose() - p).squaredNorm();
        if (e < d) d = e, best = int(i);
    }
    return best;
}

Eigen::MatrixXd vertex_normals(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
    Eigen::MatrixXd N = Eigen::MatrixXd::Zero(V.rows(), 3);
    for (Eigen::Index f = 0; f < F.rows(); ++f) {
        const Eigen::Vector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
        const Eigen::Vector3d n = (b - a).cross(c - a);  // area-weighted, outward (CCW outside)
        for (int k = 0; k < 3; ++k) N.row(F(f, k)) += n.transpose();
    }
    for (Eigen::Index i = 0; i < N.rows(); ++i) N.row(i).normalize();
    return N;
}

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

}  // namespace

bool DressingOptions::is_valid(std::string* why) const {
    auto fail = [&](const std::string& t) {
        if (why) *why = t;
        return false;
    };
    if (!(clearance_m > 0 && clearance_m <= 0.1))
        return fail("DressingOptions::clearance_m = " + std::to_string(clearance_m) + " must be in (0, 0.1] m");
    if (max_iterations < 1)
        return fail("DressingOptions::max_iterations = " + std::to_string(max_iterations) + " must be >= 1");
    if (!(constraint_weight > 0))
        return fail("DressingOptions::constraint_weight = " + std::to_string(constraint_weight) + " must be > 0");
    return true;
}

std::string DressingSummary::brief_report() const {
    std::ostringstream os;
    os << (usable() ? "dressed" : "dressing NOT usable") << ": " << vertices_inside
       << " vertices inside the body, " << vertices_pushed << " pushed, " << iterations
       << " round(s), max seam gap " << 100 * max_seam_gap_m << " cm (" << 100 * wrapped_seam_gap_m
       << " cm before push-out), alignment rms "
       << alignment_rms_m << " m, " << seconds << " s";
    if (!message.empty()) os << " (" << message << ")";
    return os.str();
}

std::vector<Joint> garment_skeleton_joints(const Pattern& pattern) {
    std::set<int> ids = {index(Joint::pelvis), index(Joint::spine)};
    for (const PanelPlacement& p : pattern.placements) {
        switch (p.body_part) {
            case BodyPart::front_torso:
            case BodyPart::back_torso:
                for (Joint j : {Joint::chest, Joint::neck}) ids.insert(index(j));
                break;
            case BodyPart::left_sleeve:
                for (Joint j : {Joint::left_shoulder, Joint::left_elbow}) ids.insert(index(j));
                break;
            case BodyPart::right_sleeve:
                for (Joint j : {Joint::right_shoulder, Joint::right_elbow}) ids.insert(index(j));
                break;
            case BodyPart::left_leg:
                for (Joint j : {Joint::left_hip, Joint::left_knee, Joint::left_ankle}) ids.insert(index(j));
                break;
            case BodyPart::right_leg:
                for (Joint j : {Joint::right_hip, Joint::right_knee, Joint::right_ankle}) ids.insert(index(j));
                break;
        }
    }
    std::vector<Joint> out;
    for (int i : ids) out.push_back(static_cast<Joint>(i));
    return out;
}

Eigen::Isometry3d rigid_align(const Eigen::MatrixX3d& q, const Eigen::MatrixX3d& t) {
    require(q.rows() == t.rows() && q.rows() >= 1, "rigid_align: q has ", q.rows(),
            " rows and t has ", t.rows(), " (need equal, >= 1)");
    const Eigen::RowVector3d cq = q.colwise().mean(), ct = t.colwise().mean();
    const Eigen::Matrix3d H = (q.rowwise() - cq).transpose() * (t.rowwise() - ct);
    Eigen::JacobiSVD<Eigen::Matrix3d> svd(H, Eigen::ComputeFullU | Eigen::ComputeFullV);
    Eigen::Matrix3d D = Eigen::Matrix3d::Identity();
    D(2, 2) = (svd.matrixV() * svd.matrixU().transpose()).determinant() < 0 ? -1.0 : 1.0;
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = svd.matrixV() * D * svd.matrixU().transpose();
    T.translation() = ct.transpose() - T.linear() * cq.transpose();
    return T;
}

DressingSummary dress_garment(const Pattern& pattern, const GarmentMesh& mesh,
                              const body::BodyModel& model, const body::ShapedBody& shaped,
                              const body::Pose& pose, const DressingOptions& options,
                              Eigen::MatrixX3d& positions) {
    const auto t0 = std::chrono::steady_clock::now();
    std::string why;
    require(options.is_valid(&why), "dress_garment: ", why);
    require(pose.is_valid(&why), "dress_garment: pose: ", why);
    require(shaped.vertices.rows() == model.vertex_count() && shaped.vertices.cols() == 3,
            "dress_garment: shaped body has ", shaped.vertices.rows(), " vertices, the model ",
            model.vertex_count());
    const int nv = mesh.cloth.vertex_count();
    require(nv > 0 && mesh.panel_of_vertex.size() == nv && mesh.panel_point_cm.rows() == nv,
            "dress_garment: the garment mesh is empty or inconsistent");
    for (int v = 0; v < nv; ++v)
        require(mesh.panel_of_vertex(v) >= 0 && mesh.panel_of_vertex(v) < int(pattern.panels.size()),
                "dress_garment: mesh vertex ", v, " names panel ", mesh.panel_of_vertex(v),
                " not in the pattern");
    DressingSummary summary;

    // 1. The garment template lives in its own frame (root joint at the origin); T aligns
    //    its skeleton Q_c with the body's rest joints Q_h.
    const detail::Joints& rest = shaped.joints;
    const Eigen::RowVector3d root = rest.row(index(Joint::pelvis));
    const detail::Joints garment_joints = rest.rowwise() - root;
    const std::vector<Joint> skeleton = garment_skeleton_joints(pattern);
    Eigen::MatrixX3d q(skeleton.size(), 3), t(skeleton.size(), 3);
    for (size_t i = 0; i < skeleton.size(); ++i) {
        q.row(Eigen::Index(i)) = garment_joints.row(index(skeleton[i]));
        t.row(Eigen::Index(i)) = rest.row(index(skeleton[i]));
    }
    const Eigen::Isometry3d T = rigid_align(q, t);
    summary.alignment_rms_m = std::sqrt(((T * q.transpose()).transpose() - t).rowwise().squaredNorm().mean());
    // Torso sections of the rest body (garment frame), in 1 cm height bins: bounding-box
    // half extents of the vertices skinned mainly to the trunk joints.
    const Eigen::MatrixXd rest_local = shaped.vertices.rowwise() - root;
    const double y_lo = rest_local.col(1).minCoeff(), bin = 0.01;
    const int nbins = int(std::ceil((rest_local.col(1).maxCoeff() - y_lo) / bin)) + 1;
    std::vector<Eigen::Vector4d> box(size_t(nbins), Eigen::Vector4d(1e300, -1e300, 1e300, -1e300));
    {
        const Eigen::SparseMatrix<double, Eigen::RowMajor> Wr = model.skin_weights;
        const std::set<int> trunk = {index(Joint::pelvis), index(Joint::spine), index(Joint::chest),
                                     index(Joint::neck), index(Joint::left_clavicle),
                                     index(Joint::right_clavicle)};
        for (Eigen::Index v = 0; v < rest_local.rows(); ++v) {
            int best = -1;
            double w = 0;
            for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(Wr, v); it; ++it)
                if (it.value() > w) w = it.value(), best = int(it.col());
            if (!trunk.count(best)) continue;
            Eigen::Vector4d& b = box[size_t((rest_local(v, 1) - y_lo) / bin)];
            b << std::min(b[0], rest_local(v, 0)), std::max(b[1], rest_local(v, 0)),
                std::min(b[2], rest_local(v, 2)), std::max(b[3], rest_local(v, 2));
        }
    }
    const auto torso_section = [&](double y) {
        const int k = std::clamp(int((y - y_lo) / bin), 0, nbins - 1);
        for (int d = 0; d < nbins; ++d)  // nearest filled bin
            for (int kk : {k - d, k + d})
                if (kk >= 0 && kk < nbins && box[size_t(kk)][0] < box[size_t(kk)][1])
                    return Eigen::Vector2d(0.5 * (box[size_t(kk)][1] - box[size_t(kk)][0]),
                                           0.5 * (box[size_t(kk)][3] - box[size_t(kk)][2]));
        return Eigen::Vector2d(0.15, 0.1);
    };
    Eigen::MatrixX3d X = detail::wrap_panels(pattern, mesh, garment_joints, torso_section);
    X = (T * X.transpose()).transpose();

    // 2. Linear blend skinning with the weights of the nearest rest body vertex.
    const body::PosedSkeleton skel = body::forward_kinematics(rest, pose);
    const Eigen::SparseMatrix<double, Eigen::RowMajor> W = model.skin_weights;
    for (int v = 0; v < nv; ++v) {
        const int b = nearest_vertex(shaped.vertices, X.row(v).transpose());
        Eigen::Vector3d p = Eigen::Vector3d::Zero();
        double sum = 0;
        for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(W, b); it; ++it) {
            p += it.value() * (skel.skinning[size_t(it.col())] * Eigen::Vector3d(X.row(v).transpose()));
            sum += it.value();
        }
        if (sum > 0) X.row(v) = (p / sum).transpose();
    }

    // 3. Interpenetration removal: push offending vertices out along the body normal and
    //    let an as-rigid-as-possible deformation carry their neighbours.
    const Eigen::MatrixXd body_v = body::pose_body(model, shaped, pose).vertices;
    const Eigen::MatrixXd body_n = vertex_normals(body_v, model.faces);
    const MeshInsideTest inside_test(body_v, model.faces);
    // Stitched vertex pairs join the ARAP graph, so seams that wrapping closed stay closed.
    // Stitch springs (rest length zero, stiffer than cloth edges: kStitchWeight) pull seams
    // that wrapping or skinning opened towards closing while the garment is pushed out.
    auto edges = detail::mesh_edges(mesh.cloth.faces);
    std::vector<double> edge_weight(edges.size(), 1.0);
    std::vector<bool> zero_rest(edges.size(), false);
    for (const auto& st : mesh.stitches) {
        edges.push_back({std::min(st[0], st[1]), std::max(st[0], st[1])});
        edge_weight.push_back(kStitchWeight);
        zero_rest.push_back(true);
    }
    const Eigen::MatrixX3d X0 = X;
    for (const auto& s : mesh.stitches)
        summary.wrapped_seam_gap_m = std::max(summary.wrapped_seam_gap_m, (X.row(s[0]) - X.row(s[1])).norm());
    std::vector<bool> ever(size_t(nv), false);
    auto offenders = [&](std::vector<int>* ids, Eigen::MatrixX3d* targets) {
        std::vector<std::pair<int, Eigen::Vector3d>> list;
        const std::vector<bool> in = inside_test.inside(X);
        for (int v = 0; v < nv; ++v) {
            const Eigen::Vector3d x = X.row(v).transpose();
            const int b = nearest_vertex(body_v, x);
            const Eigen::Vector3d p = body_v.row(b).transpose(), n = body_n.row(b).transpose();
            const double d = (x - p).dot(n);
            if (in[size_t(v)] || d < 0.5 * options.clearance_m)
                list.emplace_back(v, in[size_t(v)] && d > 0 ? Eigen::Vector3d(p + options.clearance_m * n)
                                                            : Eigen::Vector3d(x + (options.clearance_m - d) * n));
        }
        ids->clear();
        *targets = Eigen::MatrixX3d(Eigen::Index(list.size()), 3);
        for (size_t k = 0; k < list.size(); ++k) {
            ids->push_back(list[k].first);
            targets->row(Eigen::Index(k)) = list[k].second.transpose();
        }
    };
    std::vector<int> ids;
    Eigen::MatrixX3d targets;
    for (int it = 0; it < options.max_iterations; ++it) {
        offenders(&ids, &targets);
        summary.iterations = it + 1;
        if (ids.empty()) break;
        for (int v : ids) ever[size_t(v)] = true;
        arap(X0, edges, edge_weight, zero_rest, ids, targets, options.constraint_weight, 2, X);
    }
    // Whatever is still inside is projected onto its target (the hard constraint), marching
    // further along the normal where the nearest-vertex target is itself inside (folds of
    // the body such as an armpit).
    offenders(&ids, &targets);
    for (size_t k = 0; k < ids.size(); ++k) {
        Eigen::Vector3d x = targets.row(Eigen::Index(k)).transpose();
        const Eigen::Vector3d step =
            0.005 * (x - Eigen::Vector3d(X.row(ids[k]).transpose())).normalized();
        for (int m = 0; m < 40 && inside_test.inside(x) && step.allFinite(); ++m) x += step;
        X.row(ids[k]) = x.transpose();
    }
    summary.vertices_pushed = int(std::count(ever.begin(), ever.end(), true));
    const std::vector<bool> in = inside_test.inside(X);
    summary.vertices_inside = int(std::count(in.begin(), in.end(), true));
    for (const auto& s : mesh.stitches)
        summary.max_seam_gap_m = std::max(summary.max_seam_gap_m, (X.row(s[0]) - X.row(s[1])).norm());
    if (!summary.usable()) {
        summary.termination = DressingTermination::penetration_left;
        summary.message = std::to_string(summary.vertices_inside) + " garment vertices remain inside the body";
    }
    positions = X;
    summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return summary;
}

}  // namespace drape::garment
