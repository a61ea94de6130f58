// The self-contact of one cloth mesh (self_contact.hpp): topology and exclusions, the energy
// of the candidate pairs, contact frames for friction and the conservative step bound. The
// broad phase is in contact_broad_phase.cpp.
#include "self_contact.hpp"
#include "self_contact_internal.hpp"

#include <drape/core/errors.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace drape::cloth::internal {

SelfContact::SelfContact(const Eigen::MatrixX3i& faces, int vertex_count,
                         const std::vector<std::pair<int, int>>& excluded)
    : faces_(faces), vertex_count_(vertex_count), partners_(std::max(vertex_count, 0)) {
    require(vertex_count >= 0, "SelfContact: vertex_count must be >= 0, got ", vertex_count);
    for (int f = 0; f < faces.rows(); ++f) {
        for (int c = 0; c < 3; ++c) {
            const int v = faces(f, c);
            require(v >= 0 && v < vertex_count, "SelfContact: faces(", f, ", ", c, ") = ", v,
                    " is out of range [0, ", vertex_count, ")");
        }
        for (int c = 0; c < 3; ++c) {
            const int a = faces(f, c), b = faces(f, (c + 1) % 3);
            edges_.push_back({std::min(a, b), std::max(a, b)});
        }
    }
    std::sort(edges_.begin(), edges_.end());
    edges_.erase(std::unique(edges_.begin(), edges_.end()), edges_.end());
    for (std::size_t e = 0; e < excluded.size(); ++e) {
        const auto [a, b] = excluded[e];
        require(a >= 0 && a < vertex_count && b >= 0 && b < vertex_count,
                "SelfContact: excluded pair ", e, " = (", a, ", ", b, ") is out of range [0, ",
                vertex_count, ")");
        partners_[a].push_back(b);
        partners_[b].push_back(a);
    }
    for (auto& list : partners_) {
        std::sort(list.begin(), list.end());
        list.erase(std::unique(list.begin(), list.end()), list.end());
    }
}

bool SelfContact::excluded(int a, int b) const {
    return a == b || std::binary_search(partners_[a].begin(), partners_[a].end(), b);
}

std::vector<double> translation_reduced_lengths(const Eigen::MatrixX3d& d) {
    // T = 0 suits cloth resting on a body, T = the mean a falling sheet.
    if (d.rows() == 0) return {};
    const Eigen::RowVector3d mean = d.colwise().mean();
    const Eigen::VectorXd still = d.rowwise().norm();
    const Eigen::VectorXd relative = (d.rowwise() - mean).rowwise().norm();
    const Eigen::VectorXd& best = relative.maxCoeff() < still.maxCoeff() ? relative : still;
    return {best.data(), best.data() + best.size()};
}

std::vector<double> SelfContact::vertex_offsets(const Eigen::MatrixX3d& q) const {
    return translation_reduced_lengths(q - reference_);
}

double SelfContact::energy(const Eigen::MatrixX3d& q, const SelfContactParams& params,
                           Eigen::VectorXd* gradient, std::vector<PairHessian>* hessians,
                           HessianMode mode) const {
    std::string why;
    require(params.is_valid(&why), "SelfContact::energy: ", why);
    require(q.rows() == vertex_count_, "SelfContact::energy: positions have ", q.rows(),
            " rows, expected ", vertex_count_);
    require(!gradient || gradient->size() == 3 * vertex_count_,
            "SelfContact::energy: gradient has size ", gradient ? gradient->size() : 0,
            ", expected ", 3 * vertex_count_);

    // Pass 1: which pairs are within the thickness (distances only). Pass 2 writes each
    // active pair's gradient and block straight into place, so that a caller reusing its
    // `hessians` vector pays no reallocation or page faults.
    const int n = static_cast<int>(candidates_.size());
    const double h2 = params.thickness_m * params.thickness_m;
    // Candidates that were too far to have come within h since find_candidates are skipped
    // without looking at their coordinates (most of them, with a generous radius).
    const std::vector<double> moved = n > 0 ? vertex_offsets(q) : std::vector<double>();
    const double reach = params.thickness_m * (1 + 1e-9);
    std::vector<std::vector<int>> active(chunk_count(n));
    for_each_chunk(n, [&](int c, int begin, int end) {
        for (int i = begin; i < end; ++i) {
            if (reference_distance_[static_cast<std::size_t>(i)] - pair_offset(candidates_[i], moved) >= reach)
                continue;
            const Mat34 x = gather(q, candidates_[i]);
            if (box_gap_squared(candidates_[i].kind, x) < h2 &&
                pair_distance_squared(candidates_[i].kind, x) < h2)
                active[c].push_back(i);
        }
    });
    std::vector<int> order;
    for (const auto& list : active) order.insert(order.end(), list.begin(), list.end());
    const int m = static_cast<int>(order.size());
    const std::size_t offset = hessians ? hessians->size() : 0;
    if (hessians) hessians->resize(offset + m);
    std::vector<Vector12d> gradients(gradient ? m : 0);
    std::vector<double> energies(m);
    core::parallel_for(m, [&](int j) {
        const ContactPair& pair = candidates_[order[j]];
        energies[j] = pair_energy(pair.kind, gather(q, pair), params,
                                  gradient ? &gradients[j] : nullptr,
                                  hessians ? &(*hessians)[offset + j].hessian : nullptr, mode);
        if (hessians) (*hessians)[offset + j].pair = pair;
    }, 1);
    double total = 0;
    for (int j = 0; j < m; ++j) {
        total += energies[j];
        if (gradient)
            for (int k = 0; k < 4; ++k)
                gradient->segment<3>(3 * candidates_[order[j]].v[k]) +=
                    gradients[j].segment<3>(3 * k);
    }
    return total;
}

