// drape bench-cloth: the anchor scene benchmark's command line (figures and JSON contract of
// issue 3; the timing itself is recorded in docs/benchmarks.md, not asserted).
#include "cli_runner.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <string>

using drape::test::run_drape;

TEST_CASE("drape bench-cloth prints the split timing and one JSON object on its last line",
          "[apps][bench-cloth]") {
    const auto r = run_drape("bench-cloth --scene square-sphere --grid 8 --steps 60 --json --quiet");
    INFO(r.out);
    REQUIRE(r.exit_code == 0);
    CHECK(r.out.find("assembly") != std::string::npos);
    CHECK(r.out.find("factorisation + solve") != std::string::npos);
    CHECK(r.out.find("contact detection") != std::string::npos);
    std::string body = r.out;
    while (!body.empty() && body.back() == '\n') body.pop_back();
    const nlohmann::json j = nlohmann::json::parse(body.substr(body.rfind('\n') + 1));
    for (const char* key : {"ms_per_step", "centre_z_m", "min_z_m", "max_penetration_m",
                            "self_intersections", "steps", "ms_assembly_per_step",
                            "ms_solve_per_step", "ms_contact_per_step"})
        CHECK(j.contains(key));
    CHECK(j["steps"] == 60);
    CHECK(j["nodes"] == 81);
    // 0.3 s: a 1 m square dropped 0.1 m onto a 0.5 m sphere lies on its top.
    CHECK(j["centre_z_m"].get<double>() == Approx(0.505).margin(0.003));
    CHECK(j["max_penetration_m"].get<double>() <= 1e-3);
    CHECK(j["self_intersections"] == 0);
    CHECK(j["ms_per_step"].get<double>() > 0);
    // Every Newton iteration that computes a step factors its matrix at least once.
    CHECK(j["factorisations_per_step"].get<double>() >= j["newton_iterations_per_step"].get<double>());
    CHECK(j["max_nonconvex_step_iterations"] == 4);
}

TEST_CASE("drape bench-cloth rejects unknown scenes and bad sizes", "[apps][bench-cloth]") {
    CHECK(run_drape("bench-cloth --scene cube --steps 1").exit_code == 2);
    CHECK(run_drape("bench-cloth --grid 7 --steps 1").exit_code == 2);
    CHECK(run_drape("bench-cloth --steps 0").exit_code == 2);
    CHECK(run_drape("bench-cloth --max-nonconvex -3 --steps 1").exit_code == 2);
    const auto r = run_drape("bench-cloth --scene cube --steps 1");
    CHECK(r.out.find("--scene cube") != std::string::npos);
}
