#include <drape/garment/sizing_search.hpp>

#include <drape/core/errors.hpp>

#include <pagmo/algorithms/pso_gen.hpp>
#include <pagmo/bfe.hpp>
#include <pagmo/population.hpp>
#include <pagmo/problem.hpp>
#include <pagmo/types.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <mutex>
#include <sstream>
#include <thread>

namespace drape::garment {

namespace {

// A candidate that cannot be made or whose objective is not finite: large, finite, so the
// swarm's arithmetic stays finite.
constexpr double kRefused = 1e30;

// Maps the free parameters (the search variables) onto a full sizing and evaluates it.
struct Evaluator {
    GarmentSizing start;
    std::vector<int> free_index;  // sizing_values index of each search variable
    const SizingObjective* objective = nullptr;
    const std::function<GarmentSizing(const GarmentSizing&)>* constrain = nullptr;
    std::atomic<long>* evaluations = nullptr;

    GarmentSizing sizing_of(const pagmo::vector_double& x) const {
        std::vector<double> values = sizing_values(start);
        for (size_t i = 0; i < free_index.size(); ++i) values[static_cast<size_t>(free_index[i])] = x[i];
        GarmentSizing g = with_sizing_values(start, values);
        if (constrain && *constrain) g = (*constrain)(g);
        return g;
    }

    double evaluate(const pagmo::vector_double& x, int worker) const {
        ++*evaluations;
        try {
            const double f = (*objective)(sizing_of(x), worker);
            return std::isfinite(f) ? std::min(f, kRefused) : kRefused;
        } catch (const InvalidInput&) {
            return kRefused;
        }
    }
};

// pagmo's user-defined problem: a box-bounded single objective.
struct SizingProblem {
    const Evaluator* evaluator = nullptr;
    pagmo::vector_double lower, upper;

    pagmo::vector_double fitness(const pagmo::vector_double& x) const { return {evaluator->evaluate(x, 0)}; }
    std::pair<pagmo::vector_double, pagmo::vector_double> get_bounds() const { return {lower, upper}; }
    std::string get_name() const { return "drape garment sizing"; }
};

// pagmo's user-defined batch evaluator: the batch split over `threads` workers, each with
// its own index (the caller's per-worker resources), taking particles in turn.
struct WorkerBfe {
    const Evaluator* evaluator = nullptr;
    int threads = 1;