std::vector<PairFrame> SelfContact::contact_frames(const Eigen::MatrixX3d& q, double thickness_m) const {
    require(q.rows() == vertex_count_, "SelfContact::contact_frames: positions have ", q.rows(),
            " rows, expected ", vertex_count_);
    const double h2 = thickness_m * thickness_m;
    std::vector<PairFrame> frames;
    const std::vector<double> offset = candidates_.empty() ? std::vector<double>() : vertex_offsets(q);
    for (std::size_t i = 0; i < candidates_.size(); ++i) {
        const ContactPair& pair = candidates_[i];
        if (reference_distance_[i] - pair_offset(pair, offset) >= thickness_m * (1 + 1e-9)) continue;
        const Mat34 x = gather(q, pair);
        if (box_gap_squared(pair.kind, x) >= h2) continue;
        DistanceRegime regime;
        const double d2 = pair_distance_squared(pair.kind, x, &regime);
        if (!(d2 < h2 && d2 > 0)) continue;
        PairFrame f;
        f.pair = pair;
        f.weights = regime_weights(regime, x);
        const Eigen::Vector3d r = x * f.weights;
        if (!(r.norm() > 0)) continue;
        f.normal = r.normalized();
        f.distance_m = std::sqrt(d2);
        frames.push_back(f);
    }
    return frames;
}

double SelfContact::covered_radius(const Eigen::MatrixX3d& q) const {
    if (radius_ <= 0 || q.rows() != reference_.rows()) return 0.0;
    const std::vector<double> offsets = vertex_offsets(q);
    const double moved = offsets.empty() ? 0.0 : *std::max_element(offsets.begin(), offsets.end());
    return std::max(0.0, radius_ - 2 * moved);
}

