// Outfits with known projections for the output tests: axis-aligned rectangles seen by a
// weak-perspective camera (100 px/m), whose pixel counts follow from their corners.
#pragma once

#include <drape/body/camera.hpp>
#include <drape/recover/outfit_meshes.hpp>

namespace drape::test {

/// A rectangle [x0, x1] x [y0, y1] at depth z (two triangles), UV = (x, y).
recover::OutfitGarment rectangle(double x0, double x1, double y0, double y1, double z, int class_id);

/// 300 x 300 pixels: u = 100 x + 150, v = -100 y + 150.
body::Camera rectangle_camera();

/// The body: [-1, 1]^2 at z = 0 (pixels 50..249 in x and y: 40 000). Garment 0: a skirt
/// [-0.5, 0.5] x [-1.2, 0] at z = 0.1, in front (pixels x 100..199, y 150..269: 12 000,
/// 10 000 of them over the body). Garment 1: a t-shirt [-0.8, 0.8] x [0.2, 0.9] at
/// z = -0.1, behind the body and wholly hidden (coverage 160 x 70 = 11 200).
recover::OutfitMeshes rectangle_outfit();

}  // namespace drape::test
