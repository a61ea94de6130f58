#include "garment_json.hpp"

#include <drape/garment/sizing_proposal.hpp>

#include "json_io.hpp"

#include <drape/core/errors.hpp>

namespace drape::app {

namespace {

template <class Sizing, class Table>
void read_group(const nlohmann::json& j, const Table& table, Sizing& sizing,
                const std::string& file, const std::string& prefix) {
    if (!j.is_object()) throw InvalidInput(file + ": " + (prefix.empty() ? "sizing" : prefix) +
                                           " must be a JSON object, got " + j.dump());
    for (auto it = j.begin(); it != j.end(); ++it) {
        bool known = false;
        for (const auto& p : table) known = known || it.key() == p.name;
        if (!known) {
            std::string names;
            for (const auto& p : table) names += std::string(names.empty() ? "" : ", ") + p.name;
            throw InvalidInput(file + ": unknown sizing key '" + prefix + it.key() +
                               "' (expected " + names + ")");
        }
    }
    for (const auto& p : table)
        if (const auto v = optional_number(j, p.name, file)) sizing.*(p.field) = *v;
}

template <class Sizing, class Table>
nlohmann::json write_group(const Sizing& sizing, const Table& table) {
    nlohmann::json j = nlohmann::json::object();
    for (const auto& p : table) j[p.name] = sizing.*(p.field);
    return j;
}

}  // namespace

GarmentSizing sizing_from_json(GarmentType type, const nlohmann::json& j, const std::string& file) {
    GarmentSizing g;
    g.type = type;
    switch (type) {
        case GarmentType::skirt: read_group(j, garment::SkirtSizing::parameters(), g.skirt, file, ""); break;
        case GarmentType::pants: read_group(j, garment::PantsSizing::parameters(), g.pants, file, ""); break;
        case GarmentType::tshirt: read_group(j, garment::TShirtSizing::parameters(), g.tshirt, file, ""); break;
        case GarmentType::dress:
            reject_unknown_keys(j, {"bodice", "skirt"}, file);
            if (j.contains("bodice"))
                read_group(j["bodice"], garment::TShirtSizing::parameters(), g.dress.bodice, file, "bodice.");
            if (j.contains("skirt"))
                read_group(j["skirt"], garment::SkirtSizing::parameters(), g.dress.skirt, file, "skirt.");
            break;
    }
    return g;
}

nlohmann::json to_json(const GarmentSizing& g) {
    switch (g.type) {
        case GarmentType::skirt: return write_group(g.skirt, garment::SkirtSizing::parameters());
        case GarmentType::pants: return write_group(g.pants, garment::PantsSizing::parameters());
        case GarmentType::tshirt: return write_group(g.tshirt, garment::TShirtSizing::parameters());
        case GarmentType::dress:
            return {{"bodice", write_group(g.dress.bodice, garment::TShirtSizing::parameters())},
                    {"skirt", write_group(g.dress.skirt, garment::SkirtSizing::parameters())}};
    }
    return {};
}

std::vector<GarmentType> outfit_from_spec(const std::string& spec) {
    std::vector<GarmentType> types;
    try {
        for (size_t a = 0; a <= spec.size();) {
            const size_t b = std::min(spec.find('+', a), spec.size());
            types.push_back(garment::garment_type_from_name(spec.substr(a, b - a)));
            a = b + 1;
        }
        return garment::outfit_layers(types);
    } catch (const InvalidInput& e) {
        throw InvalidInput("--garment '" + spec + "': " + e.what());
    }
}

namespace {

template <class Table>
nlohmann::json table_json(const Table& t) {
    nlohmann::json j = nlohmann::json::array();
    for (const auto& row : t) j.push_back(std::vector<double>(row.begin(), row.end()));
    return j;
}

}  // namespace

nlohmann::json material_to_json(const cloth::Material& m, const std::string& base_fabric) {
    return {{"bending_scale", m.bending_scale},
            {"stretching_scale", m.stretching_scale},
            {"base_fabric", base_fabric},
            {"stretching", table_json(m.stretching_n_per_m)},
            {"bending", table_json(m.bending_n_m)},
            {"density", m.density_kg_per_m2}};
}

}  // namespace drape::app
