// The Newton minimiser of the incremental potential: projected Newton with a sparse
// Cholesky factorisation, Levenberg-style shifts when the matrix is not positive definite,
// and a backtracking line search from the largest contact-safe step.
#include "simulator_impl.hpp"

#include <drape/core/errors.hpp>

#include <algorithm>
#include <iterator>
#include <cmath>

namespace drape::cloth {

namespace {

// Self-contact candidates are collected this many thicknesses beyond the radius a Newton
// iteration needs, so that they can be reused while the cloth moves less than half of it.
constexpr double kCandidateMargin = 1.0;
// When self-contact cuts the step under this fraction of the obstacle's bound (two layers
// pressed together by the body, often sliding over each other), the pairs that hold it back
// are released from the direction until the step is at least this long again, in at most
// kReleaseRounds rounds (docs/self-contact.md, "Pressed layers").
constexpr double kReleaseBelow = 0.5;
constexpr int kReleaseRounds = 8;

}  // namespace

StepSummary Simulator::Impl::minimise(Eigen::MatrixX3d& p, const Eigen::MatrixX3d& target,
                                      double inertia_weight, double relative_tolerance) {
    const auto t_start = Clock::now();
    StepSummary s;
    const double weight = mass.maxCoeff() * options.gravity_m_per_s2.norm();
    s.tolerance_n = weight > 0 ? relative_tolerance * weight : 1e-12;
    const Eigen::MatrixX3d p_start = p;
    const double h = options.contact_thickness_m;
    const bool use_self = options.self_contact;
    std::vector<internal::PairHessian> pair_hessians;
    double last_move = 0;
    // The last iteration was a full, unregularised Newton step that moved no vertex farther
    // than step_displacement_tolerance_m: the step may end here (confirmed below).
    bool small_full_step = false;
    bool renew_next = false;
    // How far the cloth moves relative to itself (up to a common translation, which brings
    // no two of its points closer): what the self-contact candidates must cover.
    auto spread = [](const Eigen::MatrixX3d& d) {
        const std::vector<double> lengths = internal::translation_reduced_lengths(d);
        return lengths.empty() ? 0.0 : *std::max_element(lengths.begin(), lengths.end());
    };
    double last_spread = 0;
    const double v_spread = inertia_weight > 0 ? spread(v) : 0.0;

    auto total = [&](const Eigen::MatrixX3d& q, Eigen::VectorXd* g, double* values,
                     std::vector<internal::PairHessian>* ph) {
        return incremental_potential(q, target, inertia_weight, g, values, ph);
    };
    // Largest per-vertex move the inertia term alone would answer the gradient with.
    auto inertia_scaled_residual = [&](const Eigen::VectorXd& g, double w) {
        double r = 0;
        for (Eigen::Index i = 0; i < mass.size(); ++i) {
            if (!(mass(i) > 0)) continue;
            double n2 = 0;
            for (int c = 0; c < 3; ++c)
                if (dof(static_cast<int>(i), c) >= 0) n2 += g(3 * i + c) * g(3 * i + c);
            r = std::max(r, std::sqrt(n2) / (w * mass(i)));
        }
        return r;
    };
    auto free_inf_norm = [&](const Eigen::VectorXd& g) {
        double n = 0;
        for (std::size_t k = 0; k < dof_index.size(); ++k)
            if (dof_index[k] >= 0) n = std::max(n, std::abs(g(static_cast<Eigen::Index>(k))));
        return n;
    };

    if (!pattern_ready) build_pattern();
    Eigen::SparseMatrix<double> hessian = pattern;
    Eigen::VectorXd g;
    double shift = 0;  // Levenberg-style diagonal shift, × mass-like scale
    int nonconvex_iterations = 0;  // time-step iterations that needed a PSD fallback or shift
    const double mass_scale = mass.maxCoeff();
    for (int it = 0;; ++it) {
        auto t0 = Clock::now();
        // Dynamic steps look the stretching table up once, at the step's start (like ArcSim's
        // one linearised solve per step): with k frozen over the step the incremental
        // potential is one fixed function and Newton converges quadratically, where
        // re-freezing k every iteration can cycle between two strain states.
        // The static solve renews the stiffness and the contact planes every few iterations
        // (outer fixed-point iterations around Newton on a fixed energy).
        const bool renew = it == 0 || (inertia_weight == 0 && (it % 8 == 0 || renew_next));
        renew_next = false;
        if (renew) {
            refresh_stiffness(p, inertia_weight > 0 && options.relax_stretching_stiffness);
            planes.clear();
            plane_of_vertex.assign(static_cast<std::size_t>(p.rows()), {-1, -1});
        }
        auto tc = Clock::now();
        update_obstacle_contacts(p);
        // The obstacle friction is lagged at the step's start (contact normal and normal
        // force); a vertex that leaves the contact layer during the step loses its friction
        // at the next iteration. Kept, the friction of a contact that no longer exists
        // pumps energy into vertices at the edge of the layer: a period-2 chatter that
        // never came to rest (docs/cloth.md). Contacts made during the step get their
        // friction at the next step, as before.
        if (it == 0) {
            lag_friction();
        } else {
            drop_released_friction();
        }
        // Self-contact candidates within h + twice the expected motion of this iteration
        // (the last step's, or the velocity's over the step, both less any common
        // translation of the whole cloth): the energy ignores pairs
        // beyond h, and the step bound below shortens any step that could bring an
        // uncollected pair (farther than the radius now) within reach.
        // The candidates are reused while they still cover that radius at p (vertices moved
        // less than half the extra margin since they were collected).
        if (use_self) {
            double expected = last_spread;
            if (it == 0) expected = step_dt > 0 ? v_spread * step_dt : 0.0;
            const double needed = h + 2 * std::min(expected, 4 * h) + 1e-9;
            if (self_contact.covered_radius(p) < needed)
                self_contact.find_candidates(p, needed + kCandidateMargin * h);
        }
        if (it == 0) lag_pair_friction(p);
        // A moving body carries the cloth it holds by friction (FrictionContact::surface_motion):
        // Newton starts with those vertices moved along with it, as far as that is collision-safe.
        // From where they were, the friction's slip starts in its sliding regime, whose Hessian
        // is zero along the slip, and Newton overshot into the sticking regime and back for
        // every iteration of the step (a skirt on a body gliding at 1.2 m/s used all 8 of every
        // step and fell 11 cm behind).
        if (it == 0 && inertia_weight > 0 && !friction.empty()) p += start_carry(p);
        const double contact_seconds = seconds_since(tc);
        s.seconds_contact += contact_seconds;
        if (small_full_step) {
            // Confirm before assembling and factoring again: the correction Newton would still
            // make is about |g_i| / (m_i / dt²) per vertex, a bound where the step's matrix is
            // the inertia plus a positive semi-definite part. Where Newton is in its quadratic
            // regime this is far below the step just taken; where the energy is much stiffer
            // than the step's model (smoothed friction sticking at the step's start) it is
            // not, and Newton goes on.
            const auto t_check = Clock::now();
            Eigen::VectorXd g_now;
            const double e_now = total(p, &g_now, nullptr, nullptr);
            const bool done = std::isfinite(e_now) && g_now.allFinite() &&
                              inertia_scaled_residual(g_now, inertia_weight) <= options.step_displacement_tolerance_m;
            s.seconds_assembly += seconds_since(t_check);
            if (done) {
                s.energy_j = e_now;
                s.gradient_inf_norm_n = free_inf_norm(g_now);
                s.newton_iterations = it;
                s.termination = StepTermination::converged;
                break;
            }
            small_full_step = false;
        }
        hessian_mode = inertia_weight > 0 ? options.step_hessian : options.static_hessian;
        std::fill(hessian.valuePtr(), hessian.valuePtr() + hessian.nonZeros(), 0.0);
        pair_hessians.clear();
        const double e = total(p, &g, hessian.valuePtr(), &pair_hessians);
        s.seconds_assembly += seconds_since(t0) - contact_seconds;
        s.energy_j = e;
        s.gradient_inf_norm_n = free_inf_norm(g);
        // Without gravity there is no natural force scale: take the initial unbalance.
        if (it == 0 && weight <= 0)
            s.tolerance_n = std::max(1e-12, relative_tolerance * s.gradient_inf_norm_n);
        s.newton_iterations = it;
        s.self_contact_pairs = static_cast<int>(pair_hessians.size());
        if (!std::isfinite(e) || !g.allFinite()) {
            p = p_start;
            s.termination = StepTermination::non_finite;
            s.message = "energy or gradient is not finite";
            break;
        }
        if (s.gradient_inf_norm_n <= s.tolerance_n) {
            // The static solve converged on a frozen stiffness: confirm with a fresh one.
            if (inertia_weight == 0 && !renew) {
                renew_next = true;
                continue;
            }
            s.termination = StepTermination::converged;
            break;
        }
        if (it >= options.max_newton_iterations) {
            s.termination = StepTermination::max_iterations;
            break;
        }
        if (options.on_iteration && !options.on_iteration(it, s.gradient_inf_norm_n)) {
            s.termination = StepTermination::cancelled;
            s.message = "cancelled by the caller";
            break;
        }
        t0 = Clock::now();
        Eigen::VectorXd rhs(free_dofs);
        for (std::size_t k = 0; k < dof_index.size(); ++k)
            if (dof_index[k] >= 0) rhs(dof_index[k]) = -g(static_cast<Eigen::Index>(k));
        Eigen::SparseMatrix<double> full;
        bool use_full = false;
        // Inertia on the diagonal; self-contact blocks in a second matrix with their own
        // (growing) pattern, summed into `full`.
        // The static solve has no inertia; a mass-proportional damping M/τ² in the Newton
        // matrix (Levenberg-Marquardt) keeps its steps bounded along zero-energy modes (a
        // skirt turning about a round body) without changing the equilibrium it finds.
        const double newton_weight =
            inertia_weight > 0 ? inertia_weight
                               : 1 / (options.static_damping_time_s * options.static_damping_time_s);
        auto add_inertia_and_pairs = [&]() {
            for (Eigen::Index i = 0; i < p.rows(); ++i)
                for (int c = 0; c < 3; ++c) {
                    const int d = dof(static_cast<int>(i), c);
                    if (d >= 0) hessian.valuePtr()[diagonal_slots[static_cast<std::size_t>(d)]] += newton_weight * mass(i);
                }
            const bool has_pairs = !pair_hessians.empty();
            if (has_pairs && update_contact_blocks(pair_hessians)) solver.reset();
            if (has_pairs || analysed_with_contacts) {
                Eigen::SparseMatrix<double> extra = contact_pattern;
                std::fill(extra.valuePtr(), extra.valuePtr() + extra.nonZeros(), 0.0);
                for (const internal::PairHessian& ph : pair_hessians)
                    for (int a = 0; a < 4; ++a)
                        for (int b = 0; b < 4; ++b) {
                            const int va = ph.pair.v[static_cast<std::size_t>(a)], vb = ph.pair.v[static_cast<std::size_t>(b)];
                            if (va == vb) continue;  // vertex blocks are in the main pattern
                            for (int ca = 0; ca < 3; ++ca)
                                for (int cb = 0; cb < 3; ++cb) {
                                    const int r = dof(va, ca), c = dof(vb, cb);
                                    if (r < 0 || c < 0) continue;
                                    const int slot = slot_in(extra, r, c);
                                    if (slot >= 0) extra.valuePtr()[slot] += ph.hessian(3 * a + ca, 3 * b + cb);
                                }
                        }
                // Same-vertex blocks of the pairs (a == b) go into the main pattern.
                for (const internal::PairHessian& ph : pair_hessians)
                    for (int a = 0; a < 4; ++a)
                        for (int b = 0; b < 4; ++b) {
                            const int va = ph.pair.v[static_cast<std::size_t>(a)];
                            if (va != ph.pair.v[static_cast<std::size_t>(b)]) continue;
                            for (int k = 0; k < 9; ++k) {
                                const int slot = vertex_slots[static_cast<std::size_t>(9 * va + k)];
                                if (slot >= 0)
                                    hessian.valuePtr()[slot] += ph.hessian(3 * a + k % 3, 3 * b + k / 3);
                            }
                        }
                full = hessian + extra;
                if (!analysed_with_contacts) solver.reset();
                analysed_with_contacts = true;
            }
            use_full = has_pairs || analysed_with_contacts;
        };
        add_inertia_and_pairs();
        Eigen::VectorXd step;
        for (int attempt = 0; attempt < 12; ++attempt) {
            Eigen::SparseMatrix<double> shifted;
            if (shift > 0) {
                shifted = use_full ? full : hessian;
                for (Eigen::Index i = 0; i < p.rows(); ++i)
                    for (int c = 0; c < 3; ++c) {
                        const int d = dof(static_cast<int>(i), c);
                        if (d >= 0) shifted.coeffRef(d, d) += shift * mass(i) / mass_scale;
                    }
            }
            const Eigen::SparseMatrix<double>& base = use_full ? full : hessian;
            const Eigen::SparseMatrix<double>& matrix = shift > 0 ? shifted : base;
            ++s.factorisations;
            if (solver.factorize(matrix)) {
                step = solver.solve(rhs);
                if (step.allFinite() && step.dot(rhs) > 0) break;
            }
            step.resize(0);
            if (hessian_mode == HessianMode::exact) {
                // Indefinite: assemble the projected (PSD) element Hessians instead.
                hessian_mode = HessianMode::projected_psd;
                std::fill(hessian.valuePtr(), hessian.valuePtr() + hessian.nonZeros(), 0.0);
                pair_hessians.clear();
                Eigen::VectorXd unused;
                total(p, &unused, hessian.valuePtr(), &pair_hessians);
                add_inertia_and_pairs();
                ++s.regularised_factorisations;
                continue;
            }
            if (shift > 0) {
                shift *= 10;
            } else {
                const Eigen::VectorXd diagonal = (use_full ? full : hessian).diagonal();
                shift = 1e-8 * diagonal.cwiseAbs().maxCoeff() + 1e-12;
            }
            ++s.regularised_factorisations;
        }
        s.seconds_solve += seconds_since(t0);
        if (step.size() == 0) {
            s.termination = StepTermination::line_search_failed;
            s.message = "no positive-definite regularisation of the Hessian found";
            break;
        }
        const bool unregularised = shift == 0 && hessian_mode == HessianMode::exact;
        if (inertia_weight > 0 && options.step_hessian == HessianMode::exact && !unregularised)
            ++nonconvex_iterations;
        shift /= 10;  // let it decay once things are well conditioned
        if (shift < 1e-14) shift = 0;

        // Backtracking (Armijo) line search on the frozen model, from the largest step that
        // keeps contacts safe (no crossing of the obstacle or of another cloth layer).
        Eigen::MatrixX3d dx = Eigen::MatrixX3d::Zero(p.rows(), 3);
        for (Eigen::Index i = 0; i < p.rows(); ++i)
            for (int c = 0; c < 3; ++c) {
                const int d = dof(static_cast<int>(i), c);
                if (d >= 0) dx(i, c) = step(d);
            }
        tc = Clock::now();
        // The energy's directional derivative along a per-vertex step (rhs is minus the gradient).
        const auto slope_along = [&](const Eigen::MatrixX3d& v) {
            double sl = 0;
            for (Eigen::Index i = 0; i < p.rows(); ++i)
                for (int c = 0; c < 3; ++c) {
                    const int d = dof(static_cast<int>(i), c);
                    if (d >= 0) sl -= v(i, c) * rhs(d);
                }
            return sl;
        };
        double slope = -step.dot(rhs);
        if (options.strict_body_contact) {
            // Vertices falling onto the body stop short of it on their own; the clamped
            // direction is taken only while it still descends.
            Eigen::MatrixX3d clamped = dx;
            if (clamp_free_approach(p, clamped)) {
                const double clamped_slope = slope_along(clamped);
                if (clamped_slope < 0) {
                    dx.swap(clamped);
                    slope = clamped_slope;
                }
            }
        }
        const double obstacle_alpha = obstacle_step_bound(p, dx);
        double alpha = obstacle_alpha;
        bool released = false;
        Eigen::MatrixX3d released_dx;
        if (use_self) {
            alpha = std::min(alpha, self_contact.max_safe_step(p, dx * obstacle_alpha, 0.9) * obstacle_alpha);
            if (alpha < kReleaseBelow * obstacle_alpha) {
                // Two layers pressed together: a global step length stops every vertex of the
                // garment with them. Take out the closing motion of the pairs that hold the
                // step under kReleaseBelow of the obstacle's bound (more pairs each round, as
                // the next ones come to hold it), and keep the direction that certifies the
                // longest step while it still descends.
                std::vector<char> movable(static_cast<std::size_t>(p.rows()), 1);
                for (Eigen::Index i = 0; i < p.rows(); ++i)
                    for (int c = 0; c < 3; ++c)
                        if (dof(static_cast<int>(i), c) < 0) movable[static_cast<std::size_t>(i)] = 0;
                // Pairs that still hold the step after losing their closing motion (layers
                // sliding over each other at a tiny gap) move as one instead.
                std::vector<int> holding, together, more, merged;
                Eigen::MatrixX3d trial_dx = dx;
                double trial_alpha = alpha;
                for (int round = 0; round < kReleaseRounds && trial_alpha < kReleaseBelow * obstacle_alpha; ++round) {
                    self_contact.max_safe_step(p, trial_dx * obstacle_alpha, 0.9, 0.0, &more, kReleaseBelow);
                    // Round 0 releases the closing motion of the pairs that hold the step;
                    // from round 1 on, every pair that (still) holds it moves as one.
                    std::vector<int>& grow = round == 0 ? holding : together;
                    merged.clear();
                    std::set_union(grow.begin(), grow.end(), more.begin(), more.end(), std::back_inserter(merged));
                    const bool grown = merged.size() > grow.size();
                    grow.swap(merged);
                    if (!grown) break;  // nothing new holds it
                    trial_dx = dx;
                    self_contact.remove_closing_motion(p, trial_dx, holding, movable);
                    if (!together.empty()) self_contact.move_pairs_together(trial_dx, together, movable);
                    const double trial_slope = slope_along(trial_dx);
                    trial_alpha = obstacle_step_bound(p, trial_dx);
                    trial_alpha = std::min(trial_alpha,
                                           self_contact.max_safe_step(p, trial_dx * trial_alpha, 0.9) * trial_alpha);
                    if (trial_slope < 0 && trial_alpha > alpha) {
                        released_dx = trial_dx;
                        alpha = trial_alpha;
                        slope = trial_slope;
                        released = true;
                    }
                }
                if (released) {
                    dx = released_dx;
                    ++s.released_steps;
                }
            }
        }
        s.seconds_contact += seconds_since(tc);
        const bool pure_newton = alpha >= 1 && unregularised && !released;
        bool accepted = false, full_step = false;
        t0 = Clock::now();
        for (int k = 0; k <= options.max_line_search_halvings; ++k, alpha /= 2) {
            const Eigen::MatrixX3d trial = p + alpha * dx;
            const double et = total(trial, nullptr, nullptr, nullptr);
            if (std::isfinite(et) && et <= e + 1e-4 * alpha * slope) {
                p = trial;
                last_move = alpha * dx.rowwise().norm().maxCoeff();
                if (use_self) last_spread = alpha * spread(dx);
                accepted = true;
                full_step = pure_newton && k == 0;
                break;
            }
        }
        s.seconds_assembly += seconds_since(t0);
        if (!accepted) {
            s.termination = StepTermination::line_search_failed;
            s.message = "no energy decrease along the Newton direction";
            break;
        }
        small_full_step = inertia_weight > 0 && full_step && last_move <= options.step_displacement_tolerance_m;
        // Where the step's incremental potential is not convex (buckling), the projected
        // Newton matrix converges only linearly and can crawl along the unstable mode for
        // the whole iteration budget; the step ends instead and the next step goes on from
        // here (docs/cloth.md, "Nonconvex steps").
        if (inertia_weight > 0 && options.max_nonconvex_step_iterations > 0 &&
            nonconvex_iterations >= options.max_nonconvex_step_iterations) {
            s.newton_iterations = it + 1;
            s.termination = StepTermination::max_iterations;
            s.message = detail::concat("ended after ", nonconvex_iterations,
                                       " regularised Newton iterations (not convex)");
            break;
        }
    }
    s.contacts = 0;
    for (const VertexContact& c : contacts)
        if (c.vertex >= 0 && c.distance < h) ++s.contacts;
    s.max_stitch_gap_m = max_stitch_gap(p);
    s.seconds_total = seconds_since(t_start);
    return s;
}

}  // namespace drape::cloth
