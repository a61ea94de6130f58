#include <drape/render/lighting.hpp>

#include <drape/core/errors.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace drape::render {

namespace {

bool non_negative(const Eigen::Vector3d& c) { return c.allFinite() && c.minCoeff() >= 0.0; }

/// Unit vector towards a light at `elevation_deg` above the horizon and `azimuth_deg`
/// measured from +Z (the body's front) towards +X (the body's left).
Eigen::Vector3d from_angles(double elevation_deg, double azimuth_deg) {
    const double e = elevation_deg * 3.14159265358979323846 / 180.0;
    const double a = azimuth_deg * 3.14159265358979323846 / 180.0;
    return {std::cos(e) * std::sin(a), std::sin(e), std::cos(e) * std::cos(a)};
}

}  // namespace

bool Lighting::is_valid(std::string* why) const {
    auto fail = [&](const std::string& m) {
        if (why) *why = m;
        return false;
    };
    if (!sun_direction.allFinite() || sun_direction.norm() < 1e-12)
        return fail("lighting sun_direction must be a finite non-zero vector");
    if (!fill_direction.allFinite() || fill_direction.norm() < 1e-12)
        return fail("lighting fill_direction must be a finite non-zero vector");
    if (!non_negative(sun_colour) || !non_negative(sky_zenith) || !non_negative(sky_horizon) ||
        !non_negative(ground) || !non_negative(bounce) || !non_negative(fill_colour))
        return fail("lighting colours must be finite and non-negative");
    if (!(sun_angular_radius_rad >= 0 && sun_angular_radius_rad <= 0.5)) {
        std::ostringstream os;
        os << "lighting sun_angular_radius_rad must be in [0, 0.5], got " << sun_angular_radius_rad;
        return fail(os.str());
    }
    if (!(std::isfinite(exposure) && exposure > 0)) {
        std::ostringstream os;
        os << "lighting exposure must be a positive number, got " << exposure;
        return fail(os.str());
    }
    return true;
}

Eigen::Vector3d Lighting::sky(const Eigen::Vector3d& d) const {
    if (d.y() <= 0) return ground;
    // sqrt: the sky pales quickly towards the horizon.
    const double t = std::sqrt(std::min(1.0, d.y()));
    return (1.0 - t) * sky_horizon + t * sky_zenith;
}

Lighting lighting_preset(LightingPreset preset) {
    Lighting l;
    switch (preset) {
        case LightingPreset::midday:
            l.name = "midday";
            l.sun_direction = from_angles(62.0, 30.0);
            l.sun_colour = {2.3, 2.25, 2.15};
            l.sun_angular_radius_rad = 0.03;  // a bit wider than the real 0.0047: softer edges
            l.sky_zenith = {0.30, 0.45, 0.80};
            l.sky_horizon = {0.70, 0.76, 0.85};
            l.ground = {0.28, 0.26, 0.24};
            l.bounce = {0.14, 0.14, 0.14};
            l.fill_colour = {0.0, 0.0, 0.0};
            l.exposure = 0.6;
            break;
        case LightingPreset::sunset:
            l.name = "sunset";
            l.sun_direction = from_angles(9.0, -50.0);
            l.sun_colour = {2.6, 1.45, 0.65};
            l.sun_angular_radius_rad = 0.02;
            l.sky_zenith = {0.16, 0.18, 0.32};
            l.sky_horizon = {0.55, 0.36, 0.28};
            l.ground = {0.14, 0.10, 0.08};
            l.bounce = {0.10, 0.07, 0.05};
            l.fill_colour = {0.0, 0.0, 0.0};
            l.exposure = 0.6;
            break;
        case LightingPreset::studio:
            l.name = "studio";
            l.sun_direction = from_angles(30.0, 40.0);
            l.sun_colour = {1.7, 1.7, 1.7};
            l.sun_angular_radius_rad = 0.25;  // a large soft box
            l.sky_zenith = {0.55, 0.55, 0.55};
            l.sky_horizon = {0.55, 0.55, 0.55};
            l.ground = {0.25, 0.25, 0.25};
            l.bounce = {0.15, 0.15, 0.15};
            l.fill_direction = from_angles(10.0, -45.0);
            l.fill_colour = {0.22, 0.22, 0.24};
            l.exposure = 0.55;
            break;
    }
    return l;
}

LightingPreset parse_lighting_preset(const std::string& name) {
    if (name == "midday") return LightingPreset::midday;
    if (name == "sunset") return LightingPreset::sunset;
    if (name == "studio") return LightingPreset::studio;
    throw InvalidInput("lighting preset '" + name + "' is not one of midday, sunset, studio");
}

}  // namespace drape::render
