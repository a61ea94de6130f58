// Multi-label graph cut on the pixel grid: alpha-expansion (Boykov, Veksler & Zabih 2001)
// with a contrast-sensitive Potts term, each expansion solved by OpenCV's max-flow
// (cv::detail::GCGraph, the solver behind cv::grabCut).
#pragma once

#include <opencv2/core.hpp>

#include <vector>

namespace drape::vision::detail {

struct GridEnergy {
    int width = 0, height = 0, labels = 0;
    /// Data costs, (y * width + x) * labels + label.
    std::vector<float> unary;
    /// Pairwise Potts weights to the right, down, down-right and down-left neighbours.
    std::vector<float> w_right, w_down, w_down_right, w_down_left;
};

/// Fills the pairwise weights of `e` from the image (CV_8UC3 of e.width x e.height):
/// gamma * exp(-beta |dc|^2) / distance, beta = 1 / (2 <|dc|^2>) as in GrabCut.
void set_contrast_weights(const cv::Mat& image_bgr, double gamma, GridEnergy& e);

/// Total energy of a labelling.
double energy(const GridEnergy& e, const std::vector<std::uint8_t>& labels);

/// Runs `cycles` sweeps of expansions over every label, improving `labels` (values in
/// 0..e.labels-1) in place. Returns the final energy.
double alpha_expansion(const GridEnergy& e, std::vector<std::uint8_t>& labels, int cycles);

}  // namespace drape::vision::detail
