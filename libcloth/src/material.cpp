#include <drape/cloth/material.hpp>

#include "builtin_materials.hpp"

#include <drape/core/atomic_file.hpp>
#include <drape/core/errors.hpp>
#include <drape/core/limits.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <utility>
#include <sstream>

namespace drape::cloth {

namespace {

constexpr double kPi = 3.14159265358979323846;

bool finite_positive(double x) { return std::isfinite(x) && x > 0; }

// Splits t in [0, n] into a cell index in [0, n-1] and a fraction in [0, 1].
void cell(double t, int n, int& index, double& fraction) {
    index = std::clamp(static_cast<int>(std::floor(t)), 0, n - 1);
    fraction = t - index;
}

template <std::size_t N>
void read_row(const nlohmann::json& row, const std::string& where, std::array<double, N>& out) {
    if (!row.is_array() || row.size() != N)
        throw InvalidInput(detail::concat(where, " must be an array of ", N, " numbers"));
    for (std::size_t i = 0; i < N; ++i) {
        if (!row[i].is_number())
            throw InvalidInput(detail::concat(where, "[", i, "] is not a number"));
        out[i] = row[i].get<double>();
        if (!std::isfinite(out[i]))
            throw InvalidInput(detail::concat(where, "[", i, "] is not finite"));
    }
}

template <std::size_t R, std::size_t C>
void read_table(const nlohmann::json& doc, const std::string& file, const char* field,
                std::array<std::array<double, C>, R>& out) {
    const std::string where = detail::concat("material file '", file, "': field '", field, "'");
    if (!doc.contains(field)) throw InvalidInput(where + " is missing");
    const nlohmann::json& table = doc[field];
    if (!table.is_array() || table.size() != R)
        throw InvalidInput(detail::concat(where, " must be an array of ", R, " rows of ", C,
                                          " numbers"));
    for (std::size_t r = 0; r < R; ++r) read_row(table[r], detail::concat(where, " row ", r), out[r]);
}

constexpr const char* kFormatName = "drape-material";
constexpr int kFormatVersion = 1;

std::string field_where(const std::string& file, const char* field) {
    return detail::concat("material file '", file, "': field '", field, "'");
}

double read_number(const nlohmann::json& doc, const std::string& file, const char* field) {
    const std::string where = field_where(file, field);
    if (!doc.contains(field)) throw InvalidInput(where + " is missing");
    if (!doc[field].is_number()) throw InvalidInput(where + " is not a number");
    const double x = doc[field].get<double>();
    if (!finite_positive(x)) throw InvalidInput(detail::concat(where, " = ", x, " must be > 0"));
    return x;
}

// ArcSim: {"density", "stretching", "bending"}; the numbers are already our SI units.
Material read_arcsim_material(const nlohmann::json& doc, const std::string& file) {
    Material m;
    m.density_kg_per_m2 = read_number(doc, file, "density");
    read_table(doc, file, "stretching", m.stretching_n_per_m);
    read_table(doc, file, "bending", m.bending_n_m);
    return m;
}

// Drape's own format, version 1 (docs/materials.md). Unknown fields are errors, so that a
// misspelt optional field (a scale) is not silently replaced by its default.
Material read_drape_material(const nlohmann::json& doc, const std::string& file,
                             MaterialInfo& info) {
    const nlohmann::json& format = doc["format"];
    if (!format.is_string() || format.get<std::string>() != kFormatName)
        throw InvalidInput(detail::concat(field_where(file, "format"), " = ", format.dump(),
                                          " is not \"", kFormatName, "\""));
    if (!doc.contains("version"))
        throw InvalidInput(field_where(file, "version") + " is missing");
    const nlohmann::json& version = doc["version"];
    if (!version.is_number_integer() || version.get<long long>() != kFormatVersion)
        throw InvalidInput(detail::concat(field_where(file, "version"), " = ", version.dump(),
                                          " is not supported (this build reads version ",
                                          kFormatVersion, ")"));
    static const char* const kKnown[] = {"format", "version", "name", "description", "source",
                                         "license", "density_kg_per_m2", "stretching_n_per_m",
                                         "bending_n_m", "stretching_scale", "bending_scale"};
    for (const auto& item : doc.items())
        if (std::find_if(std::begin(kKnown), std::end(kKnown),
                         [&](const char* k) { return item.key() == k; }) == std::end(kKnown))
            throw InvalidInput(detail::concat("material file '", file, "': unknown field '",
                                              item.key(), "'"));
    for (auto [field, target] : {std::pair<const char*, std::string*>{"name", &info.name},
                                 {"description", &info.description},
                                 {"source", &info.source},
                                 {"license", &info.license}}) {
        if (!doc.contains(field)) continue;
        if (!doc[field].is_string())
            throw InvalidInput(field_where(file, field) + " is not a string");
        *target = doc[field].get<std::string>();
    }
    Material m;
    m.density_kg_per_m2 = read_number(doc, file, "density_kg_per_m2");
    read_table(doc, file, "stretching_n_per_m", m.stretching_n_per_m);
    read_table(doc, file, "bending_n_m", m.bending_n_m);
    if (doc.contains("stretching_scale"))
        m.stretching_scale = read_number(doc, file, "stretching_scale");
    if (doc.contains("bending_scale")) m.bending_scale = read_number(doc, file, "bending_scale");
    return m;
}

// Shortest decimal text that parses back to the same double (nlohmann's dtoa).
std::string json_number(double x) { return nlohmann::json(x).dump(); }

std::string json_string(const std::string& text, const char* field) {
    try {
        return nlohmann::json(text).dump();
    } catch (const nlohmann::json::type_error& e) {
        throw InvalidInput(detail::concat("save_material: field '", field,
                                          "' is not valid UTF-8: ", e.what()));
    }
}

// One row per line: [[a, b, ...],\n [..]] indented to sit under the field.
template <std::size_t R, std::size_t C>
std::string json_table(const std::array<std::array<double, C>, R>& table) {
    std::string text = "[\n";
    for (std::size_t r = 0; r < R; ++r) {
        text += "    [";
        for (std::size_t c = 0; c < C; ++c) text += (c ? ", " : "") + json_number(table[r][c]);
        text += r + 1 < R ? "],\n" : "]\n";
    }
    return text + "  ]";
}

}  // namespace

bool Material::is_valid(std::string* why) const {
    auto fail = [&](const std::string& reason) {
        if (why) *why = reason;
        return false;
    };
    if (!finite_positive(density_kg_per_m2))
        return fail(detail::concat("density_kg_per_m2 = ", density_kg_per_m2, " must be > 0"));
    if (!finite_positive(stretching_scale))
        return fail(detail::concat("stretching_scale = ", stretching_scale, " must be > 0"));
    if (!finite_positive(bending_scale))
        return fail(detail::concat("bending_scale = ", bending_scale, " must be > 0"));
    for (std::size_t r = 0; r < stretching_n_per_m.size(); ++r)
        for (std::size_t c = 0; c < 4; ++c)
            if (!std::isfinite(stretching_n_per_m[r][c]))
                return fail(detail::concat("stretching_n_per_m[", r, "][", c, "] is not finite"));
    for (std::size_t r = 0; r < bending_n_m.size(); ++r)
        for (std::size_t c = 0; c < 5; ++c)
            if (!std::isfinite(bending_n_m[r][c]))
                return fail(detail::concat("bending_n_m[", r, "][", c, "] is not finite"));
    return true;
}

Material load_material(const std::filesystem::path& path, MaterialInfo* info) {
    const std::string text = limits::read_file_capped(path, limits::kMaxJsonFileBytes, "material file");
    const std::string file = path.string();
    limits::check_json_text(text, "material file '" + file + "'");

    nlohmann::json doc;
    try {
        // ignore_comments: paper.json and aluminium.json start with // lines (jsoncpp style).
        doc = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/true,
                                    /*ignore_comments=*/true);
    } catch (const nlohmann::json::exception& e) {  // parse_error, out_of_range (1e999)
        throw InvalidInput(detail::concat("material file '", file, "' is not valid JSON: ", e.what()));
    }
    if (!doc.is_object())
        throw InvalidInput(detail::concat("material file '", file, "': top level must be an object"));

