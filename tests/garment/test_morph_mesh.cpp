// Morphing a meshed pattern to another sizing of its template (PatternMorph): identity at
// the same sizing; at a new one every triangle keeps its orientation, boundary vertices stay
// on their edges, seams pair up with matching lengths, and the area follows the pattern's.
#include <drape/core/errors.hpp>
#include <drape/garment/garment_mesh.hpp>
#include <drape/garment/garment_sizing.hpp>
#include <drape/garment/morph_mesh.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <vector>

using namespace drape::garment;

namespace {

GarmentSizing sizing_of(GarmentType type) {
    GarmentSizing g;
    g.type = type;
    return g;
}

// Every parameter changed by ±6 % (alternating), a different sizing of the same template.
GarmentSizing perturbed(const GarmentSizing& g) {
    std::vector<double> v = sizing_values(g);
    for (size_t k = 0; k < v.size(); ++k) v[k] *= (k % 2 == 0) ? 1.06 : 0.94;
    return with_sizing_values(g, v);
}

GarmentMesh mesh_of(const Pattern& pattern, double edge_cm) {
    MeshOptions options;
    options.target_edge_cm = edge_cm;
    GarmentMesh mesh;
    REQUIRE(mesh_pattern(pattern, options, mesh).usable());
    return mesh;
}

double max_abs(const Eigen::MatrixXd& m) { return m.size() ? m.cwiseAbs().maxCoeff() : 0.0; }

// Signed pattern areas (cm²) of the mesh's faces.
std::vector<double> face_areas_cm2(const GarmentMesh& m) {
    std::vector<double> out;
    for (Eigen::Index f = 0; f < m.cloth.faces.rows(); ++f) {
        const Eigen::Vector2d p0 = m.panel_point_cm.row(m.cloth.faces(f, 0)).transpose();
        const Eigen::Vector2d e1 = m.panel_point_cm.row(m.cloth.faces(f, 1)).transpose() - p0;
        const Eigen::Vector2d e2 = m.panel_point_cm.row(m.cloth.faces(f, 2)).transpose() - p0;
        out.push_back(0.5 * (e1.x() * e2.y() - e1.y() * e2.x()));
    }
    return out;
}

double mesh_area_cm2(const GarmentMesh& m) {
    double a = 0;
    for (double x : face_areas_cm2(m)) a += x;
    return a;
}

double min_face_area_cm2(const GarmentMesh& m) {
    const std::vector<double> a = face_areas_cm2(m);
    return *std::min_element(a.begin(), a.end());
}

// Winding number of point q about a closed polyline.
int winding(const std::vector<Eigen::Vector2d>& poly, const Eigen::Vector2d& q) {
    int w = 0;
    for (size_t k = 0; k < poly.size(); ++k) {
        const Eigen::Vector2d a = poly[k], b = poly[(k + 1) % poly.size()];
        const double side = (b - a).x() * (q - a).y() - (b - a).y() * (q - a).x();
        if (a.y() <= q.y() && b.y() > q.y() && side > 0) ++w;
        if (a.y() > q.y() && b.y() <= q.y() && side < 0) --w;
    }
    return w;
}

// Pattern length (cm) of each seam side: the boundary segments whose both ends are stitched
// on that seam, per seam (side a, side b).
std::map<int, std::pair<double, double>> seam_lengths(const GarmentMesh& m) {
    std::map<std::pair<int, int>, int> side;  // (vertex, seam) -> 0 (side a) or 1 (side b)
    for (size_t s = 0; s < m.stitches.size(); ++s) {
        side[{m.stitches[s][0], m.stitch_seam[s]}] = 0;
        side[{m.stitches[s][1], m.stitch_seam[s]}] = 1;
    }
    std::map<int, std::pair<double, double>> out;
    for (const std::vector<int>& loop : m.boundary_loops)
        for (size_t k = 0; k < loop.size(); ++k) {
            const int a = loop[k], b = loop[(k + 1) % loop.size()];
            for (const auto& [key, sa] : side) {
                if (key.first != a) continue;
                const auto it = side.find({b, key.second});
                if (it == side.end() || it->second != sa) continue;
                const double len = (m.panel_point_cm.row(a) - m.panel_point_cm.row(b)).norm();
                (sa == 0 ? out[key.second].first : out[key.second].second) += len;
            }
        }
    return out;
}

}  // namespace

TEST_CASE("morph: the same sizing is the identity, for every template", "[garment][morph]") {
    for (GarmentType type : {GarmentType::skirt, GarmentType::pants, GarmentType::tshirt, GarmentType::dress}) {
        INFO(garment_type_name(type));
        const Pattern pattern = make_pattern(sizing_of(type));
        const GarmentMesh mesh = mesh_of(pattern, 4.0);
        const PatternMorph morph(pattern, mesh);
        const GarmentMesh same = morph.morph(make_pattern(sizing_of(type)));
        CHECK(max_abs(same.panel_point_cm - mesh.panel_point_cm) <= 1e-12);
        CHECK(max_abs(same.cloth.pattern - mesh.cloth.pattern) <= 1e-12);
        CHECK(max_abs(same.cloth.positions - mesh.cloth.positions) <= 1e-12);
        CHECK(max_abs(same.uv - mesh.uv) <= 1e-12);
        CHECK(same.cloth.faces == mesh.cloth.faces);
        CHECK(same.stitches == mesh.stitches);
    }
}

