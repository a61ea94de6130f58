#include <drape/vision/segmentation_score.hpp>

#include <drape/core/errors.hpp>

namespace drape::vision {

cv::Mat role_mask(const cv::Mat& labels, const LabelTable& table, LabelRole role) {
    require(labels.type() == CV_8UC1, "role_mask: labels must be CV_8UC1 class ids, got type ", labels.type());
    cv::Mat m = cv::Mat::zeros(labels.size(), CV_8UC1);
    for (int y = 0; y < labels.rows; ++y) {
        const std::uint8_t* in = labels.ptr<std::uint8_t>(y);
        std::uint8_t* out = m.ptr<std::uint8_t>(y);
        for (int x = 0; x < labels.cols; ++x)
            if (table.role(in[x]) == role) out[x] = 255;
    }
    return m;
}

double iou(const cv::Mat& a, const cv::Mat& b) {
    require(a.size() == b.size(), "iou: masks must have the same size, got ", a.cols, " x ", a.rows, " and ",
            b.cols, " x ", b.rows);
    require(a.channels() == 1 && b.channels() == 1, "iou: masks must have one channel, got ", a.channels(),
            " and ", b.channels());
    const cv::Mat in_a = a != 0, in_b = b != 0;
    const int u = cv::countNonZero(in_a | in_b);
    return u > 0 ? double(cv::countNonZero(in_a & in_b)) / u : 1.0;
}

}  // namespace drape::vision
