#include <drape/cloth/simulator.hpp>

#include <drape/cloth/energies.hpp>
#include <drape/core/errors.hpp>

#include "sparse_solver.hpp"

#include <Eigen/SparseCore>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

namespace drape::cloth {

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

const char* to_string(StepTermination t) {
    switch (t) {
        case StepTermination::converged: return "converged";
        case StepTermination::max_iterations: return "max_iterations";
        case StepTermination::line_search_failed: return "line_search_failed";
        case StepTermination::non_finite: return "non_finite";
    }
    return "unknown";
}

}  // namespace

bool SimulatorOptions::is_valid(std::string* why) const {
    auto fail = [&](const std::string& reason) {
        if (why) *why = reason;
        return false;
    };
    if (!(std::isfinite(time_step_s) && time_step_s > 0))
        return fail(detail::concat("time_step_s = ", time_step_s, " must be > 0"));
    if (!gravity_m_per_s2.allFinite()) return fail("gravity_m_per_s2 is not finite");
    if (!(std::isfinite(relative_tolerance) && relative_tolerance > 0))
        return fail(detail::concat("relative_tolerance = ", relative_tolerance, " must be > 0"));
    if (max_newton_iterations < 1)
        return fail(detail::concat("max_newton_iterations = ", max_newton_iterations, " must be >= 1"));
    if (max_step_halvings < 0 || max_step_halvings > 20)
        return fail(detail::concat("max_step_halvings = ", max_step_halvings, " must be in [0, 20]"));
    if (max_line_search_halvings < 0)
        return fail(detail::concat("max_line_search_halvings = ", max_line_search_halvings,
                                   " must be >= 0"));
    return true;
}

std::string StepSummary::brief_report() const {
    std::ostringstream os;
    os << to_string(termination) << ": " << newton_iterations << " Newton iterations, |g|inf "
       << gradient_inf_norm_n << " N (tol " << tolerance_n << "), E " << energy_j << " J, "
       << seconds_total * 1e3 << " ms (assembly " << seconds_assembly * 1e3 << ", solve "
       << seconds_solve * 1e3 << ")";
    if (!message.empty()) os << "; " << message;
    return os.str();
}

struct Simulator::Impl {
    ClothMesh mesh;
    Material material;
    SimulatorOptions options;
    Eigen::MatrixX3d x, v;
    Eigen::VectorXd mass;
    std::vector<bool> pinned;
    std::vector<TriangleRest> triangles;
    std::vector<Hinge> hinges;
    std::vector<HingeRest> hinge_rests;
    // Frozen stiffness of the current Newton iteration.
    std::vector<StretchingStiffness> k_stretch;
    std::vector<BendingCurve> bend_curves;  // per hinge, fixed: bending is conservative
    // Free-dof numbering: dof_index[3 i + c] = column in the reduced system or -1 (pinned).
    std::vector<int> dof_index;
    int free_dofs = 0;
    // The fill-reducing ordering and symbolic factorisation depend only on the free dofs
    // and the mesh, so they are kept across Newton iterations and steps.
    internal::SparseSpdSolver solver;
    // Fixed sparsity pattern of the free-dof Hessian, and for every element entry (in the
    // column-major order of its dense Hessian) the index into the value array, or -1 when
    // a pinned dof is involved. Rebuilt when the pins change.
    Eigen::SparseMatrix<double> pattern;
    std::vector<int> face_slots, hinge_slots, diagonal_slots;
    bool pattern_ready = false;

    Impl() = default;
    // Copies carry the state, not the factorisation (used by the const forces()).
    Impl(const Impl& o)
        : mesh(o.mesh), material(o.material), options(o.options), x(o.x), v(o.v), mass(o.mass),
          pinned(o.pinned), triangles(o.triangles), hinges(o.hinges), hinge_rests(o.hinge_rests),
          k_stretch(o.k_stretch), bend_curves(o.bend_curves), dof_index(o.dof_index),
          free_dofs(o.free_dofs) {}

    void renumber() {
        solver.reset();
        pattern_ready = false;
        dof_index.assign(static_cast<std::size_t>(3 * x.rows()), -1);
        free_dofs = 0;
        for (Eigen::Index i = 0; i < x.rows(); ++i)
            if (!pinned[static_cast<std::size_t>(i)])
                for (int c = 0; c < 3; ++c) dof_index[static_cast<std::size_t>(3 * i + c)] = free_dofs++;
    }

