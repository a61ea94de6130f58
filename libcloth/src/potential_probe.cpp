#include "potential_probe.hpp"

#include "simulator_impl.hpp"

namespace drape::cloth::internal {

PotentialProbe::PotentialProbe(Simulator& sim, double self_contact_radius_m) : sim_(sim) {
    Simulator::Impl& m = *sim_.impl_;
    // As backward_euler and the first iteration of minimise set the step up.
    const double h = m.options.time_step_s;
    target_ = m.x + h * m.v;
    for (std::size_t i = 0; i < m.pinned.size(); ++i)
        if (m.pinned[i]) target_.row(static_cast<Eigen::Index>(i)) = m.x.row(static_cast<Eigen::Index>(i));
    inertia_weight_ = 1 / (h * h);
    m.step_start = m.x;
    m.step_dt = h;
    m.refresh_stiffness(m.x, false);
    m.planes.clear();
    m.plane_of_vertex.assign(static_cast<std::size_t>(m.x.rows()), {-1, -1});
    m.update_obstacle_contacts(m.x);
    m.lag_friction();
    if (m.options.self_contact) m.self_contact.find_candidates(m.x, self_contact_radius_m);
    m.lag_pair_friction(m.x);
    if (!m.pattern_ready) m.build_pattern();
    m.hessian_mode = HessianMode::exact;
    m.exact_hessians = true;

    terms_.faces = m.mesh.face_count();
    terms_.hinges = static_cast<int>(m.hinges.size());
    terms_.stitches = static_cast<int>(m.stitches.size());
    for (bool p : m.pinned) terms_.pinned += p ? 1 : 0;
    terms_.contact_planes = static_cast<int>(m.planes.size());
    terms_.friction = static_cast<int>(m.friction.size());
    terms_.pair_friction = static_cast<int>(m.pair_friction.size());
    terms_.self_candidates = static_cast<int>(m.self_contact.candidates().size());
}

Eigen::MatrixX3d PotentialProbe::start_carry() const { return sim_.impl_->start_carry(sim_.impl_->x); }

int PotentialProbe::dof(int vertex, int c) const { return sim_.impl_->dof(vertex, c); }
int PotentialProbe::free_dofs() const { return sim_.impl_->free_dofs; }

double PotentialProbe::evaluate(const Eigen::MatrixX3d& q, Eigen::VectorXd* gradient,
                                Eigen::MatrixXd* hessian, int* active_self_pairs) {
    Simulator::Impl& m = *sim_.impl_;
    Eigen::SparseMatrix<double> values = m.pattern;
    std::fill(values.valuePtr(), values.valuePtr() + values.nonZeros(), 0.0);
    std::vector<PairHessian> pairs;
    Eigen::VectorXd g;
    const double e = m.incremental_potential(q, target_, inertia_weight_, &g,
                                             hessian ? values.valuePtr() : nullptr, &pairs);
    if (gradient) *gradient = g;
    if (active_self_pairs)
        *active_self_pairs = static_cast<int>(pairs.size()) - (m.friction_active() ? terms_.pair_friction : 0);
    if (hessian) {
        *hessian = Eigen::MatrixXd(values);
        for (Eigen::Index i = 0; i < q.rows(); ++i)
            for (int c = 0; c < 3; ++c) {
                const int d = m.dof(static_cast<int>(i), c);
                if (d >= 0) (*hessian)(d, d) += inertia_weight_ * m.mass(i);
            }
        for (const PairHessian& ph : pairs)
            for (int a = 0; a < 4; ++a)
                for (int b = 0; b < 4; ++b)
                    for (int ca = 0; ca < 3; ++ca)
                        for (int cb = 0; cb < 3; ++cb) {
                            const int r = m.dof(ph.pair.v[static_cast<std::size_t>(a)], ca);
                            const int c = m.dof(ph.pair.v[static_cast<std::size_t>(b)], cb);
                            if (r >= 0 && c >= 0) (*hessian)(r, c) += ph.hessian(3 * a + ca, 3 * b + cb);
                        }
    }
    return e;
}

}  // namespace drape::cloth::internal
