#include <drape/io/render_camera.hpp>

#include <drape/io/body_json.hpp>
#include <drape/io/json_io.hpp>

#include <drape/core/errors.hpp>

namespace drape::io {

render::Camera render_camera_from_json(const nlohmann::json& j, const std::string& where, int width, int height) {
    if (!j.is_object()) throw InvalidInput(where + ": a camera must be a JSON object, got " + j.dump());
    const nlohmann::json& c = j.contains("camera") && j["camera"].is_object() ? j["camera"] : j;
    if (c.contains("eye")) {
        reject_unknown_keys(c, {"eye", "target", "up", "focal_px"}, where);
        if (!c.contains("target")) throw InvalidInput(where + ": look-at camera field 'target' is missing");
        const Eigen::Vector3d up = c.contains("up") ? vector3_from_json(c["up"], "'up'", where) : Eigen::Vector3d(0, 1, 0);
        return render::Camera::look_at(vector3_from_json(c["eye"], "'eye'", where),
                                       vector3_from_json(c["target"], "'target'", where), up,
                                       required_number(c, "focal_px", where), width, height);
    }
    return render::Camera::from_body(camera_from_json(c, where), width, height);
}

}  // namespace drape::io
