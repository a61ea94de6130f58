// Multi-label graph cut on the pixel grid (or any graph of pixels): alpha-expansion (Boykov, Veksler & Zabih 2001)
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

/// The same energy on any graph: `nodes` variables, unary (node * labels + label) and Potts
/// edges (from, to, weight). Neighbours held fixed fold into the unary terms.
struct GraphEnergy {
    int nodes = 0, labels = 0;
    std::vector<float> unary;
    std::vector<int> edge_from, edge_to;
    std::vector<float> edge_weight;
};

/// GrabCut's beta = 1 / (2 <|dc|^2>) over the 4-neighbour pairs of a BGR image (0 if flat).
double contrast_beta(const cv::Mat& image_bgr);

/// Fills the pairwise weights of `e` from the image (CV_8UC3 of e.width x e.height):
/// gamma * exp(-beta |dc|^2) / distance, beta = 1 / (2 <|dc|^2>) as in GrabCut.
void set_contrast_weights(const cv::Mat& image_bgr, double gamma, GridEnergy& e);

/// Total energy of a labelling.
double energy(const GridEnergy& e, const std::vector<std::uint8_t>& labels);

/// Runs `cycles` sweeps of expansions over every label, improving `labels` (values in
/// 0..e.labels-1) in place. Returns the final energy.
double alpha_expansion(const GridEnergy& e, std::vector<std::uint8_t>& labels, int cycles);

/// Total energy of a labelling of a GraphEnergy.
double energy(const GraphEnergy& e, const std::vector<std::uint8_t>& labels);

/// alpha_expansion on a GraphEnergy (the grid version converts to this one).
double alpha_expansion(const GraphEnergy& e, std::vector<std::uint8_t>& labels, int cycles);

}  // namespace drape::vision::detail
