#include <drape/body/body_model.hpp>
#include <drape/body/measurements.hpp>
#include <drape/core/errors.hpp>
#include <drape/garment/circle_skirt.hpp>
#include <drape/garment/dress.hpp>
#include <drape/garment/garment_sizing.hpp>
#include <drape/garment/garment_type.hpp>
#include <drape/garment/pants.hpp>
#include <drape/garment/sizing_proposal.hpp>
#include <drape/garment/tshirt.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <string>

using namespace drape::garment;

namespace {
constexpr double kPi = 3.14159265358979323846;

// The error message of `f`, or "" if it does not throw InvalidInput.
template <class F>
std::string error_of(F f) {
    try {
        f();
    } catch (const drape::InvalidInput& e) {
        return e.what();
    }
    return "";
}

double max_mismatch(const Pattern& p) {
    double m = 0;
    for (const Seam& s : p.seams) m = std::max(m, p.seam_mismatch(s));
    return m;
}
}  // namespace

TEST_CASE("circle skirt: geometry follows <l1, r1, r2, alpha>", "[garment][templates]") {
    SkirtSizing g;
    g.l1 = 40;
    g.r1 = 40 / (kPi / 2);  // quarter circle waist per panel
    g.r2 = 60;
    g.alpha = 90;           // = waist sweep: an exact annular sector
    const Pattern p = make_circle_skirt(g);
    REQUIRE(p.panels.size() == 2);
    CHECK(p.panels[0].edges[2].length() == Approx(40.0).epsilon(1e-12));  // waist arc = l1
    CHECK(p.panels[0].edges[1].length() == Approx(60.0).epsilon(1e-12));  // side = r2
    const double sector = 0.5 * (kPi / 2) * (std::pow(g.r1 + g.r2, 2) - g.r1 * g.r1);
    CHECK(p.panels[0].area() == Approx(sector).epsilon(1e-10));
    CHECK(max_mismatch(p) < 1e-12);
    // alpha = 0: parallel sides, straight hem.
    g.alpha = 0;
    const Pattern straight = make_circle_skirt(g);
    CHECK(straight.panels[0].edges[0].kind == EdgeKind::line);
}

TEST_CASE("circle skirt: bad parameters name the parameter and value", "[garment][templates]") {
    SkirtSizing g;
    g.alpha = 200;
    CHECK(error_of([&] { make_circle_skirt(g); }).find("parameter alpha = 200 deg") != std::string::npos);
    g = SkirtSizing{};
    g.r1 = 10;  // l1 / r1 = 3.8 rad > pi
    CHECK(error_of([&] { make_circle_skirt(g); }).find("at most 180") != std::string::npos);
    g = SkirtSizing{};
    g.l1 = 60;
    g.r1 = 60 / kPi;  // half-circle waist
    g.alpha = 0;      // parallel sides: the hem cuts through the waist curve
    g.r2 = 16;
    CHECK(error_of([&] { make_circle_skirt(g); }).find("self-intersects") != std::string::npos);
    g.l1 = std::nan("");
    CHECK(error_of([&] { make_circle_skirt(g); }).find("parameter l1 = nan") != std::string::npos);
}

TEST_CASE("pants: seams match and lengths follow <w1..w4, h1..h3>", "[garment][templates]") {
    const PantsSizing g;
    const Pattern p = make_pants(g);
    REQUIRE(p.panels.size() == 4);
    CHECK(p.seams.size() == 14);  // 2 x (3 side + 2 inseam) + 2 x 2 crotch
    CHECK(max_mismatch(p) < 1e-6);
    // Hem width of a front and back panel = half the ankle girth each.
    CHECK(p.panels[0].edges[0].length() + p.panels[3].edges[0].length() == Approx(g.w4));
    // The waist edges' horizontal widths sum to the waist girth (the back waist is sloped).
    double waist = 0;
    for (int i = 0; i < 4; ++i)
        for (const Edge& e : p.panels[i].edges)
            if (e.kind == EdgeKind::line && std::min(e.start.y(), e.end.y()) > g.h1 - 1)
                waist += std::abs(e.end.x() - e.start.x());
    CHECK(waist == Approx(g.w1).epsilon(1e-12));
    // Shorts: no knee line.
    PantsSizing s = g;
    s.h1 = 50;
    const Pattern shorts = make_pants(s);
    CHECK(shorts.panels[0].edges.size() == p.panels[0].edges.size() - 2);
    CHECK(shorts.seams.size() == 10);
    CHECK(max_mismatch(shorts) < 1e-6);
    // Hot pants (inseam 5-15 cm): the back's crotch extension lies further from the hem than
    // the front inseam is long, so the back crotch drops at most 2.5 cm (15 % of the inseam)
    // and the back leg opening widens at the inseam instead. Seams still match; every inseam
    // from 5 to 40 cm makes a valid pattern; the back opening changes continuously.
    for (const double h3 : {15.0, 21.8, 28.0}) {
        double last_back_hem = -1;
        for (double inseam = 5; inseam <= 40; inseam += 0.5) {
            PantsSizing h = g;
            h.h3 = h3;
            h.h2 = h3 + 5;
            h.h1 = h.h3 + inseam;
            if (h.h1 < 30) continue;  // the parameter's range
            INFO("h3 " << h3 << " cm, inseam " << inseam << " cm");
            std::string why;
            Pattern hp;
            REQUIRE_NOTHROW(hp = make_pants(h));
            CHECK(hp.is_valid(&why));
            CHECK(max_mismatch(hp) < 1e-6);
            // Edge 1 is the inseam (no knee): the back's crotch end lies at most 2.5 cm below
            // the front's, and its hem is at least the front's.
            const Edge& fi = hp.panels[0].edges[1];
            const Edge& bi = hp.panels[3].edges[1];
            CHECK(fi.end.y() - bi.end.y() <= std::min(2.5, 0.15 * inseam) + 1e-9);
            CHECK(hp.panels[3].edges[0].length() >= hp.panels[0].edges[0].length() - 1e-9);
            const double back_hem = hp.panels[3].edges[0].length();
            if (last_back_hem > 0) CHECK(std::abs(back_hem - last_back_hem) < 1.5);
            last_back_hem = back_hem;
        }
    }
    s.h3 = 48;  // inseam 2 cm
    CHECK(error_of([&] { make_pants(s); }).find("inseam h1 - h3 = 2") != std::string::npos);
    PantsSizing bad = g;
    bad.w2 = 20;
    CHECK(error_of([&] { make_pants(bad); }).find("parameter w2 = 20 cm") != std::string::npos);
}

