// Where a panel goes on the body: the body part it wraps and a 3D placement hint.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <string_view>

namespace drape::garment {

/// The body part a panel wraps (used by dressing to pick a wrapping cylinder).
enum class BodyPart { front_torso, back_torso, left_sleeve, right_sleeve, left_leg, right_leg };

std::string_view body_part_name(BodyPart part);
/// \throw drape::InvalidInput naming the string if it is not a body part name.
BodyPart body_part_from_name(std::string_view name);

/// What a panel is to the dressing, declared by each template: how it is wrapped on the
/// body at rest, which joints skin it and how it is placed outside the posed body. Torso
/// panels wrap the trunk from the neck down, skirt panels hang from the waist (or from a
/// bodice's hem), leg panels wrap a leg and share a tube about the pelvis above the crotch,
/// sleeves wrap an arm. `other`: the panel starts at its placement hint.
enum class PanelRole { other, front_torso, back_torso, sleeve, skirt, front_leg, back_leg };
std::string_view panel_role_name(PanelRole role);
/// \throw drape::InvalidInput naming the string if it is not a panel role name.
PanelRole panel_role_from_name(std::string_view name);

/// Placement hint of a panel: the panel's 2D frame (x, y, 0) in centimetres is rotated by
/// `rotation_deg` (Euler angles in degrees about the fixed X, then Y, then Z axes:
/// R = Rz Ry Rx, as GarmentCode's euler_xyz_to_R) and
/// translated by `translation_cm` into the body frame (cm, +Y up, facing +Z, left = +X).
struct PanelPlacement {
    BodyPart body_part = BodyPart::front_torso;
    PanelRole role = PanelRole::other;  ///< see PanelRole
    Eigen::Vector3d translation_cm = Eigen::Vector3d::Zero();
    Eigen::Vector3d rotation_deg = Eigen::Vector3d::Zero();

    /// Maps a panel point (cm) to the world frame in metres.
    Eigen::Vector3d to_world_m(const Eigen::Vector2d& panel_point_cm) const;
    /// The rotation matrix of `rotation_deg`.
    Eigen::Matrix3d rotation() const;
};

}  // namespace drape::garment
