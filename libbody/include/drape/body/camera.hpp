// Cameras that map world points (metres, +Y up) to image pixels (x right, y down, origin at
// the top-left pixel's corner; pixel centres at +0.5).
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <string>
#include <vector>

namespace drape::body {

enum class CameraModel {
    weak_perspective,  ///< scaled orthographic (the paper's): u = s x + tx, v = -s y + ty
    pinhole,           ///< perspective, known focal length, camera on +Z looking down -Z
};

struct Camera {
    CameraModel model = CameraModel::weak_perspective;
    double scale_px_per_m = 300.0;                          ///< weak perspective s
    Eigen::Vector2d offset_px = Eigen::Vector2d::Zero();    ///< (tx, ty), or the principal point
    double focal_px = 1000.0;                               ///< pinhole focal length
    double distance_m = 5.0;  ///< pinhole: camera centre at (0, 0, distance_m), looking down -Z

    /// Projects a world point to pixels. Pinhole: x_c = X, y_c = -Y, z_c = distance_m - Z,
    /// u = focal_px x_c / z_c + offset_px.x, v = focal_px y_c / z_c + offset_px.y.
    Eigen::Vector2d project(const Eigen::Vector3d& X) const;
    bool is_valid(std::string* why = nullptr) const;
};

/// A binary image mask, row-major, 0 = outside, non-zero = inside.
struct Mask {
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> pixels;  ///< width * height

    bool inside(int x, int y) const { return pixels[static_cast<size_t>(y) * width + x] != 0; }
    int count() const;
};

/// The silhouette of a mesh seen by `camera`, rasterised at pixel centres.
Mask render_silhouette(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const Camera& camera,
                       int width, int height);

}  // namespace drape::body
