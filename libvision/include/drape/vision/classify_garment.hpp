// Garment type from mask geometry relative to the joints.
#pragma once

#include <drape/vision/garment_type.hpp>
#include <drape/vision/joints.hpp>
#include <drape/vision/label_table.hpp>

#include <opencv2/core.hpp>

namespace drape::vision {

/// Measurements the classifier uses (also reported as features).
struct GarmentShapeCues {
    /// Longest run of garment from the shoulder down the arm (shoulder -> elbow -> hand
    /// polyline, sampled every pixel), as a fraction of the arm length; max of both arms.
    /// A point of the arm is covered when the garment lies on the arm line and on its outer
    /// half, 1.5 % of the body height beside it away from the torso (a sleeve wraps the
    /// arm; a torso next to a hanging arm touches one side). Hair or occluders on the arm
    /// line (measure_shape_cues' `hiding`) neither grow nor end the run.
    double sleeve_fraction = 0;
    /// Lowest garment row (98th percentile) below the mid-hip, as a fraction of the
    /// mid-hip -> mid-ankle height (0 at the hips, 1 at the ankles).
    double hem_fraction = 0;
    /// Highest garment row (2nd percentile) relative to hips: 0 at the hips, 1 at the
    /// shoulders (> 0.6: reaches the chest).
    double top_fraction = 0;
    /// Fraction of rows in the lower 40 % of the garment below the crotch whose mid-point
    /// between the legs is garment (1: one tube, a skirt; 0: two legs, pants/shorts).
    double between_legs_fraction = 0;
    /// How far the garment reaches continuously down the legs: each leg line (hip ->
    /// knee -> ankle) is walked down row by row from the hip row while the garment covers it
    /// (disc radius 0.4 % of the body height, gaps up to 3 % bridged); the mean of the two
    /// lowest rows, as a fraction of the mid-hip -> mid-ankle height like hem_fraction.
    /// Unlike hem_fraction it ignores garment pieces below a stretch of bare leg (boots,
    /// shadows or bag pixels merged into the garment).
    double leg_fraction = 0;
    /// Garment pixels per row at the knee row over the widest row of the upper thighs
    /// (20-40 % of hip -> knee), each averaged over +-1 % of the body height of rows:
    /// ~0.5-0.8 for trousers (legs narrow from thigh to knee), >= 1 for a skirt that
    /// reaches the knees. 0 when the garment does not reach the knee row.
    double knee_width_ratio = 0;
};

/// Measures the cues of a garment mask (CV_8UC1, non-zero = garment); connected pieces
/// smaller than 15 % of the largest are ignored (here and in measure_features).
/// \param hiding optional CV_8UC1 mask of the mask's size (empty = none) of pixels that may
///        hide the garment (hair, occluders; sleeve_hiding_mask): where one lies on an
///        arm's line the sleeve run neither grows nor breaks (long hair over a shoulder
///        does not end the sleeve that shows below it).
GarmentShapeCues measure_shape_cues(const cv::Mat& mask, const Joints& joints,
                                    const cv::Mat& hiding = cv::Mat());

/// Pixels of a label map (CV_8UC1 class ids) whose class may hide a sleeve: hair and
/// occluders (LabelRole::hair, LabelRole::occluder), as CV_8UC1 0/255.
cv::Mat sleeve_hiding_mask(const cv::Mat& labels, const LabelTable& table);

/// Upper garment: tank top if sleeve_fraction < 0.12, long-sleeve top if >= 0.6, else t-shirt.
GarmentType classify_upper(const GarmentShapeCues& cues);
/// Lower garment: a long garment (hem_fraction >= 0.75 and leg_fraction >= 0.4: long, and
/// reaching at least near the knees without a gap) is a skirt if knee_width_ratio > 1.1
/// (wider at the knees than at the thighs), else pants; otherwise shorts if between_legs_fraction < 0.5
/// (two legs) or leg_fraction < 0.25 (the hem ends above mid-thigh, the range of shorts),
/// else skirt. Straight (pencil) maxi skirts are reported as pants (docs/vision.md).
GarmentType classify_lower(const GarmentShapeCues& cues);

}  // namespace drape::vision
