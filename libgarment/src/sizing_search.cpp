#include <drape/garment/sizing_search.hpp>

#include <drape/core/errors.hpp>
#include <drape/garment/particle_swarm.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace drape::garment {

bool SizingSearchOptions::is_valid(std::string* why) const {
    if (!SwarmOptions::is_valid(why)) return false;
    if (!(box_fraction > 0) || !std::isfinite(box_fraction)) {
        if (why) *why = "box_fraction must be > 0 (got " + std::to_string(box_fraction) + ")";
        return false;
    }
    return true;
}

std::string SizingSearchSummary::brief_report() const {
    static const char* names[] = {"converged", "max_generations", "cancelled", "failed"};
    std::ostringstream s;
    s << "sizing search: " << names[static_cast<int>(termination)] << ", objective " << start_objective << " -> "
      << best_objective << " in " << generations << " generations, " << evaluations << " evaluations, " << seconds
      << " s";
    if (!message.empty()) s << " (" << message << ")";
    return s.str();
}

GarmentSizing tie_dress_waist(GarmentSizing g) {
    if (g.type == GarmentType::dress) g.dress.skirt.l1 = g.dress.bodice.w2;
    return g;
}

SizingSearchSummary search_sizing(const GarmentSizing& start, const SizingObjective& objective,
                                  const SizingSearchOptions& options) {
    std::string why;
    if (!options.is_valid(&why)) throw InvalidInput("sizing search options: " + why);
    if (!objective) throw InvalidInput("sizing search: no objective given");
    const auto params = sizing_parameters(start.type);
    if (!options.lower_bounds.empty() && options.lower_bounds.size() != params.size())
        throw InvalidInput("sizing search options: lower_bounds has " + std::to_string(options.lower_bounds.size()) +
                           " entries, the " + garment_type_name(start.type) + " template has " +
                           std::to_string(params.size()) + " parameters");
    if (!options.free.empty() && options.free.size() != params.size())
        throw InvalidInput("sizing search options: free has " + std::to_string(options.free.size()) +
                           " entries, the " + garment_type_name(start.type) + " template has " +
                           std::to_string(params.size()) + " parameters");
    // The search variables: the free parameters, each in its box around the start.
    const std::vector<double> values = sizing_values(start);
    std::vector<int> free_index;
    std::vector<double> x0, lower, upper;
    for (size_t i = 0; i < params.size(); ++i) {
        if (!options.free.empty() && !options.free[i]) continue;
        const double half = options.box_fraction * (params[i].max - params[i].min);
        const double floor_i = options.lower_bounds.empty() || std::isnan(options.lower_bounds[i])
                                   ? params[i].min
                                   : std::clamp(options.lower_bounds[i], params[i].min, params[i].max);
        const double v = std::clamp(values[i], floor_i, params[i].max);
        const double lo = std::max(floor_i, v - half), hi = std::min(params[i].max, v + half);
        if (!(hi > lo)) continue;  // a parameter pinned at a degenerate range stays fixed
        free_index.push_back(static_cast<int>(i));
        lower.push_back(lo);
        upper.push_back(hi);
        x0.push_back(v);
    }
    auto sizing_of = [&](const std::vector<double>& x) {
        std::vector<double> v = values;
        for (size_t i = 0; i < free_index.size(); ++i) v[static_cast<size_t>(free_index[i])] = x[i];
        GarmentSizing g = with_sizing_values(start, v);
        if (options.constrain) g = options.constrain(g);
        return g;
    };
    const SwarmSummary sw = minimise_swarm(
        x0, lower, upper, [&](const std::vector<double>& x, int worker) { return objective(sizing_of(x), worker); },
        options);

    SizingSearchSummary out;
    out.start_objective = sw.start_objective;
    out.best_objective = sw.best_objective;
    out.history = sw.history;
    out.evaluations = sw.evaluations;
    out.generations = sw.generations;
    out.seconds = sw.seconds;
    out.best = sizing_of(sw.best);
    switch (sw.termination) {
        case SwarmTermination::converged: out.termination = SizingSearchTermination::converged; break;
        case SwarmTermination::max_generations: out.termination = SizingSearchTermination::max_generations; break;
        case SwarmTermination::cancelled: out.termination = SizingSearchTermination::cancelled; break;
        case SwarmTermination::failed:
            out.termination = SizingSearchTermination::failed;
            out.message = "no candidate sizing could be evaluated";
            out.best = options.constrain ? options.constrain(start) : start;
            break;
    }
    if (free_index.empty()) out.message = "no free parameter";
    return out;
}

}  // namespace drape::garment
