// The accuracy measures of recovery, exactly as issue 21 and the paper define them (section
// 7, Tables 1-2), so that figures compare with the paper's: sizing, material and curvature
// accuracy on synthetic scenes, and the mask IoU per garment group on photos.
#pragma once

#include <drape/cloth/material.hpp>
#include <drape/garment/garment_sizing.hpp>

#include <opencv2/core.hpp>

#include <array>
#include <string>
#include <vector>

namespace drape::recover {

/// The relative accuracy of one value: max(0, 1 − |est − gt| / |gt|); 1 when both are 0,
/// 0 when only gt is 0.
double relative_accuracy(double est, double gt);

/// Mean relative_accuracy over the template's G parameters (a dress: both groups).
/// \throw drape::InvalidInput if the types differ.
double sizing_accuracy(const garment::GarmentSizing& est, const garment::GarmentSizing& gt);

/// Mean relative_accuracy over the 15 bending and 24 stretching entries of the simulated
/// material (each table times its scale).
double material_accuracy(const cloth::Material& est, const cloth::Material& gt);

/// |log10(est.bending_scale / gt.bending_scale)|.
double bending_log_error(const cloth::Material& est, const cloth::Material& gt);

/// max(0, 1 − |K_est − K_gt| / K_gt).
double curvature_accuracy(double k_est, double k_gt);

/// One recovered garment against its truth, by the measures above.
struct GarmentScore {
    double sizing = 0;          ///< sizing_accuracy
    double initial_sizing = 0;  ///< sizing_accuracy of the starting sizing (what the search added)
    double material = 0;        ///< material_accuracy
    double bending_log10 = 0;   ///< bending_log_error
    double curvature = 0;       ///< curvature_accuracy
};
/// \throw drape::InvalidInput if the sizing types differ.
GarmentScore score_garment(const garment::GarmentSizing& est, const garment::GarmentSizing& est_initial,
                           const cloth::Material& est_material, double est_k, const garment::GarmentSizing& gt,
                           const cloth::Material& gt_material, double gt_k);

/// The garment groups of the photo evaluation (labels.txt ids).
enum class GarmentGroup { upper, lower, dress };
/// upper = blouse, bodysuit, shirt, sweater, sweatshirt, t-shirt, top (5 6 38 48 49 51 54);
/// lower = jeans, leggings, pants, shorts, skirt (25 27 31 40 42); dress = 14.
const std::vector<int>& group_ids(GarmentGroup g);
std::string group_name(GarmentGroup g);

struct GroupIou {
    GarmentGroup group = GarmentGroup::upper;
    bool counted = false;     ///< the group covers >= 1 % of the photo in the hand labels
    double iou = 0;           ///< of the predicted and labelled group pixels
    double truth_fraction = 0;
    // Where the IoU is lost (0 / NaN when the predicted or the labelled group is empty):
    double precision = 0;     ///< predicted pixels that are labelled the group
    double recall = 0;        ///< labelled pixels that are predicted the group
    /// Predicted minus labelled top row / bottom row, px (> 0: lower in the image). A
    /// group's top (bottom) row is the 2nd (98th) percentile of its pixels' rows, so a few
    /// stray pixels do not move it.
    double top_row_error_px = 0;
    double bottom_row_error_px = 0;
    /// Mean over the rows both cover of predicted minus labelled pixels per row, px (> 0:
    /// the prediction is wider).
    double width_error_px = 0;
    /// What the photo's labels hold where the prediction wrongly has the group, as shares of
    /// the predicted group pixels (they sum to 1 − precision): skin (41), hair (19),
    /// background (0), another garment group, anything else (bags, belts, shoes, ...).
    std::array<double, 5> false_positive_shares{};
    /// What the prediction holds where the labels have the group but the prediction does
    /// not, as shares of the labelled group pixels (they sum to 1 − recall): the body (41),
    /// background (0), another garment group.
    std::array<double, 3> false_negative_shares{};
};

/// Names of GroupIou::false_positive_shares and false_negative_shares, in order.
const std::array<const char*, 5>& false_positive_names();  ///< skin, hair, background, garment, other
const std::array<const char*, 3>& false_negative_names();  ///< body, background, garment

/// Per group, the IoU of a predicted label map (mask.png) against the hand labels, and
/// where it is lost (precision, recall, the top and bottom rows, the width).
/// \throw drape::InvalidInput if the sizes or types (CV_8UC1) differ.
std::array<GroupIou, 3> group_ious(const cv::Mat& predicted, const cv::Mat& truth);

}  // namespace drape::recover
