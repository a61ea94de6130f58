// drape bench-sizing-drape: its arguments are checked before any simulation (the figures
// themselves are measured by running the command, docs/benchmarks.md).
#include "cli_runner.hpp"

#include <catch2/catch.hpp>

using drape::test::run_drape;

TEST_CASE("drape bench-sizing-drape rejects bad arguments, naming them", "[apps][bench-sizing-drape]") {
    const auto edge = run_drape("bench-sizing-drape --edge 0");
    CHECK(edge.exit_code == 2);
    CHECK(edge.out.find("--edge 0") != std::string::npos);
    CHECK(run_drape("bench-sizing-drape --samples 0").exit_code == 2);
    CHECK(run_drape("bench-sizing-drape --perturb 0.7").exit_code == 2);
    CHECK(run_drape("bench-sizing-drape --samples 2 --compare 3").exit_code == 2);
    const auto warm = run_drape("bench-sizing-drape --warm sideways");
    CHECK(warm.exit_code == 2);
    CHECK(warm.out.find("--warm sideways") != std::string::npos);
}
