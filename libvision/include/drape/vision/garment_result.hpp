// Everything libvision reports per garment: type, silhouette polygons, sizing features,
// wrinkle density and how much of it is hidden.
#pragma once

#include <drape/vision/classify_garment.hpp>
#include <drape/vision/garment_features.hpp>
#include <drape/vision/garment_type.hpp>
#include <drape/vision/joints.hpp>
#include <drape/vision/segmentation.hpp>
#include <drape/vision/wrinkle_density.hpp>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include <string>
#include <vector>

namespace drape::vision {

/// One connected piece of a silhouette: outer boundary and holes, image frame pixels
/// (pixel centres at +0.5), each `#points x 2`, outer counter-clockwise on screen... as
/// cv::findContours returns them (outer and holes have opposite orientation).
struct SilhouettePiece {
    Eigen::Matrix<double, Eigen::Dynamic, 2> outer;
    std::vector<Eigen::Matrix<double, Eigen::Dynamic, 2>> holes;
};

struct GarmentOptions {
    WrinkleOptions wrinkles;
    /// Douglas-Peucker tolerance of the polygons, fraction of the body height (0 = exact).
    double polygon_tolerance_fraction = 0.002;
    /// Garment classes covering less than this fraction of the image are ignored.
    double min_area_fraction = 0.002;

    bool is_valid(std::string* why = nullptr) const;
};

struct GarmentResult {
    int label_id = 0;             ///< class id in the label map
    std::string class_name;       ///< its name in the table
    GarmentType type = GarmentType::t_shirt;
    std::vector<SilhouettePiece> silhouette;
    GarmentShapeCues cues;
    GarmentFeatures features;
    WrinkleSummary wrinkles;
    std::vector<Fold> folds;
    int area_px = 0;
    /// Hidden part: occluded pixels inside the garment's outline / (garment + those).
    double occlusion_fraction = 0;
};

/// Describes every garment of a parse. Garment types come from `seg.garment_types` when
/// listed there, else from the class (dress/skirt/pants/jeans/shorts/leggings by name,
/// upper garments by the sleeve cue; `hint` overrides garments of its part).
/// \return one entry per garment class present, largest first; empty = no garment found.
/// \throw drape::InvalidInput on mismatched sizes or invalid options.
std::vector<GarmentResult> describe_garments(const cv::Mat& image_bgr, const Segmentation& seg,
                                             const Joints& joints, const LabelTable& table,
                                             const GarmentOptions& options,
                                             const std::optional<GarmentType>& hint = {});

/// Garment type of a labelled garment class (see describe_garments); `hiding` as for
/// measure_shape_cues.
GarmentType garment_type_of_class(const cv::Mat& mask, int label_id, const LabelTable& table,
                                  const Joints& joints, const cv::Mat& hiding = cv::Mat());

}  // namespace drape::vision
