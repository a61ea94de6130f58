// The box-bounded particle swarm (pagmo2's generational PSO) behind the sizing search and the
// joint material-pose search: it finds known minima, keeps to the box, and never returns
// worse than its start.
#include <drape/core/errors.hpp>
#include <drape/garment/particle_swarm.hpp>

#include <catch2/catch.hpp>

#include <atomic>
#include <chrono>
#include <thread>
#include <cmath>

using namespace drape::garment;

TEST_CASE("particle swarm: a shifted quadratic bowl's minimum, in parallel", "[garment][swarm]") {
    const std::vector<double> centre = {1.5, -0.7, 2.2};
    std::atomic<int> calls{0};
    std::atomic<int> worker_max{0};
    auto bowl = [&](const std::vector<double>& x, int worker) {
        ++calls;
        int w = worker_max.load();
        while (worker > w && !worker_max.compare_exchange_weak(w, worker)) {
        }
        // Slow enough that the second worker takes particles of every batch (a drape takes ~1 s).
        std::this_thread::sleep_for(std::chrono::microseconds(300));
        double s = 0;
        for (size_t i = 0; i < x.size(); ++i) s += (x[i] - centre[i]) * (x[i] - centre[i]);
        return s;
    };
    SwarmOptions o;
    o.particles = 24;
    o.generations = 40;
    o.threads = 2;
    o.tolerance = 0;
    const SwarmSummary s = minimise_swarm({0, 0, 0}, {-3, -3, -3}, {3, 3, 3}, bowl, o);
    CHECK(s.termination == SwarmTermination::max_generations);
    CHECK(s.start_objective == Approx(1.5 * 1.5 + 0.7 * 0.7 + 2.2 * 2.2));
    CHECK(s.best_objective < 1e-3);
    for (size_t i = 0; i < centre.size(); ++i) CHECK(s.best[i] == Approx(centre[i]).margin(0.05));
    CHECK(s.evaluations == calls.load());
    CHECK(s.evaluations >= 24 * 40);
    CHECK(worker_max.load() == 1);
    for (size_t i = 1; i < s.history.size(); ++i) CHECK(s.history[i] <= s.history[i - 1]);
}

TEST_CASE("particle swarm: a minimum outside the box ends on its wall, refused points never win",
          "[garment][swarm]") {
    SwarmOptions o;
    o.particles = 16;
    o.generations = 25;
    o.threads = 1;
    // The bowl's centre is at x = 5, the box ends at 2; points with x < -1 are refused.
    const SwarmSummary s = minimise_swarm(
        {0}, {-2}, {2},
        [](const std::vector<double>& x, int) {
            if (x[0] < -1) throw drape::InvalidInput("refused");
            return (x[0] - 5) * (x[0] - 5);
        },
        o);
    CHECK(s.best[0] <= 2.0);
    CHECK(s.best[0] == Approx(2.0).margin(0.02));
    CHECK(s.best_objective <= s.start_objective);
}

TEST_CASE("particle swarm: bad boxes and options are refused", "[garment][swarm]") {
    auto f = [](const std::vector<double>&, int) { return 0.0; };
    using Catch::Matchers::Contains;
    CHECK_THROWS_WITH(minimise_swarm({0}, {1}, {2}, f, {}), Contains("dimension 0") && Contains("start 0"));
    CHECK_THROWS_WITH(minimise_swarm({0, 0}, {-1}, {1}, f, {}), Contains("must be equal"));
    SwarmOptions o;
    o.particles = 1;
    CHECK_THROWS_WITH(minimise_swarm({0}, {-1}, {1}, f, o), Contains("particles"));
    CHECK_THROWS_WITH(minimise_swarm({0}, {-1}, {1}, SwarmObjective{}, {}), Contains("no objective"));
    // Cancelled after the initial swarm.
    SwarmOptions c;
    c.on_progress = [](const SwarmProgress&) { return false; };
    CHECK(minimise_swarm({0}, {-1}, {1}, f, c).termination == SwarmTermination::cancelled);
}
