#include <drape/vision/image_io.hpp>

#include "encoded_image_check.hpp"

#include <drape/core/errors.hpp>

#include <opencv2/imgcodecs.hpp>

#include <fstream>
#include <iterator>
#include <system_error>
#include <vector>

namespace drape::vision {

bool ImageLimits::is_valid(std::string* why) const {
    auto fail = [&](const char* m) { if (why) *why = m; return false; };
    if (max_width_px <= 0) return fail("max_width_px must be > 0");
    if (max_height_px <= 0) return fail("max_height_px must be > 0");
    if (max_pixels <= 0) return fail("max_pixels must be > 0");
    if (max_file_bytes <= 0) return fail("max_file_bytes must be > 0");
    if (min_side_px < 1) return fail("min_side_px must be >= 1");
    return true;
}

namespace {

/// The size limits of `limits` (valid) for an image of `size`.
void check_size(const cv::Size& size, const std::string& what, const ImageLimits& limits) {
    require(size.width <= limits.max_width_px && size.height <= limits.max_height_px &&
                static_cast<std::int64_t>(size.width) * size.height <= limits.max_pixels,
            what, " is too large: ", size.width, " x ", size.height, " px (limits ",
            limits.max_width_px, " x ", limits.max_height_px, ", ", limits.max_pixels,
            " pixels)");
    require(size.width >= limits.min_side_px && size.height >= limits.min_side_px, what,
            " is too small: ", size.width, " x ", size.height, " px (min side ",
            limits.min_side_px, ")");
}

}  // namespace

void check_image(const cv::Mat& image, int type, const std::string& what,
                 const ImageLimits& limits) {
    std::string why;
    require(limits.is_valid(&why), "ImageLimits: ", why);
    require(!image.empty(), what, " is empty");
    require(image.type() == type, what, " has OpenCV type ", image.type(), ", expected ",
            type == CV_8UC3 ? "8-bit 3-channel (BGR)" : "8-bit single-channel");
    check_size(image.size(), what, limits);
}

namespace {

cv::Mat read(const std::filesystem::path& path, int flags, const std::string& what,
             const ImageLimits& limits) {
    std::string why;
    require(limits.is_valid(&why), "ImageLimits: ", why);
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec))
        throw IoError("cannot read " + what + " '" + path.string() + "': file missing");
    const auto bytes = std::filesystem::file_size(path, ec);
    if (ec) throw IoError("cannot read " + what + " '" + path.string() + "': " + ec.message());
    require(static_cast<std::int64_t>(bytes) <= limits.max_file_bytes, what, " '",
            path.string(), "' is too large: ", bytes, " bytes (limit ", limits.max_file_bytes,
            ")");
    // Read once: the encoded structure is checked first (a JPEG cut short decodes without
    // an error, the missing rows gray), then the same bytes are decoded (imdecode applies
    // the EXIF orientation as imread does).
    std::ifstream in(path, std::ios::binary);
    if (!in) throw IoError("cannot read " + what + " '" + path.string() + "': cannot open the file");
    const std::vector<std::uint8_t> encoded((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (in.bad()) throw IoError("cannot read " + what + " '" + path.string() + "': read error");
    const std::string defect = detail::encoded_image_defect(encoded.data(), encoded.size());
    if (!defect.empty()) throw IoError("cannot read " + what + " '" + path.string() + "': " + defect);
    // The size limits hold before any pixel is decoded: a 100000 x 100000 header in a
    // 100-byte file must not make the decoder allocate 30 GB. Only formats whose header
    // we read are decoded (docs/hardening.md, "Resource limits").
    const detail::EncodedImageHeader header = detail::encoded_image_header(encoded.data(), encoded.size());
    if (header.format.empty())
        throw IoError("cannot read " + what + " '" + path.string() + "': not a PNG or JPEG file (Drape reads only those)");
    if (header.width <= 0 || header.height <= 0)
        throw IoError("cannot read " + what + " '" + path.string() + "': corrupt " + header.format +
                      ": no image dimensions in its header");
    require(header.width <= limits.max_width_px && header.height <= limits.max_height_px &&
                header.width * header.height <= limits.max_pixels,
            what, " '", path.string(), "' is too large: ", header.width, " x ", header.height, " px in its ",
            header.format, " header (limits ", limits.max_width_px, " x ", limits.max_height_px, ", ",
            limits.max_pixels, " pixels)");
    cv::Mat image;
    try {
        image = cv::imdecode(encoded, flags);
    } catch (const cv::Exception& e) {
        throw IoError("cannot read " + what + " '" + path.string() + "': " + e.what());
    }
    if (image.empty())
        throw IoError("cannot read " + what + " '" + path.string() +
                      "': not a readable image (PNG, JPEG, ...) or larger than OpenCV's limit");
    return image;
}

}  // namespace

cv::Mat load_image(const std::filesystem::path& path, const ImageLimits& limits) {
    // IMREAD_COLOR applies the EXIF orientation (IMREAD_IGNORE_ORIENTATION is not set).
    cv::Mat image = read(path, cv::IMREAD_COLOR, "photo", limits);
    check_image(image, CV_8UC3, "photo '" + path.string() + "'", limits);
    return image;
}

cv::Mat load_image_unchanged(const std::filesystem::path& path, const std::string& what,
                             const ImageLimits& limits) {
    cv::Mat image = read(path, cv::IMREAD_UNCHANGED, what, limits);
    require(image.depth() == CV_8U && (image.channels() == 1 || image.channels() == 3 || image.channels() == 4),
            what, " '", path.string(), "' must be an 8-bit image with 1, 3 or 4 channels (got ",
            image.channels(), " channel(s), depth code ", image.depth(), ")");
    check_size(image.size(), what + " '" + path.string() + "'", limits);
    return image;
}

cv::Mat load_label_map(const std::filesystem::path& path, const std::string& what,
                       const ImageLimits& limits) {
    cv::Mat map = read(path, cv::IMREAD_UNCHANGED, what, limits);
    require(map.type() == CV_8UC1, what, " '", path.string(),
            "' must be an 8-bit single-channel PNG of class ids (got ", map.channels(),
            " channel(s), depth code ", map.depth(), ")");
    check_image(map, CV_8UC1, what + " '" + path.string() + "'", limits);
    return map;
}

}  // namespace drape::vision
