// Image-space sizing features of one garment, to initialise its sewing-pattern parameters
// (docs/vision.md defines each one). Pixels in the image frame, plus the same values
// divided by the body height in pixels (Joints::body_height_px), which makes them
// independent of the photo's resolution; multiply by the stature to get metres.
#pragma once

#include <drape/vision/garment_type.hpp>
#include <drape/vision/joints.hpp>

#include <opencv2/core.hpp>

#include <string>
#include <utility>
#include <vector>

namespace drape::vision {

/// NaN marks a feature that does not apply to the garment (e.g. inseam of a skirt) or
/// could not be measured (the row is outside the garment).
struct GarmentFeatures {
    double body_height_px = 0;     ///< the normaliser
    /// Rows: the garment spans the first to the last row at least 5 % as wide as its widest
    /// row; widths count the garment pixels on a row.
    double top_width_px = 0;       ///< width 5 % of the garment's height below its top row
    double waist_width_px = 0;     ///< width at the natural waist row (62 % shoulder -> hip)
    double hip_width_px = 0;       ///< width at the hip-joint row
    double hem_width_px = 0;       ///< width 3 % above the lowest row; per leg for pants/shorts
    double length_px = 0;          ///< top row to lowest row of the garment
    double length_from_waist_px = 0;  ///< natural waist row to lowest row
    /// Shoulder line (the shoulder joints' mean row) to the lowest row: the length of a top
    /// or dress whatever the arms do (raised arms lift the top row to the elbows).
    double hem_below_shoulders_px = 0;
    double sleeve_length_px = 0;   ///< upper/dress: covered arm length from the shoulder
    double inseam_px = 0;          ///< pants/shorts: crotch row to hem row
    double neckline_depth_px = 0;  ///< upper/dress: neck joint down to the first garment row
                                   ///< on the body's mid-line

    /// (name, px, normalised) for every feature, NaN-free entries only; names as in the
    /// fields without "_px".
    std::vector<std::pair<std::string, std::pair<double, double>>> list() const;
};

/// Measures the features of a garment mask (CV_8UC1, non-zero = garment) of the given type.
/// \param hiding as for measure_shape_cues (the sleeve length bridges hair and occluders).
GarmentFeatures measure_features(const cv::Mat& mask, GarmentType type, const Joints& joints,
                                 const cv::Mat& hiding = cv::Mat());

}  // namespace drape::vision
