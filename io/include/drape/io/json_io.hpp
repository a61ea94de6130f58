// JSON files (drape::io, shared by the CLI and the C API): reading with errors that name the file and the field.
#pragma once

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <optional>
#include <string>

namespace drape::io {

/// Parses a JSON file. \throw drape::IoError (unreadable), drape::InvalidInput (bad JSON,
/// with the file name and the parser's position).
nlohmann::json read_json_file(const std::filesystem::path& path);

/// Parses JSON text handed over in memory (e.g. by the C API), with the same limits as a file
/// (core/limits.hpp: size, nesting depth). `what` names the text in messages.
/// \throw drape::InvalidInput naming `what`: too large, too deep, or not valid JSON.
nlohmann::json parse_json_text(const std::string& text, const std::string& what);

/// Writes JSON (pretty, 2 spaces) atomically.
void write_json_file(const std::filesystem::path& path, const nlohmann::json& j);

/// A finite number at `key` of object `j`, or nullopt when absent; throws InvalidInput
/// "<file>: field '<key>' must be a finite number, got <value>" otherwise.
std::optional<double> optional_number(const nlohmann::json& j, const std::string& key,
                                      const std::string& file);

/// A finite number at `key` of object `j`; throws InvalidInput "<file>: field '<key>' is
/// missing" when absent, as optional_number otherwise.
double required_number(const nlohmann::json& j, const std::string& key, const std::string& file);

/// An array of N finite numbers (a point, a vector); throws InvalidInput naming `file` and
/// `what` ("'translation'", "camera 'offset_px'") otherwise.
Eigen::Vector2d vector2_from_json(const nlohmann::json& j, const std::string& what, const std::string& file);
Eigen::Vector3d vector3_from_json(const nlohmann::json& j, const std::string& what, const std::string& file);

/// Throws InvalidInput if `j` has keys outside `allowed` (catches typos such as "hieght_m").
void reject_unknown_keys(const nlohmann::json& j, const std::initializer_list<std::string>& allowed,
                         const std::string& file);

}  // namespace drape::io
