#include <drape/vision/image_io.hpp>

#include <drape/core/errors.hpp>

#include "test_paths.hpp"

#include <catch2/catch.hpp>
#include <opencv2/imgcodecs.hpp>

#include <fstream>

using namespace drape;
using namespace drape::vision;

namespace {

/// A JPEG whose EXIF block says "rotate 90 degrees clockwise to view" (orientation 6).
std::vector<std::uint8_t> jpeg_with_orientation(const cv::Mat& img, std::uint16_t orientation) {
    std::vector<std::uint8_t> jpg;
    REQUIRE(cv::imencode(".jpg", img, jpg));
    // APP1: "Exif\0\0" + little-endian TIFF header + IFD0 with one entry (0x0112 SHORT).
    std::vector<std::uint8_t> tiff = {'I', 'I', 42, 0, 8, 0, 0, 0,  // header, IFD at 8
                                      1, 0,                          // one entry
                                      0x12, 0x01, 3, 0, 1, 0, 0, 0,  // tag, type SHORT, count 1
                                      std::uint8_t(orientation), 0, 0, 0,
                                      0, 0, 0, 0};                   // no next IFD
    const char exif[6] = {'E', 'x', 'i', 'f', 0, 0};
    const std::size_t len = sizeof(exif) + tiff.size() + 2;
    std::vector<std::uint8_t> out;
    out.reserve(jpg.size() + len + 4);
    for (std::uint8_t b : {std::uint8_t(0xFF), std::uint8_t(0xD8), std::uint8_t(0xFF),
                           std::uint8_t(0xE1), std::uint8_t(len >> 8), std::uint8_t(len & 0xFF)})
        out.push_back(b);
    for (char c : exif) out.push_back(std::uint8_t(c));
    for (std::uint8_t b : tiff) out.push_back(b);
    for (std::size_t i = 2; i < jpg.size(); ++i) out.push_back(jpg[i]);  // skip the original SOI
    return out;
}

void write_bytes(const std::filesystem::path& p, const std::vector<std::uint8_t>& b) {
    std::ofstream f(p, std::ios::binary);
    f.write(reinterpret_cast<const char*>(b.data()), std::streamsize(b.size()));
}

}  // namespace

TEST_CASE("load_image applies the EXIF orientation", "[vision][image]") {
    const auto dir = test::scratch_dir("vision_exif");
    cv::Mat img(40, 60, CV_8UC3, cv::Scalar(20, 20, 20));
    img(cv::Rect(0, 0, 10, 10)).setTo(cv::Scalar(250, 250, 250));  // bright top-left corner
    write_bytes(dir / "plain.jpg", jpeg_with_orientation(img, 1));
    write_bytes(dir / "rotated.jpg", jpeg_with_orientation(img, 6));
    const cv::Mat plain = load_image(dir / "plain.jpg");
    CHECK(plain.cols == 60);
    CHECK(plain.rows == 40);
    const cv::Mat rotated = load_image(dir / "rotated.jpg");
    REQUIRE(rotated.cols == 40);
    REQUIRE(rotated.rows == 60);
    // Rotating 90 degrees clockwise moves the top-left corner to the top-right.
    CHECK(rotated.at<cv::Vec3b>(3, 36)[0] > 200);
    CHECK(rotated.at<cv::Vec3b>(3, 3)[0] < 60);
}

TEST_CASE("load_image rejects missing, broken and oversized files clearly", "[vision][image][errors]") {
    const auto dir = test::scratch_dir("vision_bad_images");
    CHECK_THROWS_AS(load_image(dir / "missing.jpg"), IoError);
    write_bytes(dir / "broken.jpg", {0xFF, 0xD8, 0xFF, 0x00, 1, 2, 3});
    CHECK_THROWS_AS(load_image(dir / "broken.jpg"), IoError);
    cv::imwrite((dir / "big.png").string(), cv::Mat(300, 200, CV_8UC3, cv::Scalar(1, 2, 3)));
    ImageLimits limits;
    limits.max_pixels = 10000;
    try {
        load_image(dir / "big.png", limits);
        FAIL("expected InvalidInput");
    } catch (const InvalidInput& e) {
        CHECK(std::string(e.what()).find("too large: 200 x 300") != std::string::npos);
    }
    limits = ImageLimits{};
    limits.max_file_bytes = 10;
    CHECK_THROWS_AS(load_image(dir / "big.png", limits), InvalidInput);
    CHECK(load_image(dir / "big.png").cols == 200);
    // A colour PNG is not a label map.
    CHECK_THROWS_WITH(load_label_map(dir / "big.png", "strokes"),
                      Catch::Contains("8-bit single-channel"));
}

TEST_CASE("truncated or damaged JPEG and PNG files are refused, naming the file", "[vision][image]") {
    const auto dir = test::scratch_dir("vision_truncated");
    cv::Mat img(120, 90, CV_8UC3);
    cv::randu(img, cv::Scalar::all(0), cv::Scalar::all(255));  // noise: long entropy-coded data
    std::vector<std::uint8_t> jpg, png;
    REQUIRE(cv::imencode(".jpg", img, jpg));
    REQUIRE(cv::imencode(".png", img, png));
    REQUIRE(jpg.size() > 4000);
    write_bytes(dir / "whole.jpg", jpg);
    write_bytes(dir / "whole.png", png);
    CHECK(load_image(dir / "whole.jpg").size() == img.size());
    CHECK(load_image(dir / "whole.png").size() == img.size());
    // Bytes after the end-of-image marker are ignored, as decoders do.
    std::vector<std::uint8_t> padded = jpg;
    padded.insert(padded.end(), {0, 0, 0, 0});
    write_bytes(dir / "padded.jpg", padded);
    CHECK_NOTHROW(load_image(dir / "padded.jpg"));

    const auto refused = [&](const std::string& name, const std::vector<std::uint8_t>& bytes,
                             const std::string& defect) {
        INFO(name);
        write_bytes(dir / name, bytes);
        try {
            load_image(dir / name);
            FAIL("accepted");
        } catch (const IoError& e) {
            const std::string msg = e.what();
            CHECK(msg.find(name) != std::string::npos);
            CHECK(msg.find(defect) != std::string::npos);
        }
    };
    // Cut inside the scan data (OpenCV alone decodes this, gray below the cut), inside the
    // headers, and just before the end-of-image marker.
    refused("cut_3000.jpg", {jpg.begin(), jpg.begin() + 3000}, "truncated JPEG");
    refused("cut_100.jpg", {jpg.begin(), jpg.begin() + 100}, "truncated JPEG");
    refused("cut_eoi.jpg", {jpg.begin(), jpg.end() - 2}, "truncated JPEG");
    refused("cut.png", {png.begin(), png.begin() + long(png.size() / 2)}, "truncated PNG");
    refused("no_iend.png", {png.begin(), png.end() - 12}, "truncated PNG");
    std::vector<std::uint8_t> flipped = png;
    flipped[png.size() / 2] ^= 0x10;  // a bit inside the image data
    refused("flipped.png", flipped, "CRC mismatch");
    // The stroke and label readers check the same way.
    std::vector<std::uint8_t> gray_png;
    REQUIRE(cv::imencode(".png", cv::Mat(40, 40, CV_8UC1, cv::Scalar(255)), gray_png));
    write_bytes(dir / "strokes_cut.png", {gray_png.begin(), gray_png.end() - 20});
    CHECK_THROWS_AS(load_label_map(dir / "strokes_cut.png", "strokes"), IoError);
    CHECK_THROWS_AS(load_image_unchanged(dir / "strokes_cut.png", "strokes"), IoError);
}
