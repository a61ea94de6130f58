// Simulated strokes: erode each region, thin it to its medial axis, draw the longest
// geodesic paths through the axis (docs/vision.md, "Simulated strokes").
#include <drape/vision/strokes.hpp>

#include <drape/vision/label_table.hpp>

#include "thinning.hpp"

#include <drape/core/errors.hpp>

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <deque>

namespace drape::vision {

bool StrokeOptions::is_valid(std::string* why) const {
    auto fail = [&](const char* m) { if (why) *why = m; return false; };
    if (!(erosion_fraction >= 0)) return fail("erosion_fraction must be >= 0");
    if (!(min_region_fraction >= 0)) return fail("min_region_fraction must be >= 0");
    if (max_strokes_per_region < 1) return fail("max_strokes_per_region must be >= 1");
    if (!(min_stroke_fraction >= 0)) return fail("min_stroke_fraction must be >= 0");
    if (stroke_width_px < 1) return fail("stroke_width_px must be >= 1");
    if (!(max_marked_fraction > 0 && max_marked_fraction <= 1))
        return fail("max_marked_fraction must be in (0, 1]");
    return true;
}

namespace {

/// BFS over 8-connected set pixels of `img` from `start`; returns the farthest pixel and
/// fills `parent` (index y * cols + x, -1 for the start).
cv::Point bfs(const cv::Mat& img, cv::Point start, std::vector<int>& parent,
              std::vector<int>& dist) {
    std::fill(dist.begin(), dist.end(), -1);
    std::deque<cv::Point> q{start};
    dist[static_cast<size_t>(start.y * img.cols + start.x)] = 0;
    parent[static_cast<size_t>(start.y * img.cols + start.x)] = -1;
    cv::Point far = start;
    int far_d = 0;
    while (!q.empty()) {
        const cv::Point p = q.front();
        q.pop_front();
        const int d = dist[static_cast<size_t>(p.y * img.cols + p.x)];
        if (d > far_d) { far_d = d; far = p; }
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                const cv::Point n(p.x + dx, p.y + dy);
                if ((!dx && !dy) || n.x < 0 || n.y < 0 || n.x >= img.cols || n.y >= img.rows)
                    continue;
                const size_t k = static_cast<size_t>(n.y * img.cols + n.x);
                if (!img.at<std::uint8_t>(n) || dist[k] >= 0) continue;
                dist[k] = d + 1;
                parent[k] = p.y * img.cols + p.x;
                q.push_back(n);
            }
    }
    return far;
}

struct Stroke {
    int id = 0;
    bool first = false;
    std::vector<cv::Point> pixels;  ///< full-image coordinates
};

/// Longest geodesic paths through the skeleton `skel` (cropped, offset `origin`).
void medial_strokes(cv::Mat skel, cv::Point origin, int id, int max_strokes, double min_len,
                    std::vector<Stroke>& out) {
    const size_t n = static_cast<size_t>(skel.rows) * static_cast<size_t>(skel.cols);
    std::vector<int> parent(n), dist(n);
    for (int s = 0; s < max_strokes; ++s) {
        // Longest path over every connected piece of the remaining axis.
        std::vector<cv::Point> best;
        cv::Mat seen = cv::Mat::zeros(skel.size(), CV_8UC1);
        for (int y = 0; y < skel.rows; ++y)
            for (int x = 0; x < skel.cols; ++x) {
                if (!skel.at<std::uint8_t>(y, x) || seen.at<std::uint8_t>(y, x)) continue;
                const cv::Point a = bfs(skel, {x, y}, parent, dist);
                for (size_t k = 0; k < n; ++k)
                    if (dist[k] >= 0) seen.data[k] = 1;
                const cv::Point b = bfs(skel, a, parent, dist);
                if (dist[static_cast<size_t>(b.y * skel.cols + b.x)] + 1 <=
                    static_cast<int>(best.size()))
                    continue;
                best.clear();
                for (int k = b.y * skel.cols + b.x; k >= 0; k = parent[static_cast<size_t>(k)])
                    best.emplace_back(k % skel.cols, k / skel.cols);
            }
        if (best.empty() || (s > 0 && static_cast<double>(best.size()) < min_len)) break;
        Stroke st;
        st.id = id;
        st.first = s == 0;
        for (const auto& p : best) {
            st.pixels.push_back(p + origin);
            // Remove the path and its neighbours so the next stroke takes another branch.
            cv::rectangle(skel, cv::Rect(p.x - 1, p.y - 1, 3, 3), cv::Scalar(0), cv::FILLED);
        }
        out.push_back(std::move(st));
    }
}

}  // namespace

