#include <drape/recover/label_mask.hpp>

#include <drape/core/errors.hpp>

#include <utility>

namespace drape::recover {

bool LabelMaskOptions::is_valid(std::string* why) const {
    render::RasterOptions r;
    r.width_px = width_px;
    r.height_px = height_px;
    return r.is_valid(why);
}

render::RasterSummary label_mask(const OutfitMeshes& outfit, const body::Camera& camera,
                                 const LabelMaskOptions& options, LabelMask& out) {
    std::string why;
    require(options.is_valid(&why), "label_mask: ", why);
    outfit.validate();
    // Drawn outer garment first, body last: at equal depth the earlier mesh shows.
    const std::size_t garments = outfit.garments.size();
    std::vector<render::Mesh> meshes(garments + 1);
    for (std::size_t i = 0; i < garments; ++i) {
        const OutfitGarment& g = outfit.garments[garments - 1 - i];
        render::Mesh& m = meshes[i];
        m.name = outfit_mesh_name(outfit, garments - i);
        m.V = g.V;
        m.F = g.F;
        m.label = g.class_id;
    }
    render::Mesh& body = meshes[garments];
    body.name = "body";
    body.V = outfit.body_V;
    body.F = outfit.body_F;
    body.label = outfit.body_class_id;

    render::RasterOptions ro;
    ro.width_px = options.width_px;
    ro.height_px = options.height_px;
    ro.coverage = options.coverage;
    render::RasterImages images;
    render::RasterSummary summary = render::rasterize(meshes, camera, ro, images);

    // Raster index i holds outfit index (garments - i): garment garments-1-i, or the body.
    const std::size_t n = garments + 1;
    out.labels = images.labels;
    out.visible.assign(n, cv::Mat());
    out.coverage.assign(n, cv::Mat());
    out.visible_pixels.assign(n, 0);
    for (std::size_t i = 0; i < n; ++i) {
        const std::size_t k = garments - i;
        out.visible[k] = std::move(images.visible[i]);
        if (options.coverage) out.coverage[k] = std::move(images.coverage[i]);
        out.visible_pixels[k] = summary.visible_pixels[i];
    }
    summary.visible_pixels = out.visible_pixels;
    return summary;
}

}  // namespace drape::recover
