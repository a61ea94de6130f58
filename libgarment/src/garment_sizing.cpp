#include <drape/garment/garment_sizing.hpp>

#include <drape/core/errors.hpp>

namespace drape::garment {

Pattern make_pattern(const GarmentSizing& g) {
    switch (g.type) {
        case GarmentType::skirt: return make_circle_skirt(g.skirt);
        case GarmentType::pants: return make_pants(g.pants);
        case GarmentType::tshirt: return make_tshirt(g.tshirt);
        case GarmentType::dress: return make_dress(g.dress);
    }
    throw InvalidInput("unknown garment type");
}

namespace {

// Calls visit(double&) on every parameter of the sizing's template, in table order.
template <class Sizing, class Visit>
void visit_parameters(Sizing& sizing, Visit&& visit) {
    for (const auto& spec : Sizing::parameters()) visit(sizing.*(spec.field));
}

template <class Visit>
void visit_sizing(GarmentSizing& g, Visit&& visit) {
    switch (g.type) {
        case GarmentType::skirt: visit_parameters(g.skirt, visit); return;
        case GarmentType::pants: visit_parameters(g.pants, visit); return;
        case GarmentType::tshirt: visit_parameters(g.tshirt, visit); return;
        case GarmentType::dress:
            visit_parameters(g.dress.bodice, visit);
            visit_parameters(g.dress.skirt, visit);
            return;
    }
    throw InvalidInput("unknown garment type");
}

}  // namespace

std::vector<double> sizing_values(const GarmentSizing& sizing) {
    GarmentSizing copy = sizing;
    std::vector<double> out;
    visit_sizing(copy, [&](double& v) { out.push_back(v); });
    return out;
}

GarmentSizing with_sizing_values(GarmentSizing sizing, const std::vector<double>& values) {
    const size_t n = sizing_values(sizing).size();
    require(values.size() == n, "with_sizing_values: ", values.size(), " values for a ",
            garment_type_name(sizing.type), ", which has ", n, " sizing parameters");
    size_t k = 0;
    visit_sizing(sizing, [&](double& v) { v = values[k++]; });
    return sizing;
}

}  // namespace drape::garment
