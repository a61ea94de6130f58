// mask.png: the recovered body and garments projected with the fitted camera, with
// occlusion, at the photo's size; each pixel holds a class id of labels.txt (the body's,
// 41 skin, each garment's own, 0 elsewhere). Also each mesh's visible silhouette, so that
// the recovery can score candidate garments against the segmentation (docs/recovery.md,
// "Output files"). It is librender's rasteriser (render/rasterize.hpp) on the outfit's
// meshes: a z-buffer at pixel centres, no shading.
#pragma once

#include <drape/body/camera.hpp>
#include <drape/recover/outfit_meshes.hpp>
#include <drape/render/rasterize.hpp>

#include <opencv2/core.hpp>

#include <string>
#include <vector>

namespace drape::recover {

struct LabelMaskOptions {
    int width_px = 600;   ///< the photo's size, 1..32768
    int height_px = 900;
    /// Also fill LabelMask::coverage (each mesh's projection ignoring the others): one more
    /// W x H mask per mesh.
    bool coverage = false;

    bool is_valid(std::string* why = nullptr) const;
};

/// One projection of an outfit. Per-mesh vectors are in the outfit's order: [0] the body,
/// [1 + k] garment k.
struct LabelMask {
    cv::Mat labels;  ///< CV_8UC1 height x width: class id of the nearest surface, 0 where none
    std::vector<cv::Mat> visible;   ///< CV_8UC1 0/255: where the mesh is the nearest surface
    std::vector<cv::Mat> coverage;  ///< CV_8UC1 0/255: its whole projection (LabelMaskOptions::coverage), else empty
    std::vector<long long> visible_pixels;  ///< pixels of each visible silhouette
};

/// Projects the outfit with `camera` (body::Camera::project: weak perspective or pinhole)
/// into `out` (reallocated). Where surfaces are at exactly the same depth, an outer garment
/// (later in OutfitMeshes::garments) shows over an inner one and any garment over the body.
/// \return the rasteriser's summary (triangles, pixels covered, seconds; `nothing_in_view`
///         when no triangle lands in the image: `out` is then all 0); its visible_pixels
///         are in the outfit's order.
/// \throw drape::InvalidInput naming the mesh or option: an invalid outfit
///        (OutfitMeshes::validate), camera or options.
render::RasterSummary label_mask(const OutfitMeshes& outfit, const body::Camera& camera,
                                 const LabelMaskOptions& options, LabelMask& out);

}  // namespace drape::recover