    Eigen::Matrix3d face_positions(const Eigen::MatrixX3d& p, int f) const {
        Eigen::Matrix3d xf;
        for (int c = 0; c < 3; ++c) xf.col(c) = p.row(mesh.faces(f, c)).transpose();
        return xf;
    }
    Eigen::Matrix<double, 3, 4> hinge_positions(const Eigen::MatrixX3d& p, const Hinge& h) const {
        Eigen::Matrix<double, 3, 4> xh;
        for (int c = 0; c < 4; ++c) xh.col(c) = p.row(h.v[static_cast<std::size_t>(c)]).transpose();
        return xh;
    }

    // Looks the stretching table up at the strain of `p` (ArcSim also evaluates k at the
    // current state and treats it as constant when differentiating). Bending needs no
    // refresh: its curvature dependence is integrated into the energy (BendingCurve).
    void refresh_stiffness(const Eigen::MatrixX3d& p) {
        k_stretch.resize(triangles.size());
        for (int f = 0; f < mesh.face_count(); ++f)
            k_stretch[static_cast<std::size_t>(f)] = stretching_stiffness(
                material, green_strain(face_positions(p, f), triangles[static_cast<std::size_t>(f)]));
    }

    void build_pattern() {
        std::vector<Eigen::Triplet<double>> entries;
        auto add = [&](const int* verts, int n) {
            for (int a = 0; a < n; ++a)
                for (int b = 0; b < n; ++b)
                    for (int ca = 0; ca < 3; ++ca)
                        for (int cb = 0; cb < 3; ++cb) {
                            const int r = dof_index[static_cast<std::size_t>(3 * verts[a] + ca)];
                            const int c = dof_index[static_cast<std::size_t>(3 * verts[b] + cb)];
                            if (r >= 0 && c >= 0) entries.emplace_back(r, c, 0.0);
                        }
        };
        for (int f = 0; f < mesh.face_count(); ++f) {
            const int verts[3] = {mesh.faces(f, 0), mesh.faces(f, 1), mesh.faces(f, 2)};
            add(verts, 3);
        }
        for (const Hinge& h : hinges) add(h.v.data(), 4);
        for (int d = 0; d < free_dofs; ++d) entries.emplace_back(d, d, 0.0);
        pattern.resize(free_dofs, free_dofs);
        pattern.setFromTriplets(entries.begin(), entries.end());
        pattern.makeCompressed();
        auto slot = [&](int r, int c) {
            const int* inner = pattern.innerIndexPtr();
            const int* begin = inner + pattern.outerIndexPtr()[c];
            const int* end = inner + pattern.outerIndexPtr()[c + 1];
            return static_cast<int>(std::lower_bound(begin, end, r) - inner);
        };
        auto fill = [&](const int* verts, int n, int* out) {
            for (int b = 0; b < n; ++b)
                for (int cb = 0; cb < 3; ++cb)
                    for (int a = 0; a < n; ++a)
                        for (int ca = 0; ca < 3; ++ca) {
                            const int r = dof_index[static_cast<std::size_t>(3 * verts[a] + ca)];
                            const int c = dof_index[static_cast<std::size_t>(3 * verts[b] + cb)];
                            out[(3 * b + cb) * 3 * n + 3 * a + ca] = (r >= 0 && c >= 0) ? slot(r, c) : -1;
                        }
        };
        face_slots.assign(static_cast<std::size_t>(81 * mesh.face_count()), -1);
        for (int f = 0; f < mesh.face_count(); ++f) {
            const int verts[3] = {mesh.faces(f, 0), mesh.faces(f, 1), mesh.faces(f, 2)};
            fill(verts, 3, face_slots.data() + 81 * f);
        }
        hinge_slots.assign(144 * hinges.size(), -1);
        for (std::size_t h = 0; h < hinges.size(); ++h)
            fill(hinges[h].v.data(), 4, hinge_slots.data() + 144 * h);
        diagonal_slots.resize(static_cast<std::size_t>(free_dofs));
        for (int d = 0; d < free_dofs; ++d) diagonal_slots[static_cast<std::size_t>(d)] = slot(d, d);
        pattern_ready = true;
    }

