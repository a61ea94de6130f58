// The C facade, part 2: segmentation of a photo and its garments' features (libvision).
#include "capi_internal.hpp"

#include <drape/io/image_io.hpp>
#include <drape/io/vision_json.hpp>

#include <drape/vision/garment_result.hpp>
#include <drape/vision/image_io.hpp>
#include <drape/vision/segmentation.hpp>
#include <drape/vision/strokes.hpp>

#include <cstring>
#include <filesystem>
#include <vector>

struct drape_segmentation_s {
    std::string image;
    cv::Mat photo;  // what was segmented, for the folder's overlays
    int width = 0, height = 0;
    std::string mode;
    double height_m = 1.70;
    drape::vision::Segmentation seg;
    drape::vision::SegmentationSummary summary;
    std::vector<drape::vision::GarmentResult> garments;
};

namespace drape::capi {

template <>
struct StructTraits<drape_segment_options> {
    static constexpr const char* name = "drape_segment_options";
    static auto fields() {
        using S = drape_segment_options;
        return std::make_tuple(&S::strokes_path, &S::palette_path, &S::hint, &S::height_m);
    }
    static drape_segment_options defaults() {
        drape_segment_options d{};
        d.struct_size = sizeof d;
        d.height_m = 1.70;
        return d;
    }
};

}  // namespace drape::capi

namespace {

using namespace drape::capi;
namespace dv = drape::vision;

// A CV_8UC1 image through the size-query protocol (capacity in bytes).
drape_status copy_image(const cv::Mat& m, uint8_t* out, size_t capacity, size_t* required, const char* what) {
    const size_t n = static_cast<size_t>(m.rows) * static_cast<size_t>(m.cols);
    if (required) *required = n;
    if (!out) return DRAPE_OK;
    if (capacity < n)
        return fail(DRAPE_ERROR_INVALID_ARGUMENT, [&] {
            return std::string(what) + ": buffer holds " + std::to_string(capacity) + " bytes, " + std::to_string(n) +
                   " needed";
        });
    for (int r = 0; r < m.rows; ++r) std::memcpy(out + static_cast<size_t>(r) * m.cols, m.ptr<uint8_t>(r), m.cols);
    return DRAPE_OK;
}

}  // namespace

extern "C" {

drape_status drape_segment_options_init(drape_segment_options* options) {
    return init_struct(options, __func__, "options");
}

drape_status drape_segment(const char* image_path, const char* joints_path, const drape_segment_options* options,
                           drape_segmentation* out_segmentation) {
    DRAPE_REQUIRE_ARG(image_path, "image_path must not be NULL");
    DRAPE_REQUIRE_ARG(joints_path, "joints_path must not be NULL");
    DRAPE_REQUIRE_ARG(out_segmentation, "out_segmentation must not be NULL");
    *out_segmentation = nullptr;
    return guarded(__func__, [&] {
        const drape_segment_options opt = read_struct(options, "options");
        if (!(opt.height_m > 0.5 && opt.height_m < 2.6))
            throw drape::InvalidInput("options->height_m = " + std::to_string(opt.height_m) +
                                      " m is outside 0.5 .. 2.6 m");
        if (opt.palette_path && !opt.strokes_path)
            throw drape::InvalidInput("options->palette_path is for colour-coded strokes; no strokes_path given");
        dv::SegmentationOptions so;
        if (opt.hint) {
            so.hint = dv::parse_garment_type(opt.hint);
            if (!so.hint)
                throw drape::InvalidInput(std::string("options->hint '") + opt.hint +
                                          "' is not one of t-shirt, tank-top, long-sleeve-top, dress, skirt, pants, "
                                          "shorts");
        }
        auto s = std::make_unique<drape_segmentation_s>();
        const cv::Mat photo = dv::load_image(image_path);
        const dv::Joints joints = drape::io::read_vision_joints(joints_path, photo.cols, photo.rows);
        if (opt.strokes_path) {
            const dv::StrokePalette palette = drape::io::read_stroke_palette(str(opt.palette_path), so.table);
            const cv::Mat strokes = dv::load_strokes(opt.strokes_path, palette);
            s->summary = dv::segment_with_strokes(photo, strokes, &joints, so, s->seg);
            s->mode = "strokes";
        } else {
            s->summary = dv::segment_automatic(photo, joints, so, s->seg);
            s->mode = "auto";
        }
        dv::GarmentOptions go;
        go.wrinkles.person_height_m = opt.height_m;
        s->garments = dv::describe_garments(photo, s->seg, joints, so.table, go, so.hint);
        s->image = image_path;
        s->photo = photo;
        s->width = photo.cols;
        s->height = photo.rows;
        s->height_m = opt.height_m;
        *out_segmentation = s.release();
        return DRAPE_OK;
    });
}

void drape_segmentation_destroy(drape_segmentation segmentation) { delete segmentation; }

drape_status drape_segmentation_get_size(drape_segmentation s, int32_t* width, int32_t* height) {
    DRAPE_REQUIRE_ARG(s, "segmentation must not be NULL");
    if (width) *width = s->width;
    if (height) *height = s->height;
    return DRAPE_OK;
}

drape_status drape_segmentation_get_labels(drape_segmentation s, uint8_t* out, size_t capacity, size_t* required) {
    DRAPE_REQUIRE_ARG(s, "segmentation must not be NULL");
    return guarded(__func__, [&, function = __func__] { return copy_image(s->seg.labels, out, capacity, required, function); });
}

drape_status drape_segmentation_get_occlusion(drape_segmentation s, uint8_t* out, size_t capacity, size_t* required) {
    DRAPE_REQUIRE_ARG(s, "segmentation must not be NULL");
    return guarded(__func__, [&, function = __func__] { return copy_image(s->seg.occlusion, out, capacity, required, function); });
}

drape_status drape_segmentation_garments_json(drape_segmentation s, char** out_json) {
    DRAPE_REQUIRE_ARG(s, "segmentation must not be NULL");
    DRAPE_REQUIRE_ARG(out_json, "out_json must not be NULL");
    *out_json = nullptr;
    return guarded(__func__, [&] {
        *out_json = copy_string(
            drape::io::garments_json(s->garments, s->summary, s->image, s->width, s->height, s->mode, s->height_m)
                .dump(2));
        return DRAPE_OK;
    });
}

drape_status drape_segmentation_export_labels(drape_segmentation s, const char* path) {
    DRAPE_REQUIRE_ARG(s, "segmentation must not be NULL");
    DRAPE_REQUIRE_ARG(path, "path must not be NULL");
    return guarded(__func__, [&] {
        const std::filesystem::path p(path);
        if (p.extension() != ".png") throw drape::InvalidInput("path '" + p.string() + "' must end in .png");
        drape::io::write_png(p, s->seg.labels);
        return DRAPE_OK;
    });
}

drape_status drape_segmentation_write_folder(drape_segmentation s, const char* folder) {
    DRAPE_REQUIRE_ARG(s, "segmentation must not be NULL");
    DRAPE_REQUIRE_ARG(folder, "folder must not be NULL");
    return guarded(__func__, [&] {
        drape::io::write_segmentation_folder(folder, s->photo, s->seg, s->summary, s->garments, s->image, s->mode,
                                             s->height_m);
        return DRAPE_OK;
    });
}

}  // extern "C"
