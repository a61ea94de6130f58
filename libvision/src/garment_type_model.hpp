#pragma once
// Learned garment-type decisions of the automatic segmentation (docs/vision.md, "Garment
// type from mask geometry"): appearance and geometry features of the refined upper and
// lower regions, and small multinomial logistic models over them, trained by
// tools/train_garment_types.cpp on the tuning part of photos-dev and the 30 shared photos
// (coefficients in garment_type_model_data.cpp, generated).
#include <drape/vision/garment_type.hpp>
#include <drape/vision/joints.hpp>

#include <opencv2/core.hpp>

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace drape::vision::detail {

/// Features of "one dress or two pieces?" on the upper and lower regions.
inline constexpr int kDressFeatureCount = 10;
inline constexpr std::array<const char*, kDressFeatureCount> kDressFeatureNames = {
    "similarity_all",   // Bhattacharyya coefficient, 8x8x8 Lab histograms, regions without the waist band
    "similarity_band",  // the same, bands of 8 % H above / below the upper-lower boundary
    "lab_distance_band",  // distance of the bands' mean Lab (8-bit units)
    "lab_distance_all",   // distance of the regions' mean Lab (without the waist band)
    "waist_edge",         // vertical Lab step across the boundary / the garment's mean step
    "boundary_height",    // boundary row, 0 shoulders .. 1 hips
    "hem_fraction",       // the lower region's hem (classify_garment.hpp)
    "upper_share",        // upper area / (upper + lower)
    "texture_difference", // |std L upper - std L lower| / (sum + 1)
    "contact"};           // share of the torso's columns where upper meets lower

/// Features of the lower garment's type (skirt, pants, shorts).
inline constexpr int kLowerFeatureCount = 10;
inline constexpr std::array<const char*, kLowerFeatureCount> kLowerFeatureNames = {
    "hem_fraction", "leg_fraction", "between_legs_fraction", "knee_width_ratio",
    "width_25",      // width at 25 % hips -> ankles / the widest upper-thigh row
    "width_50",      // ... at 50 %
    "width_75",      // ... at 75 %
    "hem_width",     // width 3 % above the lowest row / the widest upper-thigh row
    "runs",          // mean pieces per row from the crotch down
    "midline_edge"}; // horizontal Lab step on the line between the legs / the garment's mean

std::array<double, kDressFeatureCount> dress_features(const cv::Mat& image_bgr, const cv::Mat& upper,
                                                      const cv::Mat& lower, const Joints& joints);
std::array<double, kLowerFeatureCount> lower_features(const cv::Mat& image_bgr, const cv::Mat& lower,
                                                      const Joints& joints, const cv::Mat& hiding);

/// A multinomial logistic model on standardised features: class scores
/// bias[c] + sum_k weight[c][k] * (x[feature[k]] - mean[k]) / scale[k].
struct LinearTypeModel {
    std::vector<GarmentType> classes;  ///< empty: no trained model (use the rules)
    std::vector<int> features;
    std::vector<double> mean, scale;
    std::vector<std::vector<double>> weight;
    std::vector<double> bias;
    bool trained() const { return !classes.empty(); }
    /// Class probabilities for a full feature vector.
    std::vector<double> probabilities(const double* x) const;
};

/// The embedded models (garment_type_model_data.cpp). The dress model's classes are
/// {dress, t_shirt} (t_shirt standing for "two pieces").
extern const LinearTypeModel kDressModel;
extern const LinearTypeModel kLowerModel;
extern const char* const kTypeModelProvenance;

/// Dress when p(dress) > 2/3: a two-piece outfit read as a dress loses both garments, a
/// dress read as two pieces one, so 2 (1 - p) < p is the decision of fewest expected errors.
inline constexpr double kDressDecision = 2.0 / 3.0;

/// The trained decisions; nullopt when the model is the untrained bootstrap.
std::optional<bool> learned_is_dress(const cv::Mat& image_bgr, const cv::Mat& upper, const cv::Mat& lower,
                                     const Joints& joints);
std::optional<GarmentType> learned_lower_type(const cv::Mat& image_bgr, const cv::Mat& lower,
                                              const Joints& joints, const cv::Mat& hiding);

}  // namespace drape::vision::detail
