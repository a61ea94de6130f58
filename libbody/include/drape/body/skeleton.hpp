// The body skeleton: a fixed tree of 22 joints shared by every Drape body model.
//
// Frame: world, metres, +Y up, the body faces +Z, the person's left is +X, feet on Y = 0
// in the rest pose. Joint rotations are parent-relative axis-angle vectors (radians).
#pragma once

#include <array>
#include <string_view>

namespace drape::body {

/// Joint indices. The order is part of the model file format; do not reorder.
enum class Joint : int {
    pelvis = 0,      ///< root, between the hip joints
    spine = 1,       ///< lower back, about navel height
    chest = 2,       ///< thorax, about bust height
    neck = 3,        ///< base of the neck (the image "neck" joint)
    head = 4,        ///< skull base / top of the neck
    head_top = 5,    ///< vertex of the skull (the image "head" joint); end site
    right_clavicle = 6,
    right_shoulder = 7,
    right_elbow = 8,
    right_wrist = 9,  ///< the image "hand" joint
    left_clavicle = 10,
    left_shoulder = 11,
    left_elbow = 12,
    left_wrist = 13,
    right_hip = 14,
    right_knee = 15,
    right_ankle = 16,
    right_toe = 17,  ///< end site at the ball of the foot
    left_hip = 18,
    left_knee = 19,
    left_ankle = 20,
    left_toe = 21,
};

inline constexpr int kJointCount = 22;

/// Parent of each joint (-1 for the root), indexed by Joint.
inline constexpr std::array<int, kJointCount> kJointParents = {
    -1, 0, 1, 2, 3, 4,   // pelvis spine chest neck head head_top
    2, 6, 7, 8,          // right arm
    2, 10, 11, 12,       // left arm
    0, 14, 15, 16,       // right leg
    0, 18, 19, 20,       // left leg
};

/// Joint names as used in files (glTF node names, HDF5 strings, JSON).
inline constexpr std::array<std::string_view, kJointCount> kJointNames = {
    "pelvis",         "spine",          "chest",        "neck",        "head",
    "head_top",       "right_clavicle", "right_shoulder", "right_elbow", "right_wrist",
    "left_clavicle",  "left_shoulder",  "left_elbow",   "left_wrist",  "right_hip",
    "right_knee",     "right_ankle",    "right_toe",    "left_hip",    "left_knee",
    "left_ankle",     "left_toe",
};

/// The 14 image joints, in the order of the Fashionista / PARSE annotation files.
inline constexpr int kImageJointCount = 14;
inline constexpr std::array<Joint, kImageJointCount> kImageJoints = {
    Joint::right_ankle,    Joint::right_knee,    Joint::right_hip,      Joint::left_hip,
    Joint::left_knee,      Joint::left_ankle,    Joint::right_wrist,    Joint::right_elbow,
    Joint::right_shoulder, Joint::left_shoulder, Joint::left_elbow,     Joint::left_wrist,
    Joint::neck,           Joint::head_top,
};
inline constexpr std::array<std::string_view, kImageJointCount> kImageJointNames = {
    "right_ankle",    "right_knee",    "right_hip",  "left_hip",   "left_knee",
    "left_ankle",     "right_hand",    "right_elbow", "right_shoulder", "left_shoulder",
    "left_elbow",     "left_hand",     "neck",       "head",
};

constexpr int index(Joint j) { return static_cast<int>(j); }

}  // namespace drape::body
