// Structural checks of an encoded image before it is decoded. OpenCV's decoders accept a
// JPEG cut short (libjpeg warns on stderr and fills the missing rows with gray) and some
// damaged PNGs; a photo read that way gives a silently wrong segmentation and body fit.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace drape::vision::detail {

/// Why `bytes` (a whole file) is not a complete JPEG or PNG, or "" when it is, or when it
/// is neither format (other formats are left to the decoder).
///
/// JPEG: the marker segments are walked from the start-of-image marker, every
/// entropy-coded scan is skipped to its next marker, and an end-of-image marker (FFD9)
/// must be reached before the file ends (anything after it is ignored, as decoders do).
/// PNG: every chunk must lie inside the file and carry a matching CRC-32, up to IEND.
std::string encoded_image_defect(const std::uint8_t* bytes, std::size_t size);

/// The format and pixel dimensions an encoded image declares in its header, read without
/// decoding (PNG: the IHDR chunk, which must come first; JPEG: the first start-of-frame
/// segment before the first scan). `format` is "PNG", "JPEG" or "" (another format, or a
/// header too short to tell); width and height are -1 when not found.
struct EncodedImageHeader {
    std::string format;
    std::int64_t width = -1;
    std::int64_t height = -1;
};
EncodedImageHeader encoded_image_header(const std::uint8_t* bytes, std::size_t size);

}  // namespace drape::vision::detail