double SelfContact::max_safe_step(const Eigen::MatrixX3d& p, const Eigen::MatrixX3d& dx,
                                  double fraction, double min_separation_m, std::vector<int>* limiting,
                                  double limit_alpha) const {
    require(p.rows() == vertex_count_ && dx.rows() == vertex_count_,
            "SelfContact::max_safe_step: positions/dx have ", p.rows(), "/", dx.rows(),
            " rows, expected ", vertex_count_);
    require(fraction > 0 && fraction <= 1, "SelfContact::max_safe_step: fraction must be in "
            "(0, 1], got ", fraction);
    require(min_separation_m >= 0 && std::isfinite(min_separation_m),
            "SelfContact::max_safe_step: min_separation_m must be >= 0, got ", min_separation_m);
    require(dx.allFinite(), "SelfContact::max_safe_step: dx is not finite");
    const double s = min_separation_m;
    auto floor_of = [&](double d0) {
        return d0 > s ? s + (1 - fraction) * (d0 - s) : (1 - fraction) * d0;
    };

    // Pairs that are not candidates were at distance >= radius; any two points of the
    // cloth approach each other at most at 2 max_v |dx_v − m| per unit α (any m).
    double alpha = 1.0;
    const double covered = covered_radius(p);
    if (vertex_count_ > 0) {
        const Eigen::RowVector3d mean = dx.colwise().mean();
        const double lmax = 2 * (dx.rowwise() - mean).rowwise().norm().maxCoeff();
        // With radius <= s nothing but a rigid motion (up to rounding in the mean) can be
        // certified.
        if (lmax > 1e-12 * dx.rowwise().norm().maxCoeff())
            alpha = covered > s ? std::min(1.0, (covered - floor_of(covered)) / lmax) : 0.0;
    }

    // Per candidate pair: additive CCD. The distance between the primitives moving linearly
    // decreases at most at rate l = max_{a∈A}|Δa − m| + max_{b∈B}|Δb − m| (m: mean of the 4
    // displacements; translating all four by m leaves the distance unchanged), because every
    // point of a primitive moves by a convex combination of its vertices' displacements.
    // From α_i with distance d_i, [α_i, α_i + (d_i − F)/l] is therefore safe; iterate.
    // A pair at distance d0 >= s + l / fraction stays above its floor over all of [0, 1]
    // (below). Per-vertex bounds decide that for most pairs without touching coordinates:
    // d0 >= (distance at find_candidates) − (offsets since), and l <= the largest |dx − T|
    // of each primitive summed, T one common translation of dx (any will do).
    const int n = static_cast<int>(candidates_.size());
    std::vector<double> offset, spread;
    if (n > 0) {
        offset = vertex_offsets(p);
        spread = translation_reduced_lengths(dx);
    }
    std::vector<double> chunk_alpha(chunk_count(n), 1.0);
    // A pair is followed up to the larger of the best step so far and limit_alpha, so that
    // every pair below limit_alpha is known.
    if (!limiting) limit_alpha = 0;
    std::vector<std::vector<int>> chunk_limiting(limiting ? chunk_alpha.size() : 0);
    for_each_chunk(n, [&](int c, int begin, int end) {
        double best = 1.0;
        for (int i = begin; i < end; ++i) {
            const ContactPair& pair = candidates_[i];
            const double d0_bound = reference_distance_[static_cast<std::size_t>(i)] - pair_offset(pair, offset);
            if (d0_bound >= (s + pair_offset(pair, spread) / fraction) * (1 + 1e-9) + 1e-12) continue;
            const Mat34 x0 = gather(p, pair), d = gather(dx, pair);
            const Mat34 rel = d.colwise() - d.rowwise().mean();
            const int na = first_primitive_size(pair.kind);
            double la = 0, lb = 0;
            for (int k = 0; k < 4; ++k) {
                double& bound = k < na ? la : lb;
                bound = std::max(bound, rel.col(k).norm());
            }
            const double l = la + lb;
            if (!(l > 0)) continue;
            // The distance stays >= d0 − α l >= the floor over all of [0, 1] when
            // d0 >= s + l / fraction; the box gap bounds d0 from below.
            const double clear = s + l / fraction;
            if (box_gap_squared(pair.kind, x0) >= clear * clear) continue;
            const double d0 = std::sqrt(pair_distance_squared(pair.kind, x0));
            if (!(d0 > 0)) continue;
            const double floor = floor_of(d0);
            double a = 0, dist = d0;
            for (int iter = 0; iter < 64 && a < std::max(best, limit_alpha); ++iter) {
                const double step = (dist - floor) / l;
                if (!(step > 0)) break;
                a += step;
                if (a >= 1) {
                    a = 1;
                    break;
                }
                dist = std::sqrt(pair_distance_squared(pair.kind, x0 + a * d));
                if (dist - floor < 1e-3 * (d0 - floor)) break;  // converged onto the floor
            }
            best = std::min(best, a);
            if (limiting && a < limit_alpha) chunk_limiting[static_cast<std::size_t>(c)].push_back(i);
        }
        chunk_alpha[c] = best;
    });
    for (double a : chunk_alpha) alpha = std::min(alpha, a);
    if (limiting) {
        limiting->clear();
        for (const auto& list : chunk_limiting) limiting->insert(limiting->end(), list.begin(), list.end());
    }
    return alpha;
}

