#include <drape/vision/garment_features.hpp>

#include <drape/vision/classify_garment.hpp>

#include "mask_geometry.hpp"

#include <drape/core/errors.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace drape::vision {

std::vector<std::pair<std::string, std::pair<double, double>>> GarmentFeatures::list() const {
    std::vector<std::pair<std::string, std::pair<double, double>>> out;
    auto add = [&](const char* name, double px) {
        if (std::isfinite(px) && body_height_px > 0) out.push_back({name, {px, px / body_height_px}});
    };
    add("top_width", top_width_px);
    add("waist_width", waist_width_px);
    add("hip_width", hip_width_px);
    add("hem_width", hem_width_px);
    add("length", length_px);
    add("length_from_waist", length_from_waist_px);
    add("hem_below_shoulders", hem_below_shoulders_px);
    add("sleeve_length", sleeve_length_px);
    add("inseam", inseam_px);
    add("neckline_depth", neckline_depth_px);
    return out;
}

GarmentFeatures measure_features(const cv::Mat& full_mask, GarmentType type, const Joints& j,
                                 const cv::Mat& hiding) {
    using namespace detail;
    require(!full_mask.empty() && full_mask.type() == CV_8UC1, "measure_features: mask must be CV_8UC1");
    require(hiding.empty() || (hiding.type() == CV_8UC1 && hiding.size() == full_mask.size()),
            "measure_features: the hiding mask must be empty or CV_8UC1 of the mask's size");
    const cv::Mat mask = main_pieces(full_mask);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    GarmentFeatures f;
    f.body_height_px = j.body_height_px();
    // Extent: first and last rows at least 5 % as wide as the widest row (and >= 3 px).
    int top = -1, bottom = -1, widest = 0;
    for (int y = 0; y < mask.rows; ++y) widest = std::max(widest, row_width(mask, y));
    for (int y = 0; y < mask.rows; ++y)
        if (row_width(mask, y) >= std::max(3.0, 0.05 * widest)) {
            if (top < 0) top = y;
            bottom = y;
        }
    if (top < 0) {
        f.top_width_px = f.waist_width_px = f.hip_width_px = f.hem_width_px = f.length_px =
            f.length_from_waist_px = f.hem_below_shoulders_px = f.sleeve_length_px = f.inseam_px =
                f.neckline_depth_px = nan;
        return f;
    }
    const GarmentPart part = part_of(type);
    auto width = [&](double y) {
        const int w = row_width(mask, int(std::floor(y)));
        return w > 0 ? double(w) : nan;
    };
    f.length_px = bottom - top + 1;
    f.top_width_px = width(top + 0.05 * f.length_px);
    const double waist_y = j.mid_shoulder().y() + 0.62 * (j.mid_hip().y() - j.mid_shoulder().y());
    f.waist_width_px = width(waist_y);
    f.hip_width_px = width(j.mid_hip().y());
    const int hem_row = int(std::floor(bottom - 0.03 * f.length_px));
    int runs = 0;
    const int hem_w = row_width(mask, hem_row, &runs);
    const bool legs = type == GarmentType::pants || type == GarmentType::shorts;
    f.hem_width_px = hem_w > 0 ? (legs && runs >= 2 ? hem_w / double(runs) : double(hem_w)) : nan;
    f.length_from_waist_px = bottom + 0.5 > waist_y ? bottom + 0.5 - waist_y : nan;
    const double shoulder_y = j.mid_shoulder().y();
    f.hem_below_shoulders_px = bottom + 0.5 > shoulder_y ? bottom + 0.5 - shoulder_y : nan;
    f.sleeve_length_px = nan;
    f.neckline_depth_px = nan;
    f.inseam_px = nan;
    if (part != GarmentPart::lower) {
        f.sleeve_length_px = sleeve_runs(mask, j, hiding).max_run_px();
        const Eigen::Vector2d neck = j[Joint::neck];
        for (double y = neck.y(); y < j.mid_hip().y(); y += 1.0)
            if (covered(mask, {neck.x(), y}, 1)) { f.neckline_depth_px = y - neck.y(); break; }
    }
    if (legs) {
        for (double y = j.mid_hip().y(); y <= bottom; y += 1.0)
            if (!covered(mask, between_legs(j, y), 1)) { f.inseam_px = bottom + 0.5 - y; break; }
    }
    return f;
}

}  // namespace drape::vision