    // Potential energy (elastic + gravity) with frozen stiffness; optionally the full
    // gradient (3V) and, added into `values` (the value array of `pattern`), the free-dof
    // Hessian.
    double potential(const Eigen::MatrixX3d& p, Eigen::VectorXd* gradient, double* values) const {
        double e = 0;
        if (gradient) gradient->setZero(3 * p.rows());
        auto scatter = [&](const int* verts, int n, const double* g, const double* h,
                           const int* slots) {
            if (gradient)
                for (int a = 0; a < n; ++a)
                    for (int ca = 0; ca < 3; ++ca) (*gradient)(3 * verts[a] + ca) += g[3 * a + ca];
            if (values)
                for (int k = 0; k < 9 * n * n; ++k)
                    if (slots[k] >= 0) values[slots[k]] += h[k];
        };
        const bool derivatives = gradient || values;
        Vector9d g9;
        Matrix9d h9;
        for (int f = 0; f < mesh.face_count(); ++f) {
            const auto fs = static_cast<std::size_t>(f);
            e += stretching_energy(face_positions(p, f), triangles[fs], k_stretch[fs],
                                   gradient ? &g9 : nullptr, values ? &h9 : nullptr);
            if (derivatives) {
                const int verts[3] = {mesh.faces(f, 0), mesh.faces(f, 1), mesh.faces(f, 2)};
                scatter(verts, 3, g9.data(), h9.data(),
                        values ? face_slots.data() + 81 * f : nullptr);
            }
        }
        Vector12d g12;
        Matrix12d h12;
        for (std::size_t h = 0; h < hinges.size(); ++h) {
            e += bending_energy(hinge_positions(p, hinges[h]), hinge_rests[h], bend_curves[h],
                                gradient ? &g12 : nullptr, values ? &h12 : nullptr,
                                options.bending_hessian);
            if (derivatives)
                scatter(hinges[h].v.data(), 4, g12.data(), h12.data(),
                        values ? hinge_slots.data() + 144 * h : nullptr);
        }
        Eigen::MatrixX3d gg;
        e += gravity_energy(p, mass, options.gravity_m_per_s2, gradient ? &gg : nullptr);
        if (gradient)
            for (Eigen::Index i = 0; i < p.rows(); ++i)
                gradient->segment<3>(3 * i) += gg.row(i).transpose();
        return e;
    }

    // One backward-Euler step of length h; on failure the state is left unchanged.
    StepSummary backward_euler(double h, int halvings_left);

