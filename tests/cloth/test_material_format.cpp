// Drape's own material file format (save_material / load_material) and the built-in
// materials transcribed from ArcSim's files (docs/materials.md).
#include <drape/cloth/material.hpp>
#include <drape/core/errors.hpp>

#include <catch2/catch.hpp>

#include "gray_interlock_fixture.hpp"
#include <test_paths.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <random>
#include <set>
#include <sstream>
#include <string>

using namespace drape::cloth;
using Catch::Matchers::Contains;

namespace {

std::uint64_t bits(double x) {
    std::uint64_t b = 0;
    std::memcpy(&b, &x, sizeof b);
    return b;
}

// Every number equal bit for bit (so -0.0 != 0.0 and the last ulp counts); names the first
// difference in the assertion message.
std::string first_difference(const Material& a, const Material& b) {
    auto cmp = [](double x, double y, const std::string& what) {
        if (bits(x) == bits(y)) return std::string();
        std::ostringstream os;
        os.precision(17);
        os << what << ": " << x << " != " << y;
        return os.str();
    };
    std::string d = cmp(a.density_kg_per_m2, b.density_kg_per_m2, "density");
    if (d.empty()) d = cmp(a.stretching_scale, b.stretching_scale, "stretching_scale");
    if (d.empty()) d = cmp(a.bending_scale, b.bending_scale, "bending_scale");
    for (std::size_t r = 0; r < 6 && d.empty(); ++r)
        for (std::size_t c = 0; c < 4 && d.empty(); ++c)
            d = cmp(a.stretching_n_per_m[r][c], b.stretching_n_per_m[r][c],
                    "stretching[" + std::to_string(r) + "][" + std::to_string(c) + "]");
    for (std::size_t r = 0; r < 3 && d.empty(); ++r)
        for (std::size_t c = 0; c < 5 && d.empty(); ++c)
            d = cmp(a.bending_n_m[r][c], b.bending_n_m[r][c],
                    "bending[" + std::to_string(r) + "][" + std::to_string(c) + "]");
    return d;
}

#define CHECK_SAME_MATERIAL(a, b)                          \
    do {                                                   \
        const std::string diff_ = first_difference(a, b);  \
        INFO(diff_);                                       \
        CHECK(diff_.empty());                              \
    } while (false)

std::string read_text(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream os;
    os << in.rdbuf();
    return os.str();
}

std::filesystem::path write_text(const std::filesystem::path& path, const std::string& text) {
    std::ofstream(path, std::ios::binary) << text;
    return path;
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
    const auto at = text.find(from);
    REQUIRE(at != std::string::npos);
    return text.replace(at, from.size(), to);
}

// A finite double drawn uniformly over bit patterns (all magnitudes, subnormals, -0.0).
double random_finite(std::mt19937_64& rng) {
    for (;;) {
        const std::uint64_t b = rng();
        double x = 0;
        std::memcpy(&x, &b, sizeof x);
        if (std::isfinite(x)) return x;
    }
}

}  // namespace

TEST_CASE("save_material then load_material is bit-identical", "[cloth][material]") {
    const auto dir = drape::test::scratch_dir("material_format_roundtrip");
    SECTION("gray-interlock with awkward scales and info text") {
        Material m = drape::test::gray_interlock_material();
        m.stretching_scale = 0.1 + 0.2;  // 0.30000000000000004
        m.bending_scale = 1.0 / 3.0;
        m.stretching_n_per_m[0][1] = -0.0;
        m.bending_n_m[1][2] = 5e-324;  // smallest subnormal
        m.stretching_n_per_m[5][0] = std::numeric_limits<double>::max();
        MaterialInfo info{"gray \"interlock\"", "line 1\nline 2\t\\ 60% coton, 40% polyester, ±",
                          "Wang et al. 2011", "research only"};
        const auto path = dir / "m.json";
        save_material(m, path, info);
        MaterialInfo back;
        const Material loaded = load_material(path, &back);
        CHECK_SAME_MATERIAL(loaded, m);
        CHECK(back.name == info.name);
        CHECK(back.description == info.description);
        CHECK(back.source == info.source);
        CHECK(back.license == info.license);
        const std::string text = read_text(path);
        CHECK_THAT(text, Contains("\"format\": \"drape-material\""));
        CHECK_THAT(text, Contains("\"version\": 1"));
        CHECK_THAT(text, Contains("\"density_kg_per_m2\": 0.187"));
        CHECK_THAT(text, Contains("[16.593832, -0.0, 34.477123, 36.860302]"));
    }
    SECTION("1000 random materials over all finite bit patterns") {
        std::mt19937_64 rng(20111);
        const auto path = dir / "random.json";
        for (int i = 0; i < 1000; ++i) {
            Material m;
            m.density_kg_per_m2 = std::abs(random_finite(rng));
            m.stretching_scale = std::abs(random_finite(rng));
            m.bending_scale = std::abs(random_finite(rng));
            if (!(m.density_kg_per_m2 > 0 && m.stretching_scale > 0 && m.bending_scale > 0))
                continue;  // zero: not a valid material
            for (auto& row : m.stretching_n_per_m)
                for (double& x : row) x = random_finite(rng);
            for (auto& row : m.bending_n_m)
                for (double& x : row) x = random_finite(rng);
            save_material(m, path);
            const Material loaded = load_material(path);
            const std::string diff = first_difference(loaded, m);
            if (!diff.empty()) FAIL("material " << i << ": " << diff);
        }
    }
    SECTION("overwrites atomically and leaves no temporary behind") {
        const auto path = dir / "twice.json";
        Material m = drape::test::gray_interlock_material();
        save_material(m, path);
        m.density_kg_per_m2 = 0.5;
        save_material(m, path);
        CHECK(load_material(path).density_kg_per_m2 == 0.5);
        int files = 0;
        for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir)) ++files;
        CHECK(files == 1);
        // An invalid material is refused before anything is written.
        m.density_kg_per_m2 = -1;
        CHECK_THROWS_WITH(save_material(m, path), Contains("density_kg_per_m2"));
        CHECK(load_material(path).density_kg_per_m2 == 0.5);
        CHECK_THROWS_AS(save_material(drape::test::gray_interlock_material(),
                                      dir / "no_such_folder" / "x.json"),
                        drape::IoError);
        CHECK_THROWS_WITH(save_material(drape::test::gray_interlock_material(), dir / "bad.json",
                                        MaterialInfo{"\xff\xfe", "", "", ""}),
                          Contains("'name'") && Contains("UTF-8"));
    }
}

