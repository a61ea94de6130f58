// The starting sizing's search bounds: girths may shrink to the least ease over the body (2 cm by default),
// lengths and angles are not bounded below (docs/recovery.md, "Sizing").
#include "../../librecover/src/initial_sizing.hpp"

#include <drape/body/measurements.hpp>
#include <drape/garment/garment_sizing.hpp>
#include <drape/garment/sizing_proposal.hpp>
#include <drape/recover/recover.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <string>

using namespace drape;
using namespace drape::recover;

namespace {

body::BodyMeasurements woman() {
    body::BodyMeasurements m;
    m.height_m = 1.65;
    m.chest_girth_m = 0.92;
    m.waist_girth_m = 0.76;
    m.hip_girth_m = 1.00;
    m.thigh_girth_m = 0.58;
    m.shoulder_height_m = 1.35;
    m.crotch_height_m = 0.76;
    return m;
}

// The bound at the library's default least ease unless one is given.
double bound_of(const garment::GarmentSizing& g, const std::string& name,
                double min_ease_cm = RecoverOptions().min_ease_cm) {
    const auto params = garment::sizing_parameters(g.type);
    const auto b = lower_bounds(g, min_ease_cm);
    REQUIRE(b.size() == params.size());
    for (size_t i = 0; i < params.size(); ++i)
        if (params[i].name == name) return b[i];
    FAIL("no parameter " << name);
    return 0;
}

}  // namespace

TEST_CASE("sizing search bounds: girths down to 2 cm of ease over the body, nothing else bounded",
          "[recover][sizing]") {
    const body::BodyMeasurements m = woman();
    const garment::GarmentSizing top = garment::proposed_sizing(garment::GarmentType::tshirt, m);
    // A panel is half the chest: (chest + 10) / 2 proposed, (chest + 2) / 2 at the bound.
    CHECK(bound_of(top, "w2") == Approx((92.0 + 2.0) / 2));
    CHECK(bound_of(top, "w1") == Approx(top.tshirt.w1 - 4.0));
    for (const char* n : {"h1", "h2", "l1", "r"}) CHECK(std::isnan(bound_of(top, n)));
    const garment::GarmentSizing pants = garment::proposed_sizing(garment::GarmentType::pants, m);
    CHECK(bound_of(pants, "w1") == Approx(76.0 + 2.0));
    CHECK(bound_of(pants, "w2") == Approx(100.0 + 2.0));
    CHECK(bound_of(pants, "w3") == Approx(pants.pants.w3 - 6.0));
    CHECK(bound_of(pants, "w4") == Approx(pants.pants.w4 - 6.0));
    for (const char* n : {"h1", "h2", "h3"}) CHECK(std::isnan(bound_of(pants, n)));
    const garment::GarmentSizing skirt = garment::proposed_sizing(garment::GarmentType::skirt, m);
    // A panel's waist arc is half the waist: (waist + 4) / 2 proposed, (waist + 2) / 2 bound.
    CHECK(bound_of(skirt, "l1") == Approx(skirt.skirt.l1 - 1.0));
    for (const char* n : {"r1", "r2", "alpha"}) CHECK(std::isnan(bound_of(skirt, n)));
    const garment::GarmentSizing dress = garment::proposed_sizing(garment::GarmentType::dress, m);
    CHECK(bound_of(dress, "bodice.w2") == Approx((92.0 + 2.0) / 2));
    CHECK(std::isnan(bound_of(dress, "skirt.r2")));
    // Every bound lies below its start: the search can narrow a garment, never must widen it.
    for (const auto* g : {&top, &pants, &skirt, &dress}) {
        const auto b = lower_bounds(*g, RecoverOptions().min_ease_cm);
        const auto v = garment::sizing_values(*g);
        for (size_t i = 0; i < b.size(); ++i)
            if (!std::isnan(b[i])) CHECK(b[i] < v[i]);
    }
    // A negative least ease lets a knit top be smaller than the body: (92 - 4) / 2.
    CHECK(bound_of(top, "w2", -4.0) == Approx((92.0 - 4.0) / 2));
    CHECK(bound_of(top, "w1", -4.0) == Approx(top.tshirt.w1 - 7.0));
    CHECK(bound_of(pants, "w2", -4.0) == Approx(100.0 - 4.0));
    CHECK(bound_of(skirt, "l1", 0.0) == Approx(skirt.skirt.l1 - 2.0));
    // An ease above the proposal's leaves the girth at its start.
    CHECK(bound_of(top, "w2", 12.0) == Approx(top.tshirt.w2));
}

TEST_CASE("RecoverOptions: the least ease is checked and named", "[recover][sizing]") {
    RecoverOptions o;
    std::string why;
    CHECK(o.is_valid(&why));
    o.min_ease_cm = -4;
    CHECK(o.is_valid(&why));
    for (double bad : {-10.5, 11.0, std::nan("")}) {
        o.min_ease_cm = bad;
        CHECK_FALSE(o.is_valid(&why));
        CHECK(why.find("min_ease_cm") != std::string::npos);
    }
}

TEST_CASE("RecoverOptions: the base fabric is a measured fabric", "[recover][options]") {
    RecoverOptions o;
    std::string why;
    for (const char* name : {"gray-interlock", "11oz-black-denim", "ivory-rib-knit"}) {
        o.base_fabric = name;
        CHECK(o.is_valid(&why));
    }
    for (const char* bad : {"", "velvet", "Gray-Interlock"}) {
        o.base_fabric = bad;
        CHECK_FALSE(o.is_valid(&why));
        CHECK(why.find("base_fabric '" + std::string(bad) + "' is not a measured fabric") != std::string::npos);
        CHECK(why.find("camel-ponte-roma") != std::string::npos);  // the names it takes
    }
}
