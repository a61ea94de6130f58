// Surface appearance of a render mesh: a base colour, an optional simple print (stripes,
// checks, dots) or an image texture mapped by UV (for garments: pattern coordinates), and
// a roughness that sets how much of a soft highlight the surface shows.
#pragma once

#include <opencv2/core.hpp>

#include <Eigen/Core>

#include <string>

namespace drape::render {

/// Procedural prints over UV space (tiling, no seams at pattern-piece borders).
enum class PrintKind {
    solid,    ///< colour only
    stripes,  ///< bands of colour / second_colour, each half a period wide, across u'
    checks,   ///< checkerboard of squares half a period wide
    dots,     ///< second_colour dots (radius dot_radius x period) on a square lattice
};

struct Print {
    PrintKind kind = PrintKind::solid;
    Eigen::Vector3d second_colour_srgb{1.0, 1.0, 1.0};  ///< sRGB in [0, 1]
    double period = 0.05;     ///< UV units per repeat (metres of pattern space for garments)
    double angle_rad = 0.0;   ///< rotation of the print in UV space (0: stripes vary along u)
    double dot_radius = 0.25; ///< dots: radius as a fraction of the period, in (0, 0.5]
};

struct Material {
    Eigen::Vector3d colour_srgb{0.8, 0.8, 0.8};  ///< base colour, sRGB in [0, 1]
    Print print;
    /// Optional 8-bit BGR image texture (CV_8UC3), tiled over UV space with one image
    /// width per `texture_period` UV units; it replaces colour and print when present.
    cv::Mat texture;
    double texture_period = 1.0;
    /// 0 = glossy (small bright highlight) .. 1 = fully matte; cloth is ~0.7-0.9.
    double roughness = 0.8;

    /// Finite colours in [0, 1], positive periods, roughness in [0, 1], texture type.
    bool is_valid(std::string* why = nullptr) const;
};

/// The surface colour (linear RGB reflectance in [0, 1]) at texture coordinate `uv`.
/// \pre material.is_valid()
Eigen::Vector3d albedo_at(const Material& material, const Eigen::Vector2d& uv);

/// Whether the print shows its second colour at `uv` (false for solid).
bool print_second_colour(const Print& print, const Eigen::Vector2d& uv);

/// The texel of a tiled texture at `uv`, linear RGB. \pre !material.texture.empty()
Eigen::Vector3d texture_at(const Material& material, const Eigen::Vector2d& uv);

/// sRGB in [0, 1] -> linear RGB (the IEC 61966-2-1 transfer function), and back.
double srgb_to_linear(double c);
double linear_to_srgb(double c);
Eigen::Vector3d srgb_to_linear(const Eigen::Vector3d& c);

}  // namespace drape::render
