// Ready-made views for showing a result: the studio preview of a dressed body (`drape
// dress`, `drape eval-dress`) and a front camera framing a whole scene (`drape render`).
#pragma once

#include <drape/render/camera.hpp>
#include <drape/render/scene.hpp>

#include <Eigen/Core>

#include <vector>

namespace drape::render {

/// One garment of a preview: its draped surface.
struct PreviewGarment {
    Eigen::MatrixXd V;   ///< #V x 3 world positions, metres
    Eigen::MatrixXi F;   ///< #F x 3 vertex indices
    Eigen::MatrixXd UV;  ///< #V x 2 pattern coordinates, or empty
};

/// The studio preview scene of a dressed body: the body in a neutral skin colour, the
/// garments in blue, then terracotta, then olive (repeating), drawn on their
/// Phong-tessellated surfaces (kSimulatedGarmentSubdivisions: flat, a coarse simulated
/// mesh cuts chords through the body), and a floor under the lowest point of all.
/// \param body_V #B x 3 world positions (metres, +Y up); \param body_F #F x 3.
/// \throw drape::InvalidInput if body_V has no rows or is not #B x 3.
Scene preview_scene(const Eigen::MatrixXd& body_V, const Eigen::MatrixXi& body_F,
                    const std::vector<PreviewGarment>& garments);

/// The preview camera: a 30° vertical field of view from the front-left and slightly
/// above, aimed at the centre of the body's bounding box and framing its height with a
/// 15 % margin.
/// \param body_V #B x 3 world positions; \param width_px, height_px the image size (> 0).
/// \throw drape::InvalidInput if body_V has no rows or the size is not positive.
Camera preview_camera(const Eigen::MatrixXd& body_V, int width_px, int height_px);

/// A camera in front (+Z) of every mesh of `scene`, at mid height, with a 30° vertical field
/// of view (a 50 mm-like portrait lens), framing the whole scene with a 12 % margin.
/// \throw drape::InvalidInput if the scene has no mesh or the size is not positive.
Camera front_camera(const Scene& scene, int width_px, int height_px);

}  // namespace drape::render
