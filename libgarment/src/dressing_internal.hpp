// Shared between the dressing_*.cpp files (not installed).
#pragma once

#include <drape/body/skeleton.hpp>
#include <drape/garment/garment_mesh.hpp>
#include <drape/garment/pattern.hpp>

#include <Eigen/Core>

#include <functional>
#include <vector>

namespace drape::garment::detail {

using Joints = Eigen::Matrix<double, body::kJointCount, 3>;

/// Positions (#V x 3, metres) of the mesh wrapped around a body whose rest joints are
/// `joints`: torso panels on vertical cylinders/cones around the spine, leg panels around
/// the leg axes, sleeves around the arm chains. Panels of unknown patterns: placement hint.
/// `torso_section(y)` gives the body's torso half-width and half-depth (metres) about the
/// spine axis at height y (garment frame), so torso panels wrap on matching ellipses.
Eigen::MatrixX3d wrap_panels(const Pattern& pattern, const GarmentMesh& mesh, const Joints& joints,
                             const std::function<Eigen::Vector2d(double)>& torso_section);

/// Garment edges (i, j), i < j, from the faces.
std::vector<std::array<int, 2>> mesh_edges(const Eigen::MatrixX3i& faces);

}  // namespace drape::garment::detail
