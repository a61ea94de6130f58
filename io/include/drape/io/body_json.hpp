// JSON forms of the body types, shared by the CLI commands.
#pragma once

#include <drape/body/measurements.hpp>
#include <drape/body/pose.hpp>
#include <drape/body/semantic_shape.hpp>

#include <drape/body/camera.hpp>
#include <nlohmann/json.hpp>

#include <string>

namespace drape::io {

/// P.json: any subset of "gender" and the semantic keys (kSemanticKeys).
body::SemanticRequest semantic_request_from_json(const nlohmann::json& j, const std::string& file);
nlohmann::json to_json(const body::SemanticShape& shape);
/// The measurable keys (every semantic key but muscle) of a measurement.
nlohmann::json to_json(const body::BodyMeasurements& m, body::Gender gender);

/// POSE.json: {"preset": "a_pose"|"arms_down"|"walking"|"t_pose" (optional),
///             "translation": [x, y, z] (optional, metres),
///             "rotations": {"<joint name>": [x, y, z] axis-angle radians, ...} (optional)}
body::Pose pose_from_json(const nlohmann::json& j, const std::string& file);
nlohmann::json to_json(const body::Pose& pose);

/// The `drape fit-body` camera object (weak perspective or pinhole, principal point, pixel
/// frame); saved alone it is a `drape render --camera FILE` camera.
nlohmann::json to_json(const body::Camera& camera);
/// The inverse of to_json(camera): {"model": "pinhole", "focal_px", "distance_m",
/// "offset_px"} or {"model": "weak_perspective", "scale_px_per_m", ["distance_m"],
/// "offset_px"} ("pixel_frame" is read as a comment).
/// \throw drape::InvalidInput naming `file` and the field.
body::Camera camera_from_json(const nlohmann::json& j, const std::string& file);

}  // namespace drape::io
