// Image files for the CLI and the C API (drape::io; the estimation libraries see drape::body::Mask):
// photos with their EXIF orientation applied, binary masks and label maps from PNG,
// atomic PNG writing and the fit overlay.
#pragma once

#include <drape/body/camera.hpp>
#include <drape/body/skeleton.hpp>

#include <opencv2/core.hpp>

#include <Eigen/Core>

#include <filesystem>
#include <string>
#include <vector>

namespace drape::io {

/// Reads a photo as 8-bit BGR, rotated upright by its EXIF orientation (cv::IMREAD_COLOR).
/// \throw drape::IoError naming the file if it is missing or not a decodable image.
cv::Mat read_photo(const std::filesystem::path& path);

/// Reads a binary mask: any non-zero grey value is inside.
/// \param what names the mask in error messages ("silhouette", "skin").
/// \throw drape::IoError (unreadable), drape::InvalidInput (no pixel set).
body::Mask read_mask(const std::filesystem::path& path, const std::string& what);

/// Masks derived from a class-id label map (8-bit single-channel PNG, labels.txt ids of
/// the Fashionista / Clothing Co-Parsing datasets).
struct LabelMasks {
    body::Mask person;  ///< every class except those of kNotPersonLabels
    body::Mask skin;    ///< class 41 "skin"
};
/// Classes that are not the body or the clothes on it: null (background), accessories,
/// bag, hair, hat, purse, wallet. Hair and hat are excluded because they extend beyond the
/// skull; bags, purses and wallets because they hang off the body.
inline const std::vector<int> kNotPersonLabels = {0, 1, 2, 19, 20, 33, 56};
inline constexpr int kSkinLabel = 41;
LabelMasks read_label_masks(const std::filesystem::path& path);

/// Converts a mask to an 8-bit image (0 / 255).
cv::Mat to_image(const body::Mask& mask);

/// Writes a PNG atomically (temporary file + rename). \throw drape::IoError.
void write_png(const std::filesystem::path& path, const cv::Mat& image);

/// The photo with the body silhouette (semi-transparent fill + outline) and the fitted
/// joints (filled dots) joined to the input joints (rings) by a line; both in the
/// camera.hpp pixel frame (origin at the top-left corner).
cv::Mat draw_fit_overlay(const cv::Mat& photo, const body::Mask& body,
                         const Eigen::Matrix<double, body::kImageJointCount, 2>& fitted_px,
                         const Eigen::Matrix<double, body::kImageJointCount, 2>& input_px);

}  // namespace drape::io
