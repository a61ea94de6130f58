#include <drape/core/errors.hpp>
#include <drape/garment/circle_skirt.hpp>
#include <drape/garment/dress.hpp>
#include <drape/garment/pants.hpp>
#include <drape/garment/pattern_dxf.hpp>
#include <drape/garment/pattern_json.hpp>
#include <drape/garment/pattern_svg.hpp>
#include <drape/garment/tshirt.hpp>

#include "test_paths.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>

using namespace drape::garment;

namespace {

// A minimal DXF reader: the (group code, value) pairs of an ASCII DXF file.
std::vector<std::pair<int, std::string>> dxf_pairs(const std::string& text) {
    std::istringstream in(text);
    std::vector<std::pair<int, std::string>> pairs;
    std::string code, value;
    while (std::getline(in, code) && std::getline(in, value)) pairs.emplace_back(std::stoi(code), value);
    return pairs;
}

struct DxfBlock {
    std::string name;
    std::vector<std::vector<Eigen::Vector2d>> polylines;  // closed, layer 1
    std::map<std::string, int> entities_per_layer;
    std::vector<std::string> texts;
};

// Parses the BLOCKS section; checks the overall section structure on the way.
std::vector<DxfBlock> parse_dxf_blocks(const std::string& text, std::vector<std::string>* sections,
                                       int* inserts) {
    const auto pairs = dxf_pairs(text);
    std::vector<DxfBlock> blocks;
    std::string section, entity, layer;
    bool closed = false;
    *inserts = 0;
    REQUIRE(!pairs.empty());
    REQUIRE(pairs.back() == std::make_pair(0, std::string("EOF")));
    for (size_t i = 0; i < pairs.size(); ++i) {
        const auto& [c, v] = pairs[i];
        if (c == 0 && v == "SECTION") {
            REQUIRE(pairs[i + 1].first == 2);
            section = pairs[i + 1].second;
            sections->push_back(section);
            continue;
        }
        if (c == 0) {
            entity = v;
            layer.clear();
            if (section == "BLOCKS" && v == "BLOCK") blocks.push_back({});
            if (section == "BLOCKS" && v == "POLYLINE") {
                blocks.back().polylines.push_back({});
                closed = false;
            }
            if (section == "ENTITIES" && v == "INSERT") ++*inserts;
            continue;
        }
        if (section != "BLOCKS" || blocks.empty()) continue;
        DxfBlock& b = blocks.back();
        if (entity == "BLOCK" && c == 2) b.name = v;
        if (c == 8) {
            layer = v;
            if (entity == "LINE" || entity == "TEXT" || entity == "POLYLINE") ++b.entities_per_layer[layer];
        }
        if (entity == "POLYLINE" && c == 70) {
            closed = (std::stoi(v) & 1) != 0;
            REQUIRE(closed);
        }
        if (entity == "VERTEX" && c == 10) {
            REQUIRE(layer == "1");
            REQUIRE(pairs[i + 1].first == 20);
            b.polylines.back().emplace_back(std::stod(v), std::stod(pairs[i + 1].second));
        }
        if (entity == "TEXT" && c == 1) b.texts.push_back(v);
    }
    return blocks;
}

double closed_length(const std::vector<Eigen::Vector2d>& p) {
    double l = 0;
    for (size_t i = 0; i < p.size(); ++i) l += (p[(i + 1) % p.size()] - p[i]).norm();
    return l;
}

std::vector<std::pair<std::string, Pattern>> samples() {
    return {{"skirt", make_circle_skirt({})}, {"pants", make_pants({})},
            {"tshirt", make_tshirt({})}, {"dress", make_dress({})}};
}

}  // namespace

