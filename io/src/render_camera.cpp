#include <drape/io/render_camera.hpp>

#include <drape/io/body_json.hpp>
#include <drape/io/json_io.hpp>

#include <drape/core/errors.hpp>

#include <optional>

namespace drape::io {

namespace {

Eigen::Vector3d vec3(const nlohmann::json& j, const std::string& what, const std::string& where) {
    if (!j.is_array() || j.size() != 3 || !j[0].is_number() || !j[1].is_number() || !j[2].is_number())
        throw InvalidInput(where + ": " + what + " must be [x, y, z] numbers, got " + j.dump());
    return {j[0].get<double>(), j[1].get<double>(), j[2].get<double>()};
}

}  // namespace

render::Camera render_camera_from_json(const nlohmann::json& j, const std::string& where, int width, int height) {
    if (!j.is_object()) throw InvalidInput(where + ": a camera must be a JSON object, got " + j.dump());
    const nlohmann::json& c = j.contains("camera") && j["camera"].is_object() ? j["camera"] : j;
    if (c.contains("eye")) {
        reject_unknown_keys(c, {"eye", "target", "up", "focal_px"}, where);
        if (!c.contains("target")) throw InvalidInput(where + ": look-at camera field 'target' is missing");
        const Eigen::Vector3d up = c.contains("up") ? vec3(c["up"], "'up'", where) : Eigen::Vector3d(0, 1, 0);
        const std::optional<double> focal = optional_number(c, "focal_px", where);
        if (!focal) throw InvalidInput(where + ": look-at camera field 'focal_px' is missing");
        return render::Camera::look_at(vec3(c["eye"], "'eye'", where), vec3(c["target"], "'target'", where), up,
                                       *focal, width, height);
    }
    return render::Camera::from_body(camera_from_json(c, where), width, height);
}

}  // namespace drape::io
