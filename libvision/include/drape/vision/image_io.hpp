// Reading photos and label maps for libvision, with the EXIF orientation applied and size
// limits checked, so that a corrupt or enormous file gives a clear error instead of a crash
// or an out-of-memory kill.
#pragma once

#include <drape/core/limits.hpp>

#include <opencv2/core.hpp>

#include <cstdint>
#include <filesystem>
#include <string>

namespace drape::vision {

/// Limits on the images libvision reads. Defaults allow any ordinary photo.
struct ImageLimits {
    int max_width_px = limits::kMaxImageSidePx;                ///< > 0
    int max_height_px = limits::kMaxImageSidePx;               ///< > 0
    std::int64_t max_pixels = limits::kMaxImagePixels;         ///< > 0, width x height
    std::int64_t max_file_bytes = limits::kMaxImageFileBytes;  ///< > 0, checked before reading
    int min_side_px = 16;                     ///< >= 1; smaller images are rejected

    bool is_valid(std::string* why = nullptr) const;
};

/// Reads a photo as 8-bit 3-channel BGR, rotated upright by its EXIF orientation.
/// A JPEG or PNG must be complete and intact: a file cut short (no end-of-image marker, a
/// chunk past the end) or with a damaged PNG chunk (CRC) is refused, since the decoders
/// would fill the missing part with gray without an error. Only PNG and JPEG are read:
/// their header's dimensions are checked against `limits` before any pixel is decoded (a
/// forged header cannot make the decoder allocate). The same holds for the readers below.
/// \throw drape::IoError naming the file when it is missing, unreadable, truncated or
///        damaged (naming the defect) or not a PNG or JPEG; drape::InvalidInput when it breaks
///        `limits` (naming the size and the limit).
cv::Mat load_image(const std::filesystem::path& path, const ImageLimits& limits = {});

/// Reads a class-id map (8-bit single-channel PNG, ids of LabelTable) or a stroke map
/// (same, 255 = unmarked). EXIF orientation is not applied: PNG maps have none.
/// \param what names the map in messages ("labels", "strokes").
/// \throw drape::IoError (missing/unreadable), drape::InvalidInput (not 8-bit 1-channel,
///        or breaking `limits`).
cv::Mat load_label_map(const std::filesystem::path& path, const std::string& what,
                       const ImageLimits& limits = {});

/// Reads an 8-bit image with its channels as stored (1 gray, 3 BGR or 4 BGRA), no EXIF
/// rotation: for stroke maps. \throw drape::IoError (missing/unreadable),
/// drape::InvalidInput (16-bit or other formats, breaking `limits`).
cv::Mat load_image_unchanged(const std::filesystem::path& path, const std::string& what,
                             const ImageLimits& limits = {});

/// Checks an in-memory image against `limits` and type (CV_8UC3 or CV_8UC1 as `type`).
/// \throw drape::InvalidInput naming `what`, the size and the broken limit.
void check_image(const cv::Mat& image, int type, const std::string& what,
                 const ImageLimits& limits = {});

}  // namespace drape::vision