    pagmo::vector_double operator()(const pagmo::problem& p, const pagmo::vector_double& dvs) const {
        const size_t n = p.get_nx();
        const size_t count = n == 0 ? 0 : dvs.size() / n;
        pagmo::vector_double f(count, kRefused);
        std::atomic<size_t> next{0};
        std::mutex error_mutex;
        std::exception_ptr error;
        auto work = [&](int worker) {
            for (size_t i = next++; i < count; i = next++) {
                try {
                    const pagmo::vector_double x(dvs.begin() + static_cast<long>(i * n),
                                                 dvs.begin() + static_cast<long>((i + 1) * n));
                    f[i] = evaluator->evaluate(x, worker);
                } catch (...) {
                    const std::lock_guard<std::mutex> lock(error_mutex);
                    if (!error) error = std::current_exception();
                }
            }
        };
        const int workers = std::max(1, std::min<int>(threads, static_cast<int>(count)));
        std::vector<std::thread> pool;
        for (int w = 1; w < workers; ++w) pool.emplace_back(work, w);
        work(0);
        for (auto& t : pool) t.join();
        if (error) std::rethrow_exception(error);
        // pagmo's problem counts the evaluations it is told of.
        const_cast<pagmo::problem&>(p).increment_fevals(count);
        return f;
    }
    std::string get_name() const { return "drape per-worker batch evaluator"; }
};

}  // namespace

bool SizingSearchOptions::is_valid(std::string* why) const {
    auto fail = [&](const std::string& m) {
        if (why) *why = m;
        return false;
    };
    if (particles < 2) return fail("particles must be >= 2 (got " + std::to_string(particles) + ")");
    if (generations < 0) return fail("generations must be >= 0 (got " + std::to_string(generations) + ")");
    if (threads < 1) return fail("threads must be >= 1 (got " + std::to_string(threads) + ")");
    if (!(box_fraction > 0) || !std::isfinite(box_fraction))
        return fail("box_fraction must be > 0 (got " + std::to_string(box_fraction) + ")");
    if (!(tolerance >= 0) || !std::isfinite(tolerance))
        return fail("tolerance must be >= 0 (got " + std::to_string(tolerance) + ")");
    if (patience < 1) return fail("patience must be >= 1 (got " + std::to_string(patience) + ")");
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
    const auto t0 = std::chrono::steady_clock::now();
    auto seconds = [&] {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    };
    std::atomic<long> evaluations{0};
    Evaluator ev;
    ev.start = start;
    ev.objective = &objective;
    ev.constrain = &options.constrain;
    ev.evaluations = &evaluations;
    const std::vector<double> values = sizing_values(start);
    SizingProblem problem;
    problem.evaluator = &ev;
    pagmo::vector_double x0;
    for (size_t i = 0; i < params.size(); ++i) {
        if (!options.free.empty() && !options.free[i]) continue;
        const double half = options.box_fraction * (params[i].max - params[i].min);
        const double floor_i = options.lower_bounds.empty() || std::isnan(options.lower_bounds[i])
                                   ? params[i].min
                                   : std::clamp(options.lower_bounds[i], params[i].min, params[i].max);
        const double v = std::clamp(values[i], floor_i, params[i].max);
        double lo = std::max(floor_i, v - half), hi = std::min(params[i].max, v + half);
        if (!(hi > lo)) continue;  // a parameter pinned at a degenerate range stays fixed
        ev.free_index.push_back(static_cast<int>(i));
        problem.lower.push_back(lo);
        problem.upper.push_back(hi);
        x0.push_back(v);
    }

    SizingSearchSummary out;
    out.best = options.constrain ? options.constrain(start) : start;
    if (ev.free_index.empty()) {
        out.best_objective = out.start_objective = ev.evaluate({}, 0);
        out.evaluations = evaluations;
        out.termination = SizingSearchTermination::converged;
        out.message = "no free parameter";
        out.seconds = seconds();
        return out;
    }

    pagmo::problem prob{problem};
    const pagmo::bfe bfe{WorkerBfe{&ev, options.threads}};
    // The initial swarm: the start and particles - 1 uniform draws in the box, one batch.
    pagmo::population pop{prob, bfe, static_cast<pagmo::population::size_type>(options.particles), options.seed};
    const double f0 = ev.evaluate(x0, 0);
    pop.set_xf(0, x0, {f0});
    out.start_objective = f0;
    auto best_now = [&] { return pop.champion_f()[0]; };
    out.history.push_back(best_now());
    auto report = [&](int generation) {
        if (!options.on_progress) return true;
        SizingSearchProgress p;
        p.generation = generation;
        p.generations = options.generations;
        p.evaluations = evaluations;
        p.best = best_now();
        p.seconds = seconds();
        return options.on_progress(p);
    };
    out.termination = SizingSearchTermination::max_generations;
    if (!report(0)) {
        out.termination = SizingSearchTermination::cancelled;
    } else {
        // One generation per evolve (memory keeps the velocities between calls), so that
        // progress, cancel and convergence are checked between generations.
        pagmo::pso_gen pso(1u, 0.7298, 2.05, 2.05, 0.5, 5u, 2u, 4u, true, options.seed);
        pso.set_bfe(bfe);
        for (int g = 1; g <= options.generations; ++g) {
            pop = pso.evolve(pop);
            out.generations = g;
            out.history.push_back(best_now());
            if (!report(g)) {
                out.termination = SizingSearchTermination::cancelled;
                break;
            }
            if (options.tolerance > 0 && g >= options.patience) {
                const double before = out.history[out.history.size() - 1 - static_cast<size_t>(options.patience)];
                const double now = out.history.back();
                if (before - now <= options.tolerance * std::abs(before)) {
                    out.termination = SizingSearchTermination::converged;
                    break;
                }
            }
        }
    }
    out.evaluations = evaluations;
    out.best_objective = best_now();
    if (out.best_objective >= kRefused) {
        out.termination = SizingSearchTermination::failed;
        out.message = "no candidate sizing could be evaluated";
        out.best_objective = std::numeric_limits<double>::infinity();
    } else {
        out.best = ev.sizing_of(pop.champion_x());
    }
    out.seconds = seconds();
    return out;
}

}  // namespace drape::garment
