#include <drape/cloth/material.hpp>
#include <drape/core/errors.hpp>

#include <catch2/catch.hpp>

#include "gray_interlock_fixture.hpp"
#include <test_paths.hpp>

#include <cmath>
#include <fstream>
#include <map>
#include <string>

using namespace drape::cloth;
using Catch::Matchers::Contains;

namespace {

constexpr double kPi = 3.14159265358979323846;

// Densities from ../shared/materials/README.md.
const std::map<std::string, double> kDensities = {
    {"gray-interlock.json", 0.187},   {"11oz-black-denim.json", 0.324},
    {"camel-ponte-roma.json", 0.284}, {"ivory-rib-knit.json", 0.276},
    {"navy-sparkle-sweat.json", 0.224}, {"pink-ribbon-brown.json", 0.228},
    {"royal-target.json", 0.22},      {"tango-red-jet-set.json", 0.113},
    {"white-dots-on-blk.json", 0.128}, {"white-swim-solid.json", 0.204},
    {"paper.json", 0.1},              {"aluminium.json", 0.071},
};

double row0(const Material& m, int c) { return m.stretching_n_per_m[0][static_cast<std::size_t>(c)]; }

Material gray_like() { return drape::test::gray_interlock_material(); }

std::filesystem::path write_file(const std::string& name, const std::string& text) {
    const auto path = drape::test::scratch_dir("cloth_material") / name;
    std::ofstream(path) << text;
    return path;
}

const char* kGood = R"({"density": 0.2,
 "stretching": [[1,2,3,4],[1,2,3,4],[1,2,3,4],[1,2,3,4],[1,2,3,4],[1,2,3,4]],
 "bending": [[1,2,3,4,5],[1,2,3,4,5],[1,2,3,4,5]]})";

}  // namespace

TEST_CASE("every shipped material loads with the README's densities", "[cloth][material]") {
    DRAPE_REQUIRE_SHARED(dir, "materials");
    int loaded = 0;
    for (const auto& [name, density] : kDensities) {
        const auto path = dir / name;
        if (!std::filesystem::exists(path)) {
            WARN("skipped: " << path << " absent");
            continue;
        }
        INFO(name);
        const Material m = load_material(path);
        CHECK(m.density_kg_per_m2 == Approx(density).epsilon(1e-12));
        CHECK(m.is_valid());
        CHECK(m.stretching_scale == 1);
        CHECK(m.bending_scale == 1);
        for (const auto& row : m.bending_n_m)
            for (double b : row) {
                CHECK(b > 0);
                CHECK(b < 1e-3);  // N·m: fabrics are ~1e-5, paper 4e-4
            }
        ++loaded;
    }
    CHECK(loaded == 12);
}

TEST_CASE("material values match the files and the README's units", "[cloth][material]") {
    DRAPE_REQUIRE_SHARED(dir, "materials");
    if (std::filesystem::exists(dir / "gray-interlock.json")) {
        const Material m = load_material(dir / "gray-interlock.json");
        const Material ref = gray_like();
        CHECK(m.stretching_n_per_m == ref.stretching_n_per_m);
        CHECK(m.bending_n_m == ref.bending_n_m);
        CHECK(m.stretching_n_per_m[4][3] == -174.43853);
    }
    if (std::filesystem::exists(dir / "paper.json")) {
        // "stretching stiffness = Eh = 0.5 MN/m", "E h³/12 = 0.4 mNm" (file comments).
        const Material m = load_material(dir / "paper.json");
        CHECK(m.stretching_n_per_m[3][0] == 0.5e6);
        CHECK(m.stretching_n_per_m[3][1] == 0);
        CHECK(m.bending_n_m[2][4] == 0.4e-3);
        const auto k = stretching_stiffness(m, Eigen::Matrix2d::Zero());
        CHECK(k.k_uu == 1e6);  // ArcSim's factor 2
    }
    if (std::filesystem::exists(dir / "aluminium.json")) {
        const Material m = load_material(dir / "aluminium.json");
        CHECK(m.stretching_n_per_m[0][2] == 1.8e6);
        CHECK(m.bending_n_m[1][1] == 96e-6);
    }
}

