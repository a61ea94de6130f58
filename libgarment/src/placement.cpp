#include <drape/garment/placement.hpp>

#include <drape/core/errors.hpp>

#include <array>
#include <string>

namespace drape::garment {

namespace {
constexpr std::array<std::string_view, 6> kNames = {
    "front_torso", "back_torso", "left_sleeve", "right_sleeve", "left_leg", "right_leg"};
constexpr std::array<std::string_view, 7> kRoleNames = {"other",  "front_torso", "back_torso", "sleeve",
                                                         "skirt",  "front_leg",   "back_leg"};
constexpr double kDegToRad = 3.14159265358979323846 / 180.0;
}  // namespace

std::string_view body_part_name(BodyPart part) { return kNames[static_cast<int>(part)]; }

std::string_view panel_role_name(PanelRole role) { return kRoleNames[static_cast<int>(role)]; }

PanelRole panel_role_from_name(std::string_view name) {
    for (size_t i = 0; i < kRoleNames.size(); ++i)
        if (kRoleNames[i] == name) return static_cast<PanelRole>(i);
    throw InvalidInput("unknown panel role '" + std::string(name) +
                       "' (expected other, front_torso, back_torso, sleeve, skirt, front_leg or back_leg)");
}

BodyPart body_part_from_name(std::string_view name) {
    for (size_t i = 0; i < kNames.size(); ++i)
        if (kNames[i] == name) return static_cast<BodyPart>(i);
    throw InvalidInput("unknown body part '" + std::string(name) +
                       "' (expected front_torso, back_torso, left_sleeve, right_sleeve, "
                       "left_leg or right_leg)");
}

Eigen::Matrix3d PanelPlacement::rotation() const {
    const Eigen::Vector3d r = rotation_deg * kDegToRad;
    // Extrinsic X, then Y, then Z (GarmentCode's euler_xyz_to_R): R = Rz Ry Rx.
    return (Eigen::AngleAxisd(r.z(), Eigen::Vector3d::UnitZ()) *
            Eigen::AngleAxisd(r.y(), Eigen::Vector3d::UnitY()) *
            Eigen::AngleAxisd(r.x(), Eigen::Vector3d::UnitX()))
        .toRotationMatrix();
}

Eigen::Vector3d PanelPlacement::to_world_m(const Eigen::Vector2d& p) const {
    return 0.01 * (rotation() * Eigen::Vector3d(p.x(), p.y(), 0.0) + translation_cm);
}

}  // namespace drape::garment
