// Meshes with known geometry for the renderer and rasteriser tests.
#pragma once

#include <drape/render/scene.hpp>

#include <Eigen/Core>

namespace drape::test {

/// An icosphere: an icosahedron subdivided `level` times, its vertices projected onto the
/// sphere (so they lie exactly on it), with the exact normals.
render::Mesh icosphere(const Eigen::Vector3d& centre, double radius, int level, int label);

/// A square in the plane z = 0, x and y in [-half, half], UV = (x, y).
render::Mesh square(double half, int label);

}  // namespace drape::test