    MaterialInfo scratch;
    MaterialInfo& out_info = info ? *info : scratch;
    out_info = MaterialInfo{};
    Material m = doc.contains("format") ? read_drape_material(doc, file, out_info)
                                        : read_arcsim_material(doc, file);
    if (!doc.contains("format")) out_info.name = path.stem().string();
    std::string why;
    if (!m.is_valid(&why))
        throw InvalidInput(detail::concat("material file '", file, "': ", why));
    return m;
}

void save_material(const Material& material, const std::filesystem::path& path,
                   const MaterialInfo& info) {
    std::string why;
    if (!material.is_valid(&why))
        throw InvalidInput(detail::concat("save_material('", path.string(), "'): ", why));
    std::ostringstream os;
    os << "{\n"
       << "  \"format\": " << json_string(kFormatName, "format") << ",\n"
       << "  \"version\": " << kFormatVersion << ",\n"
       << "  \"name\": " << json_string(info.name, "name") << ",\n"
       << "  \"description\": " << json_string(info.description, "description") << ",\n"
       << "  \"source\": " << json_string(info.source, "source") << ",\n"
       << "  \"license\": " << json_string(info.license, "license") << ",\n"
       << "  \"density_kg_per_m2\": " << json_number(material.density_kg_per_m2) << ",\n"
       << "  \"stretching_n_per_m\": " << json_table(material.stretching_n_per_m) << ",\n"
       << "  \"bending_n_m\": " << json_table(material.bending_n_m) << ",\n"
       << "  \"stretching_scale\": " << json_number(material.stretching_scale) << ",\n"
       << "  \"bending_scale\": " << json_number(material.bending_scale) << "\n"
       << "}\n";
    write_text_atomically(path, os.str());
}