TEST_CASE("morph: a new sizing keeps triangles, boundary, seams and area, for every template",
          "[garment][morph]") {
    for (GarmentType type : {GarmentType::skirt, GarmentType::pants, GarmentType::tshirt, GarmentType::dress}) {
        INFO(garment_type_name(type));
        const GarmentSizing g0 = sizing_of(type), g1 = perturbed(g0);
        const Pattern pattern = make_pattern(g0), next = make_pattern(g1);
        const GarmentMesh mesh = mesh_of(pattern, 4.0);
        const GarmentMesh fresh = mesh_of(next, 4.0);
        const GarmentMesh m = PatternMorph(pattern, mesh).morph(next);
        m.cloth.validate();
        // It moved, and no triangle inverted or collapsed (relative to the original's smallest).
        CHECK(max_abs(m.panel_point_cm - mesh.panel_point_cm) > 1.0);
        CHECK(min_face_area_cm2(m) > 0.5 * min_face_area_cm2(mesh));
        // Boundary vertices stay on their edge at their fraction (at the chord offset the
        // mesher left them, below 1 mm); interior vertices inside their new panel.
        int interior = 0;
        for (int v = 0; v < m.cloth.vertex_count(); ++v) {
            const Panel& panel = next.panels[size_t(m.panel_of_vertex(v))];
            const Eigen::Vector2d q = m.panel_point_cm.row(v).transpose();
            if (m.boundary_edge(v) >= 0) {
                const double off = (q - panel.edges[size_t(m.boundary_edge(v))].point_at_fraction(m.boundary_fraction(v))).norm();
                const Panel& old_panel = pattern.panels[size_t(m.panel_of_vertex(v))];
                const double off0 = (mesh.panel_point_cm.row(v).transpose() -
                                     old_panel.edges[size_t(m.boundary_edge(v))].point_at_fraction(m.boundary_fraction(v)))
                                        .norm();
                CHECK(off <= off0 + 1e-9);
                CHECK(off < 0.1);
            } else {
                ++interior;
                CHECK(winding(panel.outline(0.2), q) == 1);
            }
        }
        CHECK(interior > 0);
        // Seams: both sides as long as each other, as closely as a fresh mesh of the new
        // pattern has them; each side's polyline as much shorter than its curve as before.
        const auto lengths = seam_lengths(m), fresh_lengths = seam_lengths(fresh), old_lengths = seam_lengths(mesh);
        CHECK(lengths.size() == next.seams.size());
        for (const auto& [seam, ab] : lengths) {
            INFO("seam " << seam << ": " << ab.first << " / " << ab.second << " cm");
            const auto fab = fresh_lengths.at(seam);
            const double mismatch = std::abs(ab.first - ab.second) / std::max(ab.first, ab.second);
            const double fresh_mismatch = std::abs(fab.first - fab.second) / std::max(fab.first, fab.second);
            CHECK(mismatch <= std::max(fresh_mismatch, next.seam_mismatch(next.seams[size_t(seam)])) + 1e-9);
            const Seam& s = next.seams[size_t(seam)];
            const double curve = next.panels[size_t(s.panel_a)].edges[size_t(s.edge_a)].length();
            const double curve0 = pattern.panels[size_t(s.panel_a)].edges[size_t(s.edge_a)].length();
            CHECK(ab.first / curve == Approx(old_lengths.at(seam).first / curve0).epsilon(2e-3));
        }
        // Area: the morphed mesh covers the new pattern as a fresh mesh of it does.
        const double area = mesh_area_cm2(m), fresh_area = mesh_area_cm2(fresh);
        INFO("area " << area << " cm², fresh mesh " << fresh_area << ", pattern " << next.total_area());
        CHECK(area == Approx(fresh_area).epsilon(5e-4));
        CHECK(area == Approx(next.total_area()).epsilon(1.5e-3));
    }
}

TEST_CASE("morph: a pattern of another structure is refused, saying to re-mesh", "[garment][morph]") {
    const Pattern tshirt = make_tshirt({});
    const PatternMorph morph(tshirt, mesh_of(tshirt, 5.0));
    TShirtSizing tank;
    tank.l1 = 0;  // a tank top: no sleeve panels
    using Catch::Matchers::Contains;
    CHECK_THROWS_WITH(morph.morph(make_tshirt(tank)), Contains("panels") && Contains("re-mesh"));
    CHECK_THROWS_WITH(morph.morph(make_pants({})), Contains("re-mesh"));
    CHECK_THROWS_AS(PatternMorph(make_pants({}), mesh_of(tshirt, 5.0)), drape::InvalidInput);
}

TEST_CASE("sizing_values and with_sizing_values see G as a vector in table order", "[garment][morph]") {
    GarmentSizing dress = sizing_of(GarmentType::dress);
    const std::vector<double> v = sizing_values(dress);
    REQUIRE(v.size() == 10);
    CHECK(v[0] == dress.dress.bodice.r);
    CHECK(v[5] == dress.dress.bodice.l1);
    CHECK(v[6] == dress.dress.skirt.l1);
    CHECK(v[9] == dress.dress.skirt.alpha);
    std::vector<double> w = v;
    w[8] += 5;
    CHECK(with_sizing_values(dress, w).dress.skirt.r2 == dress.dress.skirt.r2 + 5);
    CHECK(sizing_values(sizing_of(GarmentType::pants)).size() == 7);
    CHECK_THROWS_WITH(with_sizing_values(sizing_of(GarmentType::skirt), w),
                      Catch::Matchers::Contains("skirt sizing: 10 values given, the template has 4 parameters"));
}
