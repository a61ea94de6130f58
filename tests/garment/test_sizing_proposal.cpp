// `--sizing auto` (proposed_sizing with the body) on bodies at the edges of the shape prior's
// range and on the ANSUR II people of issue 20 for whom it proposed sizings the templates
// refused (a t-shirt sleeve opening of 183 cm on a man of 1.76 m and 110 kg).
#include <drape/body/body_model.hpp>
#include <drape/body/measurements.hpp>
#include <drape/body/shape_body.hpp>
#include <drape/core/errors.hpp>
#include <drape/garment/garment_sizing.hpp>
#include <drape/garment/sizing_proposal.hpp>

#include <catch2/catch.hpp>

#include <string>
#include <vector>

using namespace drape::garment;
namespace body = drape::body;

namespace {

struct NamedRequest {
    std::string name;
    body::SemanticRequest request;
};

body::SemanticRequest request_of(body::Gender gender, double height_m, double weight_kg, double chest_m = 0,
                                 double waist_m = 0, double hip_m = 0) {
    body::SemanticRequest r;
    r.gender = gender;
    r[body::Semantic::height_m] = height_m;
    r[body::Semantic::weight_kg] = weight_kg;
    if (chest_m > 0) r[body::Semantic::chest_girth_m] = chest_m;
    if (waist_m > 0) r[body::Semantic::waist_girth_m] = waist_m;
    if (hip_m > 0) r[body::Semantic::hip_girth_m] = hip_m;
    return r;
}

// The four corners of the prior's stature x body mass range (0.5th and 99.5th percentiles)
// per gender, and the bodies of issue 20.
std::vector<NamedRequest> extreme_bodies(const body::BodyModel& model) {
    std::vector<NamedRequest> bodies;
    for (const body::Gender g : {body::Gender::female, body::Gender::male}) {
        const body::GaussianPrior& p = model.prior.of(g);
        const int h = int(body::Semantic::height_m), w = int(body::Semantic::weight_kg);
        for (const double height : {p.min[h], p.max[h]})
            for (const double weight : {p.min[w], p.max[w]})
                bodies.push_back({std::string(body::to_string(g)) + " " + std::to_string(height) + " m " +
                                      std::to_string(weight) + " kg",
                                  request_of(g, height, weight)});
    }
    bodies.push_back({"issue 20 woman 1.66 m 112 kg hip 1.34 m", request_of(body::Gender::female, 1.66, 112, 0, 0, 1.34)});
    bodies.push_back({"issue 20 man 1.76 m 110 kg", request_of(body::Gender::male, 1.76, 110)});
    bodies.push_back({"issue 20 man 1.83 m 92 kg", request_of(body::Gender::male, 1.83, 92, 1.07, 0.97, 1.05)});
    return bodies;
}

// Every parameter of the sizing inside its template's table range.
template <class Sizing>
void check_in_range(const Sizing& g) {
    for (const auto& spec : Sizing::parameters()) {
        INFO(spec.name << " = " << g.*(spec.field) << " " << spec.unit << ", range [" << spec.min << ", " << spec.max << "]");
        CHECK(g.*(spec.field) >= spec.min);
        CHECK(g.*(spec.field) <= spec.max);
    }
}

}  // namespace

TEST_CASE("sizing: --sizing auto gives a valid sizing of every template at the edges of the prior's range",
          "[garment][sizing]") {
    const body::BodyModel& model = body::BodyModel::default_model();
    for (const NamedRequest& b : extreme_bodies(model)) {
        body::ShapedBody shaped;
        const body::ShapeSummary shape = body::shape_body(model, model.prior.complete(b.request), {}, shaped);
        INFO(b.name << ": " << shape.brief_report());
        REQUIRE(shape.usable());
        const body::BodyMeasurements m = body::measure_body(model, shaped.vertices);
        for (const GarmentType type : {GarmentType::skirt, GarmentType::pants, GarmentType::tshirt, GarmentType::dress}) {
            INFO(garment_type_name(type));
            GarmentSizing g;
            bool proposed = false;
            CHECK_NOTHROW((g = proposed_sizing(type, model, shaped, m), proposed = true));
            if (!proposed) continue;
            CHECK_NOTHROW(make_pattern(g));
            switch (type) {
                case GarmentType::skirt: check_in_range(g.skirt); break;
                case GarmentType::pants: check_in_range(g.pants); break;
                case GarmentType::tshirt: check_in_range(g.tshirt); break;
                case GarmentType::dress: check_in_range(g.dress.bodice); check_in_range(g.dress.skirt); break;
            }
            if (type == GarmentType::tshirt) {
                // The sleeve opening holds the upper arm (+ ease) and is narrower than the chest.
                const double arm = upper_arm_girth(model, shaped, g.tshirt.l1);
                INFO("upper arm " << 100 * arm << " cm, thigh " << 100 * m.thigh_girth_m << " cm, chest "
                                  << 100 * m.chest_girth_m << " cm, w1 " << g.tshirt.w1 << " cm");
                CHECK(arm < m.thigh_girth_m);
                CHECK(g.tshirt.w1 < 100 * m.chest_girth_m / 2);
            }
        }
    }
}
