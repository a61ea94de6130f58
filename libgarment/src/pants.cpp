#include <drape/garment/pants.hpp>

#include <drape/core/errors.hpp>

#include <cmath>
#include <sstream>

namespace drape::garment {

namespace {

constexpr double kKappa = 0.5523;           // cubic approximation of a quarter ellipse
constexpr double kShortsInseamCm = 40.0;    // below this inseam there is no knee line
constexpr double kKneeFraction = 0.55;      // knee line height / inseam, from the hem
// Shorts: the back crotch drops at most this far below the front's (the classic drop of long
// trousers is 2-3 cm, e.g. 2.7 cm at w2 = 100, inseam 78 cm).
constexpr double kShortsMaxCrotchDropCm = 2.5;
constexpr double kShortsMaxCrotchDropFraction = 0.15;  // of the inseam
constexpr double kNominalWaistHeightCm = 105.0;
constexpr double kNominalLegOffsetCm = 9.5;
constexpr double kNominalHalfDepthCm = 12.0;

// Edge indices of one leg panel ("generic" orientation: side seam at -x, crotch at +x).
struct LegEdges {
    int hem = 0;
    std::vector<int> inseam;  // hem upwards
    int crotch = 0, centre = 0, waist = 0;
    std::vector<int> side;    // waist downwards
};

// Builds the right-leg front panel (back = false) or the left-leg back panel (back = true)
// in the frame: hem on y = 0, leg crease on x = 0, side seam at -x, crotch at +x. For the
// back, `front_inseam_upper` is the length of the front's upper inseam edge, matched by
// lowering the back crotch point.
Panel leg_panel(const PantsSizing& g, bool back, double front_inseam_upper, LegEdges* idx) {
    const double inseam = g.h1 - g.h3;          // L: crotch line height on the front
    const bool knee = inseam >= kShortsInseamCm;
    const double yk = knee ? kKneeFraction * inseam : 0.0;
    const double a = g.w4 / 4, k = knee ? g.w3 / 4 : a;
    const double q = g.w2 / 4;                  // quarter seat girth
    const double width_hip = back ? q + 1.0 : q - 1.0;
    const double ext = back ? g.w2 / 8 : g.w2 / 16;  // crotch extension
    const double x_side_hip = -q / 2, x_centre = x_side_hip + width_hip;
    const double x_crotch = x_centre + ext;
    const double x_side_waist = -g.w1 / 8;
    const double x_centre_waist = x_side_waist + (back ? g.w1 / 4 + 1.0 : g.w1 / 4 - 1.0);
    const double y_waist_centre = back ? inseam + g.h2 : g.h1;
    const double curve_height = (back ? 0.45 : 0.4) * (y_waist_centre - inseam);
    double y_crotch = inseam;
    double x_hem_in = a;
    if (back) {  // the classic lowered back crotch: equal inseam lengths
        const double dx = x_crotch - k;
        const double L = front_inseam_upper;
        y_crotch = yk + std::sqrt(std::max(0.0, L * L - dx * dx));
        // Short legs (no knee line): the back's wider crotch extension can be further from the
        // hem's inner corner than the whole front inseam is long, and lowering the crotch
        // cannot match it (it would reach the hem). As shorts patterns do, the crotch drops
        // at most kShortsMaxCrotchDrop and the back leg opening widens at the inseam instead
        // (the back hem's inner corner moves out); continuous with the classic construction
        // where the drop is within the bound.
        const double drop = std::min(kShortsMaxCrotchDropCm, kShortsMaxCrotchDropFraction * inseam);
        if (!knee && y_crotch < inseam - drop) {
            y_crotch = inseam - drop;
            x_hem_in = x_crotch - std::sqrt(std::max(0.0, L * L - y_crotch * y_crotch));
        }
    }
    const Eigen::Vector2d hem_side(-a, 0), hem_in(x_hem_in, 0), knee_in(knee ? k : x_hem_in, yk),
        knee_side(-k, yk);
    const Eigen::Vector2d crotch(x_crotch, y_crotch), centre_low(x_centre, inseam + curve_height);
    const Eigen::Vector2d centre_waist(x_centre_waist, y_waist_centre), side_waist(x_side_waist, g.h1);
    const Eigen::Vector2d side_hip(x_side_hip, inseam);

    Panel p;
    auto add = [&](const Edge& e) {
        p.edges.push_back(e);
        return static_cast<int>(p.edges.size()) - 1;
    };
    idx->hem = add(Edge::line(hem_side, hem_in));
    idx->inseam.clear();
    idx->side.clear();
    if (knee) idx->inseam.push_back(add(Edge::line(hem_in, knee_in)));
    idx->inseam.push_back(add(Edge::line(knee_in, crotch)));
    const double ex = x_crotch - x_centre, ey = centre_low.y() - y_crotch;
    idx->crotch = add(Edge::cubic(crotch, Eigen::Vector2d(x_crotch - kKappa * ex, y_crotch),
                                  Eigen::Vector2d(x_centre, centre_low.y() - kKappa * ey), centre_low));
    idx->centre = add(Edge::line(centre_low, centre_waist));
    idx->waist = add(Edge::line(centre_waist, side_waist));
    const double rise = g.h1 - inseam;
    idx->side.push_back(add(Edge::cubic(side_waist,
                                        Eigen::Vector2d(x_side_waist + 0.3 * (x_side_hip - x_side_waist), g.h1 - 0.3 * rise),
                                        Eigen::Vector2d(x_side_hip, inseam + 0.45 * rise), side_hip)));
    idx->side.push_back(add(Edge::line(side_hip, knee_side)));
    if (knee) idx->side.push_back(add(Edge::line(knee_side, hem_side)));  // else knee_side == hem_side
    p.grain = Eigen::Vector2d(0, 1);
    p.internal_lines.push_back({Eigen::Vector2d(0, 0), Eigen::Vector2d(0, inseam)});  // crease
    if (knee) p.notches.push_back({idx->inseam.front(), 1.0});
    p.notches.push_back({idx->side.front(), 1.0});
    return p;
}

}  // namespace

const std::array<ParameterSpec<PantsSizing>, 7>& PantsSizing::parameters() {
    static const std::array<ParameterSpec<PantsSizing>, 7> table = {{
        {"w1", &PantsSizing::w1, 50.0, 170.0, "cm", "waist girth of the garment"},
        {"w2", &PantsSizing::w2, 70.0, 190.0, "cm", "bottom (seat / hip) girth of the garment"},
        {"w3", &PantsSizing::w3, 25.0, 90.0, "cm", "knee girth of one leg"},
        {"w4", &PantsSizing::w4, 20.0, 90.0, "cm", "ankle (leg opening) girth of one leg"},
        {"h1", &PantsSizing::h1, 30.0, 135.0, "cm", "total length, waist to hem at the side"},
        {"h2", &PantsSizing::h2, 15.0, 55.0, "cm", "back upper length, crotch line to back waist"},
        {"h3", &PantsSizing::h3, 15.0, 50.0, "cm", "front upper length, crotch line to front waist"},
    }};
    return table;
}

Pattern make_pants(const PantsSizing& g) {
    const std::string garment = "pants";
    check_parameters(garment, g, PantsSizing::parameters());
    require(g.h1 - g.h3 >= 5.0, garment, ": inseam h1 - h3 = ", g.h1 - g.h3,
            " cm (h1 = ", g.h1, ", h3 = ", g.h3, ") must be >= 5 cm");
    require(g.h2 >= g.h3 - 5.0, garment, ": back upper length h2 = ", g.h2,
            " cm must be >= front upper length h3 - 5 = ", g.h3 - 5.0, " cm");

    LegEdges fe, be;
    const Panel front = leg_panel(g, false, 0.0, &fe);
    const double front_upper = front.edges[fe.inseam.back()].length();
    const Panel back = leg_panel(g, true, front_upper, &be);

    Pattern pattern;
    pattern.name = "pants";
    // 0 front_right (generic front), 1 front_left (mirror), 2 back_right (mirror of the
    // generic back), 3 back_left (generic back). Front x -> world +X, back x -> world -X.
    Panel fr = front, fl = front.mirrored("front_left"), br = back.mirrored("back_right"), bl = back;
    fr.name = "front_right";
    bl.name = "back_left";
    pattern.panels = {fr, fl, br, bl};
    const auto placement = [](BodyPart part, double x, bool is_back) {
        PanelPlacement pl;
        pl.body_part = part;
        pl.role = is_back ? PanelRole::back_leg : PanelRole::front_leg;
        pl.translation_cm = Eigen::Vector3d(x, 0.0, is_back ? -kNominalHalfDepthCm : kNominalHalfDepthCm);
        if (is_back) pl.rotation_deg = Eigen::Vector3d(0, 180, 0);
        return pl;
    };
    const double y0 = kNominalWaistHeightCm - g.h1;
    pattern.placements = {placement(BodyPart::right_leg, -kNominalLegOffsetCm, false),
                          placement(BodyPart::left_leg, kNominalLegOffsetCm, false),
                          placement(BodyPart::right_leg, -kNominalLegOffsetCm, true),
                          placement(BodyPart::left_leg, kNominalLegOffsetCm, true)};
    // Back panels turn about Y: their panel x runs along world -X, so the generic back
    // (side at -x) sits on the person's left and its mirror on the right.
    for (auto& pl : pattern.placements) pl.translation_cm.y() = y0;

    const int nf = static_cast<int>(front.edges.size()), nb = static_cast<int>(back.edges.size());
    const auto rev = SeamOrientation::reversed;
    const auto leg_seams = [&](const std::vector<int>& f, const std::vector<int>& b) {
        for (size_t i = 0; i < f.size(); ++i) {
            pattern.seams.push_back({0, f[i], 2, nb - 1 - b[i], rev});  // right leg
            pattern.seams.push_back({1, nf - 1 - f[i], 3, b[i], rev});  // left leg
        }
    };
    leg_seams(fe.side, be.side);
    leg_seams(fe.inseam, be.inseam);
    for (int e : {fe.crotch, fe.centre}) pattern.seams.push_back({0, e, 1, nf - 1 - e, rev});
    for (int e : {be.crotch, be.centre}) pattern.seams.push_back({3, e, 2, nb - 1 - e, rev});
    std::string why;
    if (!pattern.is_valid(&why)) {
        std::ostringstream os;
        os << garment << ": parameters <w1 = " << g.w1 << ", w2 = " << g.w2 << ", w3 = " << g.w3
           << ", w4 = " << g.w4 << ", h1 = " << g.h1 << ", h2 = " << g.h2 << ", h3 = " << g.h3
           << "> give an invalid pattern: " << why;
        throw InvalidInput(os.str());
    }
    return pattern;
}

}  // namespace drape::garment
