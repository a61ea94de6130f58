// JSON and files of the vision commands (segment, eval-segment, strokes): the 14-joint
// file reader for libvision and the garments.json writer. The library sees typed joints.
#pragma once

#include <drape/vision/classify_garment.hpp>
#include <drape/vision/garment_result.hpp>
#include <drape/vision/joints.hpp>
#include <drape/vision/segmentation.hpp>
#include <drape/vision/strokes.hpp>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace drape::io {

/// Reads a 14-joint file (../shared/data/photos/joints format): {"joints": [[x, y] x 14],
/// optional "joint_names" (must be the Fashionista order), "image_size" [w, h] (must match
/// width x height), "pixel_origin": one_based (default) | zero_based | corner}, and returns
/// the joints in libvision's image frame. `*shift` receives the offset added to the file's
/// values (to write coordinates back in the file's convention: subtract it).
/// \throw drape::IoError (unreadable), drape::InvalidInput naming the file and field.
vision::Joints read_vision_joints(const std::filesystem::path& file, int width, int height,
                                  double* shift = nullptr);

/// garments.json: {"format": "drape.garments", "version": 1, "image": {...},
/// "segmentation": {...}, "garments": [...]} (docs/vision.md). Polygon coordinates are
/// written in the libvision image frame (pixel centres at +0.5).
nlohmann::json garments_json(const std::vector<vision::GarmentResult>& garments,
                             const vision::SegmentationSummary& summary,
                             const std::string& image_file, int width, int height,
                             const std::string& mode, double person_height_m);

/// The shape cues of a garment (classify_garment.hpp) as a JSON object.
nlohmann::json cues_json(const vision::GarmentShapeCues& cues);

/// A stroke palette file: {"tolerance": 40 (optional), "colours": {"<class name of
/// labels.txt>": "#rrggbb", ...}} (docs/vision.md, "Colour-coded strokes"), which replaces
/// the default palette; an empty `file` gives the default palette.
/// \throw drape::IoError (unreadable), drape::InvalidInput naming the file and the field
/// (unknown class, bad colour, colours too close).
vision::StrokePalette read_stroke_palette(const std::filesystem::path& file, const vision::LabelTable& table);

/// Writes the folder of `drape segment` (docs/vision.md, "CLI"): labels.png (class ids),
/// occlusion.png, overlay.png (the labels over the photo), folds.png (each garment's folds)
/// and garments.json (garments_json), staged in a folder inside `out` and moved in only once
/// all are written, so a failure leaves `out` as it was. Shared by the CLI and the C API.
/// \param photo the 8-bit BGR photo that was segmented
/// \throw drape::IoError naming the file or folder.
void write_segmentation_folder(const std::filesystem::path& out, const cv::Mat& photo,
                               const vision::Segmentation& segmentation, const vision::SegmentationSummary& summary,
                               const std::vector<vision::GarmentResult>& garments, const std::string& image_file,
                               const std::string& mode, double person_height_m);

/// Creates `dir` (and parents). \throw drape::IoError when it cannot.
void make_output_dir(const std::filesystem::path& dir);

}  // namespace drape::io
