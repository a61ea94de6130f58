#include <drape/io/json_io.hpp>

#include <drape/core/atomic_file.hpp>
#include <drape/core/errors.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

namespace drape::io {

nlohmann::json read_json_file(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw IoError("cannot read '" + path.string() + "': file missing or unreadable");
    std::stringstream buffer;
    buffer << in.rdbuf();
    try {
        return nlohmann::json::parse(buffer.str());
    } catch (const nlohmann::json::parse_error& e) {
        throw InvalidInput("'" + path.string() + "' is not valid JSON: " + e.what());
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

}  // namespace drape::io
