// Garment type from mask geometry relative to the joints.
#pragma once

#include <drape/vision/garment_type.hpp>
#include <drape/vision/joints.hpp>

#include <opencv2/core.hpp>

namespace drape::vision {

/// Measurements the classifier uses (also reported as features).
struct GarmentShapeCues {
    /// Longest run of garment pixels from the shoulder down the arm (shoulder -> elbow ->
    /// hand polyline, sampled every pixel), as a fraction of the arm length; max of both arms.
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
};

/// Measures the cues of a garment mask (CV_8UC1, non-zero = garment); connected pieces
/// smaller than 15 % of the largest are ignored (here and in measure_features).
GarmentShapeCues measure_shape_cues(const cv::Mat& mask, const Joints& joints);

/// Upper garment: tank top if sleeve_fraction < 0.12, long-sleeve top if >= 0.6, else t-shirt.
GarmentType classify_upper(const GarmentShapeCues& cues);
/// Lower garment: pants if hem_fraction >= 0.75; otherwise skirt if between_legs_fraction
/// >= 0.5, else shorts.
GarmentType classify_lower(const GarmentShapeCues& cues);

}  // namespace drape::vision
