#include <drape/garment/garment_sizing.hpp>

#include <drape/core/errors.hpp>

#include <string>

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

template <class Sizing>
void append_parameters(std::vector<SizingParameter>& out, const std::string& prefix) {
    for (const auto& p : Sizing::parameters()) out.push_back({prefix + p.name, p.min, p.max, p.unit, p.meaning});
}

template <class Sizing>
void append_values(std::vector<double>& out, const Sizing& s) {
    for (const auto& p : Sizing::parameters()) out.push_back(s.*(p.field));
}

template <class Sizing>
void take_values(Sizing& s, const std::vector<double>& values, size_t& at) {
    for (const auto& p : Sizing::parameters()) s.*(p.field) = values[at++];
}

}  // namespace

std::vector<SizingParameter> sizing_parameters(GarmentType type) {
    std::vector<SizingParameter> out;
    switch (type) {
        case GarmentType::skirt: append_parameters<SkirtSizing>(out, ""); break;
        case GarmentType::pants: append_parameters<PantsSizing>(out, ""); break;
        case GarmentType::tshirt: append_parameters<TShirtSizing>(out, ""); break;
        case GarmentType::dress:
            append_parameters<TShirtSizing>(out, "bodice.");
            append_parameters<SkirtSizing>(out, "skirt.");
            break;
    }
    return out;
}

std::vector<double> sizing_values(const GarmentSizing& g) {
    std::vector<double> out;
    switch (g.type) {
        case GarmentType::skirt: append_values(out, g.skirt); break;
        case GarmentType::pants: append_values(out, g.pants); break;
        case GarmentType::tshirt: append_values(out, g.tshirt); break;
        case GarmentType::dress:
            append_values(out, g.dress.bodice);
            append_values(out, g.dress.skirt);
            break;
    }
    return out;
}

GarmentSizing with_sizing_values(GarmentSizing g, const std::vector<double>& values) {
    const size_t count = sizing_parameters(g.type).size();
    if (values.size() != count)
        throw InvalidInput(garment_type_name(g.type) + " sizing: " + std::to_string(values.size()) +
                           " values given, the template has " + std::to_string(count) + " parameters");
    size_t at = 0;
    switch (g.type) {
        case GarmentType::skirt: take_values(g.skirt, values, at); break;
        case GarmentType::pants: take_values(g.pants, values, at); break;
        case GarmentType::tshirt: take_values(g.tshirt, values, at); break;
        case GarmentType::dress:
            take_values(g.dress.bodice, values, at);
            take_values(g.dress.skirt, values, at);
            break;
    }
    return g;
}

}  // namespace drape::garment
