// Bare arms mistaken for sleeves: garment pixels along an arm that have the colour of the
// person's skin rather than of the garment's torso (automatic segmentation).
#pragma once

#include <drape/vision/joints.hpp>

#include <opencv2/core.hpp>

namespace drape::vision {

/// Garment pixels along the arms that belong to a bare arm, not to a sleeve.
///
/// A sleeve is cut from the garment's fabric, so along the arm it has the chromaticity of
/// the garment's torso; a bare arm has the chromaticity of the person's skin elsewhere.
/// Chromaticity (CIELAB a*, b*) rather than the full colour: an arm is lit differently from
/// the torso and the face (an over-exposed forearm is far lighter than the face), but
/// shading and exposure change mostly the lightness L*. For each arm, the garment pixels
/// within the arm's half-width (2.5 % of the body height; an arm is ~5 % H wide) of the arm
/// line over the garment's sleeve run (detail::sleeve_runs, from the shoulder) and outside
/// the torso quad (shoulders, hips) are compared by their median (a*, b*) with the median
/// of the garment inside the torso quad and with the median of the skin pixels. The arm is
/// bare when its median lies at least 10 units (ΔE*ab in the a*b* plane; about 4 just
/// noticeable differences: clearly another colour) from the garment's and at most half as
/// far from the skin's; then the arm's band pixels nearer the skin's median than the
/// garment's are returned (fabric on that band, e.g. the torso's side, stays garment).
/// Each median needs at least (2.5 % H)^2 pixels (one arm-width square); otherwise the
/// arm, or the whole check, is skipped.
///
/// \param photo   CV_8UC3 BGR photo.
/// \param garment CV_8UC1 mask of the upper garment (or the upper part of a dress), photo size.
/// \param skin    CV_8UC1 mask of the skin pixels, photo size.
/// \param joints  image-frame joints of the photo.
/// \param hiding  optional CV_8UC1 mask (photo size, empty = none) of hair and occluders,
///                as for measure_shape_cues (the sleeve run is measured the same way).
/// \return CV_8UC1 0/255 mask of the garment pixels that are bare arm (a subset of `garment`).
/// \throw drape::InvalidInput on empty or mismatched masks or a wrong photo type.
cv::Mat bare_arm_pixels(const cv::Mat& photo, const cv::Mat& garment, const cv::Mat& skin,
                        const Joints& joints, const cv::Mat& hiding = cv::Mat());

}  // namespace drape::vision