cv::Mat simulate_strokes(const cv::Mat& labels, const StrokeOptions& options) {
    std::string why;
    require(options.is_valid(&why), "StrokeOptions: ", why);
    require(!labels.empty() && labels.type() == CV_8UC1,
            "simulate_strokes: labels must be a non-empty 8-bit single-channel class map");
    const double diag = std::hypot(labels.cols, labels.rows);
    const int r = std::max(1, static_cast<int>(std::lround(options.erosion_fraction * diag)));
    const cv::Mat kernel = cv::getStructuringElement(cv::MORPH_ELLIPSE, {2 * r + 1, 2 * r + 1});
    const double min_area = options.min_region_fraction * labels.total();
    const double min_len = options.min_stroke_fraction * diag;

    std::vector<Stroke> strokes;
    bool present[256] = {};
    for (auto it = labels.begin<std::uint8_t>(); it != labels.end<std::uint8_t>(); ++it)
        present[*it] = true;
    for (int id = 0; id < kUnmarked; ++id) {
        if (!present[id]) continue;
        const cv::Mat mask = labels == id;
        cv::Mat comp, stats, centroids;
        const int n = cv::connectedComponentsWithStats(mask, comp, stats, centroids, 8, CV_32S);
        for (int c = 1; c < n; ++c) {
            if (stats.at<int>(c, cv::CC_STAT_AREA) < min_area) continue;
            const cv::Rect box(stats.at<int>(c, cv::CC_STAT_LEFT), stats.at<int>(c, cv::CC_STAT_TOP),
                               stats.at<int>(c, cv::CC_STAT_WIDTH),
                               stats.at<int>(c, cv::CC_STAT_HEIGHT));
            // Crop with a frame of 1 px so thinning never touches the crop's border.
            const cv::Rect padded(box.x - 1, box.y - 1, box.width + 2, box.height + 2);
            cv::Mat region = cv::Mat::zeros(padded.size(), CV_8UC1);
            const cv::Rect inside = padded & cv::Rect(0, 0, labels.cols, labels.rows);
            cv::Mat sub = comp(inside) == c;
            sub.copyTo(region(inside - padded.tl()));
            cv::Mat eroded;
            cv::erode(region, eroded, kernel, {-1, -1}, 1, cv::BORDER_CONSTANT, cv::Scalar(0));
            if (cv::countNonZero(eroded) == 0) eroded = region;  // thin region: stroke its axis
            eroded = eroded / 255;
            // Keep the zero frame after erosion.
            eroded.row(0).setTo(0); eroded.row(eroded.rows - 1).setTo(0);
            eroded.col(0).setTo(0); eroded.col(eroded.cols - 1).setTo(0);
            detail::thin(eroded);
            medial_strokes(eroded, padded.tl(), id, options.max_strokes_per_region, min_len,
                           strokes);
        }
    }
    // Every region's first stroke first, then longer before shorter, until the budget.
    std::stable_sort(strokes.begin(), strokes.end(), [](const Stroke& a, const Stroke& b) {
        if (a.first != b.first) return a.first;
        return a.pixels.size() > b.pixels.size();
    });
    cv::Mat out(labels.size(), CV_8UC1, cv::Scalar(kUnmarked));
    const double budget = options.max_marked_fraction * labels.total();
    int marked = 0;
    const int w = options.stroke_width_px;
    for (const Stroke& st : strokes) {
        cv::Mat draw(labels.size(), CV_8UC1, cv::Scalar(0));
        for (const auto& p : st.pixels) {
            if (w == 1) draw.at<std::uint8_t>(p) = 255;
            else cv::circle(draw, p, (w - 1) / 2, cv::Scalar(255), cv::FILLED);
        }
        draw &= (labels == st.id);     // never mark a pixel of another class
        draw &= (out == kUnmarked);
        const int add = cv::countNonZero(draw);
        if (marked + add > budget) continue;
        out.setTo(st.id, draw);
        marked += add;
    }
    return out;
}

double marked_fraction(const cv::Mat& strokes) {
    if (strokes.empty()) return 0;
    return static_cast<double>(cv::countNonZero(strokes != kUnmarked)) / strokes.total();
}

}  // namespace drape::vision
