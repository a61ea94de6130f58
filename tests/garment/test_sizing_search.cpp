// The sizing search (PSO through pagmo2) and the silhouette distance of recovery.
#include <drape/core/errors.hpp>
#include <drape/garment/silhouette_distance.hpp>
#include <drape/garment/sizing_search.hpp>

#include <catch2/catch.hpp>

#include <atomic>
#include <cmath>
#include <set>
#include <mutex>

using namespace drape;
using namespace drape::garment;

namespace {

// A smooth bowl over the template's parameters with its minimum at `target`.
double bowl(const GarmentSizing& g, const GarmentSizing& target) {
    const auto p = sizing_parameters(g.type);
    const auto v = sizing_values(g), t = sizing_values(target);
    double s = 0;
    for (size_t i = 0; i < p.size(); ++i) {
        const double d = (v[i] - t[i]) / (p[i].max - p[i].min);
        s += d * d;
    }
    return s;
}

BinaryImage rectangle(int w, int h, int x0, int y0, int x1, int y1) {
    BinaryImage b;
    b.width = w;
    b.height = h;
    b.pixels.assign(static_cast<size_t>(w * h), 0);
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) b.pixels[static_cast<size_t>(y * w + x)] = 1;
    return b;
}

}  // namespace

TEST_CASE("sizing parameters flatten and restore every template", "[sizing_search]") {
    for (const auto type : {GarmentType::skirt, GarmentType::pants, GarmentType::tshirt, GarmentType::dress}) {
        GarmentSizing g;
        g.type = type;
        const auto p = sizing_parameters(type);
        auto v = sizing_values(g);
        REQUIRE(v.size() == p.size());
        for (size_t i = 0; i < v.size(); ++i) v[i] = 0.5 * (p[i].min + p[i].max) + 0.01 * double(i);
        const auto back = sizing_values(with_sizing_values(g, v));
        for (size_t i = 0; i < v.size(); ++i) CHECK(back[i] == v[i]);
        CHECK_THROWS_AS(with_sizing_values(g, std::vector<double>(v.size() + 1, 1.0)), InvalidInput);
    }
    CHECK(sizing_parameters(GarmentType::dress).size() ==
          sizing_parameters(GarmentType::tshirt).size() + sizing_parameters(GarmentType::skirt).size());
    CHECK(sizing_parameters(GarmentType::dress)[0].name == "bodice.r");
}

TEST_CASE("the PSO finds the minimum of a bowl from an offset start", "[sizing_search]") {
    GarmentSizing target;
    target.type = GarmentType::skirt;
    target.skirt = {40.0, 26.0, 60.0, 110.0};
    GarmentSizing start = target;
    start.skirt = {36.0, 23.0, 52.0, 95.0};
    std::mutex m;
    std::set<int> workers;
    SizingSearchOptions o;
    o.particles = 24;
    o.generations = 25;
    o.threads = 2;
    o.tolerance = 0;
    const auto s = search_sizing(
        start,
        [&](const GarmentSizing& g, int worker) {
            {
                const std::lock_guard<std::mutex> lock(m);
                workers.insert(worker);
            }
            return bowl(g, target);
        },
        o);
    CHECK(s.termination == SizingSearchTermination::max_generations);
    CHECK(s.generations == 25);
    CHECK(s.start_objective == Approx(bowl(start, target)));
    CHECK(s.best_objective < 1e-2 * s.start_objective);  // within ~1 % of each range
    for (size_t i = 1; i < s.history.size(); ++i) CHECK(s.history[i] <= s.history[i - 1]);
    CHECK(std::abs(s.best.skirt.r2 - 60.0) < 1.0);
    CHECK(std::abs(s.best.skirt.alpha - 110.0) < 4.0);
    CHECK(s.evaluations >= 24L * 26L);
    for (int w : workers) CHECK((w == 0 || w == 1));
    // Same seed, same search.
    const auto again = search_sizing(start, [&](const GarmentSizing& g, int) { return bowl(g, target); }, o);
    CHECK(again.best_objective == s.best_objective);
}