TEST_CASE("material scales are preserved by the format", "[cloth][material]") {
    const auto dir = drape::test::scratch_dir("material_format_scales");
    Material m = builtin_material("gray-interlock");
    m.stretching_scale = 0.25;
    m.bending_scale = 4;
    save_material(m, dir / "scaled.json");
    const Material loaded = load_material(dir / "scaled.json");
    CHECK(loaded.stretching_scale == 0.25);
    CHECK(loaded.bending_scale == 4);
    CHECK(bending_stiffness(loaded, 0, 0) == 4 * m.bending_n_m[0][0]);
    CHECK(stretching_stiffness(loaded, 1.0, 0).k_uu == 2 * 0.25 * m.stretching_n_per_m[0][0]);
    // The scales are optional: absent means 1.
    std::string text = read_text(dir / "scaled.json");
    text = replaced(text, ",\n  \"stretching_scale\": 0.25,\n  \"bending_scale\": 4.0", "");
    const Material unscaled = load_material(write_text(dir / "unscaled.json", text));
    CHECK(unscaled.stretching_scale == 1);
    CHECK(unscaled.bending_scale == 1);
    CHECK(unscaled.stretching_n_per_m == m.stretching_n_per_m);
}

TEST_CASE("built-in materials: names, lookup and errors", "[cloth][material]") {
    const std::vector<std::string> names = builtin_material_names();
    REQUIRE(names.size() == 12);
    CHECK(names.front() == "gray-interlock");
    CHECK(std::set<std::string>(names.begin(), names.end()).size() == 12);
    for (const char* expected : {"11oz-black-denim", "white-swim-solid", "paper", "aluminium"})
        CHECK(std::find(names.begin(), names.end(), expected) != names.end());
    // The test fixture was typed in separately from the generated table.
    CHECK_SAME_MATERIAL(builtin_material("gray-interlock"), drape::test::gray_interlock_material());
    CHECK(builtin_material("11oz-black-denim").density_kg_per_m2 == 0.324);
    CHECK(builtin_material("paper").stretching_n_per_m[3][0] == 0.5e6);
    for (const std::string& name : names) {
        INFO(name);
        const Material m = builtin_material(name);
        CHECK(m.is_valid());
        CHECK(m.stretching_scale == 1);
        CHECK(m.bending_scale == 1);
        const MaterialInfo info = builtin_material_info(name);
        CHECK(info.name == name);
        CHECK_THAT(info.source, Contains("ArcSim 0.3.1") && Contains("materials/" + name + ".json"));
        CHECK_THAT(info.license, Contains("Regents of the University of California") &&
                                     Contains("Huamin Wang"));
        if (name != "paper" && name != "aluminium") {
            CHECK_THAT(info.source, Contains("Data-Driven Elastic Models for Cloth"));
            CHECK_THAT(info.description, Contains("(measured)"));
        }
    }
    CHECK_THROWS_AS(builtin_material("grey-interlock"), drape::InvalidInput);
    CHECK_THROWS_WITH(builtin_material("grey-interlock"),
                      Contains("'grey-interlock'") && Contains("gray-interlock") &&
                          Contains("aluminium"));
    CHECK_THROWS_AS(builtin_material_info(""), drape::InvalidInput);
}

