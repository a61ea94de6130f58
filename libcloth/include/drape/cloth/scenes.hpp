// Reference scenes for tests, benchmarks and `drape bench-cloth`: an icosphere obstacle and
// the anchor scene of issue 3 (a 1 m square dropped onto a 0.5 m sphere, as measured on
// ArcSim 0.3.1).
#pragma once

#include <drape/cloth/cloth_mesh.hpp>
#include <drape/cloth/material.hpp>
#include <drape/cloth/obstacle.hpp>
#include <drape/cloth/simulator.hpp>

#include <Eigen/Core>

namespace drape::cloth {

/// A closed triangle mesh (outward, counter-clockwise faces).
struct TriangleMesh {
    Eigen::MatrixX3d positions;  ///< #V x 3, world, metres
    Eigen::MatrixX3i faces;      ///< #F x 3
};

/// An icosphere: the icosahedron subdivided `subdivisions` times (10·4^s + 2 vertices: 642
/// for s = 3), vertices on the sphere. \pre 0 <= subdivisions <= 7, radius > 0.
/// \throw drape::InvalidInput otherwise.
TriangleMesh make_icosphere(int subdivisions, double radius_m,
                            const Eigen::Vector3d& centre_m = Eigen::Vector3d::Zero());

/// The anchor scene: a 1 m square grid with n x n cells (alternating diagonals) in the
/// plane z = 0.6 centred on the z axis, a fixed sphere of radius 0.5 m at the origin (a
/// 642-vertex icosphere), gravity −9.8 m/s² along z, Δt = 5 ms, friction 0.6 (cloth) and
/// 0.3 (obstacle), contact thickness 5 mm. Simulate 2.0 s (400 steps).
struct AnchorScene {
    ClothMesh cloth;
    TriangleMesh sphere;
    SimulatorOptions options;
    double duration_s = 2.0;
    int centre_vertex = -1;  ///< the grid's centre node
};

/// \pre n >= 2 and even (so that a node sits at the centre). \throw drape::InvalidInput.
AnchorScene make_anchor_scene(int n);

}  // namespace drape::cloth
