#include <drape/render/material.hpp>

#include <cmath>
#include <sstream>

namespace drape::render {

namespace {

bool colour_ok(const Eigen::Vector3d& c) {
    return c.allFinite() && c.minCoeff() >= 0.0 && c.maxCoeff() <= 1.0;
}

double frac(double x) { return x - std::floor(x); }

}  // namespace

double srgb_to_linear(double c) {
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

double linear_to_srgb(double c) {
    return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
}

Eigen::Vector3d srgb_to_linear(const Eigen::Vector3d& c) {
    return {srgb_to_linear(c.x()), srgb_to_linear(c.y()), srgb_to_linear(c.z())};
}

bool Material::is_valid(std::string* why) const {
    auto fail = [&](const std::string& m) {
        if (why) *why = m;
        return false;
    };
    std::ostringstream os;
    if (!colour_ok(colour_srgb)) {
        os << "colour_srgb must hold three numbers in [0, 1], got " << colour_srgb.transpose();
        return fail(os.str());
    }
    if (!colour_ok(print.second_colour_srgb)) {
        os << "print second_colour_srgb must hold three numbers in [0, 1], got "
           << print.second_colour_srgb.transpose();
        return fail(os.str());
    }
    if (!std::isfinite(print.period) || print.period <= 0) {
        os << "print period must be a positive number of UV units, got " << print.period;
        return fail(os.str());
    }
    if (!std::isfinite(print.angle_rad)) return fail("print angle_rad is not finite");
    if (!(print.dot_radius > 0 && print.dot_radius <= 0.5)) {
        os << "print dot_radius must be in (0, 0.5], got " << print.dot_radius;
        return fail(os.str());
    }
    if (!texture.empty() && (texture.type() != CV_8UC3 || texture.cols < 1 || texture.rows < 1))
        return fail("texture must be an 8-bit 3-channel (BGR) image");
    if (!std::isfinite(texture_period) || texture_period <= 0) {
        os << "texture_period must be a positive number of UV units, got " << texture_period;
        return fail(os.str());
    }
    if (!(roughness >= 0 && roughness <= 1)) {
        os << "roughness must be in [0, 1], got " << roughness;
        return fail(os.str());
    }
    return true;
}

Eigen::Vector3d texture_at(const Material& m, const Eigen::Vector2d& uv) {
    // Nearest texel of the tiled image; v grows upwards in UV space, rows downwards.
    const double s = frac(uv.x() / m.texture_period), t = frac(uv.y() / m.texture_period);
    const int w = m.texture.cols, h = m.texture.rows;
    const int i = std::min(w - 1, static_cast<int>(s * w));
    const int j = std::min(h - 1, static_cast<int>((1.0 - t) * h));
    const cv::Vec3b bgr = m.texture.at<cv::Vec3b>(j, i);
    return srgb_to_linear(Eigen::Vector3d(bgr[2], bgr[1], bgr[0]) / 255.0);
}

bool print_second_colour(const Print& p, const Eigen::Vector2d& uv) {
    if (p.kind == PrintKind::solid) return false;
    const double c = std::cos(p.angle_rad), s = std::sin(p.angle_rad);
    const double a = (c * uv.x() + s * uv.y()) / p.period;
    const double b = (-s * uv.x() + c * uv.y()) / p.period;
    switch (p.kind) {
        case PrintKind::stripes: return frac(a) >= 0.5;
        case PrintKind::checks: return (frac(a) >= 0.5) != (frac(b) >= 0.5);
        case PrintKind::dots: {
            const double da = frac(a) - 0.5, db = frac(b) - 0.5;
            return da * da + db * db <= p.dot_radius * p.dot_radius;
        }
        case PrintKind::solid: break;
    }
    return false;
}

Eigen::Vector3d albedo_at(const Material& m, const Eigen::Vector2d& uv) {
    if (!m.texture.empty()) return texture_at(m, uv);
    return srgb_to_linear(print_second_colour(m.print, uv) ? m.print.second_colour_srgb : m.colour_srgb);
}

}  // namespace drape::render
