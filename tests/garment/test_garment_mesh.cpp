#include <drape/core/errors.hpp>
#include <drape/garment/circle_skirt.hpp>
#include <drape/garment/dress.hpp>
#include <drape/garment/garment_mesh.hpp>
#include <drape/garment/pants.hpp>
#include <drape/garment/tshirt.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

using namespace drape::garment;

namespace {

struct Named {
    const char* name;
    Pattern pattern;
};

std::vector<Named> all_templates() {
    TShirtSizing tank;
    tank.l1 = 0;
    PantsSizing shorts;
    shorts.h1 = 50;
    return {{"skirt", make_circle_skirt({})}, {"pants", make_pants({})},
            {"shorts", make_pants(shorts)},   {"tshirt", make_tshirt({})},
            {"tank top", make_tshirt(tank)},  {"dress", make_dress({})}};
}

// Arc length (cm) of a boundary vertex from the start of its seam edge, measured along the
// panel's meshed boundary loop.
std::map<int, double> boundary_arclength(const GarmentMesh& m, int panel, int edge) {
    std::map<int, double> s;
    const auto& loop = m.boundary_loops[panel];
    const int n = static_cast<int>(loop.size());
    int start = -1;
    for (int k = 0; k < n; ++k)
        if (m.boundary_edge(loop[k]) == edge && m.boundary_fraction(loop[k]) == 0.0) start = k;
    REQUIRE(start >= 0);
    double acc = 0;
    for (int k = 0; k <= n; ++k) {
        const int v = loop[(start + k) % n];
        if (k > 0) acc += (m.panel_point_cm.row(v) - m.panel_point_cm.row(loop[(start + k - 1) % n])).norm();
        s[v] = acc;
        if (k > 0 && m.boundary_edge(v) != edge) break;  // reached the next edge's corner
    }
    return s;
}

}  // namespace

TEST_CASE("mesh: every template meshes into a valid cloth mesh with stitched seams",
          "[garment][mesh]") {
    for (const Named& t : all_templates()) {
        INFO(t.name);
        GarmentMesh m;
        MeshOptions options;
        options.target_edge_cm = 2.0;
        const MeshSummary s = mesh_pattern(t.pattern, options, m);
        WARN(t.name << ": " << s.brief_report());
        REQUIRE(s.usable());
        REQUIRE_NOTHROW(m.cloth.validate());
        CHECK(s.min_angle_deg >= 20.0);
        CHECK(s.mean_edge_cm == Approx(options.target_edge_cm).epsilon(0.2));
        // Area: meshed pattern (m²) vs the analytic panel areas (cm²).
        double area = 0;
        for (int f = 0; f < m.cloth.face_count(); ++f) {
            const Eigen::Vector2d a = m.cloth.pattern.row(m.cloth.faces(f, 0));
            const Eigen::Vector2d b = m.cloth.pattern.row(m.cloth.faces(f, 1));
            const Eigen::Vector2d c = m.cloth.pattern.row(m.cloth.faces(f, 2));
            area += 0.5 * ((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x());
        }
        CHECK(area * 1e4 == Approx(t.pattern.total_area()).epsilon(0.005));
        // Every seam: stitched partners sit at equal arc length along their edges, and
        // every boundary vertex of a seam edge is stitched.
        REQUIRE(m.stitches.size() == m.stitch_seam.size());
        std::map<int, std::vector<std::array<int, 2>>> by_seam;
        std::set<int> stitched;
        for (size_t k = 0; k < m.stitches.size(); ++k) {
            by_seam[m.stitch_seam[k]].push_back(m.stitches[k]);
            stitched.insert(m.stitches[k][0]);
            stitched.insert(m.stitches[k][1]);
        }
        const auto longest = [](const std::map<int, double>& lengths) {
            double l = 0;
            for (const auto& kv : lengths) l = std::max(l, kv.second);
            return l;
        };
        for (size_t si = 0; si < t.pattern.seams.size(); ++si) {
            const Seam& seam = t.pattern.seams[si];
            const auto sa = boundary_arclength(m, seam.panel_a, seam.edge_a);
            const auto sb = boundary_arclength(m, seam.panel_b, seam.edge_b);
            const double la = longest(sa), lb = longest(sb);
            double worst = 0;
            for (const auto& [i, j] : by_seam[int(si)]) {
                REQUIRE(sa.count(i) == 1);
                REQUIRE(sb.count(j) == 1);
                const double fa = sa.at(i) / la;
                const double fb = seam.orientation == SeamOrientation::same ? sb.at(j) / lb : 1 - sb.at(j) / lb;
                worst = std::max(worst, std::abs(fa - fb));
            }
            CHECK(worst < 1e-6);
            for (const auto& kv : sa) CHECK(stitched.count(kv.first) == 1);
            for (const auto& kv : sb) CHECK(stitched.count(kv.first) == 1);
        }
        // Panels stay separate: no face mixes panels; uv in [0, 1].
        for (int f = 0; f < m.cloth.face_count(); ++f)
            CHECK(m.panel_of_vertex(m.cloth.faces(f, 0)) == m.panel_of_vertex(m.cloth.faces(f, 2)));
        CHECK(m.uv.minCoeff() >= 0.0);
        CHECK(m.uv.maxCoeff() <= 1.0 + 1e-12);
    }
}

TEST_CASE("mesh: a t-shirt at 1.5 cm has about 5k vertices", "[garment][mesh]") {
    GarmentMesh m;
    const MeshSummary s = mesh_pattern(make_tshirt({}), MeshOptions{}, m);
    WARN("t-shirt at 1.5 cm: " << s.brief_report());
    REQUIRE(s.usable());
    CHECK(s.vertices > 3500);
    CHECK(s.vertices < 6500);
    CHECK(s.min_angle_deg >= 20.0);
    CHECK(s.mean_edge_cm == Approx(1.5).epsilon(0.15));
}

TEST_CASE("mesh: invalid options are rejected", "[garment][mesh]") {
    GarmentMesh m;
    MeshOptions o;
    o.target_edge_cm = 0;
    CHECK_THROWS_AS(mesh_pattern(make_circle_skirt({}), o, m), drape::InvalidInput);
    o = MeshOptions{};
    o.min_angle_deg = 30;
    CHECK_THROWS_WITH(mesh_pattern(make_circle_skirt({}), o, m), Catch::Contains("min_angle_deg"));
}

TEST_CASE("mesh: boundary refinement mirrors seam splits onto partner edges", "[garment][mesh]") {
    GarmentMesh m;
    MeshOptions o;
    o.target_edge_cm = 2.0;
    o.refine_boundary = true;
    const Pattern skirt = make_circle_skirt({});
    const MeshSummary s = mesh_pattern(skirt, o, m);
    WARN("skirt with boundary refinement: " << s.brief_report());
    REQUIRE(s.usable());
    REQUIRE_NOTHROW(m.cloth.validate());
    // Each side seam: both sides carry the same number of boundary vertices.
    for (size_t si = 0; si < skirt.seams.size(); ++si) {
        const Seam& seam = skirt.seams[si];
        int na = 0, nb = 0;
        for (int v = 0; v < m.cloth.vertex_count(); ++v) {
            na += m.panel_of_vertex(v) == seam.panel_a && m.boundary_edge(v) == seam.edge_a;
            nb += m.panel_of_vertex(v) == seam.panel_b && m.boundary_edge(v) == seam.edge_b;
        }
        CHECK(na == nb);
        CHECK(std::count(m.stitch_seam.begin(), m.stitch_seam.end(), int(si)) == na + 1);
    }
}
