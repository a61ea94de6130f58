// Projection of meshes into a photo's label map with a z-buffer: the fast path that
// recovery runs many times per photo (render a candidate body + garments with the fitted
// camera, compare each garment's visible silhouette with the segmentation). No shading,
// one thread, no BVH: a few milliseconds at 600 x 900 (docs/rendering.md, "Rasteriser").
//
// Sampling convention (the path tracer's `RenderImages::labels` uses the same one): pixel
// (x, y) shows the nearest surface whose projected triangle contains the pixel centre
// (x + 0.5, y + 0.5) in the image frame of drape/body/camera.hpp (x right, y down, origin
// at the top-left corner of the top-left pixel). A centre exactly on an edge belongs to
// both triangles (either winding: surfaces are two-sided).
#pragma once

#include <drape/body/camera.hpp>
#include <drape/render/scene.hpp>

#include <opencv2/core.hpp>

#include <string>
#include <vector>

namespace drape::render {

struct RasterOptions {
    int width_px = 600;   ///< the photo's size; 1..32768
    int height_px = 900;
    /// Also fill RasterImages::coverage (each mesh's projection ignoring the others):
    /// one byte write per covered pixel and a W x H mask per mesh.
    bool coverage = true;
    /// Pinhole: a triangle with a vertex closer to the camera plane than this (metres) is
    /// not drawn (counted in RasterSummary::triangles_behind). Weak perspective sees every
    /// triangle.
    double near_m = 1e-3;

    bool is_valid(std::string* why = nullptr) const;
};

/// Images of one rasterisation, all height_px x width_px.
struct RasterImages {
    cv::Mat labels;      ///< CV_8UC1: Mesh::label of the nearest mesh at the pixel centre, 0 where none
    cv::Mat mesh_index;  ///< CV_16SC1: index into the meshes of that surface, -1 where none
    /// CV_32FC1: camera-frame depth of that surface (metres along the viewing axis from the
    /// pinhole's centre, or from the plane z = distance_m for weak perspective; not along
    /// the ray as in RenderImages::depth), +inf where none.
    cv::Mat depth_m;
    /// Per mesh, CV_8UC1 0/255: its visible silhouette, the pixels where it is the nearest
    /// surface (not occluded by any other mesh) — `mesh_index == i`.
    std::vector<cv::Mat> visible;
    /// Per mesh, CV_8UC1 0/255: every pixel its projection covers, occluded or not (empty
    /// when RasterOptions::coverage is off). coverage[i] minus visible[i] is where mesh i
    /// is hidden.
    std::vector<cv::Mat> coverage;
};

enum class RasterTermination {
    rasterised,       ///< at least one pixel shows a mesh
    nothing_in_view,  ///< every triangle projects outside the image or lies behind the camera
};

struct RasterSummary {
    RasterTermination termination = RasterTermination::rasterised;
    std::string message;
    int width_px = 0;
    int height_px = 0;
    long long triangles = 0;         ///< in all meshes
    long long triangles_behind = 0;  ///< pinhole: skipped, a vertex within near_m of the camera plane or behind it
    long long pixels_covered = 0;    ///< pixels showing a mesh
    std::vector<long long> visible_pixels;  ///< per mesh: pixels of its visible silhouette
    double seconds = 0.0;

    bool usable() const { return termination == RasterTermination::rasterised; }
    std::string brief_report() const;
};

/// Projects `meshes` with `camera` (body::Camera::project: weak perspective or pinhole, the
/// `drape fit-body` convention, world metres) into label, mesh-index and depth maps with a
/// z-buffer, and each mesh's visible silhouette and coverage (see RasterImages). Triangles
/// are drawn flat as given: Mesh::smooth_subdivisions, normals, UVs and materials are
/// ignored. Where two meshes are at exactly the same depth the earlier one shows.
/// \param meshes each with V #V x 3 (world, metres), F #F x 3, label 0..255 (Scene::validate's
///        rules for one mesh).
/// \param out reallocated.
/// \throw drape::InvalidInput naming the mesh or option for an invalid mesh, an invalid
///        camera (body::Camera::is_valid), invalid options, or more than 32767 meshes.
RasterSummary rasterize(const std::vector<Mesh>& meshes, const body::Camera& camera,
                        const RasterOptions& options, RasterImages& out);

}  // namespace drape::render
