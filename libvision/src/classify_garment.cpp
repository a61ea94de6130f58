#include <drape/vision/classify_garment.hpp>

#include "mask_geometry.hpp"

#include <drape/core/errors.hpp>

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <functional>

namespace drape::vision {

namespace detail {

cv::Mat main_pieces(const cv::Mat& mask, double fraction) {
    cv::Mat comp, stats, cent;
    const int n = cv::connectedComponentsWithStats(mask != 0, comp, stats, cent, 8, CV_32S);
    int largest = 0;
    for (int c = 1; c < n; ++c) largest = std::max(largest, stats.at<int>(c, cv::CC_STAT_AREA));
    cv::Mat out = cv::Mat::zeros(mask.size(), CV_8UC1);
    for (int c = 1; c < n; ++c)
        if (stats.at<int>(c, cv::CC_STAT_AREA) >= fraction * largest) out.setTo(255, comp == c);
    return out;
}

bool covered(const cv::Mat& mask, const Eigen::Vector2d& p, int radius) {
    const int cx = int(std::floor(p.x())), cy = int(std::floor(p.y()));
    for (int y = std::max(0, cy - radius); y <= std::min(mask.rows - 1, cy + radius); ++y)
        for (int x = std::max(0, cx - radius); x <= std::min(mask.cols - 1, cx + radius); ++x)
            if (mask.at<std::uint8_t>(y, x) && (x - cx) * (x - cx) + (y - cy) * (y - cy) <= radius * radius)
                return true;
    return false;
}

int row_percentile(const cv::Mat& mask, double q) {
    std::vector<long> per_row(static_cast<size_t>(mask.rows), 0);
    long total = 0;
    for (int y = 0; y < mask.rows; ++y) {
        per_row[static_cast<size_t>(y)] = cv::countNonZero(mask.row(y));
        total += per_row[static_cast<size_t>(y)];
    }
    if (total == 0) return -1;
    const double target = q * double(total);
    long acc = 0;
    for (int y = 0; y < mask.rows; ++y) {
        acc += per_row[static_cast<size_t>(y)];
        if (acc >= target && acc > 0) return y;
    }
    return mask.rows - 1;
}

int row_width(const cv::Mat& mask, int y, int* runs) {
    if (runs) *runs = 0;
    if (y < 0 || y >= mask.rows) return 0;
    const auto* r = mask.ptr<std::uint8_t>(y);
    int w = 0;
    bool in = false;
    for (int x = 0; x < mask.cols; ++x) {
        if (r[x]) {
            ++w;
            if (!in && runs) ++*runs;
            in = true;
        } else {
            in = false;
        }
    }
    return w;
}

double mean_row_width(const cv::Mat& mask, double yc, const Joints& j) {
    const int band = std::max(1, int(std::lround(0.01 * j.body_height_px())));
    double sum = 0;
    int n = 0;
    for (int y = int(yc) - band; y <= int(yc) + band; ++y, ++n) sum += row_width(mask, y);
    return sum / std::max(1, n);
}

double upper_thigh_width(const cv::Mat& mask, const Joints& j) {
    const double hip_y = j.mid_hip().y(), knee_y = j.mid_knee().y();
    double widest = 0;
    for (double y = hip_y + 0.2 * (knee_y - hip_y); y <= hip_y + 0.4 * (knee_y - hip_y); y += 1.0)
        widest = std::max(widest, mean_row_width(mask, y, j));
    return widest;
}

double polyline_x_at(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                     const Eigen::Vector2d& c, double y) {
    auto on = [y](const Eigen::Vector2d& p, const Eigen::Vector2d& q) {
        if (std::abs(q.y() - p.y()) < 1e-9) return p.x();
        const double t = std::clamp((y - p.y()) / (q.y() - p.y()), 0.0, 1.0);
        return p.x() + t * (q.x() - p.x());
    };
    return y <= b.y() ? on(a, b) : on(b, c);
}

Eigen::Vector2d between_legs(const Joints& j, double y) {
    const double xr = polyline_x_at(j[Joint::right_hip], j[Joint::right_knee], j[Joint::right_ankle], y);
    const double xl = polyline_x_at(j[Joint::left_hip], j[Joint::left_knee], j[Joint::left_ankle], y);
    return {0.5 * (xr + xl), y};
}

namespace {

/// Walks a curve `at(s)`, s = 0, 1, ... length px, and returns the last s where the mask
/// covers it (disc of `radius`) before a gap longer than `max_gap` (0 if none).
double covered_run(const cv::Mat& mask, double length, int radius, double max_gap,
                   const std::function<Eigen::Vector2d(double)>& at) {
    double run = 0, gap_start = -1;
    for (double s = 0; s <= length; s += 1.0) {
        if (covered(mask, at(s), radius)) {
            run = s;
            gap_start = -1;
        } else {
            if (gap_start < 0) gap_start = s;
            if (s - gap_start > max_gap) break;
        }
    }
    return run;
}

}  // namespace

double ArmRuns::max_fraction() const {
    double best = 0;
    for (int k = 0; k < 2; ++k)
        if (length_px[k] > 0) best = std::max(best, run_px[k] / length_px[k]);
    return best;
}

bool arm_point(const Eigen::Vector2d& shoulder, const Eigen::Vector2d& elbow, const Eigen::Vector2d& hand,
               double s, Eigen::Vector2d& point, Eigen::Vector2d* direction) {
    const double l1 = (elbow - shoulder).norm();
    const bool upper = s <= l1;
    const Eigen::Vector2d from = upper ? shoulder : elbow, to = upper ? elbow : hand;
    const double len = (to - from).norm();
    if (len <= 0) return false;
    const Eigen::Vector2d d = (to - from) / len;
    point = from + d * (upper ? s : s - l1);
    if (direction) *direction = d;
    return true;
}

ArmRuns sleeve_runs(const cv::Mat& mask, const Joints& j, const cv::Mat& hiding) {
    const double H = j.body_height_px();
    const int radius = std::max(1, int(std::lround(0.008 * H)));
    const double max_gap = 0.02 * H, beside = 0.015 * H;
    // "Outward" = away from the torso's centre (half-way between mid-shoulder and mid-hip).
    const Eigen::Vector2d centre = 0.5 * (j.mid_shoulder() + j.mid_hip());
    const Joint arms[2][3] = {{Joint::right_shoulder, Joint::right_elbow, Joint::right_hand},
                              {Joint::left_shoulder, Joint::left_elbow, Joint::left_hand}};
    ArmRuns out;
    for (int k = 0; k < 2; ++k) {
        const Eigen::Vector2d a = j[arms[k][0]], b = j[arms[k][1]], c = j[arms[k][2]];
        const double l1 = (b - a).norm(), l2 = (c - b).norm();
        out.length_px[k] = l1 + l2;
        double run = 0, gap_start = -1;
        for (double s = 0; s <= l1 + l2; s += 1.0) {
            Eigen::Vector2d p, d;
            if (!arm_point(a, b, c, s, p, &d)) continue;
            Eigen::Vector2d n(-d.y(), d.x());
            if (n.dot(p - centre) < 0) n = -n;
            if (covered(mask, p, radius) && covered(mask, p + beside * n, radius)) {
                run = s;
                gap_start = -1;
            } else if (!hiding.empty() && covered(hiding, p, 0)) {
                gap_start = -1;  // hidden, not bare: unknown, the walk goes on
            } else {
                if (gap_start < 0) gap_start = s;
                if (s - gap_start > max_gap) break;
            }
        }
        out.run_px[k] = run;
    }
    return out;
}

}  // namespace detail

cv::Mat sleeve_hiding_mask(const cv::Mat& labels, const LabelTable& table) {
    require(!labels.empty() && labels.type() == CV_8UC1, "sleeve_hiding_mask: labels must be CV_8UC1");
    cv::Mat out = cv::Mat::zeros(labels.size(), CV_8UC1);
    for (size_t i = 0; i < labels.total(); ++i) {
        const LabelRole r = table.role(labels.data[i]);
        if (r == LabelRole::hair || r == LabelRole::occluder) out.data[i] = 255;
    }
    return out;
}

GarmentShapeCues measure_shape_cues(const cv::Mat& full_mask, const Joints& j, const cv::Mat& hiding) {
    using namespace detail;
    require(!full_mask.empty() && full_mask.type() == CV_8UC1, "measure_shape_cues: mask must be CV_8UC1");
    require(hiding.empty() || (hiding.type() == CV_8UC1 && hiding.size() == full_mask.size()),
            "measure_shape_cues: the hiding mask must be empty or CV_8UC1 of the mask's size");
    const cv::Mat mask = main_pieces(full_mask);
    GarmentShapeCues c;
    const double H = j.body_height_px();
    const int radius = std::max(1, int(std::lround(0.008 * H)));
    c.sleeve_fraction = sleeve_runs(mask, j, hiding).max_fraction();
    const double hip_y = j.mid_hip().y(), ankle_y = j.mid_ankle().y(),
                 sh_y = j.mid_shoulder().y();
    const int bottom = row_percentile(mask, 0.98), top = row_percentile(mask, 0.02);
    if (bottom < 0) return c;
    c.hem_fraction = (bottom + 0.5 - hip_y) / std::max(1.0, ankle_y - hip_y);
    c.top_fraction = (hip_y - (top + 0.5)) / std::max(1.0, hip_y - sh_y);
    // Between the legs, over the lower 40 % of the garment below the crotch.
    const double crotch = hip_y + 0.15 * (j.mid_knee().y() - hip_y);
    const double y0 = std::max(crotch, bottom - 0.4 * (bottom - std::max<double>(top, hip_y)));
    int rows = 0, hits = 0;
    for (int y = int(std::ceil(y0)); y <= bottom - 0.03 * (bottom - top); ++y) {
        ++rows;
        if (covered(mask, between_legs(j, y + 0.5), radius)) ++hits;
    }
    c.between_legs_fraction = rows > 0 ? double(hits) / rows : 0.0;
    // Walks down the two leg lines.
    const int walk_radius = std::max(1, int(std::lround(0.004 * H)));
    const double walk_gap = 0.03 * H;
    // A walk starts where the garment first covers the leg line at or below the hip row: a
    // top hanging over the hips, or hands or a bag in front, hide the garment's upper part
    // (a lower garment's waistband lies above the hip joints), and a walk from the hip row
    // stopped there (pants under a long top read as shorts).
    auto walk = [&](Joint hip, Joint knee, Joint ankle) {
        const auto at = [&](double s) -> Eigen::Vector2d {
            return {polyline_x_at(j[hip], j[knee], j[ankle], hip_y + s), hip_y + s};
        };
        double s0 = 0;
        while (hip_y + s0 <= bottom && !covered(mask, at(s0), walk_radius)) s0 += 1.0;
        if (hip_y + s0 > bottom) return hip_y;
        return hip_y + s0 +
               covered_run(mask, mask.rows - 1 - hip_y - s0, walk_radius, walk_gap, [&](double s) { return at(s0 + s); });
    };
    const double legs = 0.5 * (walk(Joint::right_hip, Joint::right_knee, Joint::right_ankle) +
                               walk(Joint::left_hip, Joint::left_knee, Joint::left_ankle));
    c.leg_fraction = (legs - hip_y) / std::max(1.0, ankle_y - hip_y);
    // Width at the knee row over the widest row of the upper thighs (20-40 % of hip -> knee,
    // below where a top hanging over the hips or hands in pockets hide the garment's
    // sides), each width a mean over +-1 % H of rows.
    const double thigh_width = upper_thigh_width(mask, j);
    c.knee_width_ratio = thigh_width > 0 ? mean_row_width(mask, j.mid_knee().y(), j) / thigh_width : 0.0;
    return c;
}

GarmentType classify_upper(const GarmentShapeCues& c) {
    if (c.sleeve_fraction < 0.12) return GarmentType::tank_top;
    if (c.sleeve_fraction >= 0.6) return GarmentType::long_sleeve_top;
    return GarmentType::t_shirt;
}

GarmentType classify_lower(const GarmentShapeCues& c) {
    // Long garments are pants: standing legs often touch, so the between-legs cue cannot
    // tell them from a maxi skirt (a known confusion, docs/vision.md). "Long" also needs
    // the garment to run down the legs to near the knees: a garment whose lowest pixels
    // reach the ankles only through pieces below bare legs (boots) is short.
    if (c.hem_fraction >= 0.75 && c.leg_fraction >= 0.4) {
        // ... unless it widens from the thighs to the knees: trouser legs follow the legs,
        // which narrow from thigh to knee (two knees side by side are ~0.7-0.8 of the two
        // thighs' width; straight and wide-leg cuts stay near 1), while a skirt hangs from
        // the hips and keeps or gains width downwards. 1.1: wider at the knees by 10 %.
        return c.knee_width_ratio > 1.1 ? GarmentType::skirt : GarmentType::pants;
    }
    if (c.between_legs_fraction < 0.5) return GarmentType::shorts;
    // Standing legs touch, so short garments rarely show a crotch gap: a hem above
    // mid-thigh (0.25 of hips -> ankles, i.e. about 20 cm below the hip joints) is the
    // range of shorts (crotch + inseam), a skirt from the waist ends lower.
    return c.leg_fraction < 0.25 ? GarmentType::shorts : GarmentType::skirt;
}

}  // namespace drape::vision