TEST_CASE("svg: true scale in centimetres with names, grain lines and allowance",
          "[garment][export]") {
    const Pattern p = make_tshirt({});
    const std::string svg = pattern_to_svg(p);
    std::smatch m;
    REQUIRE(std::regex_search(svg, m, std::regex("width=\"([0-9.]+)cm\" height=\"([0-9.]+)cm\" viewBox=\"0 0 ([0-9.]+) ([0-9.]+)\"")));
    CHECK(m[1].str() == m[3].str());  // 1 user unit = 1 cm
    CHECK(m[2].str() == m[4].str());
    // The layout is wider than all panels side by side.
    double widths = 0;
    for (const Panel& panel : p.panels) {
        Eigen::Vector2d lo, hi;
        panel.bounds(&lo, &hi);
        widths += hi.x() - lo.x();
    }
    CHECK(std::stod(m[1].str()) > widths);
    for (const Panel& panel : p.panels) CHECK(svg.find(">" + panel.name + "<") != std::string::npos);
    CHECK(svg.find("marker-end=\"url(#arrow)\"") != std::string::npos);
    CHECK(svg.find("seam allowance 1.000 cm") != std::string::npos);
    CHECK(svg.find("10 cm") != std::string::npos);
    // Writing goes through the atomic writer.
    const auto dir = drape::test::scratch_dir("garment_svg");
    write_pattern_svg(dir / "p.svg", p);
    std::ifstream in(dir / "p.svg");
    std::stringstream ss;
    ss << in.rdbuf();
    CHECK(ss.str() == svg);
    SvgOptions bad;
    bad.seam_allowance_cm = -1;
    CHECK_THROWS_WITH(pattern_to_svg(p, bad), Catch::Contains("seam_allowance_cm"));
}

TEST_CASE("dxf: AAMA-style blocks whose closed boundaries have the panel perimeters",
          "[garment][export]") {
    for (const auto& [name, p] : samples()) {
        INFO(name);
        const std::string dxf = pattern_to_dxf(p, 0.2);
        std::vector<std::string> sections;
        int inserts = 0;
        const auto blocks = parse_dxf_blocks(dxf, &sections, &inserts);
        CHECK(sections == std::vector<std::string>{"HEADER", "TABLES", "BLOCKS", "ENTITIES"});
        REQUIRE(blocks.size() == p.panels.size());
        CHECK(inserts == int(p.panels.size()));
        for (size_t i = 0; i < blocks.size(); ++i) {
            const Panel& panel = p.panels[i];
            CHECK(blocks[i].name == panel.name);
            REQUIRE(blocks[i].polylines.size() == 1);
            // Chords of 2 mm under-estimate curves by < 0.05 %.
            CHECK(closed_length(blocks[i].polylines[0]) == Approx(panel.perimeter()).epsilon(5e-4));
            CHECK(blocks[i].entities_per_layer.at("7") == 1);  // grain line
            CHECK(blocks[i].entities_per_layer.at("4") == int(panel.notches.size()));
            CHECK(blocks[i].entities_per_layer.at("8") == int(panel.internal_lines.size()));
            REQUIRE(!blocks[i].texts.empty());
            CHECK(blocks[i].texts[0] == "Piece Name: " + panel.name);
        }
    }
}

TEST_CASE("garmentcode json: export -> import -> export is identical", "[garment][export]") {
    for (const auto& [name, p] : samples()) {
        INFO(name);
        const std::string a = pattern_to_garmentcode_json(p);
        const Pattern q = pattern_from_garmentcode_json(a);
        const std::string b = pattern_to_garmentcode_json(q);
        CHECK(a == b);
        REQUIRE(q.panels.size() == p.panels.size());
        for (size_t i = 0; i < p.panels.size(); ++i) {
            CHECK(q.panels[i].name == p.panels[i].name);
            CHECK(q.panels[i].area() == Approx(p.panels[i].area()).epsilon(1e-9));
            CHECK(q.placements[i].body_part == p.placements[i].body_part);
            CHECK(q.placements[i].role == p.placements[i].role);
        }
        REQUIRE(q.seams.size() == p.seams.size());
        for (size_t s = 0; s < p.seams.size(); ++s) {
            const Seam &sp = p.seams[s], &sq = q.seams[s];
            CHECK(sq.orientation == sp.orientation);
            CHECK(q.panels[sq.panel_a].edges[sq.edge_a].length() ==
                  Approx(p.panels[sp.panel_a].edges[sp.edge_a].length()).epsilon(1e-9));
            CHECK(q.panels[sq.panel_b].edges[sq.edge_b].length() ==
                  Approx(p.panels[sp.panel_b].edges[sp.edge_b].length()).epsilon(1e-9));
        }
    }
}