TEST_CASE("the sizing search keeps fixed parameters, ties a dress's waist, stops and refuses bad options",
          "[sizing_search]") {
    GarmentSizing start;
    start.type = GarmentType::dress;
    start = tie_dress_waist(start);
    GarmentSizing target = start;
    target.dress.bodice.h2 += 4;
    SizingSearchOptions o;
    o.particles = 8;
    o.generations = 3;
    o.free.assign(sizing_parameters(GarmentType::dress).size(), false);
    o.free[4] = true;  // bodice.h2
    o.free[1] = true;  // bodice.w1
    o.constrain = tie_dress_waist;
    std::atomic<int> untied{0};
    const auto s = search_sizing(
        start,
        [&](const GarmentSizing& g, int) {
            if (g.dress.skirt.l1 != g.dress.bodice.w2) ++untied;
            return bowl(g, target);
        },
        o);
    CHECK(untied == 0);
    const auto v0 = sizing_values(start), v1 = sizing_values(s.best);
    for (size_t i = 0; i < v0.size(); ++i)
        if (i != 1 && i != 4) CHECK(v1[i] == v0[i]);

    // A lower bound keeps a girth from shrinking below it, even where the bowl's minimum is.
    SizingSearchOptions lb = o;
    lb.free.assign(sizing_parameters(GarmentType::dress).size(), false);
    lb.free[2] = true;  // bodice.w2
    lb.lower_bounds.assign(lb.free.size(), std::nan(""));
    lb.lower_bounds[2] = start.dress.bodice.w2;
    GarmentSizing narrower = start;
    narrower.dress.bodice.w2 -= 6;
    const auto bounded = search_sizing(start, [&](const GarmentSizing& g, int) { return bowl(g, narrower); }, lb);
    CHECK(bounded.best.dress.bodice.w2 >= start.dress.bodice.w2);
    CHECK(bounded.best.dress.bodice.w2 < start.dress.bodice.w2 + 0.5);
    lb.lower_bounds.resize(2);
    CHECK_THROWS_WITH(search_sizing(start, [](const GarmentSizing&, int) { return 0.0; }, lb),
                      Catch::Contains("lower_bounds has 2 entries"));

    int calls = 0;
    o.on_progress = [&](const SizingSearchProgress& p) { return ++calls, p.generation < 1; };
    const auto c = search_sizing(start, [&](const GarmentSizing& g, int) { return bowl(g, target); }, o);
    CHECK(c.termination == SizingSearchTermination::cancelled);
    CHECK(c.generations == 1);

    // Candidates the template refuses count as +infinity; if all do, the search failed.
    o.on_progress = nullptr;
    const auto f = search_sizing(start, [](const GarmentSizing&, int) -> double { throw InvalidInput("no"); }, o);
    CHECK(f.termination == SizingSearchTermination::failed);

    o.particles = 1;
    CHECK_THROWS_AS(search_sizing(start, [](const GarmentSizing&, int) { return 0.0; }, o), InvalidInput);
    o.particles = 8;
    o.free.resize(3);
    CHECK_THROWS_WITH(search_sizing(start, [](const GarmentSizing&, int) { return 0.0; }, o),
                      Catch::Contains("free has 3 entries"));
}

TEST_CASE("the silhouette distance measures outline offsets over the visible boundary only", "[sizing_search]") {
    const int w = 120, h = 100;
    SilhouetteTarget t;
    t.garment = rectangle(w, h, 30, 20, 90, 80);
    const SilhouetteScorer scorer(t);
    CandidateSilhouette same;
    same.visible = t.garment;
    const auto d0 = scorer.score(same);
    CHECK(d0.energy_px2 == 0.0);
    CHECK(d0.candidate_points > 200);

    // Shifted right by 5 px: the left and right sides are 5 px off, top and bottom 0 (for
    // most of their length): the RMS lies between.
    CandidateSilhouette shifted;
    shifted.visible = rectangle(w, h, 35, 20, 95, 80);
    const auto d5 = scorer.score(shifted);
    CHECK(d5.candidate_to_target_px > 2.0);
    CHECK(d5.candidate_to_target_px < 5.0);
    CHECK(d5.energy_px2 > d0.energy_px2);

    // A wider candidate whose extra part is hidden by an occluder in the photo scores as
    // the same outline where it is counted.
    SilhouetteTarget t2 = t;
    t2.occluders = rectangle(w, h, 85, 0, 120, 100);
    const SilhouetteScorer scorer2(t2);
    CandidateSilhouette wider;
    wider.visible = rectangle(w, h, 30, 20, 100, 80);
    CHECK(scorer2.score(wider).energy_px2 < 0.05 * scorer.score(wider).energy_px2 + 1e-9);

    // Occlusion edges of the candidate (something in front) are not its outline.
    CandidateSilhouette cut;
    cut.visible = rectangle(w, h, 30, 20, 70, 80);
    cut.occluded = rectangle(w, h, 70, 20, 90, 80);
    const auto dc = scorer.score(cut);
    CandidateSilhouette cut_open = cut;
    cut_open.occluded = BinaryImage{};
    CHECK(dc.energy_px2 < scorer.score(cut_open).energy_px2);

    CandidateSilhouette wrong;
    wrong.visible = rectangle(w + 1, h, 0, 0, 1, 1);
    CHECK_THROWS_WITH(scorer.score(wrong), Catch::Contains("121 x 100"));
    SilhouetteDistanceOptions bad;
    bad.cap_px = 0;
    CHECK_THROWS_WITH(SilhouetteScorer(t, bad), Catch::Contains("cap_px"));
}

#include <drape/garment/material_search.hpp>

TEST_CASE("the bending search finds the scale whose curvature matches the target", "[sizing_search]") {
    // A monotone curvature law like a drape's: stiffer cloth, fewer and wider folds.
    const auto k = [](double x) { return 8.0 * std::pow(10.0, -0.35 * x) + 1.0; };
    MaterialSearchOptions o;
    for (const double truth : {0.3, 1.0, 1.7}) {
        const auto s = search_bending(k(truth), k, o);
        CHECK(s.termination == MaterialSearchTermination::converged);
        CHECK(std::abs(s.mean_curvature_per_m - k(truth)) <= 0.01 * k(truth));
        CHECK(std::abs(s.log10_bending_scale - truth) < 0.06);
        CHECK(s.evaluations <= 20);  // each is a static drape: the search must stay cheap
    }
    // A target beyond the stiffest: the search stops at the bound.
    const auto b = search_bending(k(2.0) * 0.5, k, o);
    CHECK(b.termination == MaterialSearchTermination::at_bound);
    CHECK(b.log10_bending_scale > 1.9);
    CHECK_THROWS_WITH(search_bending(-1.0, k, o), Catch::Contains("target mean curvature"));
    o.max_iterations = 0;
    CHECK_THROWS_WITH(search_bending(1.0, k, o), Catch::Contains("max_iterations"));
}
