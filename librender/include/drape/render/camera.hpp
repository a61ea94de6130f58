// The render camera: a pinhole (perspective) or orthographic camera with a pose. Image
// frame as in drape/body/camera.hpp: pixels, x right, y down, origin at the top-left
// corner of the image, the centre of pixel (i, j) at (i + 0.5, j + 0.5).
// Camera frame: x right, y down, z forward (the viewing direction).
#pragma once

#include <drape/body/camera.hpp>

#include <Eigen/Core>

#include <string>

namespace drape::render {

enum class Projection { perspective, orthographic };

/// A ray in the world frame; `direction` is unit length.
struct Ray {
    Eigen::Vector3d origin;
    Eigen::Vector3d direction;
};

struct Camera {
    Projection projection = Projection::perspective;
    int width_px = 600;
    int height_px = 900;
    double focal_px = 1500.0;          ///< perspective
    double scale_px_per_m = 300.0;     ///< orthographic
    Eigen::Vector2d principal_px{300.0, 450.0};
    Eigen::Vector3d eye{0.0, 1.0, 5.0};  ///< world position (orthographic: a point of the image plane)
    /// Rows: the camera's x (right), y (down) and z (forward) axes in world coordinates.
    Eigen::Matrix3d world_to_camera = (Eigen::Matrix3d() << 1, 0, 0, 0, -1, 0, 0, 0, -1).finished();

    /// A perspective camera at `eye` looking at `target`, `up` giving the image's up
    /// direction; principal point at the image centre.
    /// \throw drape::InvalidInput if eye == target, up is parallel to the view, or sizes are bad.
    static Camera look_at(const Eigen::Vector3d& eye, const Eigen::Vector3d& target,
                          const Eigen::Vector3d& up, double focal_px, int width_px, int height_px);

    /// The camera of a fitted photo (drape::body::Camera), so that renders overlay it
    /// exactly: pinhole -> perspective at (0, 0, distance_m) looking down -Z; weak
    /// perspective -> orthographic with the same scale and offset (image plane at
    /// z = distance_m, so depth is measured from there).
    /// \throw drape::InvalidInput if the body camera is invalid or the size is not positive.
    static Camera from_body(const body::Camera& camera, int width_px, int height_px);

    /// The ray through image point (u, v) (pixels).
    Ray ray(double u_px, double v_px) const;
    /// Pixel coordinates of a world point (perspective: the point must be in front).
    Eigen::Vector2d project(const Eigen::Vector3d& X) const;

    /// Positive image size, finite positive focal/scale, finite pose, orthonormal rotation.
    bool is_valid(std::string* why = nullptr) const;
};

}  // namespace drape::render
