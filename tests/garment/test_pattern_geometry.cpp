#include <drape/core/errors.hpp>
#include <drape/garment/pattern.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

using namespace drape::garment;
using Eigen::Vector2d;

namespace {
constexpr double kPi = 3.14159265358979323846;

Panel disc(double r) {  // two half-circle arcs, counter-clockwise
    Panel p;
    p.name = "disc";
    p.edges = {Edge::arc({r, 0}, {-r, 0}, 1.0), Edge::arc({-r, 0}, {r, 0}, 1.0)};
    return p;
}
}  // namespace

TEST_CASE("edges: lengths, points and area terms are exact", "[garment][edge]") {
    const Edge quarter = Edge::arc({10, 0}, {0, 10}, std::tan(kPi / 8));  // CCW about origin
    CHECK(quarter.length() == Approx(10 * kPi / 2).epsilon(1e-12));
    const Vector2d mid = quarter.point_at_fraction(0.5);
    CHECK(mid.x() == Approx(10 / std::sqrt(2.0)).epsilon(1e-12));
    CHECK(mid.y() == Approx(10 / std::sqrt(2.0)).epsilon(1e-12));
    // A cubic with collinear, evenly spaced controls is a straight segment.
    const Edge straight = Edge::cubic({0, 0}, {1, 0}, {2, 0}, {3, 0});
    CHECK(straight.length() == Approx(3.0).epsilon(1e-9));
    CHECK(straight.point_at_fraction(0.25).x() == Approx(0.75).epsilon(1e-7));
    // Disc area and perimeter.
    const Panel d = disc(7.0);
    CHECK(d.area() == Approx(kPi * 49).epsilon(1e-12));
    CHECK(d.perimeter() == Approx(2 * kPi * 7).epsilon(1e-12));
    std::string why;
    CHECK(d.is_valid(&why));
    // A curved cubic: area of the region under y = Bezier, closed by a line, vs polygon.
    Panel bump;
    bump.name = "bump";
    bump.edges = {Edge::line({0, 0}, {10, 0}), Edge::cubic({10, 0}, {10, 8}, {0, 8}, {0, 0})};
    double poly = 0;
    const auto pts = bump.outline(0.01);
    for (size_t i = 0; i < pts.size(); ++i) {
        const Vector2d &a = pts[i], &b = pts[(i + 1) % pts.size()];
        poly += 0.5 * (a.x() * b.y() - a.y() * b.x());
    }
    CHECK(bump.area() == Approx(poly).epsilon(1e-4));
}

TEST_CASE("panels: validation catches open loops, clockwise loops and self-intersections",
          "[garment][panel]") {
    Panel square;
    square.name = "square";
    square.edges = {Edge::line({0, 0}, {10, 0}), Edge::line({10, 0}, {10, 10}),
                    Edge::line({10, 10}, {0, 10}), Edge::line({0, 10}, {0, 0})};
    std::string why;
    REQUIRE(square.is_valid(&why));
    Panel open = square;
    open.edges[2].end = Vector2d(1, 10);
    CHECK_FALSE(open.is_valid(&why));
    CHECK(why.find("not closed") != std::string::npos);
    Panel cw = square.mirrored("m");
    CHECK(cw.is_valid(&why));  // mirrored stays counter-clockwise
    CHECK(cw.area() == Approx(100.0));
    Panel reversed = square;
    for (auto& e : reversed.edges) e = e.reversed();
    std::reverse(reversed.edges.begin(), reversed.edges.end());
    CHECK_FALSE(reversed.is_valid(&why));
    CHECK(why.find("counter-clockwise") != std::string::npos);
    Panel bowtie;
    bowtie.name = "bowtie";
    bowtie.edges = {Edge::line({0, 0}, {10, 10}), Edge::line({10, 10}, {10, 0}),
                    Edge::line({10, 0}, {0, 10}), Edge::line({0, 10}, {-5, 20}),
                    Edge::line({-5, 20}, {0, 0})};
    CHECK_FALSE(bowtie.is_valid(&why));
}

TEST_CASE("patterns: seam length mismatch above 1 % is rejected", "[garment][pattern]") {
    Pattern p;
    p.name = "two squares";
    Panel a;
    a.name = "a";
    a.edges = {Edge::line({0, 0}, {10, 0}), Edge::line({10, 0}, {10, 10}),
               Edge::line({10, 10}, {0, 10}), Edge::line({0, 10}, {0, 0})};
    Panel b = a;
    b.name = "b";
    p.panels = {a, b};
    p.placements.resize(2);
    p.seams = {{0, 1, 1, 3, SeamOrientation::reversed}};
    REQUIRE_NOTHROW(p.validate());
    p.panels[1].edges[3].start.y() = 10.3;  // edge 3 of b becomes 10.3 cm (3 %)
    p.panels[1].edges[2].end.y() = 10.3;
    try {
        p.validate();
        FAIL("expected InvalidInput");
    } catch (const drape::InvalidInput& e) {
        CHECK(std::string(e.what()).find("differ by 2.9") != std::string::npos);
    }
    p.panels[1] = a;
    p.panels[1].name = "b";
    p.seams.push_back({0, 1, 1, 2, SeamOrientation::reversed});
    CHECK_THROWS_AS(p.validate(), drape::InvalidInput);  // edge a.1 in two seams
}