TEST_CASE("t-shirt: sleeves, tank top and consistency checks", "[garment][templates]") {
    TShirtSizing g;
    const Pattern tee = make_tshirt(g);
    CHECK(tee.panels.size() == 4);
    CHECK(tee.seams.size() == 10);
    CHECK(max_mismatch(tee) < 1e-12);
    // Sleeve cap = armhole depth on front plus back.
    const double armhole = g.h2 - kTShirtShoulderDrop - g.h1;
    CHECK(tee.panels[2].edges[2].length() == Approx(armhole));
    g.l1 = 0;
    const Pattern tank = make_tshirt(g);
    CHECK(tank.name == "tank_top");
    CHECK(tank.panels.size() == 2);
    CHECK(tank.seams.size() == 4);
    g.l1 = 3;
    CHECK(error_of([&] { make_tshirt(g); }).find("l1 = 3") != std::string::npos);
    g = TShirtSizing{};
    g.h1 = 64;  // armhole depth 2.5 cm
    CHECK(error_of([&] { make_tshirt(g); }).find("armhole depth") != std::string::npos);
    g = TShirtSizing{};
    g.r = 25;
    CHECK(error_of([&] { make_tshirt(g); }).find("parameter r = 25 cm") != std::string::npos);
}

TEST_CASE("dress: bodice and skirt joined at the waist", "[garment][templates]") {
    DressSizing g;
    const Pattern d = make_dress(g);
    CHECK(d.panels.size() == 6);
    CHECK(d.panel_index("skirt_front") == 4);
    CHECK(d.seams.size() == 10 + 2 + 2);
    CHECK(max_mismatch(d) < 0.01);
    g.skirt.l1 = 40;
    CHECK(error_of([&] { make_dress(g); }).find("waist seam") != std::string::npos);
    g = DressSizing{};
    g.skirt.alpha = -5;
    CHECK(error_of([&] { make_dress(g); }).find("parameter skirt.alpha = -5") != std::string::npos);
}

TEST_CASE("sizing proposals from the default body are valid patterns", "[garment][templates]") {
    const auto& model = drape::body::BodyModel::default_model();
    const auto m = drape::body::measure_body(model, model.template_vertices);
    const SkirtSizing skirt = propose_skirt_sizing(m);
    CHECK(skirt.l1 == Approx((100 * m.waist_girth_m + 4) / 2));
    CHECK_NOTHROW(make_circle_skirt(skirt));
    const PantsSizing pants = propose_pants_sizing(m);
    CHECK(pants.w2 == Approx(100 * m.hip_girth_m + 8));
    CHECK(pants.h1 - pants.h3 == Approx(100 * m.crotch_height_m - 5).margin(1e-9));
    CHECK_NOTHROW(make_pants(pants));
    const TShirtSizing tee = propose_tshirt_sizing(m);
    CHECK(2 * tee.w2 == Approx(100 * m.chest_girth_m + 10));
    CHECK_NOTHROW(make_tshirt(tee));
    const DressSizing dress = propose_dress_sizing(m);
    CHECK_NOTHROW(make_dress(dress));
    drape::body::BodyMeasurements broken = m;
    broken.waist_girth_m = -1;
    CHECK(error_of([&] { propose_skirt_sizing(broken); }).find("waist_girth_m = -1") != std::string::npos);
    Ease ease;
    ease.hip_cm = 100;
    CHECK(error_of([&] { propose_pants_sizing(m, ease); }).find("hip_cm") != std::string::npos);
}

