// Lighting: a sun (directional light with an angular radius, so shadows have soft edges),
// a sky dome (hemisphere light with a horizon-to-zenith gradient, shadowed like ambient
// occlusion), an unshadowed fill light and a constant bounce term for occluded sky rays.
// Colours are linear RGB; 1.0 is roughly "white paper in full light" after exposure.
#pragma once

#include <Eigen/Core>

#include <string>

namespace drape::render {

struct Lighting {
    std::string name = "custom";
    Eigen::Vector3d sun_direction{0.3, 0.85, 0.45};  ///< world, towards the sun (normalised on use)
    Eigen::Vector3d sun_colour{2.6, 2.5, 2.35};      ///< irradiance on a surface facing the sun
    double sun_angular_radius_rad = 0.02;            ///< 0 = hard shadows
    Eigen::Vector3d sky_zenith{0.35, 0.5, 0.85};     ///< radiance straight up
    Eigen::Vector3d sky_horizon{0.75, 0.8, 0.9};     ///< radiance at the horizon
    Eigen::Vector3d ground{0.3, 0.28, 0.25};         ///< radiance from below the horizon
    Eigen::Vector3d bounce{0.18, 0.17, 0.16};        ///< stands in for light from occluders
    Eigen::Vector3d fill_direction{-0.5, 0.2, 1.0};  ///< world, towards the fill light
    Eigen::Vector3d fill_colour{0.0, 0.0, 0.0};      ///< unshadowed Lambert fill
    double exposure = 1.0;                           ///< scale before the tone map

    /// Finite, non-negative colours, non-zero directions, radius in [0, 0.5] rad.
    bool is_valid(std::string* why = nullptr) const;
    /// The sky radiance seen in world direction `d` (unit).
    Eigen::Vector3d sky(const Eigen::Vector3d& d) const;
};

enum class LightingPreset {
    midday,  ///< high white sun (62 deg elevation) from front-left, blue sky
    sunset,  ///< low warm sun (9 deg) from the front-right, long shadows, dim orange sky
    studio,  ///< soft front key (large angular radius) + fill, neutral grey dome
};

/// The preset's lighting (values in docs/rendering.md).
Lighting lighting_preset(LightingPreset preset);

/// "midday" | "sunset" | "studio". \throw drape::InvalidInput naming the value otherwise.
LightingPreset parse_lighting_preset(const std::string& name);

}  // namespace drape::render
