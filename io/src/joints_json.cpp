#include <drape/io/joints_json.hpp>

#include <drape/io/json_io.hpp>

#include <drape/core/errors.hpp>

#include <cmath>
#include <string>

namespace drape::io {

double origin_offset(PixelOrigin o) {
    switch (o) {
        case PixelOrigin::one_based: return -0.5;   // MATLAB: pixel 1's centre is at 1
        case PixelOrigin::zero_based: return 0.5;   // C: pixel 0's centre is at 0
        case PixelOrigin::corner: return 0.0;
    }
    return 0.0;
}

const char* origin_name(PixelOrigin o) {
    switch (o) {
        case PixelOrigin::one_based: return "one_based";
        case PixelOrigin::zero_based: return "zero_based";
        case PixelOrigin::corner: return "corner";
    }
    return "";
}

JointsFile read_joints_file(const std::filesystem::path& path, int width, int height) {
    const std::string file = path.string();
    const nlohmann::json j = read_json_file(path);
    reject_unknown_keys(j, {"joints", "joint_names", "image_size", "pixel_origin", "marks"}, file);
    JointsFile out;
    if (j.contains("marks")) {
        const std::string m = j["marks"].is_string() ? j["marks"].get<std::string>() : j["marks"].dump();
        if (m == "hand") out.marks = vision::JointMarks::hand;
        else if (m == "model") out.marks = vision::JointMarks::model;
        else throw InvalidInput(file + ": field 'marks' = " + m + " is not one of hand, model");
    }
    if (j.contains("pixel_origin")) {
        const std::string o = j["pixel_origin"].is_string() ? j["pixel_origin"].get<std::string>()
                                                             : j["pixel_origin"].dump();
        if (o == "one_based") out.origin = PixelOrigin::one_based;
        else if (o == "zero_based") out.origin = PixelOrigin::zero_based;
        else if (o == "corner") out.origin = PixelOrigin::corner;
        else
            throw InvalidInput(file + ": field 'pixel_origin' = " + o +
                               " is not one of one_based, zero_based, corner");
    }
    if (!j.contains("joints") || !j["joints"].is_array())
        throw InvalidInput(file + ": field 'joints' must be an array of 14 [x, y] pixel pairs");
    const auto& arr = j["joints"];
    if (arr.size() != body::kImageJointCount)
        throw InvalidInput(file + ": field 'joints' has " + std::to_string(arr.size()) +
                           " entries, expected 14 (right_ankle ... head)");
    if (j.contains("joint_names")) {
        const auto& names = j["joint_names"];
        bool ok = names.is_array() && names.size() == body::kImageJointCount;
        for (size_t i = 0; ok && i < names.size(); ++i)
            ok = names[i].is_string() && names[i].get<std::string>() == body::kImageJointNames[i];
        if (!ok)
            throw InvalidInput(file + ": field 'joint_names' must list the 14 joints in the order "
                               "right_ankle, right_knee, right_hip, left_hip, left_knee, left_ankle, "
                               "right_hand, right_elbow, right_shoulder, left_shoulder, left_elbow, "
                               "left_hand, neck, head; got " + names.dump());
    }
    if (j.contains("image_size")) {
        const auto& s = j["image_size"];
        if (!s.is_array() || s.size() != 2 || !s[0].is_number() || !s[1].is_number() ||
            s[0].get<double>() != width || s[1].get<double>() != height)
            throw InvalidInput(file + ": field 'image_size' = " + s.dump() +
                               " does not match the photo's " + std::to_string(width) + " x " +
                               std::to_string(height) + " pixels");
    }
    const double shift = origin_offset(out.origin);
    for (int i = 0; i < body::kImageJointCount; ++i) {
        const auto& p = arr[static_cast<size_t>(i)];
        const std::string name = "joint " + std::to_string(i) + " (" +
                                 std::string(body::kImageJointNames[static_cast<size_t>(i)]) + ")";
        const Eigen::Vector2d xy = vector2_from_json(p, name, file);
        out.joints_px(i, 0) = xy.x() + shift;
        out.joints_px(i, 1) = xy.y() + shift;
        const double u = out.joints_px(i, 0), v = out.joints_px(i, 1);
        if (u < 0 || v < 0 || u > width || v > height)
            throw InvalidInput(file + ": " + name + " = " + p.dump() + " lies outside the " +
                               std::to_string(width) + " x " + std::to_string(height) + " photo");
    }
    return out;
}

}  // namespace drape::io
