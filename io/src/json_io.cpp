#include <drape/io/json_io.hpp>

#include <drape/core/atomic_file.hpp>
#include <drape/core/errors.hpp>
#include <drape/core/limits.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

namespace drape::io {

nlohmann::json read_json_file(const std::filesystem::path& path) {
    const std::string text = limits::read_file_capped(path, limits::kMaxJsonFileBytes, "JSON file");
    return parse_json_text(text, "'" + path.string() + "'");
}

nlohmann::json parse_json_text(const std::string& text, const std::string& what) {
    limits::check_json_text(text, what);
    try {
        return nlohmann::json::parse(text);
    } catch (const nlohmann::json::exception& e) {  // parse_error, out_of_range (1e999)
        throw InvalidInput(what + " is not valid JSON: " + e.what());
    }
}

void write_json_file(const std::filesystem::path& path, const nlohmann::json& j) {
    write_text_atomically(path, j.dump(2) + "\n");
}

std::optional<double> optional_number(const nlohmann::json& j, const std::string& key,
                                      const std::string& file) {
    if (!j.contains(key) || j.at(key).is_null()) return std::nullopt;
    const auto& v = j.at(key);
    if (!v.is_number() || !std::isfinite(v.get<double>()))
        throw InvalidInput(file + ": field '" + key + "' must be a finite number, got " + v.dump());
    return v.get<double>();
}

void reject_unknown_keys(const nlohmann::json& j, const std::initializer_list<std::string>& allowed,
                         const std::string& file) {
    if (!j.is_object()) throw InvalidInput(file + ": expected a JSON object, got " + j.type_name());
    for (const auto& item : j.items()) {
        if (std::find(allowed.begin(), allowed.end(), item.key()) == allowed.end()) {
            std::string list;
            for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
            throw InvalidInput(file + ": unknown field '" + item.key() + "' (expected one of: " +
                               list + ")");
        }
    }
}

double required_number(const nlohmann::json& j, const std::string& key, const std::string& file) {
    const std::optional<double> v = optional_number(j, key, file);
    if (!v) throw InvalidInput(file + ": field '" + key + "' is missing");
    return *v;
}

namespace {

template <int N>
Eigen::Matrix<double, N, 1> vector_from_json(const nlohmann::json& j, const std::string& what, const std::string& file) {
    if (!j.is_array() || j.size() != N)
        throw InvalidInput(file + ": " + what + " must be an array of " + std::to_string(N) + " numbers, got " +
                           j.dump());
    Eigen::Matrix<double, N, 1> v;
    for (int k = 0; k < N; ++k) {
        if (!j[k].is_number() || !std::isfinite(j[k].get<double>()))
            throw InvalidInput(file + ": " + what + " must hold finite numbers, got " + j.dump());
        v[k] = j[k].get<double>();
    }
    return v;
}

}  // namespace

Eigen::Vector2d vector2_from_json(const nlohmann::json& j, const std::string& what, const std::string& file) {
    return vector_from_json<2>(j, what, file);
}

Eigen::Vector3d vector3_from_json(const nlohmann::json& j, const std::string& what, const std::string& file) {
    return vector_from_json<3>(j, what, file);
}

}  // namespace drape::io
