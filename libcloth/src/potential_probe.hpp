// Private test hook: the incremental potential of a simulator's next time step as one
// function of the positions, with every term active that the scene sets up, for the
// finite-difference test of the whole assembled potential (tests/cloth/test_potential_fd.cpp).
// Not part of the API; compiled into libcloth so that the test runs the library's own
// assembly.
#pragma once

#include <drape/cloth/simulator.hpp>

#include <Eigen/Core>

namespace drape::cloth::internal {

/// Counts of what the potential holds at the probe's start (to guard against a vacuous pass).
struct PotentialTerms {
    int faces = 0;             ///< stretching elements
    int hinges = 0;            ///< bending elements
    int stitches = 0;
    int pinned = 0;            ///< pinned vertices (their dofs are not free)
    int contact_planes = 0;    ///< body-contact planes (obstacle)
    int friction = 0;          ///< vertices with lagged obstacle friction
    int pair_friction = 0;     ///< self-contact pairs with lagged cloth–cloth friction
    int self_candidates = 0;   ///< self-contact candidate pairs
};

/// Puts `sim` in the state of the first Newton iteration of its next time step (stiffness
/// frozen at the current positions, contact planes, friction lagged, self-contact candidates
/// within `self_contact_radius_m`), with exact Hessians for every term. Keeps a reference:
/// `sim` must outlive the probe and not be stepped meanwhile.
class PotentialProbe {
public:
    PotentialProbe(Simulator& sim, double self_contact_radius_m);

    /// Incremental potential E(q) = 1/(2Δt²) Σ m_i |q_i − x_i − Δt v_i|² + potential(q) (J).
    /// \param q #V x 3 positions (world, m).
    /// \param gradient if not null, 3#V (xyz per vertex), N.
    /// \param hessian if not null, the Hessian over the free dofs, dense (#free x #free), in
    ///        free-dof order (vertex-major, pinned vertices skipped).
    /// \param active_self_pairs if not null, the number of self-contact pairs within the
    ///        thickness at q (those with a Hessian block).
    double evaluate(const Eigen::MatrixX3d& q, Eigen::VectorXd* gradient = nullptr,
                    Eigen::MatrixXd* hessian = nullptr, int* active_self_pairs = nullptr);

    /// The move of the first iterate of a step from the current state: each vertex the body
    /// carries by friction, moved with its surface (Simulator::Impl::start_carry).
    Eigen::MatrixX3d start_carry() const;
    /// Free-dof index of coordinate c of vertex i, or −1 if the vertex is pinned.
    int dof(int vertex, int c) const;
    int free_dofs() const;
    const PotentialTerms& terms() const { return terms_; }

private:
    Simulator& sim_;
    Eigen::MatrixX3d target_;
    double inertia_weight_ = 0;
    PotentialTerms terms_;
};

}  // namespace drape::cloth::internal
