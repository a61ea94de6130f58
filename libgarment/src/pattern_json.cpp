#include <drape/garment/pattern_json.hpp>

#include <drape/core/atomic_file.hpp>
#include <drape/core/errors.hpp>
#include <drape/core/limits.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

namespace drape::garment {

namespace {

using nlohmann::json;
constexpr double kPi = 3.14159265358979323846;

// Rounded so that export -> import -> export reproduces the text exactly.
double round_to(double v, double step) {
    const double r = std::round(v / step) * step;
    return r == 0.0 ? 0.0 : r;
}
json xy(const Eigen::Vector2d& p, double step) { return json::array({round_to(p.x(), step), round_to(p.y(), step)}); }
json xyz(const Eigen::Vector3d& p, double step) {
    return json::array({round_to(p.x(), step), round_to(p.y(), step), round_to(p.z(), step)});
}
constexpr double kCm = 1e-8;    // coordinate rounding step, cm
constexpr double kRel = 1e-10;  // relative-coordinate rounding step

// Edge-relative coordinates (GarmentCode): x along start->end, y along its left normal,
// both in units of the edge's chord length.
Eigen::Vector2d to_relative(const Edge& e, const Eigen::Vector2d& p) {
    const Eigen::Vector2d d = e.end - e.start, perp(-d.y(), d.x());
    return Eigen::Vector2d((p - e.start).dot(d), (p - e.start).dot(perp)) / d.squaredNorm();
}
Eigen::Vector2d from_relative(const Eigen::Vector2d& s, const Eigen::Vector2d& e,
                              const Eigen::Vector2d& r) {
    const Eigen::Vector2d d = e - s, perp(-d.y(), d.x());
    return s + r.x() * d + r.y() * perp;
}

[[noreturn]] void bad(const std::string& where, const std::string& what) {
    throw InvalidInput("GarmentCode JSON: " + where + ": " + what);
}

const json& field(const json& j, const char* key, const std::string& where) {
    if (!j.is_object() || !j.contains(key)) bad(where, std::string("missing \"") + key + "\"");
    return j.at(key);
}

double number(const json& j, const std::string& where) {
    if (!j.is_number()) bad(where, "expected a number, got " + j.dump());
    const double v = j.get<double>();
    if (!std::isfinite(v)) bad(where, "not finite");
    return v;
}

// An index: an integral number that fits an int (get<int>() of 1e300 would be undefined).
int integer(const json& j, const std::string& where) {
    const double v = number(j, where);
    if (v != std::floor(v) || v < -2147483648.0 || v > 2147483647.0)
        bad(where, "expected an integer index, got " + j.dump());
    return static_cast<int>(v);
}

std::string text_field(const json& j, const std::string& where) {
    if (!j.is_string()) bad(where, "expected a string, got " + j.dump());
    return j.get<std::string>();
}

Eigen::Vector2d point2(const json& j, const std::string& where) {
    if (!j.is_array() || j.size() != 2) bad(where, "expected [x, y], got " + j.dump());
    return Eigen::Vector2d(number(j[0], where + "[0]"), number(j[1], where + "[1]"));
}

}  // namespace

std::string pattern_to_garmentcode_json(const Pattern& pattern) {
    pattern.validate();
    json panels = json::object(), order = json::array();
    for (size_t p = 0; p < pattern.panels.size(); ++p) {
        const Panel& panel = pattern.panels[p];
        const PanelPlacement& pl = pattern.placements[p];
        json vertices = json::array(), edges = json::array();
        const size_t n = panel.edges.size();
        for (size_t i = 0; i < n; ++i) {
            const Edge& e = panel.edges[i];
            vertices.push_back(xy(e.start, kCm));
            json je = {{"endpoints", {int(i), int((i + 1) % n)}}};
            if (e.kind == EdgeKind::arc) {
                double radius = 0;
                e.arc_geometry(nullptr, &radius, nullptr, nullptr);
                je["curvature"] = {{"type", "circle"},
                                   {"params", {round_to(radius, kCm), std::abs(e.bulge) > 1.0 ? 1 : 0,
                                               e.bulge > 0 ? 1 : 0}}};
            } else if (e.kind == EdgeKind::cubic) {
                je["curvature"] = {{"type", "cubic"},
                                   {"params", {xy(to_relative(e, e.control1), kRel),
                                               xy(to_relative(e, e.control2), kRel)}}};
            }
            edges.push_back(je);
        }
        json notches = json::array(), lines = json::array();
        for (const Notch& nt : panel.notches) notches.push_back({nt.edge, round_to(nt.fraction, kRel)});
        for (const InternalLine& l : panel.internal_lines) lines.push_back({xy(l.a, kCm), xy(l.b, kCm)});
        panels[panel.name] = {{"translation", xyz(pl.translation_cm, kCm)},
                              {"rotation", xyz(pl.rotation_deg, kCm)},
                              {"vertices", vertices},
                              {"edges", edges},
                              {"drape_body_part", std::string(body_part_name(pl.body_part))},
                              {"drape_role", std::string(panel_role_name(pl.role))},
                              {"drape_grain", xy(panel.grain, kRel)},
                              {"drape_notches", notches},
                              {"drape_internal_lines", lines}};
        order.push_back(panel.name);
    }
    json stitches = json::array();
    for (const Seam& s : pattern.seams)
        stitches.push_back(json::array(
            {{{"panel", pattern.panels[s.panel_a].name}, {"edge", s.edge_a},
              {"drape_orientation", s.orientation == SeamOrientation::same ? "same" : "reversed"}},
             {{"panel", pattern.panels[s.panel_b].name}, {"edge", s.edge_b}}}));
    json doc = {{"pattern", {{"panels", panels}, {"stitches", stitches}, {"panel_order", order}}},
                {"parameters", json::object()},
                {"parameter_order", json::array()},
                {"properties",
                 {{"curvature_coords", "relative"},
                  {"normalize_panel_translation", false},
                  {"normalized_edge_loops", true},
                  {"units_in_meter", 100},
                  {"drape_name", pattern.name}}}};
    return doc.dump(1) + "\n";
}

namespace {

Pattern parse_pattern(const std::string& text) {
    limits::check_json_text(text, "GarmentCode JSON");
    json doc;
    try {
        doc = json::parse(text);
    } catch (const json::exception& e) {
        throw InvalidInput(std::string("GarmentCode JSON: not valid JSON: ") + e.what());
    }
    const json& props = doc.contains("properties") ? doc["properties"] : json::object();
    const double scale = props.contains("units_in_meter")
                             ? 100.0 / number(props["units_in_meter"], "properties.units_in_meter")
                             : 1.0;
    if (!(scale > 0)) bad("properties.units_in_meter", "must be > 0");
    const bool relative = !props.contains("curvature_coords") ||
                          props["curvature_coords"] == "relative";
    const json& jpattern = field(doc, "pattern", "document");
    const json& jpanels = field(jpattern, "panels", "pattern");
    if (!jpanels.is_object() || jpanels.empty()) bad("pattern.panels", "expected a non-empty object");

    std::vector<std::string> names;
    if (jpattern.contains("panel_order"))
        for (const json& n : jpattern["panel_order"]) names.push_back(text_field(n, "pattern.panel_order"));
    for (auto it = jpanels.begin(); it != jpanels.end(); ++it)
        if (std::find(names.begin(), names.end(), it.key()) == names.end()) names.push_back(it.key());

    Pattern pattern;
    pattern.name = props.contains("drape_name") ? text_field(props["drape_name"], "properties.drape_name") : "garmentcode";
    std::vector<std::vector<int>> edge_map;   // json edge index -> our edge index
    std::vector<bool> flipped;                // loop reversed to make it CCW
    for (const std::string& name : names) {
        const std::string where = "pattern.panels." + name;
        if (!jpanels.contains(name)) bad("pattern.panel_order", "names unknown panel '" + name + "'");
        const json& jp = jpanels[name];
        const json& jv = field(jp, "vertices", where);
        const json& je = field(jp, "edges", where);
        std::vector<Eigen::Vector2d> verts;
        for (size_t i = 0; i < jv.size(); ++i)
            verts.push_back(scale * point2(jv[i], where + ".vertices[" + std::to_string(i) + "]"));
        Panel panel;
        panel.name = name;
        std::vector<int> map(je.size());
        for (size_t i = 0; i < je.size(); ++i) {
            const std::string we = where + ".edges[" + std::to_string(i) + "]";
            const json& ends = field(je[i], "endpoints", we);
            if (!ends.is_array() || ends.size() != 2) bad(we + ".endpoints", "expected [i, j]");
            const int a = integer(ends[0], we + ".endpoints[0]"), b = integer(ends[1], we + ".endpoints[1]");
            if (a < 0 || b < 0 || a >= int(verts.size()) || b >= int(verts.size()))
                bad(we + ".endpoints", "vertex index out of range (" + std::to_string(verts.size()) + " vertices)");
            const Eigen::Vector2d s = verts[a], e = verts[b];
            Edge edge = Edge::line(s, e);
            if (je[i].contains("curvature")) {
                const json& c = je[i]["curvature"];
                const std::string wc = we + ".curvature";
                if (c.is_array()) {  // legacy: one relative quadratic control point
                    const Eigen::Vector2d q = from_relative(s, e, point2(c, wc));
                    edge = Edge::cubic(s, s + 2.0 / 3.0 * (q - s), e + 2.0 / 3.0 * (q - e), e);
                } else {
                    const std::string type = text_field(field(c, "type", wc), wc + ".type");
                    const json& params = field(c, "params", wc);
                    auto control = [&](const json& j, const std::string& w) {
                        const Eigen::Vector2d v = point2(j, w);
                        return relative ? from_relative(s, e, v) : Eigen::Vector2d(scale * v);
                    };
                    if (type == "circle") {
                        if (!params.is_array() || params.size() != 3) bad(wc + ".params", "expected [radius, large_arc, right]");
                        const double r = scale * number(params[0], wc + ".params[0]");
                        const double chord = (e - s).norm();
                        if (!(r >= 0.5 * chord - 1e-9)) bad(wc + ".params[0]", "radius smaller than half the chord");
                        double sweep = 2 * std::asin(std::min(1.0, chord / (2 * r)));
                        if (number(params[1], wc + ".params[1]") != 0) sweep = 2 * kPi - sweep;
                        if (number(params[2], wc + ".params[2]") == 0) sweep = -sweep;
                        edge = Edge::arc(s, e, std::tan(sweep / 4));
                    } else if (type == "quadratic") {
                        const Eigen::Vector2d q = control(params.at(0), wc + ".params[0]");
                        edge = Edge::cubic(s, s + 2.0 / 3.0 * (q - s), e + 2.0 / 3.0 * (q - e), e);
                    } else if (type == "cubic") {
                        if (!params.is_array() || params.size() != 2) bad(wc + ".params", "expected two control points");
                        edge = Edge::cubic(s, control(params[0], wc + ".params[0]"),
                                           control(params[1], wc + ".params[1]"), e);
                    } else {
                        bad(wc + ".type", "unknown curvature type '" + type + "'");
                    }
                }
            }
            map[i] = static_cast<int>(i);
            panel.edges.push_back(edge);
        }
        bool flip = false;
        if (panel.area() < 0) {  // make it counter-clockwise
            flip = true;
            std::vector<Edge> rev;
            for (size_t i = panel.edges.size(); i-- > 0;) rev.push_back(panel.edges[i].reversed());
            panel.edges = rev;
            for (size_t i = 0; i < map.size(); ++i) map[i] = int(map.size() - 1 - i);
        }
        if (jp.contains("drape_grain")) panel.grain = point2(jp["drape_grain"], where + ".drape_grain");
        if (jp.contains("drape_notches"))
            for (const json& n : jp["drape_notches"]) {
                if (!n.is_array() || n.size() != 2) bad(where + ".drape_notches", "expected [edge, fraction], got " + n.dump());
                Notch nt{integer(n[0], where + ".drape_notches"), number(n[1], where + ".drape_notches")};
                if (nt.edge >= 0 && nt.edge < int(map.size())) {
                    if (flip) nt.fraction = 1 - nt.fraction;
                    nt.edge = map[nt.edge];
                }
                panel.notches.push_back(nt);
            }
        if (jp.contains("drape_internal_lines"))
            for (const json& l : jp["drape_internal_lines"])
                panel.internal_lines.push_back({scale * point2(l.at(0), where + ".drape_internal_lines"),
                                                scale * point2(l.at(1), where + ".drape_internal_lines")});
        PanelPlacement pl;
        auto vec3 = [&](const char* key) {
            Eigen::Vector3d v = Eigen::Vector3d::Zero();
            if (!jp.contains(key)) return v;
            const json& j = jp[key];
            if (!j.is_array() || j.size() != 3) bad(where + "." + key, "expected [x, y, z]");
            for (int k = 0; k < 3; ++k) v[k] = number(j[k], where + "." + key);
            return v;
        };
        pl.translation_cm = scale * vec3("translation");
        pl.rotation_deg = vec3("rotation");
        if (jp.contains("drape_body_part")) pl.body_part = body_part_from_name(text_field(jp["drape_body_part"], where + ".drape_body_part"));
        if (jp.contains("drape_role")) pl.role = panel_role_from_name(text_field(jp["drape_role"], where + ".drape_role"));
        pattern.panels.push_back(std::move(panel));
        pattern.placements.push_back(pl);
        edge_map.push_back(map);
        flipped.push_back(flip);
    }
    if (jpattern.contains("stitches")) {
        const json& js = jpattern["stitches"];
        for (size_t i = 0; i < js.size(); ++i) {
            const std::string ws = "pattern.stitches[" + std::to_string(i) + "]";
            if (!js[i].is_array() || js[i].size() < 2) bad(ws, "expected [{panel, edge}, {panel, edge}]");
            int pe[2][2];
            for (int k = 0; k < 2; ++k) {
                const std::string name = text_field(field(js[i][k], "panel", ws), ws + ".panel");
                const int p = pattern.panel_index(name);
                if (p < 0) bad(ws, "unknown panel '" + name + "'");
                const int e = integer(field(js[i][k], "edge", ws), ws + ".edge");
                if (e < 0 || e >= int(edge_map[p].size())) bad(ws, "edge " + std::to_string(e) + " out of range for panel '" + name + "'");
                pe[k][0] = p;
                pe[k][1] = edge_map[p][e];
            }
            Seam s{pe[0][0], pe[0][1], pe[1][0], pe[1][1], SeamOrientation::reversed};
            if (js[i][0].contains("drape_orientation") && js[i][0]["drape_orientation"] == "same")
                s.orientation = SeamOrientation::same;
            if (flipped[s.panel_a] != flipped[s.panel_b])
                s.orientation = s.orientation == SeamOrientation::same ? SeamOrientation::reversed
                                                                       : SeamOrientation::same;
            pattern.seams.push_back(s);
        }
    }
    std::string why;
    if (!pattern.is_valid(&why)) throw InvalidInput("GarmentCode JSON: " + why);
    return pattern;
}

}  // namespace

Pattern pattern_from_garmentcode_json(const std::string& text) {
    try {
        return parse_pattern(text);
    } catch (const nlohmann::json::exception& e) {
        throw InvalidInput(std::string("GarmentCode JSON: wrong type or missing value: ") + e.what());
    }
}

void write_pattern_json(const std::filesystem::path& path, const Pattern& pattern) {
    write_text_atomically(path, pattern_to_garmentcode_json(pattern));
}

Pattern read_pattern_json(const std::filesystem::path& path) {
    const std::string text = limits::read_file_capped(path, limits::kMaxJsonFileBytes, "pattern JSON");
    try {
        return pattern_from_garmentcode_json(text);
    } catch (const InvalidInput& e) {
        throw InvalidInput(path.string() + ": " + e.what());
    }
}

}  // namespace drape::garment
