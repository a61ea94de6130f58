// The search for a garment's sizing G (paper section 5.3, Algorithm 1, "SizingParamIdentification"):
// Particle Swarm Optimization (Kennedy & Eberhart; pagmo2's generational PSO) over the
// template's parameters, the particles of a generation evaluated in parallel. The objective
// is the caller's: recovery passes the silhouette distance of the draped candidate
// (silhouette_distance.hpp), so libgarment does not depend on how candidates are drawn.
#pragma once

#include <drape/garment/garment_sizing.hpp>
#include <drape/garment/particle_swarm.hpp>

#include <functional>
#include <string>
#include <vector>

namespace drape::garment {

/// The objective of one candidate sizing, evaluated by worker `worker` in [0, threads):
/// the caller keeps one set of mutable resources (a simulator, a render buffer) per worker,
/// so no two concurrent calls share one. Lower is better; return a large finite value (or
/// +infinity) for a candidate that cannot be made (e.g. the template refuses it). It may
/// throw drape::InvalidInput for a candidate: that candidate counts as +infinity.
using SizingObjective = std::function<double(const GarmentSizing& candidate, int worker)>;

/// After every generation (and once after the initial swarm): return false to stop.
using SizingSearchProgress = SwarmProgress;

/// The swarm's settings (particle_swarm.hpp: particles, generations, threads, seed, tolerance,
/// patience, on_progress; the paper's 40 particles by default) and the search box.
struct SizingSearchOptions : SwarmOptions {
    /// The search box around the start: each free parameter within ± this fraction of the
    /// template's range (max − min), clipped to the range. > 0.
    double box_fraction = 0.2;
    /// Per parameter (sizing_parameters order; empty = all free): false keeps the start's value.
    std::vector<bool> free;
    /// Per parameter (sizing_parameters order; empty = none): a lower bound of the search
    /// box in the parameter's unit, NaN for none. E.g. a girth that must not fall below the
    /// body's (the garment would not go on). The box is [max(its lower end, bound), upper end];
    /// a start below the bound is raised to it.
    std::vector<double> lower_bounds;
    /// Applied to every candidate before it is evaluated, e.g. a dress's skirt waist tied to
    /// the bodice (tie_dress_waist). Empty: none.
    std::function<GarmentSizing(const GarmentSizing&)> constrain;
    bool is_valid(std::string* why = nullptr) const;
};

enum class SizingSearchTermination {
    converged,        ///< the best stopped improving (tolerance, patience)
    max_generations,  ///< every generation ran
    cancelled,        ///< on_progress returned false
    failed,           ///< no candidate could be evaluated (message says why)
};

struct SizingSearchSummary {
    SizingSearchTermination termination = SizingSearchTermination::failed;
    std::string message;
    GarmentSizing best;               ///< the best candidate (constrained), or the start if none
    double best_objective = 0;
    double start_objective = 0;       ///< the start's own objective (it is particle 0)
    std::vector<double> history;      ///< best objective after the initial swarm and each generation
    long evaluations = 0;
    int generations = 0;              ///< generations run
    double seconds = 0;
    std::string brief_report() const;
};

/// Searches G around `start` with PSO: particle 0 is `start` itself, the others are drawn
/// uniformly in the box; each generation is evaluated in parallel by `threads` workers.
/// The best objective never exceeds the start's.
/// \throw drape::InvalidInput if the options are invalid (naming the field) or `free` has
///        the wrong size.
SizingSearchSummary search_sizing(const GarmentSizing& start, const SizingObjective& objective,
                                  const SizingSearchOptions& options);

/// A dress with its skirt's waist arc set to the bodice's hem width (make_dress requires
/// them equal within 1 %); other garments unchanged.
GarmentSizing tie_dress_waist(GarmentSizing sizing);

}  // namespace drape::garment
