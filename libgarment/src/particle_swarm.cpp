#include <drape/garment/particle_swarm.hpp>

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
#include <exception>
#include <limits>
#include <mutex>
#include <thread>

namespace drape::garment {

namespace {

// A point that cannot be evaluated or whose objective is not finite: large, finite, so the
// swarm's arithmetic stays finite.
constexpr double kRefused = 1e30;

struct Evaluator {
    const SwarmObjective* objective = nullptr;
    std::atomic<long>* evaluations = nullptr;

    double evaluate(const pagmo::vector_double& x, int worker) const {
        ++*evaluations;
        try {
            const double f = (*objective)(x, worker);
            return std::isfinite(f) ? std::min(f, kRefused) : kRefused;
        } catch (const InvalidInput&) {
            return kRefused;
        }
    }
};

// pagmo's user-defined problem: a box-bounded single objective.
struct BoxProblem {
    const Evaluator* evaluator = nullptr;
    pagmo::vector_double lower, upper;

    pagmo::vector_double fitness(const pagmo::vector_double& x) const { return {evaluator->evaluate(x, 0)}; }
    std::pair<pagmo::vector_double, pagmo::vector_double> get_bounds() const { return {lower, upper}; }
    std::string get_name() const { return "drape particle swarm problem"; }
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

bool SwarmOptions::is_valid(std::string* why) const {
    auto fail = [&](const std::string& m) {
        if (why) *why = m;
        return false;
    };
    if (particles < 2) return fail("particles must be >= 2 (got " + std::to_string(particles) + ")");
    if (generations < 0) return fail("generations must be >= 0 (got " + std::to_string(generations) + ")");
    if (threads < 1) return fail("threads must be >= 1 (got " + std::to_string(threads) + ")");
    if (!(tolerance >= 0) || !std::isfinite(tolerance))
        return fail("tolerance must be >= 0 (got " + std::to_string(tolerance) + ")");
    if (patience < 1) return fail("patience must be >= 1 (got " + std::to_string(patience) + ")");
    return true;
}

SwarmSummary minimise_swarm(const std::vector<double>& start, const std::vector<double>& lower,
                            const std::vector<double>& upper, const SwarmObjective& objective,
                            const SwarmOptions& options) {
    std::string why;
    if (!options.is_valid(&why)) throw InvalidInput("particle swarm options: " + why);
    if (!objective) throw InvalidInput("particle swarm: no objective given");
    require(lower.size() == start.size() && upper.size() == start.size(), "particle swarm: the start has ",
            start.size(), " values, lower ", lower.size(), " and upper ", upper.size(), " (must be equal)");
    for (size_t i = 0; i < start.size(); ++i)
        require(std::isfinite(lower[i]) && std::isfinite(upper[i]) && lower[i] <= upper[i] && start[i] >= lower[i] &&
                    start[i] <= upper[i],
                "particle swarm: dimension ", i, ": start ", start[i], " must lie in a finite box [", lower[i], ", ",
                upper[i], "]");
    const auto t0 = std::chrono::steady_clock::now();
    auto seconds = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };
    std::atomic<long> evaluations{0};
    Evaluator ev{&objective, &evaluations};
    SwarmSummary out;
    out.best = start;
    if (start.empty()) {
        out.best_objective = out.start_objective = ev.evaluate({}, 0);
        out.evaluations = evaluations;
        out.termination = SwarmTermination::converged;
        out.seconds = seconds();
        return out;
    }
    BoxProblem problem{&ev, lower, upper};
    pagmo::problem prob{problem};
    const pagmo::bfe bfe{WorkerBfe{&ev, options.threads}};
    // The initial swarm: the start and particles - 1 uniform draws in the box, one batch.
    pagmo::population pop{prob, bfe, static_cast<pagmo::population::size_type>(options.particles), options.seed};
    const double f0 = ev.evaluate(start, 0);
    pop.set_xf(0, start, {f0});
    out.start_objective = f0;
    auto best_now = [&] { return pop.champion_f()[0]; };
    out.history.push_back(best_now());
    auto report = [&](int generation) {
        if (!options.on_progress) return true;
        SwarmProgress p;
        p.generation = generation;
        p.generations = options.generations;
        p.evaluations = evaluations;
        p.best = best_now();
        p.seconds = seconds();
        return options.on_progress(p);
    };
    out.termination = SwarmTermination::max_generations;
    if (!report(0)) {
        out.termination = SwarmTermination::cancelled;
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
                out.termination = SwarmTermination::cancelled;
                break;
            }
            if (options.tolerance > 0 && g >= options.patience) {
                const double before = out.history[out.history.size() - 1 - static_cast<size_t>(options.patience)];
                const double now = out.history.back();
                if (before - now <= options.tolerance * std::abs(before)) {
                    out.termination = SwarmTermination::converged;
                    break;
                }
            }
        }
    }
    out.evaluations = evaluations;
    out.best_objective = best_now();
    if (out.best_objective >= kRefused) {
        out.termination = SwarmTermination::failed;
        out.best_objective = std::numeric_limits<double>::infinity();
    } else {
        out.best = pop.champion_x();
    }
    out.seconds = seconds();
    return out;
}

}  // namespace drape::garment
