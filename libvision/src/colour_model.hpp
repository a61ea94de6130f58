// Colour models of the segmentation: smoothed joint RGB histograms (Boykov & Jolly 2001
// style), cheaper than GrabCut's GMMs at the same job, re-estimated every round.
#pragma once

#include <opencv2/core.hpp>

#include <vector>

namespace drape::vision::detail {

/// Bin index of one BGR colour (bins per channel `bins`).
inline int colour_bin(const cv::Vec3b& c, int bins) {
    return ((c[0] * bins / 256) * bins + c[1] * bins / 256) * bins + c[2] * bins / 256;
}

/// Bin index of every pixel of a BGR image (bins per channel `bins`), CV_32S.
cv::Mat colour_bins(const cv::Mat& image_bgr, int bins);

class ColourHistogram {
public:
    explicit ColourHistogram(int bins);
    void add(int bin, double weight = 1.0) { counts_[static_cast<size_t>(bin)] += weight; }
    /// Blurs the histogram with a [1 2 1] kernel per axis, normalises it and turns it into
    /// costs -log(p + floor). An empty histogram gives a flat cost.
    void finish();
    float cost(int bin) const { return costs_[static_cast<size_t>(bin)]; }
    double total() const { return total_; }
    /// Bhattacharyya coefficient of two finished histograms (1 = same distribution).
    double similarity(const ColourHistogram& other) const;

private:
    int bins_;
    std::vector<double> counts_;
    std::vector<double> prob_;
    std::vector<float> costs_;
    double total_ = 0;
};

}  // namespace drape::vision::detail
