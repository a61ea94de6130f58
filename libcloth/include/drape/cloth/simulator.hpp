// The implicit cloth simulator: backward Euler written as the minimisation of the
// incremental potential, solved by Newton's method with a backtracking line search on a
// sparse Cholesky (LDLᵀ) factorisation; and a quasi-static mode that minimises the
// potential energy directly. First version (issue 3): stretching, bending, gravity and
// pinned vertices. Not yet: body contact, self-contact, seams, friction, air drag.
#pragma once

#include <drape/cloth/cloth_mesh.hpp>
#include <drape/cloth/energies.hpp>
#include <drape/cloth/material.hpp>

#include <Eigen/Core>

#include <memory>
#include <string>
#include <vector>

namespace drape::cloth {

struct SimulatorOptions {
    double time_step_s = 5e-3;                           ///< backward-Euler step, > 0
    Eigen::Vector3d gravity_m_per_s2{0.0, 0.0, -9.8};    ///< world frame
    /// Newton stops when the largest entry of the free gradient (N) is below
    /// relative_tolerance × the largest vertex weight m_i |g| (or 1e-12 N without gravity).
    double relative_tolerance = 1e-6;
    int max_newton_iterations = 100;  ///< per step or per static solve, >= 1
    int max_line_search_halvings = 30;
    /// A failed step (line search failure or NaN) is retried as two half steps, recursively,
    /// at most this many levels deep (so down to time_step_s / 2^max_step_halvings).
    int max_step_halvings = 3;
    /// Newton matrix of the bending terms: gauss_newton (cheap, PSD) or projected_psd.
    HessianMode bending_hessian = HessianMode::gauss_newton;
    bool is_valid(std::string* why = nullptr) const;
};

enum class StepTermination {
    converged,           ///< gradient below tolerance
    max_iterations,      ///< Newton ran out of iterations; state is the last iterate
    line_search_failed,  ///< no decrease along the Newton direction; state is the last iterate
    non_finite,          ///< a NaN or infinity appeared; the state was restored
};

struct StepSummary {
    StepTermination termination = StepTermination::non_finite;
    std::string message;
    int newton_iterations = 0;
    int regularised_factorisations = 0;  ///< times the Hessian needed a diagonal shift
    int substeps = 1;                    ///< > 1 when the step was split by halving
    double gradient_inf_norm_n = 0;      ///< at the returned state, free vertices only
    double tolerance_n = 0;              ///< the absolute tolerance that was used
    double energy_j = 0;                 ///< incremental potential (or potential, static)
    double seconds_assembly = 0;
    double seconds_solve = 0;            ///< factorisation + back substitution
    double seconds_total = 0;

    bool usable() const {
        return termination == StepTermination::converged ||
               termination == StepTermination::max_iterations;
    }
    std::string brief_report() const;
};

/// A piece of cloth in time. Owns its state; distinct simulators may run on distinct threads.
class Simulator {
public:
    /// \throw drape::InvalidInput if the mesh, the material or the options are invalid.
    Simulator(ClothMesh mesh, Material material, SimulatorOptions options = {});
    ~Simulator();
    Simulator(Simulator&&) noexcept;
    Simulator& operator=(Simulator&&) noexcept;
    Simulator(const Simulator&) = delete;
    Simulator& operator=(const Simulator&) = delete;

    /// Holds `vertex` at its current position (its velocity is set to zero).
    /// \throw drape::InvalidInput if vertex is out of range.
    void pin(int vertex);
    /// Moves a pinned vertex (a prescribed motion); \throw drape::InvalidInput if not pinned
    /// or the position is not finite.
    void set_pinned_position(int vertex, const Eigen::Vector3d& position_m);
    const std::vector<bool>& pinned() const;

    /// One backward-Euler step of options.time_step_s; a failed solve is retried as two half
    /// steps (see max_step_halvings). If it still fails the state is unchanged and the
    /// summary says why (`usable()` is false).
    StepSummary step();
    /// Minimises the potential energy (elastic + gravity) from the current positions: the
    /// static equilibrium under gravity. Velocities are set to zero.
    StepSummary solve_static();

    const Eigen::MatrixX3d& positions() const;   ///< #V x 3, world, metres
    const Eigen::MatrixX3d& velocities() const;  ///< #V x 3, m/s
    /// \throw drape::InvalidInput on a shape mismatch or non-finite entry.
    void set_positions(const Eigen::MatrixX3d& positions_m);
    void set_velocities(const Eigen::MatrixX3d& velocities_m_per_s);
    const Eigen::VectorXd& masses() const;       ///< #V, kg
    const ClothMesh& mesh() const;
    const Material& material() const;
    const SimulatorOptions& options() const;

    /// Elastic + gravity force on every vertex at the current positions (#V x 3, N), with the
    /// stiffness looked up at the current strain; on pinned vertices it is the force the
    /// pins must balance (with opposite sign).
    Eigen::MatrixX3d forces() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace drape::cloth