TEST_CASE("every built-in material equals ArcSim's file in ../shared", "[cloth][material]") {
    DRAPE_REQUIRE_SHARED(dir, "materials");
    int compared = 0;
    for (const std::string& name : builtin_material_names()) {
        const auto path = dir / (name + ".json");
        if (!std::filesystem::exists(path)) {
            WARN("skipped: " << path << " absent");
            continue;
        }
        INFO(name);
        MaterialInfo info;
        CHECK_SAME_MATERIAL(builtin_material(name), load_material(path, &info));
        CHECK(info.name == name);  // ArcSim files: the file stem
        CHECK(info.source.empty());
        ++compared;
    }
    CHECK(compared == 12);
}

TEST_CASE("every data/materials file equals the built-in material", "[cloth][material]") {
    const auto dir = drape::test::source_dir() / "data" / "materials";
    REQUIRE(std::filesystem::is_directory(dir));
    const std::vector<std::string> names = builtin_material_names();
    std::set<std::string> seen;
    for (const auto& entry : std::filesystem::directory_iterator(dir)) {
        if (entry.path().extension() != ".json") continue;
        const std::string name = entry.path().stem().string();
        INFO(entry.path());
        REQUIRE(std::find(names.begin(), names.end(), name) != names.end());
        MaterialInfo info;
        const Material m = load_material(entry.path(), &info);
        CHECK_SAME_MATERIAL(m, builtin_material(name));
        const MaterialInfo expected = builtin_material_info(name);
        CHECK(info.name == expected.name);
        CHECK(info.description == expected.description);
        CHECK(info.source == expected.source);
        CHECK(info.license == expected.license);
        CHECK_THAT(read_text(entry.path()), Contains("\"format\": \"drape-material\""));
        seen.insert(name);
    }
    CHECK(seen.size() == names.size());
}

TEST_CASE("malformed drape-material files give InvalidInput naming file and field",
          "[cloth][material]") {
    const auto dir = drape::test::scratch_dir("material_format_errors");
    save_material(builtin_material("gray-interlock"), dir / "good.json",
                  builtin_material_info("gray-interlock"));
    const std::string good = read_text(dir / "good.json");
    CHECK(load_material(dir / "good.json").density_kg_per_m2 == 0.187);

    auto rejects = [&](const std::string& name, const std::string& text, const std::string& needle) {
        INFO(name);
        const auto path = write_text(dir / name, text);
        CHECK_THROWS_AS(load_material(path), drape::InvalidInput);
        CHECK_THROWS_WITH(load_material(path), Contains(needle) && Contains(name));
    };
    struct Case {
        const char* file;
        const char* from;  // text of the good file ...
        const char* to;    // ... replaced by this
        const char* needle;
    };
    const Case cases[] = {
        {"version2.json", "\"version\": 1", "\"version\": 2", "'version' = 2 is not supported"},
        {"version_string.json", "\"version\": 1", "\"version\": \"1\"", "'version'"},
        {"no_version.json", "\"version\": 1,", "", "'version' is missing"},
        {"other_format.json", "\"drape-material\"", "\"drape-body-model\"",
         "'format' = \"drape-body-model\""},
        {"neg_density.json", "\"density_kg_per_m2\": 0.187", "\"density_kg_per_m2\": -0.187",
         "'density_kg_per_m2' = -0.187 must be > 0"},
        {"no_density.json", "\"density_kg_per_m2\": 0.187,", "", "'density_kg_per_m2' is missing"},
        {"arcsim_density_name.json", "\"density_kg_per_m2\": 0.187", "\"density\": 0.187",
         "unknown field 'density'"},
        {"five_rows.json", "    [16.593832, -14.69599, 34.477123, 36.860302],\n", "",
         "'stretching_n_per_m' must be an array of 6 rows"},
        {"short_bending_row.json", "2.4749964e-05, 1.8651314e-05,", "2.4749964e-05,",
         "'bending_n_m' row 1 must be an array of 5 numbers"},
        {"overflow.json", "139.686325", "1e999", "number overflow"},
        {"null_entry.json", "139.686325", "null", "'stretching_n_per_m' row 4[0] is not a number"},
        {"zero_scale.json", "\"bending_scale\": 1.0", "\"bending_scale\": 0",
         "'bending_scale' = 0 must be > 0"},
        {"misspelt_scale.json", "\"stretching_scale\": 1.0", "\"stretching_scal\": 2.0",
         "unknown field 'stretching_scal'"},
        {"name_number.json", "\"name\": \"gray-interlock\"", "\"name\": 7", "'name' is not a string"},
    };
    for (const Case& c : cases) rejects(c.file, replaced(good, c.from, c.to), c.needle);
    rejects("truncated.json", good.substr(0, good.size() / 2), "not valid JSON");
    CHECK_THROWS_AS(load_material(dir / "absent.json"), drape::IoError);
}
