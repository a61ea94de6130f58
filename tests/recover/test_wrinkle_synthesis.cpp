// The bending search by analysis by synthesis on known P(s_b) curves: it lands on the
// bending scale whose P matches the photo's, reports the range of equally good ones, and
// refuses a negative P.
#include "../../librecover/src/wrinkle_synthesis.hpp"

#include <drape/core/errors.hpp>

#include <catch2/catch.hpp>

#include <cmath>

using namespace drape;
using namespace drape::recover;

TEST_CASE("the synthesis search finds the bending scale whose render shows the photo's P", "[recover][synthesis]") {
    // P falls from 40 (x1) to 4 (x100), log-linearly: P = 40 * 10^(-x / 2).
    int calls = 0;
    auto p_at = [&](double x) {
        ++calls;
        return 40.0 * std::pow(10.0, -x / 2);
    };
    // The photo shows P = 12.6: x = 2 log10(40 / 12.6) = 1.00.
    const SynthesisSearch s = search_bending_by_synthesis(12.6, p_at);
    CHECK(s.log10_bending_scale == Approx(1.0).margin(0.01));
    CHECK(s.wrinkle_density_per_m2 == Approx(40.0 / std::sqrt(10.0)).epsilon(1e-9));
    CHECK(s.objective < 1e-4);
    CHECK(s.evaluations == calls);
    CHECK(s.evaluations == 7);
    CHECK(s.low <= s.log10_bending_scale);
    CHECK(s.high >= s.log10_bending_scale);
    CHECK(s.high - s.low <= 1.0);
    // Between grid points: the quarter step refines (P = 20 at x = 0.60; grid 0.5, then 0.75).
    const SynthesisSearch q = search_bending_by_synthesis(20.0, p_at);
    CHECK(q.log10_bending_scale == Approx(0.5).margin(0.01));
    // No fold in the photo: the stiffest candidate (fewest folds).
    const SynthesisSearch none = search_bending_by_synthesis(0.0, p_at);
    CHECK(none.log10_bending_scale == Approx(2.0));
    CHECK_THROWS_AS(search_bending_by_synthesis(-1.0, p_at), InvalidInput);
}

TEST_CASE("the synthesis search reports a flat P as a wide range", "[recover][synthesis]") {
    const SynthesisSearch s = search_bending_by_synthesis(10.0, [](double) { return 10.0; });
    CHECK(s.objective == Approx(0.0).margin(1e-12));
    CHECK(s.low == Approx(0.0));
    CHECK(s.high == Approx(2.0));
}