TEST_CASE("stretching lookup interpolates the table", "[cloth][material]") {
    const Material m = gray_like();
    const auto& t = m.stretching_n_per_m;
    SECTION("zero strain uses row 0 in every direction, negatives clamped to 0") {
        for (double dir : {0.0, 0.3, kPi / 2}) {
            const auto k = stretching_stiffness(m, 1.0, dir);
            CHECK(k.k_uu == Approx(2 * row0(m, 0)));
            CHECK(k.k_uv == 0);  // row 0 has k1 = -14.7
            CHECK(k.k_vv == Approx(2 * row0(m, 2)));
            CHECK(k.k_shear == Approx(2 * row0(m, 3)));
        }
        const auto compressed = stretching_stiffness(m, 0.8, 0.2);
        CHECK(compressed.k_uu == Approx(2 * row0(m, 0)));
    }
    SECTION("w = 7/6 hits the direction samples, and stays constant beyond") {
        for (int d = 0; d < 5; ++d) {
            const auto r = t[static_cast<std::size_t>(1 + d)];
            for (double w : {7.0 / 6.0, 1.5}) {
                const auto k = stretching_stiffness(m, w, d * kPi / 8);
                CHECK(k.k_uu == Approx(2 * r[0]));
                CHECK(k.k_vv == Approx(2 * r[2]));
                CHECK(k.k_shear == Approx(2 * std::max(r[3], 0.0)));
            }
        }
    }
    SECTION("bilinear between samples") {
        const double w = 1 + 1.0 / 12, dir = kPi / 16;  // half way in both
        const auto k = stretching_stiffness(m, w, dir);
        const double expected = 0.5 * t[0][0] + 0.25 * (t[1][0] + t[2][0]);
        CHECK(k.k_uu == Approx(2 * expected));
    }
    SECTION("direction folds: -x and 180 - x equal x") {
        const auto a = stretching_stiffness(m, 1.1, 0.4);
        CHECK(stretching_stiffness(m, 1.1, -0.4).k_uu == Approx(a.k_uu));
        CHECK(stretching_stiffness(m, 1.1, kPi - 0.4).k_vv == Approx(a.k_vv));
    }
    SECTION("from a Green strain: stretch along u and along v") {
        const double lambda = 1.1, g = (lambda * lambda - 1) / 2;
        Eigen::Matrix2d gu = Eigen::Matrix2d::Zero(), gv = Eigen::Matrix2d::Zero();
        gu(0, 0) = g;
        gv(1, 1) = g;
        CHECK(stretching_stiffness(m, gu).k_uu == Approx(stretching_stiffness(m, lambda, 0).k_uu));
        CHECK(stretching_stiffness(m, gv).k_vv ==
              Approx(stretching_stiffness(m, lambda, kPi / 2).k_vv));
    }
    SECTION("scale multiplies") {
        Material s = m;
        s.stretching_scale = 3;
        CHECK(stretching_stiffness(s, 1.1, 0.2).k_vv ==
              Approx(3 * stretching_stiffness(m, 1.1, 0.2).k_vv));
    }
    CHECK_THROWS_AS(stretching_stiffness(m, std::nan(""), 0), drape::InvalidInput);
}

TEST_CASE("bending lookup interpolates the table", "[cloth][material]") {
    const Material m = gray_like();
    const auto& b = m.bending_n_m;
    CHECK(bending_stiffness(m, 0, 0) == Approx(b[0][0]));
    CHECK(bending_stiffness(m, kPi / 4, 20) == Approx(b[1][2]));
    CHECK(bending_stiffness(m, kPi / 2, 40) == Approx(b[2][4]));
    CHECK(bending_stiffness(m, kPi / 2, 400) == Approx(b[2][4]));   // clamped above
    CHECK(bending_stiffness(m, kPi / 8, 5) ==
          Approx(0.25 * (b[0][0] + b[0][1] + b[1][0] + b[1][1])));
    CHECK(bending_stiffness(m, kPi, 10) == Approx(b[0][1]));        // folds to 0°
    CHECK(bending_stiffness(m, -kPi / 2, 10) == Approx(b[2][1]));   // folds to 90°
    // Negative curvature extrapolates from columns 0 and 1 (ArcSim), clamped to >= 0.
    CHECK(bending_stiffness(m, 0, -10) == Approx(2 * b[0][0] - b[0][1]).margin(1e-12));
    CHECK(bending_stiffness(m, 0, -40) == 0);  // 23.2 - 4 * 9.7 < 0
    Material s = m;
    s.bending_scale = 0.5;
    CHECK(bending_stiffness(s, 0.3, 12) == Approx(0.5 * bending_stiffness(m, 0.3, 12)));
}

TEST_CASE("load_material accepts comments and rejects malformed files naming the field",
          "[cloth][material]") {
    const Material good = load_material(write_file("good.json", std::string("// a comment\n") + kGood));
    CHECK(good.density_kg_per_m2 == 0.2);
    CHECK(good.bending_n_m[2][4] == 5);

    auto rejects = [](const std::string& name, const std::string& text, const std::string& needle) {
        INFO(name);
        const auto path = write_file(name, text);
        CHECK_THROWS_AS(load_material(path), drape::InvalidInput);
        CHECK_THROWS_WITH(load_material(path), Contains(needle) && Contains(name));
    };
    rejects("no_density.json", R"({"stretching": [], "bending": []})", "'density' is missing");
    rejects("neg_density.json",
            std::string(kGood).replace(std::string(kGood).find("0.2"), 3, "-0.2"), "'density'");
    rejects("five_rows.json",
            R"({"density": 0.2, "stretching": [[1,2,3,4],[1,2,3,4],[1,2,3,4],[1,2,3,4],[1,2,3,4]],
                "bending": [[1,2,3,4,5],[1,2,3,4,5],[1,2,3,4,5]]})",
            "'stretching'");
    rejects("short_row.json",
            R"({"density": 0.2, "stretching": [[1,2,3,4],[1,2,3,4],[1,2,3],[1,2,3,4],[1,2,3,4],[1,2,3,4]],
                "bending": [[1,2,3,4,5],[1,2,3,4,5],[1,2,3,4,5]]})",
            "'stretching' row 2");
    rejects("string_value.json",
            R"({"density": 0.2, "stretching": [[1,2,3,4],[1,2,3,4],[1,2,3,4],[1,2,3,4],[1,2,3,4],[1,2,3,4]],
                "bending": [[1,2,3,4,5],[1,2,"x",4,5],[1,2,3,4,5]]})",
            "'bending' row 1[2]");
    rejects("no_bending.json",
            R"({"density": 0.2, "stretching": [[1,2,3,4],[1,2,3,4],[1,2,3,4],[1,2,3,4],[1,2,3,4],[1,2,3,4]]})",
            "'bending' is missing");
    rejects("not_json.json", "{\"density\": 0.2,", "not valid JSON");
    CHECK_THROWS_AS(load_material("/nonexistent/dir/material.json"), drape::IoError);
    CHECK_THROWS_WITH(load_material("/nonexistent/dir/material.json"),
                      Contains("/nonexistent/dir/material.json"));
}
