#include "garment_json.hpp"

#include <drape/core/atomic_file.hpp>
#include <drape/garment/sizing_proposal.hpp>

#include <sstream>

#include "json_io.hpp"

#include <drape/core/errors.hpp>
#include <drape/garment/circle_skirt.hpp>
#include <drape/garment/tshirt.hpp>

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

GarmentType garment_type_from_name(const std::string& name) {
    if (name == "skirt") return GarmentType::skirt;
    if (name == "pants") return GarmentType::pants;
    if (name == "tshirt") return GarmentType::tshirt;
    if (name == "dress") return GarmentType::dress;
    throw InvalidInput("unknown garment '" + name + "' (expected skirt, pants, tshirt or dress)");
}

std::string garment_type_name(GarmentType type) {
    switch (type) {
        case GarmentType::skirt: return "skirt";
        case GarmentType::pants: return "pants";
        case GarmentType::tshirt: return "tshirt";
        case GarmentType::dress: return "dress";
    }
    return "?";
}

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

garment::Pattern make_pattern(const GarmentSizing& g) {
    switch (g.type) {
        case GarmentType::skirt: return garment::make_circle_skirt(g.skirt);
        case GarmentType::pants: return garment::make_pants(g.pants);
        case GarmentType::tshirt: return garment::make_tshirt(g.tshirt);
        case GarmentType::dress: return garment::make_dress(g.dress);
    }
    throw InvalidInput("unknown garment type");
}

GarmentSizing proposed_sizing(GarmentType type, const body::BodyMeasurements& measured) {
    GarmentSizing g;
    g.type = type;
    switch (type) {
        case GarmentType::skirt: g.skirt = garment::propose_skirt_sizing(measured); break;
        case GarmentType::pants: g.pants = garment::propose_pants_sizing(measured); break;
        case GarmentType::tshirt: g.tshirt = garment::propose_tshirt_sizing(measured); break;
        case GarmentType::dress: g.dress = garment::propose_dress_sizing(measured); break;
    }
    return g;
}

GarmentSizing proposed_sizing(GarmentType type, const body::BodyMeasurements& measured,
                              double skirt_waistband_girth_m) {
    GarmentSizing g = proposed_sizing(type, measured);
    if (type == GarmentType::skirt) g.skirt = garment::propose_skirt_sizing(measured, skirt_waistband_girth_m);
    return g;
}

GarmentSizing proposed_sizing(GarmentType type, const body::BodyModel& model, const body::ShapedBody& shaped,
                              const body::BodyMeasurements& measured) {
    if (type == GarmentType::skirt) return proposed_sizing(type, measured, garment::skirt_waistband(model, shaped).girth_m);
    return fit_top_to_body(proposed_sizing(type, measured), model, shaped);
}

GarmentSizing fit_top_to_body(GarmentSizing g, const body::BodyModel& model, const body::ShapedBody& shaped) {
    if (g.type != GarmentType::tshirt && g.type != GarmentType::dress) return g;
    garment::TShirtSizing& top = g.type == GarmentType::tshirt ? g.tshirt : g.dress.bodice;
    if (top.l1 > 0) top = garment::fit_sleeves(top, garment::upper_arm_girth(model, shaped, top.l1));
    top = garment::fit_neckline(top, garment::neck_girth(model, shaped));
    return g;
}

void write_garment_obj(const std::filesystem::path& path, const garment::Pattern& pattern,
                       const garment::GarmentMesh& m, const Eigen::MatrixX3d& positions,
                       const std::string& what) {
    std::ostringstream os;
    os << "# drape '" << pattern.name << "': " << what << ", metres; vt = pattern uv\n";
    for (Eigen::Index v = 0; v < positions.rows(); ++v)
        os << "v " << positions(v, 0) << " " << positions(v, 1) << " " << positions(v, 2) << "\n";
    for (int v = 0; v < m.cloth.vertex_count(); ++v) os << "vt " << m.uv(v, 0) << " " << m.uv(v, 1) << "\n";
    int group = -1;
    for (int f = 0; f < m.cloth.face_count(); ++f) {
        const int p = m.panel_of_vertex(m.cloth.faces(f, 0));
        if (p != group) os << "g " << pattern.panels[static_cast<std::size_t>(group = p)].name << "\n";
        os << "f";
        for (int k = 0; k < 3; ++k) os << " " << m.cloth.faces(f, k) + 1 << "/" << m.cloth.faces(f, k) + 1;
        os << "\n";
    }
    write_text_atomically(path, os.str());
}

}  // namespace drape::app
