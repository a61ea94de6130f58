#include <drape/io/image_io.hpp>

#include <drape/core/atomic_file.hpp>
#include <drape/core/errors.hpp>
#include <drape/vision/image_io.hpp>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>

namespace drape::io {

namespace {

body::Mask to_mask(const cv::Mat& gray) {
    body::Mask m;
    m.width = gray.cols;
    m.height = gray.rows;
    m.pixels.resize(static_cast<size_t>(m.width) * static_cast<size_t>(m.height));
    for (int y = 0; y < gray.rows; ++y) {
        const auto* row = gray.ptr<std::uint8_t>(y);
        for (int x = 0; x < gray.cols; ++x)
            m.pixels[static_cast<size_t>(y) * m.width + x] = row[x] != 0 ? 1 : 0;
    }
    return m;
}

}  // namespace

cv::Mat read_photo(const std::filesystem::path& path) { return vision::load_image(path); }

body::Mask read_mask(const std::filesystem::path& path, const std::string& what) {
    // Read like the photo (EXIF orientation, size limits), then to one channel.
    // Any size: a mask of the wrong size gets its own message against the photo's.
    vision::ImageLimits limits;
    limits.min_side_px = 1;
    cv::Mat colour;
    try {
        colour = vision::load_image(path, limits);
    } catch (const IoError& e) {
        throw IoError(what + " mask: " + e.what());
    } catch (const InvalidInput& e) {
        throw InvalidInput(what + " mask: " + e.what());
    }
    cv::Mat gray;
    cv::cvtColor(colour, gray, cv::COLOR_BGR2GRAY);
    body::Mask m = to_mask(gray);
    if (m.count() == 0)
        throw InvalidInput(what + " mask '" + path.string() + "' is empty (every pixel is 0)");
    return m;
}

LabelMasks read_label_masks(const std::filesystem::path& path) {
    const cv::Mat labels = vision::load_label_map(path, "label map");
    cv::Mat person(labels.size(), CV_8UC1), skin(labels.size(), CV_8UC1);
    for (int y = 0; y < labels.rows; ++y) {
        for (int x = 0; x < labels.cols; ++x) {
            const int id = labels.at<std::uint8_t>(y, x);
            person.at<std::uint8_t>(y, x) =
                std::find(kNotPersonLabels.begin(), kNotPersonLabels.end(), id) ==
                        kNotPersonLabels.end() ? 255 : 0;
            skin.at<std::uint8_t>(y, x) = id == kSkinLabel ? 255 : 0;
        }
    }
    LabelMasks out{to_mask(person), to_mask(skin)};
    if (out.person.count() == 0)
        throw InvalidInput("label map '" + path.string() + "' has no person pixels");
    return out;
}

cv::Mat to_image(const body::Mask& mask) {
    cv::Mat out(mask.height, mask.width, CV_8UC1);
    for (int y = 0; y < mask.height; ++y)
        for (int x = 0; x < mask.width; ++x) out.at<std::uint8_t>(y, x) = mask.inside(x, y) ? 255 : 0;
    return out;
}

void write_png(const std::filesystem::path& path, const cv::Mat& image) {
    std::vector<std::uint8_t> bytes;
    try {
        if (!cv::imencode(".png", image, bytes))
            throw IoError("cannot encode '" + path.string() + "' as PNG");
    } catch (const cv::Exception& e) {
        throw IoError("cannot encode '" + path.string() + "' as PNG: " + e.what());
    }
    write_text_atomically(path, std::string(bytes.begin(), bytes.end()));
}

cv::Mat draw_fit_overlay(const cv::Mat& photo, const body::Mask& body,
                         const Eigen::Matrix<double, body::kImageJointCount, 2>& fitted_px,
                         const Eigen::Matrix<double, body::kImageJointCount, 2>& input_px) {
    cv::Mat out = photo.clone();
    if (body.width == photo.cols && body.height == photo.rows) {
        const cv::Mat m = to_image(body);
        cv::Mat tint(photo.size(), photo.type(), cv::Scalar(255, 160, 40));
        cv::Mat blended;
        cv::addWeighted(photo, 0.55, tint, 0.45, 0.0, blended);
        blended.copyTo(out, m);
        std::vector<std::vector<cv::Point>> contours;
        cv::findContours(m, contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_NONE);
        cv::drawContours(out, contours, -1, cv::Scalar(255, 120, 0), 2, cv::LINE_AA);
    }
    // cv::Point is integer pixel indices: the pixel containing frame point (u, v) is
    // (floor(u), floor(v)); draw with 4 bits of sub-pixel precision about the centres.
    const int shift = 4;
    auto pt = [&](double u, double v) {
        return cv::Point(static_cast<int>(std::lround((u - 0.5) * (1 << shift))),
                         static_cast<int>(std::lround((v - 0.5) * (1 << shift))));
    };
    const int r = std::max(3, photo.cols / 130);
    for (int i = 0; i < body::kImageJointCount; ++i) {
        const cv::Point a = pt(input_px(i, 0), input_px(i, 1));
        const cv::Point b = pt(fitted_px(i, 0), fitted_px(i, 1));
        cv::line(out, a, b, cv::Scalar(0, 255, 255), 1, cv::LINE_AA, shift);
        cv::circle(out, a, (r + 1) << shift, cv::Scalar(0, 0, 255), 2, cv::LINE_AA, shift);
        cv::circle(out, b, r << shift, cv::Scalar(0, 220, 0), cv::FILLED, cv::LINE_AA, shift);
    }
    return out;
}

}  // namespace drape::io