TEST_CASE("garmentcode json: reads GarmentCode's own conventions", "[garment][export]") {
    // Metres, a clockwise loop, a circle edge, a relative quadratic, a stitch.
    const std::string text = R"({
      "pattern": {
        "panels": {
          "a": {"translation": [0, 1, 0.2], "rotation": [0, 0, 0],
                "vertices": [[0, 0], [0, 0.2], [0.2, 0.2], [0.2, 0]],
                "edges": [{"endpoints": [0, 1]},
                          {"endpoints": [1, 2], "curvature": {"type": "circle", "params": [0.1, 0, 1]}},
                          {"endpoints": [2, 3]},
                          {"endpoints": [3, 0], "curvature": {"type": "quadratic", "params": [[0.5, 0.2]]}}]},
          "b": {"vertices": [[0, 0], [0.2, 0], [0.2, 0.2], [0, 0.2]],
                "edges": [{"endpoints": [0, 1]}, {"endpoints": [1, 2]}, {"endpoints": [2, 3]}, {"endpoints": [3, 0]}]}
        },
        "stitches": [[{"panel": "a", "edge": 2}, {"panel": "b", "edge": 3}]]
      },
      "properties": {"units_in_meter": 1, "curvature_coords": "relative"}
    })";
    const Pattern p = pattern_from_garmentcode_json(text);
    REQUIRE(p.panels.size() == 2);
    const Panel& a = p.panels[0];
    CHECK(a.area() > 0);  // made counter-clockwise
    CHECK(p.placements[0].translation_cm.y() == Approx(100.0));
    // A 20 x 20 cm square whose top edge is a half circle of radius 10 cm bulging to the
    // right of (0,20)->(20,20), i.e. down into the square, and whose bottom edge is a
    // quadratic with relative control (0.5, 0.2) on (20,0)->(0,0): 4 cm along the left
    // normal (down, outside), a parabolic segment of height 2 cm.
    const double half_disc = 0.5 * 3.14159265358979323846 * 100;
    const double bay = 2.0 / 3.0 * 20 * 2;  // parabolic segment: 2/3 * base * height
    CHECK(a.area() == Approx(400 - half_disc + bay).epsilon(1e-9));
    REQUIRE(p.seams.size() == 1);
    CHECK(p.seams[0].panel_a == 0);
    CHECK(p.seams[0].panel_b == 1);
    CHECK(p.seams[0].edge_b == 3);
    CHECK(p.seams[0].edge_a == 1);  // edge 2 of the clockwise input is edge 1 once reversed
    CHECK(p.seams[0].orientation == SeamOrientation::same);
}

TEST_CASE("garmentcode json: bad input names the field", "[garment][export]") {
    CHECK_THROWS_WITH(pattern_from_garmentcode_json("{"), Catch::Contains("not valid JSON"));
    CHECK_THROWS_WITH(pattern_from_garmentcode_json(R"({"pattern": {}})"),
                      Catch::Contains("missing \"panels\""));
    CHECK_THROWS_WITH(
        pattern_from_garmentcode_json(R"({"pattern": {"panels": {"x": {"vertices": [[0,0],[1,0],[0,1]],
            "edges": [{"endpoints": [0, 7]}]}}}})"),
        Catch::Contains("pattern.panels.x.edges[0].endpoints"));
    CHECK_THROWS_WITH(
        pattern_from_garmentcode_json(R"({"pattern": {"panels": {"x": {"vertices": [[0,0],[1,0],[0,1]],
            "edges": [{"endpoints": [0, 1], "curvature": {"type": "spline", "params": []}},
                      {"endpoints": [1, 2]}, {"endpoints": [2, 0]}]}}}})"),
        Catch::Contains("unknown curvature type 'spline'"));
    CHECK_THROWS_AS(read_pattern_json("/nonexistent/pattern.json"), drape::IoError);
}
