// What a synthetic scene is asked for (docs/synthetic.md, "Protocol"): every choice left
// empty is drawn from the seed.
#pragma once

#include <drape/body/pose.hpp>
#include <drape/garment/garment_type.hpp>
#include <drape/render/material.hpp>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace drape::synth {

struct SynthOptions {
    std::uint64_t seed = 0;
    /// One garment, or an outfit of a lower garment (pants or skirt) and a t-shirt over it,
    /// lower first. Empty: drawn from skirt, pants, tshirt, dress, pants + tshirt,
    /// skirt + tshirt.
    std::vector<garment::GarmentType> garments;
    /// a_pose, arms_down or walking; empty: drawn.
    std::optional<body::NamedPose> pose;
    /// A built-in measured fabric (cloth::builtin_material_names() but paper and
    /// aluminium); empty: drawn.
    std::string fabric;
    /// Bending scale s_b; <= 0 = the default (drawn fabric: log-uniform in [1, 100]; named
    /// fabric: 1).
    double bending_scale = 0;
    /// The print of every garment (render::PrintKind::solid = plain); empty: drawn with the
    /// look (docs/synthetic.md, "Look"). Only the kind is forced: colours, period and angle
    /// are the drawn ones, and nothing else of the scene changes (same body, sizing,
    /// fabric, drape, labels), so one seed renders plain and printed.
    std::optional<render::PrintKind> print;
    double edge_cm = 4.0;      ///< mesh target edge length, (0, 20] cm
    /// Dynamic steps of each drape at most (>= 20); untangling and the fallback after a
    /// failed static solve are capped at a third of it each.
    int max_steps = 600;
    int width_px = 600;        ///< image size, [64, 8192]; height [600, 8192]
    int height_px = 900;
    int samples_per_pixel = 16;  ///< 1..4096
    int threads = 0;           ///< render threads (0 = all); the output does not depend on it

    /// The ranges above; garments an outfit in layering order (garment::outfit_layers: one
    /// garment, or pants or a skirt, then a t-shirt); pose not t_pose.
    bool is_valid(std::string* why = nullptr) const;
};

}  // namespace drape::synth
