#include <drape/io/garment_json.hpp>

#include <drape/garment/sizing_proposal.hpp>

#include <drape/io/json_io.hpp>

#include <drape/core/errors.hpp>

#include <cmath>

namespace drape::io {

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

nlohmann::json to_json(const garment::DrapeSummary& d) {
    return {{"vertices", d.vertices},
            {"stitches", d.stitches},
            {"seam_gap_max_m", d.seam_gap_max_m},
            {"penetration_max_m", d.penetration_max_m},
            {"vertices_inside", d.vertices_inside},
            {"self_intersections", d.self_intersections},
            {"mean_drop_m", d.mean_drop_m},
            {"converged", d.converged},
            {"usable", d.usable()},
            {"steps", d.steps},
            {"steps_to_close_seams", d.steps_to_close_seams},
            {"welded", d.welded},
            {"crossings_repaired", d.crossings_repaired},
            {"contact_stiffened", d.contact_stiffened},
            {"message", d.message},
            {"seconds_drape", d.seconds}};
}

nlohmann::json material_to_json(const cloth::Material& m, const std::string& base_fabric) {
    return {{"bending_scale", m.bending_scale},
            {"stretching_scale", m.stretching_scale},
            {"base_fabric", base_fabric},
            {"stretching", table_json(m.stretching_n_per_m)},
            {"bending", table_json(m.bending_n_m)},
            {"density", m.density_kg_per_m2}};
}

namespace {

double finite_number(const nlohmann::json& j, const std::string& file, const std::string& field) {
    if (!j.is_number() || !std::isfinite(j.get<double>()))
        throw InvalidInput(file + ": material field '" + field + "' must be a finite number, got " + j.dump());
    return j.get<double>();
}

template <size_t R, size_t C>
void read_table(const nlohmann::json& j, const std::string& key, const std::string& file,
                std::array<std::array<double, C>, R>& table) {
    if (!j.contains(key)) throw InvalidInput(file + ": material has no field '" + key + "'");
    const nlohmann::json& t = j.at(key);
    if (!t.is_array() || t.size() != R)
        throw InvalidInput(file + ": material field '" + key + "' must be " + std::to_string(R) + " rows of " +
                           std::to_string(C) + " numbers");
    for (size_t r = 0; r < R; ++r) {
        if (!t[r].is_array() || t[r].size() != C)
            throw InvalidInput(file + ": material field '" + key + "' row " + std::to_string(r) + " must hold " +
                               std::to_string(C) + " numbers, got " + t[r].dump());
        for (size_t c = 0; c < C; ++c)
            table[r][c] = finite_number(t[r][c], file, key + "[" + std::to_string(r) + "][" + std::to_string(c) + "]");
    }
}

}  // namespace

cloth::Material material_from_json(const nlohmann::json& j, const std::string& file, std::string* base_fabric) {
    if (!j.is_object()) throw InvalidInput(file + ": material must be a JSON object, got " + j.dump());
    reject_unknown_keys(j, {"bending_scale", "stretching_scale", "base_fabric", "stretching", "bending", "density",
                            "nearest_fabric", "bending_scale_range"},
                        file);
    cloth::Material m;
    for (const char* key : {"bending_scale", "stretching_scale", "density"}) {
        if (!j.contains(key)) throw InvalidInput(file + ": material has no field '" + std::string(key) + "'");
        const double v = finite_number(j.at(key), file, key);
        if (v <= 0) throw InvalidInput(file + ": material field '" + std::string(key) + "' must be positive, got " + j.at(key).dump());
    }
    m.bending_scale = j.at("bending_scale").get<double>();
    m.stretching_scale = j.at("stretching_scale").get<double>();
    m.density_kg_per_m2 = j.at("density").get<double>();
    read_table(j, "stretching", file, m.stretching_n_per_m);
    read_table(j, "bending", file, m.bending_n_m);
    if (base_fabric) {
        *base_fabric = "";
        if (j.contains("base_fabric")) {
            if (!j.at("base_fabric").is_string())
                throw InvalidInput(file + ": material field 'base_fabric' must be a string, got " + j.at("base_fabric").dump());
            *base_fabric = j.at("base_fabric").get<std::string>();
        }
    }
    return m;
}

}  // namespace drape::io
