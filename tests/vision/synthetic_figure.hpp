// A drawn standing figure for the vision tests: its 14 joints, a ground-truth label map
// (labels.txt ids) and a photo rendered from it with flat colours, a little shading and noise.
#pragma once

#include <drape/vision/joints.hpp>

#include <opencv2/core.hpp>

namespace drape::test {

struct SyntheticFigure {
    vision::Joints joints;
    cv::Mat labels;  ///< CV_8UC1: 0 background, 19 hair, 41 skin, 51 t-shirt, 42 skirt (or 31 pants)
    cv::Mat photo;   ///< CV_8UC3
};

enum class Bottom { skirt, pants };

/// A 400 x 600 figure (scaled by `scale`), t-shirt with short sleeves and a skirt or pants.
SyntheticFigure make_figure(Bottom bottom = Bottom::skirt, double scale = 1.0);

/// Paints `periods` vertical sinusoidal shading folds (+-`contrast` of the colour) across
/// the bounding box of `mask` into `photo`.
void paint_folds(cv::Mat& photo, const cv::Mat& mask, int periods, double contrast);

}  // namespace drape::test