int SelfContact::remove_closing_motion(const Eigen::MatrixX3d& p, Eigen::MatrixX3d& dx,
                                       const std::vector<int>& pairs, const std::vector<char>& movable,
                                       int sweeps) const {
    require(p.rows() == vertex_count_ && dx.rows() == vertex_count_ &&
                movable.size() == static_cast<std::size_t>(vertex_count_),
            "SelfContact::remove_closing_motion: positions/dx/movable have ", p.rows(), "/", dx.rows(), "/",
            movable.size(), " rows, expected ", vertex_count_);
    const int n = static_cast<int>(candidates_.size());
    for (int i : pairs)
        require(i >= 0 && i < n, "SelfContact::remove_closing_motion: pair ", i, " is out of range [0, ", n, ")");
    // The closest-point weights and normals are those at p: the correction is first order.
    struct Frame {
        Eigen::Vector4d w;
        Eigen::Vector3d n;
        double w2;
    };
    std::vector<Frame> frames;
    std::vector<int> kept;
    for (int i : pairs) {
        const ContactPair& pair = candidates_[static_cast<std::size_t>(i)];
        const Mat34 x = gather(p, pair);
        DistanceRegime regime;
        if (!(pair_distance_squared(pair.kind, x, &regime) > 0)) continue;
        Frame f;
        f.w = regime_weights(regime, x);
        const Eigen::Vector3d r = x * f.w;
        if (!(r.norm() > 0)) continue;
        f.n = r.normalized();
        for (int k = 0; k < 4; ++k)
            if (!movable[static_cast<std::size_t>(pair.v[static_cast<std::size_t>(k)])]) f.w(k) = 0;
        f.w2 = f.w.squaredNorm();
        if (!(f.w2 > 0)) continue;
        frames.push_back(f);
        kept.push_back(i);
    }
    int applied = 0;
    for (int sweep = 0; sweep < sweeps; ++sweep) {
        int changed = 0;
        for (std::size_t j = 0; j < kept.size(); ++j) {
            const ContactPair& pair = candidates_[static_cast<std::size_t>(kept[j])];
            const Frame& f = frames[j];
            Eigen::Vector3d closing = Eigen::Vector3d::Zero();
            for (int k = 0; k < 4; ++k) closing += f.w(k) * dx.row(pair.v[static_cast<std::size_t>(k)]).transpose();
            const double lambda = f.n.dot(closing) / f.w2;
            if (!(lambda < 0)) continue;
            for (int k = 0; k < 4; ++k)
                dx.row(pair.v[static_cast<std::size_t>(k)]) -= (lambda * f.w(k)) * f.n.transpose();
            ++changed;
        }
        applied += changed;
        if (changed == 0) break;
    }
    return applied;
}

int SelfContact::move_pairs_together(Eigen::MatrixX3d& dx, const std::vector<int>& pairs,
                                     const std::vector<char>& movable) const {
    require(dx.rows() == vertex_count_ && movable.size() == static_cast<std::size_t>(vertex_count_),
            "SelfContact::move_pairs_together: dx/movable have ", dx.rows(), "/", movable.size(), " rows, expected ",
            vertex_count_);
    const int n = static_cast<int>(candidates_.size());
    for (int i : pairs)
        require(i >= 0 && i < n, "SelfContact::move_pairs_together: pair ", i, " is out of range [0, ", n, ")");
    // Pairs that share a vertex move as one group: label each corner with its group's root.
    std::vector<int> root(static_cast<std::size_t>(vertex_count_), -1);
    auto top = [&](int v) {
        while (root[static_cast<std::size_t>(v)] != v) v = root[static_cast<std::size_t>(v)];
        return v;
    };
    for (int i : pairs) {
        const ContactPair& pair = candidates_[static_cast<std::size_t>(i)];
        int r = -1;
        for (int v : pair.v) {
            if (root[static_cast<std::size_t>(v)] < 0) root[static_cast<std::size_t>(v)] = v;
            const int t = top(v);
            if (r >= 0 && t != r) {
                const int low = std::min(t, r);
                root[static_cast<std::size_t>(std::max(t, r))] = low;
                r = low;
            } else {
                r = t;
            }
        }
    }
    // Per group: the displacement of a fixed corner if it has one, else the mean.
    std::vector<Eigen::RowVector3d> sum(static_cast<std::size_t>(vertex_count_), Eigen::RowVector3d::Zero());
    std::vector<int> count(static_cast<std::size_t>(vertex_count_), 0);
    std::vector<char> fixed(static_cast<std::size_t>(vertex_count_), 0);
    for (int v = 0; v < vertex_count_; ++v) {
        if (root[static_cast<std::size_t>(v)] < 0) continue;
        const auto g = static_cast<std::size_t>(top(v));
        if (fixed[g]) continue;
        if (!movable[static_cast<std::size_t>(v)]) {
            sum[g] = dx.row(v);
            count[g] = 1;
            fixed[g] = 1;
        } else {
            sum[g] += dx.row(v);
            ++count[g];
        }
    }
    int moved = 0;
    for (int v = 0; v < vertex_count_; ++v) {
        if (root[static_cast<std::size_t>(v)] < 0 || !movable[static_cast<std::size_t>(v)]) continue;
        const auto g = static_cast<std::size_t>(top(v));
        dx.row(v) = sum[g] / count[g];
        ++moved;
    }
    return moved;
}

}  // namespace drape::cloth::internal
