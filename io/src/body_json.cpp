#include <drape/io/body_json.hpp>

#include <drape/io/json_io.hpp>

#include <drape/core/errors.hpp>

#include <cmath>
#include <optional>

namespace drape::io {

body::SemanticRequest semantic_request_from_json(const nlohmann::json& j, const std::string& file) {
    reject_unknown_keys(j, {"gender", "height_m", "weight_kg", "muscle", "chest_girth_m",
                            "waist_girth_m", "hip_girth_m", "thigh_girth_m", "calf_girth_m",
                            "shoulder_height_m", "crotch_height_m"},
                        file);
    body::SemanticRequest r;
    if (j.contains("gender")) {
        if (!j["gender"].is_string())
            throw InvalidInput(file + ": field 'gender' must be \"female\" or \"male\", got " +
                               j["gender"].dump());
        try {
            r.gender = body::parse_gender(j["gender"].get<std::string>());
        } catch (const InvalidInput& e) {
            throw InvalidInput(file + ": field 'gender': " + e.what());
        }
    }
    for (int k = 0; k < body::kSemanticCount; ++k)
        r.values[k] = optional_number(j, std::string(body::kSemanticKeys[k]), file);
    return r;
}

nlohmann::json to_json(const body::SemanticShape& shape) {
    nlohmann::json j;
    j["gender"] = std::string(body::to_string(shape.gender));
    for (int k = 0; k < body::kSemanticCount; ++k) j[std::string(body::kSemanticKeys[k])] = shape.values[k];
    return j;
}

nlohmann::json to_json(const body::BodyMeasurements& m, body::Gender gender) {
    nlohmann::json j;
    j["gender"] = std::string(body::to_string(gender));
    j["height_m"] = m.height_m;
    j["weight_kg"] = m.weight_kg;
    j["chest_girth_m"] = m.chest_girth_m;
    j["waist_girth_m"] = m.waist_girth_m;
    j["hip_girth_m"] = m.hip_girth_m;
    j["thigh_girth_m"] = m.thigh_girth_m;
    j["calf_girth_m"] = m.calf_girth_m;
    j["shoulder_height_m"] = m.shoulder_height_m;
    j["crotch_height_m"] = m.crotch_height_m;
    return j;
}

body::Pose pose_from_json(const nlohmann::json& j, const std::string& file) {
    reject_unknown_keys(j, {"preset", "translation", "rotations"}, file);
    body::Pose pose;
    if (j.contains("preset")) {
        const std::string preset = j["preset"].is_string() ? j["preset"].get<std::string>() : j["preset"].dump();
        if (preset == "a_pose") pose = body::named_pose(body::NamedPose::a_pose);
        else if (preset == "arms_down") pose = body::named_pose(body::NamedPose::arms_down);
        else if (preset == "walking") pose = body::named_pose(body::NamedPose::walking);
        else if (preset == "t_pose") pose = body::named_pose(body::NamedPose::t_pose);
        else
            throw InvalidInput(file + ": field 'preset' = " + preset +
                               " is not one of a_pose, arms_down, walking, t_pose");
    }
    if (j.contains("translation")) pose.translation = vector3_from_json(j["translation"], "'translation'", file);
    if (j.contains("rotations")) {
        const auto& rot = j["rotations"];
        if (!rot.is_object())
            throw InvalidInput(file + ": field 'rotations' must be an object {joint name: [x, y, z]}");
        for (const auto& item : rot.items()) {
            int joint = -1;
            for (int k = 0; k < body::kJointCount; ++k)
                if (body::kJointNames[k] == item.key()) joint = k;
            if (joint < 0)
                throw InvalidInput(file + ": 'rotations' names an unknown joint '" + item.key() +
                                   "' (joints: pelvis, spine, chest, neck, head, right_shoulder, ...)");
            pose.rotations.row(joint) = vector3_from_json(item.value(), "rotation of '" + item.key() + "'", file).transpose();
        }
    }
    std::string why;
    if (!pose.is_valid(&why)) throw InvalidInput(file + ": " + why);
    return pose;
}

nlohmann::json to_json(const body::Pose& pose) {
    nlohmann::json j;
    j["translation"] = {pose.translation.x(), pose.translation.y(), pose.translation.z()};
    nlohmann::json rot = nlohmann::json::object();
    for (int k = 0; k < body::kJointCount; ++k)
        rot[std::string(body::kJointNames[k])] = {pose.rotations(k, 0), pose.rotations(k, 1),
                                                  pose.rotations(k, 2)};
    j["rotations"] = rot;
    return j;
}

nlohmann::json to_json(const body::Camera& c) {
    nlohmann::json j;
    if (c.model == body::CameraModel::weak_perspective) {
        j["model"] = "weak_perspective";
        j["scale_px_per_m"] = c.scale_px_per_m;
    } else {
        j["model"] = "pinhole";
        j["focal_px"] = c.focal_px;
        j["distance_m"] = c.distance_m;
    }
    j["offset_px"] = {c.offset_px.x(), c.offset_px.y()};
    j["pixel_frame"] = "origin at the top-left corner of the image, pixel centres at +0.5";
    return j;
}

body::Camera camera_from_json(const nlohmann::json& j, const std::string& file) {
    if (!j.is_object()) throw InvalidInput(file + ": a camera must be a JSON object, got " + j.dump());
    reject_unknown_keys(j, {"model", "scale_px_per_m", "focal_px", "distance_m", "offset_px", "pixel_frame"}, file);
    body::Camera c;
    const std::string model = j.contains("model") && j["model"].is_string() ? j["model"].get<std::string>() : "";
    if (model == "pinhole") {
        c.model = body::CameraModel::pinhole;
        c.focal_px = required_number(j, "focal_px", file);
        c.distance_m = required_number(j, "distance_m", file);
    } else if (model == "weak_perspective") {
        c.model = body::CameraModel::weak_perspective;
        c.scale_px_per_m = required_number(j, "scale_px_per_m", file);
        if (j.contains("distance_m")) c.distance_m = required_number(j, "distance_m", file);
    } else {
        throw InvalidInput(file + ": camera field 'model' must be \"pinhole\" or \"weak_perspective\", got " +
                           (j.contains("model") ? j["model"].dump() : std::string("nothing")));
    }
    if (!j.contains("offset_px")) throw InvalidInput(file + ": camera field 'offset_px' is missing");
    c.offset_px = vector2_from_json(j["offset_px"], "camera 'offset_px'", file);
    std::string why;
    if (!c.is_valid(&why)) throw InvalidInput(file + ": " + why);
    return c;
}

}  // namespace drape::io