namespace {

const builtin::Entry& find_builtin(const std::string& name) {
    for (const builtin::Entry& e : builtin::kMaterials)
        if (name == e.name) return e;
    std::string known;
    for (const builtin::Entry& e : builtin::kMaterials)
        known += (known.empty() ? "" : ", ") + std::string(e.name);
    throw InvalidInput(detail::concat("unknown built-in material '", name, "'; known: ", known));
}

}  // namespace

std::vector<std::string> builtin_material_names() {
    std::vector<std::string> names;
    for (const builtin::Entry& e : builtin::kMaterials) names.emplace_back(e.name);
    return names;
}

Material builtin_material(const std::string& name) {
    const builtin::Entry& e = find_builtin(name);
    Material m;
    m.density_kg_per_m2 = e.density_kg_per_m2;
    m.stretching_n_per_m = e.stretching_n_per_m;
    m.bending_n_m = e.bending_n_m;
    return m;
}

MaterialInfo builtin_material_info(const std::string& name) {
    const builtin::Entry& e = find_builtin(name);
    return {e.name, e.description, e.source, builtin::kLicense};
}

StretchingStiffness stretching_stiffness(const Material& material, double stretch,
                                         double direction_rad) {
    require(std::isfinite(stretch), "stretching_stiffness: stretch = ", stretch, " is not finite");
    require(std::isfinite(direction_rad), "stretching_stiffness: direction_rad = ", direction_rad,
            " is not finite");
    // Fold the direction into [0, π/2]: the model is symmetric about both pattern axes.
    double a = std::fmod(std::abs(direction_rad), kPi);
    if (a > kPi / 2) a = kPi - a;
    int ai = 0;
    double af = 0;
    cell(a * 8 / kPi, 4, ai, af);
    // Strain weight: row 0 at w = 1, rows 1..5 at w = 7/6, constant beyond, row 0 below.
    const double s = std::clamp((stretch - 1) * 6, 0.0, 1.0);
    const auto& t = material.stretching_n_per_m;
    std::array<double, 4> k{};
    for (int c = 0; c < 4; ++c) {
        const double zero = t[0][static_cast<std::size_t>(c)];
        const double sampled = (1 - af) * t[static_cast<std::size_t>(1 + ai)][static_cast<std::size_t>(c)] +
                               af * t[static_cast<std::size_t>(2 + ai)][static_cast<std::size_t>(c)];
        const double v = (1 - s) * zero + s * sampled;
        k[static_cast<std::size_t>(c)] = 2 * std::max(v, 0.0) * material.stretching_scale;
    }
    return {k[0], k[1], k[2], k[3]};
}

StretchingStiffness stretching_stiffness(const Material& material,
                                         const Eigen::Matrix2d& green_strain) {
    require(green_strain.allFinite(), "stretching_stiffness: green_strain is not finite");
    const Eigen::Matrix2d c = 2 * 0.5 * (green_strain + green_strain.transpose()) +
                              Eigen::Matrix2d::Identity();
    const double p = c(0, 0), q = c(1, 1), b = c(0, 1);
    const double mean = (p + q) / 2;
    const double radius = std::hypot((p - q) / 2, b);
    const double lambda1 = mean + radius;
    // Eigenvector of lambda1: of the two algebraically equivalent forms pick the larger one.
    Eigen::Vector2d v1(lambda1 - q, b), v2(b, lambda1 - p);
    Eigen::Vector2d v = v1.squaredNorm() >= v2.squaredNorm() ? v1 : v2;
    if (v.squaredNorm() == 0) v = Eigen::Vector2d(1, 0);  // isotropic C: any direction
    if (v.x() < 0) v = -v;
    const double direction = std::abs(std::atan2(v.y(), v.x()));
    return stretching_stiffness(material, std::sqrt(std::max(lambda1, 0.0)), direction);
}

double bending_stiffness(const Material& material, double direction_rad, double curvature_per_m) {
    require(std::isfinite(direction_rad), "bending_stiffness: direction_rad = ", direction_rad,
            " is not finite");
    require(std::isfinite(curvature_per_m), "bending_stiffness: curvature_per_m = ",
            curvature_per_m, " is not finite");
    double a = std::fmod(std::abs(direction_rad), kPi);
    if (a > kPi / 2) a = kPi - a;
    int ai = 0;
    double af = 0;
    cell(a * 4 / kPi, 2, ai, af);
    // Column j is at curvature 10 j 1/m; clamped above, extrapolated below 0 (ArcSim).
    const double v = std::min(curvature_per_m / 10, 4.0);
    int ci = 0;
    double cf = 0;
    if (v < 0) {
        ci = 0;
        cf = v;
    } else {
        cell(v, 4, ci, cf);
    }
    const auto& t = material.bending_n_m;
    auto at = [&](int r, int c) { return t[static_cast<std::size_t>(r)][static_cast<std::size_t>(c)]; };
    const double row0 = (1 - cf) * at(ai, ci) + cf * at(ai, ci + 1);
    const double row1 = (1 - cf) * at(ai + 1, ci) + cf * at(ai + 1, ci + 1);
    const double k = (1 - af) * row0 + af * row1;
    return std::max(k, 0.0) * material.bending_scale;
}

}  // namespace drape::cloth
