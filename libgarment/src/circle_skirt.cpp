#include <drape/garment/circle_skirt.hpp>

#include <drape/core/errors.hpp>

#include <cmath>

namespace drape::garment {

namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr double kNominalWaistHeightCm = 105.0;  // placement hint for a 1.75 m body
constexpr double kNominalTorsoHalfDepthCm = 13.0;
}  // namespace

const std::array<ParameterSpec<SkirtSizing>, 4>& SkirtSizing::parameters() {
    static const std::array<ParameterSpec<SkirtSizing>, 4> table = {{
        {"l1", &SkirtSizing::l1, 20.0, 120.0, "cm",
         "waist arc length of one panel = half the skirt's waist girth"},
        {"r1", &SkirtSizing::r1, 8.0, 400.0, "cm",
         "waist arc radius; the waist arc sweeps l1/r1 radians (at most 180 degrees)"},
        {"r2", &SkirtSizing::r2, 15.0, 150.0, "cm", "side-seam length = skirt length"},
        {"alpha", &SkirtSizing::alpha, 0.0, 180.0, "deg",
         "flare: angle between the two side seams of a panel (hem arc sweep)"},
    }};
    return table;
}

Pattern make_circle_skirt(const SkirtSizing& g) {
    const std::string garment = "circle skirt";
    check_parameters(garment, g, SkirtSizing::parameters());
    const double phi = g.l1 / g.r1;  // waist sweep, radians
    require(phi <= kPi + 1e-9, garment, ": parameters l1 = ", g.l1, " cm and r1 = ", g.r1,
            " cm give a waist arc sweeping ", phi * 180 / kPi,
            " degrees per panel; at most 180 (r1 >= l1 / pi = ", g.l1 / kPi, " cm)");
    const double alpha = g.alpha * kPi / 180.0;

    // Waist arc centre at (0, r1) so that the middle of the waist arc is the origin.
    const Eigen::Vector2d o(0.0, g.r1);
    const Eigen::Vector2d wr = o + g.r1 * Eigen::Vector2d(std::sin(phi / 2), -std::cos(phi / 2));
    const Eigen::Vector2d wl(-wr.x(), wr.y());
    const Eigen::Vector2d hr = wr + g.r2 * Eigen::Vector2d(std::sin(alpha / 2), -std::cos(alpha / 2));
    const Eigen::Vector2d hl(-hr.x(), hr.y());

    Panel panel;
    panel.edges.push_back(g.alpha > 1e-6 ? Edge::arc(hl, hr, std::tan(alpha / 4))
                                         : Edge::line(hl, hr));   // 0 hem
    panel.edges.push_back(Edge::line(hr, wr));                     // 1 right side
    panel.edges.push_back(Edge::arc(wr, wl, -std::tan(phi / 4)));  // 2 waist
    panel.edges.push_back(Edge::line(wl, hl));                     // 3 left side
    panel.grain = Eigen::Vector2d(0, 1);
    panel.notches = {{2, 0.5}, {1, 0.5}, {3, 0.5}};
    panel.internal_lines.push_back({Eigen::Vector2d(0, 0), panel.edges[0].point_at_fraction(0.5)});

    Pattern pattern;
    pattern.name = "circle_skirt";
    Panel front = panel, back = panel;
    front.name = "front";
    back.name = "back";
    pattern.panels = {front, back};
    PanelPlacement pf, pb;
    pf.body_part = BodyPart::front_torso;
    pf.role = pb.role = PanelRole::skirt;
    pf.translation_cm = Eigen::Vector3d(0, kNominalWaistHeightCm, kNominalTorsoHalfDepthCm);
    pb.body_part = BodyPart::back_torso;
    pb.translation_cm = Eigen::Vector3d(0, kNominalWaistHeightCm, -kNominalTorsoHalfDepthCm);
    pb.rotation_deg = Eigen::Vector3d(0, 180, 0);
    pattern.placements = {pf, pb};
    // Front panel x -> world +X, back panel x -> world -X: the front's right side (+x)
    // meets the back's left side (-x), both on the person's left.
    pattern.seams = {{0, 1, 1, 3, SeamOrientation::reversed},
                     {0, 3, 1, 1, SeamOrientation::reversed}};
    std::string why;
    if (!pattern.is_valid(&why))
        throw InvalidInput(garment + ": parameters <l1 = " + std::to_string(g.l1) + ", r1 = " +
                           std::to_string(g.r1) + ", r2 = " + std::to_string(g.r2) +
                           ", alpha = " + std::to_string(g.alpha) + "> give an invalid pattern: " + why);
    return pattern;
}

}  // namespace drape::garment
