#include <drape/garment/tshirt.hpp>

#include <drape/core/errors.hpp>

#include <sstream>

namespace drape::garment {

namespace {
constexpr double kBackNeckDepthRatio = 0.3;      // back neckline depth / r
constexpr double kNominalNeckPointHeightCm = 150.0;
constexpr double kNominalHalfDepthCm = 14.0;
}  // namespace

const std::array<ParameterSpec<TShirtSizing>, 6>& TShirtSizing::parameters() {
    static const std::array<ParameterSpec<TShirtSizing>, 6> table = {{
        {"r", &TShirtSizing::r, 4.0, 20.0, "cm", "neckline radius (half the neck opening width)"},
        {"w1", &TShirtSizing::w1, 16.0, 80.0, "cm", "sleeve width: girth of the sleeve opening"},
        {"w2", &TShirtSizing::w2, 30.0, 100.0, "cm", "shoulder width: width of each body panel"},
        {"h1", &TShirtSizing::h1, 8.0, 110.0, "cm", "bottom length: hem to underarm (side seam)"},
        {"h2", &TShirtSizing::h2, 25.0, 140.0, "cm", "total length: hem to neck point"},
        {"l1", &TShirtSizing::l1, 0.0, 80.0, "cm", "sleeve length (0 = tank top, else >= 5)"},
    }};
    return table;
}

Pattern make_tshirt(const TShirtSizing& g) {
    const std::string garment = "t-shirt";
    check_parameters(garment, g, TShirtSizing::parameters());
    const double armhole = g.h2 - kTShirtShoulderDrop - g.h1;
    require(armhole >= 10.0 && armhole <= 40.0, garment, ": armhole depth h2 - ",
            kTShirtShoulderDrop, " - h1 = ", armhole, " cm (h2 = ", g.h2, ", h1 = ", g.h1,
            ") must be in [10, 40] cm");
    require(2 * g.r <= g.w2 - 10.0, garment, ": neckline radius r = ", g.r,
            " cm leaves shoulder seams shorter than 5 cm (needs 2 r <= w2 - 10 = ", g.w2 - 10.0, ")");
    require(g.l1 == 0.0 || g.l1 >= 5.0, garment, ": sleeve length l1 = ", g.l1,
            " cm must be 0 (tank top) or >= 5 cm");

    const double x = g.w2 / 2, ytip = g.h2 - kTShirtShoulderDrop;
    const auto body = [&](const std::string& name, double neck_depth) {
        Panel p;
        p.name = name;
        p.edges = {Edge::line({-x, 0}, {x, 0}),                       // 0 hem
                   Edge::line({x, 0}, {x, g.h1}),                     // 1 side (+x)
                   Edge::line({x, g.h1}, {x, ytip}),                  // 2 armhole
                   Edge::line({x, ytip}, {g.r, g.h2}),                // 3 shoulder
                   Edge::arc({g.r, g.h2}, {-g.r, g.h2}, -neck_depth / g.r),  // 4 neckline
                   Edge::line({-g.r, g.h2}, {-x, ytip}),              // 5 shoulder (-x)
                   Edge::line({-x, ytip}, {-x, g.h1}),                // 6 armhole
                   Edge::line({-x, g.h1}, {-x, 0})};                  // 7 side
        p.grain = Eigen::Vector2d(0, 1);
        p.notches = {{0, 0.5}, {4, 0.5}, {2, 1.0}, {6, 0.0}};
        p.internal_lines.push_back({Eigen::Vector2d(0, 0), Eigen::Vector2d(0, g.h2 - neck_depth)});
        return p;
    };
    Pattern pattern;
    pattern.name = g.l1 > 0 ? "tshirt" : "tank_top";
    pattern.panels = {body("front", g.r), body("back", kBackNeckDepthRatio * g.r)};
    PanelPlacement pf, pb;
    pf.body_part = BodyPart::front_torso;
    pf.role = PanelRole::front_torso;
    pf.translation_cm = Eigen::Vector3d(0, kNominalNeckPointHeightCm - g.h2, kNominalHalfDepthCm);
    pb.body_part = BodyPart::back_torso;
    pb.role = PanelRole::back_torso;
    pb.translation_cm = Eigen::Vector3d(0, kNominalNeckPointHeightCm - g.h2, -kNominalHalfDepthCm);
    pb.rotation_deg = Eigen::Vector3d(0, 180, 0);
    pattern.placements = {pf, pb};
    const auto rev = SeamOrientation::reversed;
    // Front +x is the person's left; back +x the person's right (the back is turned).
    pattern.seams = {{0, 1, 1, 7, rev}, {0, 7, 1, 1, rev}, {0, 3, 1, 5, rev}, {0, 5, 1, 3, rev}};
    if (g.l1 > 0) {
        Panel s;
        s.edges = {Edge::line({-g.w1 / 2, 0}, {g.w1 / 2, 0}),         // 0 cuff
                   Edge::line({g.w1 / 2, 0}, {armhole, g.l1}),       // 1 underarm
                   Edge::line({armhole, g.l1}, {0, g.l1}),           // 2 cap half
                   Edge::line({0, g.l1}, {-armhole, g.l1}),          // 3 cap half
                   Edge::line({-armhole, g.l1}, {-g.w1 / 2, 0})};    // 4 underarm
        s.grain = Eigen::Vector2d(0, 1);
        s.notches = {{2, 1.0}};
        s.internal_lines.push_back({Eigen::Vector2d(0, 0), Eigen::Vector2d(0, g.l1)});
        Panel left = s, right = s;
        left.name = "left_sleeve";
        right.name = "right_sleeve";
        pattern.panels.push_back(left);
        pattern.panels.push_back(right);
        const double y_shoulder = kNominalNeckPointHeightCm - kTShirtShoulderDrop;
        PanelPlacement pl, pr;
        pl.body_part = BodyPart::left_sleeve;
        pl.role = pr.role = PanelRole::sleeve;
        pl.rotation_deg = Eigen::Vector3d(0, 0, 90);   // panel +y (towards the cap) -> -X
        pl.translation_cm = Eigen::Vector3d(x + g.l1, y_shoulder, 0);
        pr.body_part = BodyPart::right_sleeve;
        pr.rotation_deg = Eigen::Vector3d(0, 0, -90);  // panel +y -> +X
        pr.translation_cm = Eigen::Vector3d(-x - g.l1, y_shoulder, 0);
        pattern.placements.push_back(pl);
        pattern.placements.push_back(pr);
        // Left armholes: front edge 2 (underarm -> tip), back edge 6 (tip -> underarm).
        pattern.seams.push_back({0, 2, 2, 3, rev});
        pattern.seams.push_back({1, 6, 2, 2, rev});
        pattern.seams.push_back({2, 1, 2, 4, rev});  // left sleeve tube
        pattern.seams.push_back({0, 6, 3, 2, rev});
        pattern.seams.push_back({1, 2, 3, 3, rev});
        pattern.seams.push_back({3, 1, 3, 4, rev});
    }
    std::string why;
    if (!pattern.is_valid(&why)) {
        std::ostringstream os;
        os << garment << ": parameters <r = " << g.r << ", w1 = " << g.w1 << ", w2 = " << g.w2
           << ", h1 = " << g.h1 << ", h2 = " << g.h2 << ", l1 = " << g.l1
           << "> give an invalid pattern: " << why;
        throw InvalidInput(os.str());
    }
    return pattern;
}

}  // namespace drape::garment
