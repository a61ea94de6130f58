// Rig of the mannequin: joint regressor (maximum-entropy weights on a ring of vertices
// around each joint), skinning weights (part labels diffused over the mesh) and tailor
// landmarks (extreme vertices of anatomical regions).
#include "mannequin.hpp"

#include <drape/core/errors.hpp>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

namespace drape::body::detail {
namespace {

using Eigen::Vector3d;

Vector3d row(const Eigen::MatrixXd& V, int i) { return V.row(i).transpose(); }
Vector3d jrow(const JointMatrix& J, Joint j) { return J.row(index(j)).transpose(); }

std::vector<int> vertex_labels(const MannequinImplicit& body, const Eigen::MatrixXd& V) {
    std::vector<int> labels(static_cast<size_t>(V.rows()));
    parallel_for(static_cast<int>(V.rows()),
                 [&](int i) { labels[static_cast<size_t>(i)] = body.bone_at(row(V, i)); });
    return labels;
}

// Positive weights w_i ~ prior_i * exp(lambda . (v_i - target)) with sum 1 and
// sum w_i v_i = target (maximum-entropy coordinates). False if target is outside the hull.
bool max_entropy_weights(const std::vector<Vector3d>& pts, const std::vector<double>& prior,
                         const Vector3d& target, std::vector<double>& w) {
    const size_t n = pts.size();
    if (n < 4) return false;
    double scale = 0.0;
    for (const auto& p : pts) scale = std::max(scale, (p - target).norm());
    if (scale <= 0.0) return false;
    std::vector<Vector3d> d(n);
    for (size_t i = 0; i < n; ++i) d[i] = (pts[i] - target) / scale;
    Vector3d lambda = Vector3d::Zero();
    w.assign(n, 0.0);
    auto evaluate = [&](const Vector3d& lam, Vector3d& grad, Eigen::Matrix3d& hess) {
        double mx = -std::numeric_limits<double>::infinity();
        for (size_t i = 0; i < n; ++i) mx = std::max(mx, lam.dot(d[i]));
        double z = 0.0;
        for (size_t i = 0; i < n; ++i) {
            w[i] = prior[i] * std::exp(lam.dot(d[i]) - mx);
            z += w[i];
        }
        grad.setZero();
        hess.setZero();
        for (size_t i = 0; i < n; ++i) {
            w[i] /= z;
            grad += w[i] * d[i];
            hess += w[i] * d[i] * d[i].transpose();
        }
        hess -= grad * grad.transpose();
        return std::log(z) + mx;
    };
    Vector3d grad;
    Eigen::Matrix3d hess;
    double F = evaluate(lambda, grad, hess);
    for (int it = 0; it < 200; ++it) {
        if (grad.norm() < 1e-14) break;
        const Vector3d step = -(hess + 1e-12 * Eigen::Matrix3d::Identity()).ldlt().solve(grad);
        double alpha = 1.0;
        Vector3d g2;
        Eigen::Matrix3d h2;
        bool accepted = false;
        for (int ls = 0; ls < 40; ++ls) {
            const double F2 = evaluate(lambda + alpha * step, g2, h2);
            if (F2 <= F + 1e-4 * alpha * grad.dot(step) || alpha < 1e-9) {
                lambda += alpha * step;
                F = F2;
                grad = g2;
                hess = h2;
                accepted = true;
                break;
            }
            alpha *= 0.5;
        }
        if (!accepted || lambda.norm() > 400.0) return false;
    }
    evaluate(lambda, grad, hess);
    return grad.norm() * scale < 1e-12;
}

}  // namespace

Eigen::SparseMatrix<double> mannequin_joint_regressor(const MannequinImplicit& body,
                                                      const Eigen::MatrixXd& V,
                                                      const Eigen::MatrixXi& F,
                                                      const JointMatrix& joints,
                                                      int head_top_vertex) {
    const std::vector<int> labels = vertex_labels(body, V);
    // Mean edge length sets the ring thickness.
    double mean_edge = 0.0;
    for (int f = 0; f < F.rows(); ++f) mean_edge += (V.row(F(f, 0)) - V.row(F(f, 1))).norm();
    mean_edge /= std::max<Eigen::Index>(1, F.rows());

    struct Ring {
        Joint joint;
        Vector3d axis;
        double radius;
        std::set<int> bones;
    };
    auto J = [&](Joint j) { return jrow(joints, j); };
    const int pelvis = index(Joint::pelvis), spine = index(Joint::spine), chest = index(Joint::chest);
    const int neck = index(Joint::neck), head = index(Joint::head);
    std::vector<Ring> rings = {
        {Joint::pelvis, Vector3d::UnitY(), 0.22, {pelvis, spine}},
        {Joint::spine, Vector3d::UnitY(), 0.22, {pelvis, spine, chest}},
        {Joint::chest, Vector3d::UnitY(), 0.24,
         {spine, chest, index(Joint::right_clavicle), index(Joint::left_clavicle)}},
        {Joint::neck, J(Joint::head) - J(Joint::neck), 0.11,
         {chest, neck, head, index(Joint::right_clavicle), index(Joint::left_clavicle)}},
        {Joint::head, J(Joint::head) - J(Joint::neck), 0.12, {neck, head}},
    };
    for (int side = 0; side < 2; ++side) {
        const bool left = side == 1;
        const Joint cla = left ? Joint::left_clavicle : Joint::right_clavicle;
        const Joint sho = left ? Joint::left_shoulder : Joint::right_shoulder;
        const Joint elb = left ? Joint::left_elbow : Joint::right_elbow;
        const Joint wri = left ? Joint::left_wrist : Joint::right_wrist;
        const Joint hip = left ? Joint::left_hip : Joint::right_hip;
        const Joint kne = left ? Joint::left_knee : Joint::right_knee;
        const Joint ank = left ? Joint::left_ankle : Joint::right_ankle;
        const Joint toe = left ? Joint::left_toe : Joint::right_toe;
        rings.push_back({cla, J(sho) - J(cla), 0.10, {chest, neck, index(cla), index(sho)}});
        rings.push_back({sho, J(elb) - J(sho), 0.09, {chest, index(cla), index(sho)}});
        rings.push_back({elb, J(wri) - J(elb), 0.07, {index(sho), index(elb)}});
        rings.push_back({wri, J(wri) - J(elb), 0.05, {index(elb), index(wri)}});
        rings.push_back({hip, J(kne) - J(hip), 0.17, {pelvis, spine, index(hip)}});
        rings.push_back({kne, J(ank) - J(kne), 0.09, {index(hip), index(kne)}});
        rings.push_back({ank, J(ank) - J(kne), 0.08, {index(kne), index(ank)}});
        Vector3d fwd = J(toe) - J(ank);
        fwd.y() = 0.0;
        rings.push_back({toe, fwd, 0.07, {index(ank)}});
    }

    std::vector<Eigen::Triplet<double>> triplets;
    triplets.emplace_back(index(Joint::head_top), head_top_vertex, 1.0);
    for (const Ring& ring : rings) {
        const Vector3d j = J(ring.joint);
        const Vector3d axis = ring.axis.normalized();
        double slab = 0.75 * mean_edge;
        double radius = ring.radius;
        bool solved = false;
        std::vector<int> ids;
        std::vector<double> w;
        for (int attempt = 0; attempt < 12 && !solved; ++attempt) {
            ids.clear();
            std::vector<Vector3d> pts;
            std::vector<double> prior;
            for (int i = 0; i < V.rows(); ++i) {
                if (!ring.bones.count(labels[static_cast<size_t>(i)])) continue;
                const Vector3d d = row(V, i) - j;
                const double along = d.dot(axis);
                if (std::abs(along) > slab || d.norm() > radius) continue;
                ids.push_back(i);
                pts.push_back(row(V, i));
                prior.push_back(std::exp(-0.5 * (along / slab) * (along / slab)));
            }
            solved = max_entropy_weights(pts, prior, j, w);
            slab *= 1.4;
            radius *= 1.15;
        }
        if (!solved) {
            throw InvalidInput(drape::detail::concat("mannequin_joint_regressor: no vertex ring encloses joint ",
                                                     kJointNames[static_cast<size_t>(index(ring.joint))]));
        }
        // Drop negligible weights, then renormalise exactly on the kept set.
        std::vector<Vector3d> pts;
        std::vector<double> prior;
        std::vector<int> kept;
        for (size_t k = 0; k < ids.size(); ++k) {
            if (w[k] < 1e-4) continue;
            kept.push_back(ids[k]);
            pts.push_back(row(V, ids[k]));
            prior.push_back(w[k]);
        }
        if (max_entropy_weights(pts, prior, j, w)) ids = kept;
        else {
            // Keep the full ring (already exact).
            std::vector<Vector3d> all;
            std::vector<double> ones;
            for (int i : ids) all.push_back(row(V, i));
            ones.assign(ids.size(), 1.0);
            max_entropy_weights(all, ones, j, w);
        }
        for (size_t k = 0; k < ids.size(); ++k) triplets.emplace_back(index(ring.joint), ids[k], w[k]);
    }
    Eigen::SparseMatrix<double> R(kJointCount, V.rows());
    R.setFromTriplets(triplets.begin(), triplets.end());
    return R;
}

Eigen::SparseMatrix<double> mannequin_skin_weights(const MannequinImplicit& body,
                                                   const Eigen::MatrixXd& V,
                                                   const Eigen::MatrixXi& F) {
    const int nv = static_cast<int>(V.rows());
    const std::vector<int> labels = vertex_labels(body, V);
    std::vector<std::vector<int>> nbr(static_cast<size_t>(nv));
    for (int f = 0; f < F.rows(); ++f)
        for (int q = 0; q < 3; ++q) {
            const int a = F(f, q), b = F(f, (q + 1) % 3);
            nbr[static_cast<size_t>(a)].push_back(b);
            nbr[static_cast<size_t>(b)].push_back(a);
        }
    for (auto& n : nbr) {
        std::sort(n.begin(), n.end());
        n.erase(std::unique(n.begin(), n.end()), n.end());
    }
    Eigen::MatrixXd W = Eigen::MatrixXd::Zero(nv, kJointCount);
    for (int i = 0; i < nv; ++i) W(i, labels[static_cast<size_t>(i)]) = 1.0;

    // Diffusion: blend zones grow like sqrt(iterations) * edge length. The trunk, hips and
    // shoulders get extra iterations for wide, soft transitions.
    auto diffuse = [&](int iterations, const std::vector<char>& movable) {
        Eigen::MatrixXd next = W;
        for (int it = 0; it < iterations; ++it) {
            parallel_for(nv, [&](int i) {
                if (!movable[static_cast<size_t>(i)]) return;
                Eigen::Matrix<double, 1, kJointCount> avg = Eigen::Matrix<double, 1, kJointCount>::Zero();
                for (int j : nbr[static_cast<size_t>(i)]) avg += W.row(j);
                avg /= static_cast<double>(nbr[static_cast<size_t>(i)].size());
                next.row(i) = 0.5 * W.row(i) + 0.5 * avg;
            });
            W.swap(next);
        }
    };
    std::vector<char> all(static_cast<size_t>(nv), 1);
    diffuse(24, all);
    std::vector<char> trunk(static_cast<size_t>(nv), 0);
    const std::set<int> wide = {index(Joint::pelvis),         index(Joint::spine),
                                index(Joint::chest),          index(Joint::right_clavicle),
                                index(Joint::left_clavicle),  index(Joint::right_shoulder),
                                index(Joint::left_shoulder),  index(Joint::right_hip),
                                index(Joint::left_hip),       index(Joint::neck)};
    for (int i = 0; i < nv; ++i) {
        int best = 0;
        W.row(i).maxCoeff(&best);
        trunk[static_cast<size_t>(i)] = wide.count(best) ? 1 : 0;
    }
    diffuse(40, trunk);

    std::vector<Eigen::Triplet<double>> triplets;
    for (int i = 0; i < nv; ++i) {
        std::array<int, kJointCount> order;
        for (int j = 0; j < kJointCount; ++j) order[static_cast<size_t>(j)] = j;
        std::partial_sort(order.begin(), order.begin() + 4, order.end(),
                          [&](int a, int b) { return W(i, a) > W(i, b); });
        double sum = 0.0;
        for (int k = 0; k < 4; ++k) sum += W(i, order[static_cast<size_t>(k)]);
        for (int k = 0; k < 4; ++k) {
            const double w = W(i, order[static_cast<size_t>(k)]) / sum;
            if (w > 1e-6) triplets.emplace_back(i, order[static_cast<size_t>(k)], w);
        }
    }
    Eigen::SparseMatrix<double> S(nv, kJointCount);
    S.setFromTriplets(triplets.begin(), triplets.end());
    // Renormalise after dropping tiny weights.
    Eigen::VectorXd rs = S * Eigen::VectorXd::Ones(kJointCount);
    for (int k = 0; k < S.outerSize(); ++k)
        for (Eigen::SparseMatrix<double>::InnerIterator it(S, k); it; ++it) it.valueRef() /= rs(it.row());
    return S;
}

Landmarks mannequin_landmarks(const MannequinImplicit& body, const Eigen::MatrixXd& V) {
    const std::vector<int> labels = vertex_labels(body, V);
    const MannequinAnatomy& an = body.anatomy();
    const JointMatrix& J = body.joints();
    auto best_vertex = [&](auto&& accept, auto&& score) {
        int best = -1;
        double best_score = -std::numeric_limits<double>::infinity();
        for (int i = 0; i < V.rows(); ++i) {
            const Vector3d p = row(V, i);
            if (!accept(i, p)) continue;
            const double s = score(p);
            if (s > best_score) {
                best_score = s;
                best = i;
            }
        }
        return best;
    };
    auto label_is = [&](int i, std::initializer_list<Joint> js) {
        for (Joint j : js)
            if (labels[static_cast<size_t>(i)] == index(j)) return true;
        return false;
    };
    Landmarks lm;
    lm.head_top = best_vertex([](int, const Vector3d&) { return true; },
                              [](const Vector3d& p) { return p.y(); });
    for (int side = 0; side < 2; ++side) {
        const bool left = side == 1;
        const double s = left ? 1.0 : -1.0;
        const Vector3d sh = jrow(J, left ? Joint::left_shoulder : Joint::right_shoulder);
        const double ax = sh.x() + s * 0.026;
        // Top of the shoulder 2.6 cm lateral of the joint centre (the acromion's tip).
        const int acromion = best_vertex(
            [&](int, const Vector3d& p) {
                return std::abs(p.x() - ax) < 0.012 && std::abs(p.z() - sh.z()) < 0.03 && p.y() > sh.y();
            },
            [&](const Vector3d& p) { return p.y() - 2.0 * std::abs(p.x() - ax); });
        const int bust = best_vertex(
            [&](int i, const Vector3d& p) {
                return s * p.x() > 0.03 && s * p.x() < 0.17 && std::abs(p.y() - an.bust_y) < 0.06 &&
                       label_is(i, {Joint::chest, Joint::spine});
            },
            [](const Vector3d& p) { return p.z(); });
        (left ? lm.left_acromion : lm.right_acromion) = acromion;
        (left ? lm.left_bust : lm.right_bust) = bust;
    }
    lm.crotch = best_vertex(
        [](int, const Vector3d& p) { return std::abs(p.x()) < 0.015 && p.y() > 0.6 && p.y() < 1.0; },
        [](const Vector3d& p) { return -p.y(); });
    lm.navel = best_vertex(
        [&](int, const Vector3d& p) {
            return p.z() > 0 && std::abs(p.x()) < 0.02 && std::abs(p.y() - an.navel_y) < 0.02;
        },
        [&](const Vector3d& p) { return -(std::abs(p.x()) + std::abs(p.y() - an.navel_y)); });
    // Buttock: the level of the cheeks' maximum protrusion, taken on the midline.
    const int cheek = best_vertex(
        [](int, const Vector3d& p) { return p.z() < 0 && std::abs(p.x()) < 0.15 && p.y() > 0.78 && p.y() < 1.0; },
        [](const Vector3d& p) { return -p.z(); });
    const double buttock_y = cheek >= 0 ? V(cheek, 1) : an.buttock_y;
    lm.buttock = best_vertex(
        [&](int, const Vector3d& p) {
            return p.z() < 0 && std::abs(p.x()) < 0.015 && std::abs(p.y() - buttock_y) < 0.02;
        },
        [&](const Vector3d& p) { return -std::abs(p.y() - buttock_y) - 0.1 * std::abs(p.x()); });
    const double thigh_y = an.furrow_y - 0.02;
    lm.right_thigh = best_vertex(
        [&](int i, const Vector3d& p) {
            return p.x() < -0.03 && std::abs(p.y() - thigh_y) < 0.012 &&
                   label_is(i, {Joint::right_hip, Joint::pelvis});
        },
        [](const Vector3d& p) { return -p.z(); });
    lm.right_calf = best_vertex(
        [&](int i, const Vector3d& p) {
            return p.x() < 0 && std::abs(p.y() - an.calf_y) < 0.012 && label_is(i, {Joint::right_knee});
        },
        [](const Vector3d& p) { return -p.z(); });
    return lm;
}

}  // namespace drape::body::detail
