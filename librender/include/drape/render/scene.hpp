// What the renderer draws: triangle meshes (body, garments) with materials and label ids,
// and an optional photo-studio stage (floor, backdrop). World frame: metres, +Y up, the body
// faces +Z.
#pragma once

#include <drape/render/material.hpp>

#include <Eigen/Core>

#include <cstddef>
#include <string>
#include <vector>

namespace drape::render {

struct Mesh {
    std::string name;    ///< used in error messages ("body", "garment 1", a file name)
    Eigen::MatrixXd V;   ///< #V x 3 world positions, metres
    Eigen::MatrixXi F;   ///< #F x 3 vertex indices (either winding: surfaces are two-sided)
    Eigen::MatrixXd N;   ///< #V x 3 vertex normals, or empty: area-weighted smooth normals
    Eigen::MatrixXd UV;  ///< #V x 2 texture coordinates, or empty (prints then use x, y)
    Material material;
    int label = 0;       ///< written to the label map, 0..255 (labels.txt ids for garments)
    /// Levels of Phong tessellation (phong_tessellate) the renderer applies before drawing,
    /// 0..4: a coarse simulated garment (4–6 cm edges) drawn flat cuts chords through the
    /// body it rests 5 mm above (the body shows through) and shows its facets.
    int smooth_subdivisions = 0;
};

/// Phong tessellation (Boubekeur & Alexa 2008) repeated `levels` times: every edge is split at
/// its midpoint p, moved to (1 − α) p + α (π_a(p) + π_b(p)) / 2 with π_k the projection onto
/// the tangent plane of end k (its vertex normal), so a mesh of points on a curved surface
/// is refined towards that surface (the midpoint of a chord over a circle of radius r with
/// ends 37° apart lands 2 % outside r at α = 0.75 instead of 5 % inside). Each triangle becomes 4^levels;
/// normals of new vertices are the normalised mean of the edge's ends; UVs are interpolated.
/// Vertices at exactly the same position (the two sides of a seam) share their normal and
/// give identical midpoints, so no crack opens between them. Empty N: area-weighted
/// normals of the mesh with coincident vertices merged. \pre levels >= 0, α in [0, 1].
Mesh phong_tessellate(const Mesh& mesh, int levels, double alpha = 0.75);

/// Levels of Phong tessellation the apps draw simulated garments with (their 4–6 cm
/// triangles as 1–1.5 cm ones): `drape synth`, `drape dress`, `drape eval-dress`.
constexpr int kSimulatedGarmentSubdivisions = 2;

/// A horizontal floor under the meshes (infinite for the camera: 40 m square).
struct Floor {
    bool enabled = false;
    double height_m = 0.0;  ///< world y of the floor
    Material material;      ///< default: warm mid grey
    int label = 0;
    Floor();
};

/// A vertical backdrop behind the meshes at z = -distance_m, joined to the floor (when
/// the floor is on) by a quarter-cylinder cove of `cove_radius_m`, like a studio sweep.
struct Backdrop {
    bool enabled = false;
    double distance_m = 2.0;   ///< the wall is the plane z = -distance_m
    double cove_radius_m = 0.8;
    double height_m = 8.0;     ///< top of the wall above the floor
    Material material;         ///< default: light grey
    int label = 0;
    Backdrop();
};

/// Throws drape::InvalidInput naming mesh `index` (and its name) and the problem: no
/// triangles, bad shapes, indices out of range, non-finite values, bad material, label
/// outside 0..255, smooth_subdivisions outside 0..4.
void validate_mesh(const Mesh& mesh, std::size_t index);

struct Scene {
    std::vector<Mesh> meshes;
    Floor floor;
    Backdrop backdrop;

    /// Throws drape::InvalidInput naming the mesh and the problem (no triangles, bad shapes,
    /// indices out of range, non-finite values, bad material, label outside 0..255).
    void validate() const;
};

/// The stage geometry of `scene` (floor, backdrop, cove) as meshes (UV = world x and the
/// arc length along the floor/wall profile). Empty when both are disabled.
std::vector<Mesh> stage_meshes(const Scene& scene);

}  // namespace drape::render