    // Newton on E(p) = inertia_weight/2 Σ m_i |p_i − target_i|² + potential(p).
    // inertia_weight = 1/h² for backward Euler, 0 for the static solve.
    StepSummary minimise(Eigen::MatrixX3d& p, const Eigen::MatrixX3d& target, double inertia_weight) {
        const auto t_start = Clock::now();
        StepSummary s;
        const double weight = mass.maxCoeff() * options.gravity_m_per_s2.norm();
        s.tolerance_n = weight > 0 ? options.relative_tolerance * weight : 1e-12;
        const Eigen::MatrixX3d p_start = p;

        auto total = [&](const Eigen::MatrixX3d& q, Eigen::VectorXd* g,
                         double* values) {
            double e = potential(q, g, values);
            if (inertia_weight > 0) {
                const Eigen::MatrixX3d d = q - target;
                e += 0.5 * inertia_weight * (mass.transpose() * d.rowwise().squaredNorm()).value();
                if (g)
                    for (Eigen::Index i = 0; i < q.rows(); ++i)
                        g->segment<3>(3 * i) += inertia_weight * mass(i) * d.row(i).transpose();
            }
            return e;
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
        const double mass_scale = mass.maxCoeff();
        for (int it = 0;; ++it) {
            auto t0 = Clock::now();
            refresh_stiffness(p);
            std::fill(hessian.valuePtr(), hessian.valuePtr() + hessian.nonZeros(), 0.0);
            const double e = total(p, &g, hessian.valuePtr());
            s.seconds_assembly += seconds_since(t0);
            s.energy_j = e;
            s.gradient_inf_norm_n = free_inf_norm(g);
            s.newton_iterations = it;
            if (!std::isfinite(e) || !g.allFinite()) {
                p = p_start;
                s.termination = StepTermination::non_finite;
                s.message = "energy or gradient is not finite";
                break;
            }
            if (s.gradient_inf_norm_n <= s.tolerance_n) {
                s.termination = StepTermination::converged;
                break;
            }
            if (it >= options.max_newton_iterations) {
                s.termination = StepTermination::max_iterations;
                break;
            }
            t0 = Clock::now();
            Eigen::VectorXd rhs(free_dofs);
            for (std::size_t k = 0; k < dof_index.size(); ++k)
                if (dof_index[k] >= 0) rhs(dof_index[k]) = -g(static_cast<Eigen::Index>(k));
            for (Eigen::Index i = 0; i < p.rows(); ++i)
                for (int c = 0; c < 3; ++c) {
                    const int d = dof_index[static_cast<std::size_t>(3 * i + c)];
                    if (d >= 0)
                        hessian.valuePtr()[diagonal_slots[static_cast<std::size_t>(d)]] +=
                            inertia_weight * mass(i);
                }
            Eigen::VectorXd step;
            for (int attempt = 0; attempt < 12; ++attempt) {
                Eigen::SparseMatrix<double> shifted;
                if (shift > 0) {
                    shifted = hessian;
                    for (Eigen::Index i = 0; i < p.rows(); ++i)
                        for (int c = 0; c < 3; ++c) {
                            const int d = dof_index[static_cast<std::size_t>(3 * i + c)];
                            if (d >= 0) shifted.coeffRef(d, d) += shift * mass(i) / mass_scale;
                        }
                }
                const Eigen::SparseMatrix<double>& matrix = shift > 0 ? shifted : hessian;
                if (solver.factorize(matrix)) {
                    step = solver.solve(rhs);
                    if (step.allFinite() && step.dot(rhs) > 0) break;
                }
                step.resize(0);
                if (shift > 0) {
                    shift *= 10;
                } else {
                    const Eigen::VectorXd diagonal = hessian.diagonal();
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
            shift /= 10;  // let it decay once things are well conditioned
            if (shift < 1e-14) shift = 0;

            // Backtracking (Armijo) line search with the frozen stiffness.
            Eigen::MatrixX3d dx = Eigen::MatrixX3d::Zero(p.rows(), 3);
            for (Eigen::Index i = 0; i < p.rows(); ++i)
                for (int c = 0; c < 3; ++c) {
                    const int d = dof_index[static_cast<std::size_t>(3 * i + c)];
                    if (d >= 0) dx(i, c) = step(d);
                }
            const double slope = -step.dot(rhs);
            double alpha = 1;
            bool accepted = false;
            t0 = Clock::now();
            for (int k = 0; k <= options.max_line_search_halvings; ++k, alpha /= 2) {
                const Eigen::MatrixX3d trial = p + alpha * dx;
                const double et = total(trial, nullptr, nullptr);
                if (std::isfinite(et) && et <= e + 1e-4 * alpha * slope) {
                    p = trial;
                    accepted = true;
                    break;
                }
            }
            s.seconds_assembly += seconds_since(t0);
            if (!accepted) {
                s.termination = StepTermination::line_search_failed;
                s.message = "no energy decrease along the Newton direction";
                break;
            }
        }
        s.seconds_total = seconds_since(t_start);
        return s;
    }
};

Simulator::Simulator(ClothMesh mesh, Material material, SimulatorOptions options)
    : impl_(std::make_unique<Impl>()) {
    std::string why;
    require(options.is_valid(&why), "Simulator: options are invalid: ", why);
    require(material.is_valid(&why), "Simulator: material is invalid: ", why);
    mesh.validate();
    Impl& m = *impl_;
    m.mesh = std::move(mesh);
    m.material = material;
    m.options = options;
    m.x = m.mesh.positions;
    m.v = Eigen::MatrixX3d::Zero(m.x.rows(), 3);
    m.mass = vertex_masses(m.mesh, m.material);
    m.pinned.assign(static_cast<std::size_t>(m.x.rows()), false);
    for (int f = 0; f < m.mesh.face_count(); ++f) {
        Eigen::Vector2d u[3];
        for (int c = 0; c < 3; ++c) u[c] = m.mesh.pattern.row(m.mesh.pattern_faces(f, c)).transpose();
        m.triangles.push_back(triangle_rest(u[0], u[1], u[2]));
    }
    m.hinges = build_hinges(m.mesh);
    for (const Hinge& h : m.hinges) {
        m.hinge_rests.push_back(hinge_rest(m.mesh, h));
        m.bend_curves.push_back(bending_curve(m.material, m.hinge_rests.back()));
    }
    m.renumber();
}

Simulator::~Simulator() = default;
Simulator::Simulator(Simulator&&) noexcept = default;
Simulator& Simulator::operator=(Simulator&&) noexcept = default;

void Simulator::pin(int vertex) {
    require(vertex >= 0 && vertex < impl_->x.rows(), "Simulator::pin: vertex ", vertex,
            " is out of range [0, ", impl_->x.rows(), ")");
    impl_->pinned[static_cast<std::size_t>(vertex)] = true;
    impl_->v.row(vertex).setZero();
    impl_->renumber();
}

void Simulator::set_pinned_position(int vertex, const Eigen::Vector3d& position_m) {
    require(vertex >= 0 && vertex < impl_->x.rows() && impl_->pinned[static_cast<std::size_t>(vertex)],
            "Simulator::set_pinned_position: vertex ", vertex, " is not a pinned vertex");
    require(position_m.allFinite(), "Simulator::set_pinned_position: position is not finite");
    impl_->x.row(vertex) = position_m.transpose();
}

const std::vector<bool>& Simulator::pinned() const { return impl_->pinned; }

namespace {

// Sums the counters of `part` into `total` (termination/energy/norms come from the last part).
void accumulate(StepSummary& total, const StepSummary& part) {
    total.newton_iterations += part.newton_iterations;
    total.regularised_factorisations += part.regularised_factorisations;
    total.seconds_assembly += part.seconds_assembly;
    total.seconds_solve += part.seconds_solve;
    total.termination = part.termination;
    total.message = part.message;
    total.gradient_inf_norm_n = part.gradient_inf_norm_n;
    total.tolerance_n = part.tolerance_n;
    total.energy_j = part.energy_j;
}

}  // namespace

StepSummary Simulator::step() {
    const auto t0 = Clock::now();
    StepSummary s = impl_->backward_euler(impl_->options.time_step_s,
                                          impl_->options.max_step_halvings);
    s.seconds_total = seconds_since(t0);
    return s;
}

StepSummary Simulator::Impl::backward_euler(double h, int halvings_left) {
    Impl& m = *this;
    Eigen::MatrixX3d target = m.x + h * m.v;
    for (std::size_t i = 0; i < m.pinned.size(); ++i)
        if (m.pinned[i]) target.row(static_cast<Eigen::Index>(i)) = m.x.row(static_cast<Eigen::Index>(i));
    Eigen::MatrixX3d p = target;  // inertial prediction as the initial guess
    StepSummary s = m.minimise(p, target, 1 / (h * h));
    if (s.usable()) {
        m.v = (p - m.x) / h;
        m.x = p;
        return s;
    }
    if (halvings_left == 0) return s;
    // Retry as two half steps from the unchanged state.
    const Eigen::MatrixX3d x0 = m.x, v0 = m.v;
    StepSummary total = s;
    total.substeps = 0;
    for (int half = 0; half < 2; ++half) {
        const StepSummary part = backward_euler(h / 2, halvings_left - 1);
        accumulate(total, part);
        total.substeps += part.substeps;
        if (!part.usable()) {
            m.x = x0;
            m.v = v0;
            total.message = "failed even after halving the step: " + part.message;
            return total;
        }
    }
    total.message = detail::concat("step split into ", total.substeps, " substeps after: ", s.message);
    return total;
}

StepSummary Simulator::solve_static() {
    Impl& m = *impl_;
    Eigen::MatrixX3d p = m.x;
    StepSummary s = m.minimise(p, m.x, 0);
    if (s.termination != StepTermination::non_finite) {
        m.x = p;
        m.v.setZero();
    }
    return s;
}

const Eigen::MatrixX3d& Simulator::positions() const { return impl_->x; }
const Eigen::MatrixX3d& Simulator::velocities() const { return impl_->v; }

void Simulator::set_positions(const Eigen::MatrixX3d& positions_m) {
    require(positions_m.rows() == impl_->x.rows(), "Simulator::set_positions: ", positions_m.rows(),
            " rows, expected ", impl_->x.rows());
    require(positions_m.allFinite(), "Simulator::set_positions: positions are not finite");
    impl_->x = positions_m;
}

void Simulator::set_velocities(const Eigen::MatrixX3d& velocities_m_per_s) {
    require(velocities_m_per_s.rows() == impl_->v.rows(), "Simulator::set_velocities: ",
            velocities_m_per_s.rows(), " rows, expected ", impl_->v.rows());
    require(velocities_m_per_s.allFinite(), "Simulator::set_velocities: velocities are not finite");
    impl_->v = velocities_m_per_s;
    for (std::size_t i = 0; i < impl_->pinned.size(); ++i)
        if (impl_->pinned[i]) impl_->v.row(static_cast<Eigen::Index>(i)).setZero();
}

const Eigen::VectorXd& Simulator::masses() const { return impl_->mass; }
const ClothMesh& Simulator::mesh() const { return impl_->mesh; }
const Material& Simulator::material() const { return impl_->material; }
const SimulatorOptions& Simulator::options() const { return impl_->options; }

Eigen::MatrixX3d Simulator::forces() const {
    Impl copy_free = Impl(*impl_);  // refresh_stiffness mutates the frozen stiffness cache
    copy_free.refresh_stiffness(copy_free.x);
    Eigen::VectorXd g;
    copy_free.potential(copy_free.x, &g, nullptr);
    Eigen::MatrixX3d f(copy_free.x.rows(), 3);
    for (Eigen::Index i = 0; i < f.rows(); ++i) f.row(i) = -g.segment<3>(3 * i).transpose();
    return f;
}

}  // namespace drape::cloth
