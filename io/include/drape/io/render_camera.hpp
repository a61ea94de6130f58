// The camera of a render from JSON (drape::io, shared by `drape render --camera FILE` and the
// C API's drape_render): a fit-body camera, a body.json holding one, or a look-at camera.
#pragma once

#include <drape/render/camera.hpp>

#include <nlohmann/json.hpp>

#include <string>

namespace drape::io {

/// A render camera of width x height pixels from `j`: a `drape fit-body` camera object
/// (camera_from_json) or an object holding one under "camera" (body.json), or a look-at
/// camera {"eye": [x, y, z], "target": [x, y, z], "up": [x, y, z] (default +Y), "focal_px"}.
/// \throw drape::InvalidInput naming `where` and the field.
render::Camera render_camera_from_json(const nlohmann::json& j, const std::string& where, int width, int height);

}  // namespace drape::io
