// Box-bounded minimisation by Particle Swarm Optimization (Kennedy & Eberhart; pagmo2's
// generational PSO), the particles of a generation evaluated in parallel by workers that own
// their resources. The one swarm behind the sizing search (sizing_search.hpp, paper
// Algorithm 1) and the joint material-pose search (paper Algorithm 2).
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace drape::garment {

/// The objective of one point `x` (the box's dimension), evaluated by worker `worker` in
/// [0, threads): the caller keeps one set of mutable resources per worker, so no two
/// concurrent calls share one. Lower is better; return +infinity (or a large value) for a
/// point that cannot be evaluated. It may throw drape::InvalidInput for a point: that point
/// counts as +infinity.
using SwarmObjective = std::function<double(const std::vector<double>& x, int worker)>;

/// After every generation (and once after the initial swarm): return false to stop.
struct SwarmProgress {
    int generation = 0;        ///< 0 = the initial swarm
    int generations = 0;       ///< as asked
    long evaluations = 0;      ///< objective calls so far
    double best = 0;           ///< best objective so far
    double seconds = 0;        ///< since the search began
};

struct SwarmOptions {
    int particles = 40;        ///< swarm size (the paper's 40), >= 2
    int generations = 8;       ///< PSO generations after the initial swarm, >= 0
    int threads = 2;           ///< workers evaluating a generation's particles, >= 1
    unsigned seed = 1;         ///< the swarm's random draws (same seed, same search)
    /// Stop when the best objective improved by less than this fraction over the last
    /// `patience` generations (0 = run every generation).
    double tolerance = 1e-3;
    int patience = 3;
    std::function<bool(const SwarmProgress&)> on_progress;
    bool is_valid(std::string* why = nullptr) const;
};

enum class SwarmTermination {
    converged,        ///< the best stopped improving (tolerance, patience)
    max_generations,  ///< every generation ran
    cancelled,        ///< on_progress returned false
    failed,           ///< no point could be evaluated
};

struct SwarmSummary {
    SwarmTermination termination = SwarmTermination::failed;
    std::vector<double> best;         ///< the best point, or the start if none could be evaluated
    double best_objective = 0;        ///< +infinity when failed
    double start_objective = 0;       ///< the start's own objective (it is particle 0)
    std::vector<double> history;      ///< best objective after the initial swarm and each generation
    long evaluations = 0;
    int generations = 0;              ///< generations run
    double seconds = 0;
};

/// Minimises `objective` over the box [lower, upper] with PSO: particle 0 is `start`, the
/// others are drawn uniformly in the box; each generation is evaluated in parallel by
/// `threads` workers. The best objective never exceeds the start's. A zero-dimensional box
/// evaluates the start alone.
/// \throw drape::InvalidInput if the options are invalid (naming the field), the sizes differ,
///        a bound is not finite, lower > upper somewhere, or the start is outside the box.
SwarmSummary minimise_swarm(const std::vector<double>& start, const std::vector<double>& lower,
                            const std::vector<double>& upper, const SwarmObjective& objective,
                            const SwarmOptions& options);

}  // namespace drape::garment