TEST_CASE("garment types: names round-trip, unknown names are rejected", "[garment][templates]") {
    for (GarmentType t : {GarmentType::skirt, GarmentType::pants, GarmentType::tshirt, GarmentType::dress})
        CHECK(garment_type_from_name(garment_type_name(t)) == t);
    CHECK(error_of([] { garment_type_from_name("kilt"); }).find("'kilt'") != std::string::npos);
}

TEST_CASE("outfit layers: one garment, or a bottom then a top over it", "[garment][templates]") {
    using T = GarmentType;
    for (T t : {T::skirt, T::pants, T::tshirt, T::dress}) CHECK(outfit_layers({t}) == std::vector<T>{t});
    CHECK(outfit_layers({T::pants, T::tshirt}) == std::vector<T>{T::pants, T::tshirt});
    CHECK(outfit_layers({T::tshirt, T::pants}) == std::vector<T>{T::pants, T::tshirt});
    CHECK(outfit_layers({T::tshirt, T::skirt}) == std::vector<T>{T::skirt, T::tshirt});
    CHECK(error_of([] { outfit_layers({T::dress, T::tshirt}); }).find("'dress+tshirt'") != std::string::npos);
    CHECK(error_of([] { outfit_layers({T::pants, T::skirt}); }).find("a top and a bottom") != std::string::npos);
    CHECK(error_of([] { outfit_layers({T::tshirt, T::tshirt}); }).find("'tshirt+tshirt'") != std::string::npos);
    CHECK(error_of([] { outfit_layers({T::skirt, T::tshirt, T::pants}); }).find("outfit") != std::string::npos);
    CHECK(error_of([] { outfit_layers({}); }).find("outfit") != std::string::npos);
}

TEST_CASE("any-template sizing: proposals and patterns per type", "[garment][templates]") {
    const auto& model = drape::body::BodyModel::default_model();
    const drape::body::ShapedBody shaped =
        drape::body::shape_from_coefficients(model, Eigen::VectorXd::Zero(model.shape_count()));
    const auto m = drape::body::measure_body(model, shaped.vertices);
    CHECK(proposed_sizing(GarmentType::pants, m).pants.w2 == propose_pants_sizing(m).w2);
    CHECK(proposed_sizing(GarmentType::skirt, m, 0.8).skirt.l1 == propose_skirt_sizing(m, 0.8).l1);
    for (GarmentType t : {GarmentType::skirt, GarmentType::pants, GarmentType::tshirt, GarmentType::dress}) {
        const GarmentSizing g = proposed_sizing(t, model, shaped, m);
        CHECK(g.type == t);
        CHECK_FALSE(make_pattern(g).panels.empty());
    }
    // A top is fitted to the body: its sleeve opening and neckline are never narrower than proposed.
    const GarmentSizing tee = proposed_sizing(GarmentType::tshirt, model, shaped, m);
    CHECK(tee.tshirt.w1 >= propose_tshirt_sizing(m).w1);
    CHECK(tee.tshirt.r >= propose_tshirt_sizing(m).r);
    // fit_top_to_body leaves bottoms unchanged.
    const GarmentSizing pants = fit_top_to_body(proposed_sizing(GarmentType::pants, m), model, shaped);
    CHECK(pants.pants.w1 == propose_pants_sizing(m).w1);
}

TEST_CASE("templates declare a typed role per panel", "[garment][templates]") {
    const auto roles = [](const Pattern& p) {
        std::vector<PanelRole> r;
        for (const PanelPlacement& pl : p.placements) r.push_back(pl.role);
        return r;
    };
    using R = PanelRole;
    CHECK(roles(make_circle_skirt(SkirtSizing{})) == std::vector<R>{R::skirt, R::skirt});
    CHECK(roles(make_pants(PantsSizing{})) == std::vector<R>{R::front_leg, R::front_leg, R::back_leg, R::back_leg});
    CHECK(roles(make_tshirt(TShirtSizing{})) == std::vector<R>{R::front_torso, R::back_torso, R::sleeve, R::sleeve});
    TShirtSizing tank;
    tank.l1 = 0;
    CHECK(roles(make_tshirt(tank)) == std::vector<R>{R::front_torso, R::back_torso});
    CHECK(roles(make_dress(DressSizing{})) ==
          std::vector<R>{R::front_torso, R::back_torso, R::sleeve, R::sleeve, R::skirt, R::skirt});
    for (R r : {R::other, R::front_torso, R::back_torso, R::sleeve, R::skirt, R::front_leg, R::back_leg})
        CHECK(panel_role_from_name(panel_role_name(r)) == r);
    CHECK(error_of([] { panel_role_from_name("collar"); }).find("'collar'") != std::string::npos);
}
