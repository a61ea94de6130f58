// Private to libbody: Euclidean distance transforms of masks and their bilinear sampling
// (templated, so that Ceres differentiates through the interpolation).
#pragma once

#include <drape/body/camera.hpp>

#include <ceres/jet.h>

#include <cmath>
#include <vector>

namespace drape::body::detail {

/// A float image sampled at pixel centres: value(x, y) belongs to image point
/// (x + 0.5, y + 0.5) in the camera's pixel frame (origin at the top-left corner).
struct DistanceField {
    int width = 0;
    int height = 0;
    std::vector<float> values;  ///< width * height, row-major, pixels

    float at(int x, int y) const { return values[static_cast<size_t>(y) * width + x]; }
};

/// Distance (pixels) from every pixel centre to the nearest pixel centre whose mask value
/// is `target` (non-zero when target is true); 0 on such pixels. Exact Euclidean distance
/// (Felzenszwalb & Huttenlocher's lower-envelope algorithm). If no pixel has the target
/// value every distance is width + height.
DistanceField distance_transform(const Mask& mask, bool target);

inline double value_of(double x) { return x; }
template <class T, int N>
double value_of(const ceres::Jet<T, N>& x) {
    return x.a;
}

/// Bilinear sample of `field` at image point (u, v) (pixels, camera frame). Outside the
/// grid the field is continued by its border value plus the distance to the border, so
/// the result keeps growing (and keeps a gradient) away from the image.
template <class T>
T sample_bilinear(const DistanceField& field, const T& u, const T& v) {
    T gx = u - 0.5;
    T gy = v - 0.5;
    T extra = T(0);
    const double max_x = field.width - 1, max_y = field.height - 1;
    T ox = T(0), oy = T(0);
    if (value_of(gx) < 0) {
        ox = -gx;
        gx = T(0);
    } else if (value_of(gx) > max_x) {
        ox = gx - max_x;
        gx = T(max_x);
    }
    if (value_of(gy) < 0) {
        oy = -gy;
        gy = T(0);
    } else if (value_of(gy) > max_y) {
        oy = gy - max_y;
        gy = T(max_y);
    }
    if (value_of(ox) > 0 || value_of(oy) > 0) {
        using std::sqrt;
        extra = sqrt(ox * ox + oy * oy + 1e-12);
    }
    const int x0 = std::min(static_cast<int>(std::floor(value_of(gx))), std::max(0, field.width - 2));
    const int y0 = std::min(static_cast<int>(std::floor(value_of(gy))), std::max(0, field.height - 2));
    const int x1 = std::min(x0 + 1, field.width - 1);
    const int y1 = std::min(y0 + 1, field.height - 1);
    const T fx = gx - double(x0);
    const T fy = gy - double(y0);
    const double f00 = field.at(x0, y0), f10 = field.at(x1, y0);
    const double f01 = field.at(x0, y1), f11 = field.at(x1, y1);
    const T top = f00 + (f10 - f00) * fx;
    const T bottom = f01 + (f11 - f01) * fx;
    return top + (bottom - top) * fy + extra;
}

}  // namespace drape::body::detail
