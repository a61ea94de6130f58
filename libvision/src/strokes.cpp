// Simulated strokes: erode each region, thin it to its medial axis, draw the longest
// geodesic paths through the axis (docs/vision.md, "Simulated strokes").
#include <drape/vision/strokes.hpp>

#include <drape/vision/image_io.hpp>
#include <drape/vision/label_table.hpp>

#include "thinning.hpp"

#include <drape/core/errors.hpp>

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <deque>
#include <map>
#include <random>

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

// ---- Seeded stroke styles: dashes, dots, sloppy (docs/vision.md, "Simulated strokes") ----

const char* to_string(StrokeStyle style) {
    switch (style) {
        case StrokeStyle::dashes: return "dashes";
        case StrokeStyle::dots: return "dots";
        case StrokeStyle::sloppy: return "sloppy";
        case StrokeStyle::medial: break;
    }
    return "medial";
}

StrokeStyle parse_stroke_style(const std::string& text) {
    for (StrokeStyle s : {StrokeStyle::medial, StrokeStyle::dashes, StrokeStyle::dots, StrokeStyle::sloppy})
        if (text == to_string(s)) return s;
    throw InvalidInput("stroke style '" + text + "' is not one of medial, dashes, dots, sloppy");
}

double wrong_mark_fraction(const cv::Mat& strokes, const cv::Mat& labels) {
    require(strokes.type() == CV_8UC1 && labels.type() == CV_8UC1 && strokes.size() == labels.size(),
            "wrong_mark_fraction: strokes and labels must be 8-bit single-channel maps of one size");
    long long marked = 0, wrong = 0;
    for (size_t i = 0; i < strokes.total(); ++i) {
        if (strokes.data[i] == kUnmarked) continue;
        ++marked;
        wrong += strokes.data[i] != labels.data[i];
    }
    return marked > 0 ? double(wrong) / double(marked) : 0.0;
}

namespace {

/// Uniform draws from std::mt19937_64, whose output sequence the standard fixes, so the
/// strokes of a seed are the same on every platform (std's distributions are not).
struct Rng {
    std::mt19937_64 g;
    explicit Rng(std::uint64_t seed) : g(seed) {}
    double uniform() { return double(g() >> 11) * (1.0 / 9007199254740992.0); }
    double uniform(double a, double b) { return a + (b - a) * uniform(); }
    int integer(int a, int b) { return std::min(b, a + int(uniform() * (b - a + 1))); }
    template <class T> void shuffle(std::vector<T>& v) {
        for (size_t i = v.size(); i > 1; --i) std::swap(v[i - 1], v[size_t(integer(0, int(i) - 1))]);
    }
};

/// One connected region (8-connected) of a class: its crop (`box`, padded and clipped to the
/// image), the region's mask in the crop and each crop pixel's distance to the region's
/// outside (0 outside; the image border counts as outside).
struct Region {
    int id = 0;
    cv::Rect box;
    cv::Mat mask;  ///< CV_8UC1, 255 inside
    cv::Mat dist;  ///< CV_32F
    int area = 0;
};

std::vector<Region> regions_of(const cv::Mat& labels, double min_area, int pad) {
    std::vector<Region> out;
    bool present[256] = {};
    for (auto it = labels.begin<std::uint8_t>(); it != labels.end<std::uint8_t>(); ++it) present[*it] = true;
    const cv::Rect frame(0, 0, labels.cols, labels.rows);
    for (int id = 0; id < kUnmarked; ++id) {
        if (!present[id]) continue;
        cv::Mat comp, stats, centroids;
        const int n = cv::connectedComponentsWithStats(labels == id, comp, stats, centroids, 8, CV_32S);
        for (int c = 1; c < n; ++c) {
            const int area = stats.at<int>(c, cv::CC_STAT_AREA);
            if (area < min_area) continue;
            Region r;
            r.id = id;
            r.area = area;
            r.box = cv::Rect(stats.at<int>(c, cv::CC_STAT_LEFT) - pad, stats.at<int>(c, cv::CC_STAT_TOP) - pad,
                             stats.at<int>(c, cv::CC_STAT_WIDTH) + 2 * pad,
                             stats.at<int>(c, cv::CC_STAT_HEIGHT) + 2 * pad) & frame;
            r.mask = comp(r.box) == c;
            // Distance to the outside, the image border included: a 1 px zero frame.
            cv::Mat framed;
            cv::copyMakeBorder(r.mask, framed, 1, 1, 1, 1, cv::BORDER_CONSTANT, cv::Scalar(0));
            cv::Mat d;
            cv::distanceTransform(framed, d, cv::DIST_L2, 3);
            r.dist = d(cv::Rect(1, 1, r.mask.cols, r.mask.rows)).clone();
            out.push_back(std::move(r));
        }
    }
    return out;
}

/// The core of a region: pixels at least `depth` from its outside, or, where none are,
/// those at least half its largest depth.
cv::Mat core_of(const Region& r, double depth) {
    double max_d = 0;
    cv::minMaxLoc(r.dist, nullptr, &max_d);
    return r.dist >= float(std::min(depth, 0.5 * max_d));
}

struct Mark {
    int id = 0;
    /// Order within its region: every region's marks of rank 0 are drawn first (whatever
    /// the budget), then those of rank 1, ...: a person marks every region before adding
    /// more marks anywhere, not most of them in the (largest) background.
    int rank = 0;
    std::vector<cv::Point> own;        ///< pixels inside the region (full-image coordinates)
    std::vector<cv::Point> stray;      ///< pixels past the region's border (sloppy only)
};

/// Horizontal dashes along the rows of `area` (crop of `r`): rows every `row_step` px from
/// a random offset; on each run of the row, dashes of length `len` x U(0.7, 1.3) separated
/// by gaps of `gap` x U(0.5, 1.5), starting at a random offset. The centre line only. When
/// every row misses the area, one dash from the region's deepest pixel rightwards.
std::vector<std::vector<cv::Point>> dash_lines(const Region& r, const cv::Mat& area, double len,
                                               double row_step, double gap, Rng& rng) {
    std::vector<std::vector<cv::Point>> lines;
    for (double yf = rng.uniform(0, row_step); yf < area.rows; yf += row_step) {
        const int y = int(yf);
        const std::uint8_t* row = area.ptr<std::uint8_t>(y);
        for (int x = 0; x < area.cols;) {
            if (!row[x]) { ++x; continue; }
            int b = x;
            while (b + 1 < area.cols && row[b + 1]) ++b;
            // Run [x, b]: dashes along it.
            for (double xf = x + rng.uniform(0, std::min(gap, 0.5 * (b - x))); xf <= b;) {
                const int x0 = int(xf);
                const int x1 = std::min(b, x0 + std::max(1, int(std::lround(len * rng.uniform(0.7, 1.3)))) - 1);
                std::vector<cv::Point> line;
                for (int xx = x0; xx <= x1; ++xx) line.emplace_back(xx + r.box.x, y + r.box.y);
                lines.push_back(std::move(line));
                xf = x1 + 1 + gap * rng.uniform(0.5, 1.5);
            }
            x = b + 1;
        }
    }
    if (lines.empty()) {  // every row missed the area: one dash from its deepest pixel
        cv::Point at;
        cv::minMaxLoc(r.dist, nullptr, nullptr, nullptr, &at);
        std::vector<cv::Point> line;
        for (int x = at.x; x < area.cols && area.at<std::uint8_t>(at.y, x) && x - at.x < len; ++x)
            line.emplace_back(x + r.box.x, at.y + r.box.y);
        if (!line.empty()) lines.push_back(std::move(line));
    }
    return lines;
}

/// The drawing order of a region's dashes: the longest first (rank 0, so that no region
/// is marked by a sliver alone), the others in a seeded random order.
std::vector<int> ranks(const std::vector<std::vector<cv::Point>>& lines, Rng& rng) {
    size_t best = 0;
    for (size_t k = 1; k < lines.size(); ++k)
        if (lines[k].size() > lines[best].size()) best = k;
    std::vector<int> order;
    for (int k = 1; k < int(lines.size()); ++k) order.push_back(k);
    rng.shuffle(order);
    std::vector<int> rank(lines.size(), 0);
    size_t next = 0;
    for (size_t k = 0; k < lines.size(); ++k)
        if (k != best) rank[k] = order[next++];
    return rank;
}

/// Draws marks by rank (ties in a seeded random order) while the marked total stays
/// within the budget; stray pixels are added by the caller.
cv::Mat draw_marks(const cv::Mat& labels, std::vector<Mark>& marks, double budget, Rng& rng,
                   std::vector<size_t>* kept = nullptr) {
    rng.shuffle(marks);
    std::stable_sort(marks.begin(), marks.end(), [](const Mark& a, const Mark& b) { return a.rank < b.rank; });
    cv::Mat out(labels.size(), CV_8UC1, cv::Scalar(kUnmarked));
    double marked = 0;
    for (size_t k = 0; k < marks.size(); ++k) {
        const Mark& m = marks[k];
        int add = 0;
        for (const auto& p : m.own) add += out.at<std::uint8_t>(p) == kUnmarked;
        if (m.rank > 0 && marked + add > budget) continue;
        for (const auto& p : m.own) out.at<std::uint8_t>(p) = std::uint8_t(m.id);
        marked += add;
        if (kept) kept->push_back(k);
    }
    return out;
}

/// Pen of width `w` along a centre line: the rows centre - (w-1)/2 .. centre + w/2.
std::vector<cv::Point> widen(const std::vector<cv::Point>& line, int w, cv::Size size) {
    std::vector<cv::Point> out;
    for (const auto& p : line)
        for (int k = -(w - 1) / 2; k <= w / 2; ++k) {
            const cv::Point q(p.x, p.y + k);
            if (q.y >= 0 && q.y < size.height && q.x >= 0 && q.x < size.width) out.push_back(q);
        }
    return out;
}

cv::Mat dash_strokes(const cv::Mat& labels, std::uint64_t seed, const StrokeOptions& o) {
    Rng rng(seed);
    const double diag = std::hypot(labels.cols, labels.rows);
    const double len = diag * rng.uniform(0.015, 0.03);
    const double row_step = std::max(3.0, diag * rng.uniform(0.02, 0.04));
    const double gap = len * rng.uniform(0.5, 1.5);
    const int width = rng.integer(2, 3);
    const double depth = std::max(1.0, o.erosion_fraction * diag);
    std::vector<Mark> marks;
    for (const Region& r : regions_of(labels, o.min_region_fraction * double(labels.total()), 0)) {
        const cv::Mat core = core_of(r, depth);
        const auto lines = dash_lines(r, core, len, row_step, gap, rng);
        const std::vector<int> rank = ranks(lines, rng);
        for (size_t k = 0; k < lines.size(); ++k) {
            Mark m;
            m.id = r.id;
            m.rank = rank[k];
            for (const auto& p : widen(lines[k], width, labels.size()))
                if (labels.at<std::uint8_t>(p) == r.id) m.own.push_back(p);
            if (!m.own.empty()) marks.push_back(std::move(m));
        }
    }
    return draw_marks(labels, marks, o.max_marked_fraction * double(labels.total()), rng);
}

cv::Mat dot_strokes(const cv::Mat& labels, std::uint64_t seed, const StrokeOptions& o) {
    Rng rng(seed);
    const double diag = std::hypot(labels.cols, labels.rows);
    const int radius = std::max(2, int(std::lround(diag * rng.uniform(0.003, 0.006))));
    std::vector<Mark> marks;
    for (const Region& r : regions_of(labels, o.min_region_fraction * double(labels.total()), 0)) {
        const int count = r.area >= 0.01 * double(labels.total()) ? rng.integer(2, 4) : rng.integer(1, 2);
        const cv::Mat core = core_of(r, radius + 1.0);
        std::vector<cv::Point> candidates;
        for (int y = 0; y < core.rows; ++y)
            for (int x = 0; x < core.cols; ++x)
                if (core.at<std::uint8_t>(y, x)) candidates.emplace_back(x, y);
        if (candidates.empty()) continue;
        // Clicks spread over the region: each next one the farthest from the others of
        // 30 random candidates.
        std::vector<cv::Point> dots;
        for (int d = 0; d < count; ++d) {
            cv::Point best = candidates[size_t(rng.integer(0, int(candidates.size()) - 1))];
            double best_d = -1;
            for (int t = 0; t < (d == 0 ? 1 : 30); ++t) {
                const cv::Point c = t == 0 && d == 0 ? best : candidates[size_t(rng.integer(0, int(candidates.size()) - 1))];
                double nearest = 1e18;
                for (const auto& q : dots) nearest = std::min(nearest, double((c - q).dot(c - q)));
                if (nearest > best_d) { best_d = nearest; best = c; }
            }
            dots.push_back(best);
        }
        for (size_t d = 0; d < dots.size(); ++d) {
            Mark m;
            m.id = r.id;
            m.rank = int(d);
            for (int dy = -radius; dy <= radius; ++dy)
                for (int dx = -radius; dx <= radius; ++dx) {
                    if (dx * dx + dy * dy > radius * radius) continue;
                    const cv::Point q(dots[d].x + r.box.x + dx, dots[d].y + r.box.y + dy);
                    if (q.x < 0 || q.y < 0 || q.x >= labels.cols || q.y >= labels.rows) continue;
                    if (labels.at<std::uint8_t>(q) == r.id) m.own.push_back(q);
                }
            if (!m.own.empty()) marks.push_back(std::move(m));
        }
    }
    return draw_marks(labels, marks, o.max_marked_fraction * double(labels.total()), rng);
}

cv::Mat sloppy_strokes(const cv::Mat& labels, std::uint64_t seed, const StrokeOptions& o) {
    Rng rng(seed);
    const double diag = std::hypot(labels.cols, labels.rows);
    const double len = diag * rng.uniform(0.03, 0.06);
    const double row_step = std::max(3.0, diag * rng.uniform(0.025, 0.05));
    const double gap = len * rng.uniform(0.5, 1.0);
    const int width = rng.integer(3, 4);
    const int stray = rng.integer(2, 5);  // px a stroke may run past its region's border
    std::vector<Mark> marks;
    for (const Region& r : regions_of(labels, o.min_region_fraction * double(labels.total()), stray + width)) {
        // The whole region, borders included: a hasty hand does not keep clear of them.
        auto lines = dash_lines(r, r.mask, len, row_step, gap, rng);
        if (lines.empty()) continue;
        cv::Mat outside_dist;  // distance of crop pixels to the region
        cv::distanceTransform(~r.mask, outside_dist, cv::DIST_L2, 3);
        const std::vector<int> rank = ranks(lines, rng);
        for (size_t k = 0; k < lines.size(); ++k) {
            auto& line = lines[k];
            // A drifting hand: a slope of up to +-0.1, and overshoot past the run's ends.
            const double slope = rng.uniform(-0.1, 0.1);
            const int over_l = rng.integer(0, stray), over_r = rng.integer(0, stray);
            const cv::Point a = line.front(), b = line.back();
            std::vector<cv::Point> drawn;
            for (int x = a.x - over_l; x <= b.x + over_r; ++x)
                drawn.emplace_back(x, a.y + int(std::lround(slope * (x - a.x))));
            Mark m;
            m.id = r.id;
            m.rank = rank[k];
            for (const auto& p : widen(drawn, width, labels.size())) {
                if (p.x < 0 || p.x >= labels.cols) continue;
                if (labels.at<std::uint8_t>(p) == r.id) {
                    m.own.push_back(p);
                    continue;
                }
                const cv::Point c = p - r.box.tl();
                if (c.x >= 0 && c.y >= 0 && c.x < r.box.width && c.y < r.box.height &&
                    outside_dist.at<float>(c) <= float(stray))
                    m.stray.push_back(p);
            }
            if (!m.own.empty()) marks.push_back(std::move(m));
        }
    }
    std::vector<size_t> kept;
    // The budget holds the strays too (at most 0.6 % of the marks, below).
    cv::Mat out = draw_marks(labels, marks, 0.994 * o.max_marked_fraction * double(labels.total()), rng, &kept);
    // About 1 % of the marks in a wrong class: stray pixels past the borders up to 0.6 % of
    // the marks, then one slip of the pen's colour (a piece of a stroke drawn in another
    // class present in the image) up to 1 %.
    const double marked = double(cv::countNonZero(out != kUnmarked));
    const double stray_budget = 0.006 * marked, wrong_budget = 0.01 * marked;
    double wrong = 0;
    for (size_t k : kept) {
        const Mark& m = marks[k];
        int add = 0;
        for (const auto& p : m.stray) add += out.at<std::uint8_t>(p) == kUnmarked;
        if (add == 0 || wrong + add > stray_budget) continue;
        for (const auto& p : m.stray)
            if (out.at<std::uint8_t>(p) == kUnmarked) out.at<std::uint8_t>(p) = std::uint8_t(m.id);
        wrong += add;
    }
    std::vector<int> ids;
    for (const Mark& m : marks)
        if (std::find(ids.begin(), ids.end(), m.id) == ids.end()) ids.push_back(m.id);
    std::sort(ids.begin(), ids.end());
    if (ids.size() >= 2 && !kept.empty()) {
        for (int attempt = 0; attempt < 20 && wrong < wrong_budget; ++attempt) {
            const Mark& m = marks[kept[size_t(rng.integer(0, int(kept.size()) - 1))]];
            if (m.rank == 0) continue;  // keep every region's first stroke right
            int other = ids[size_t(rng.integer(0, int(ids.size()) - 2))];
            if (other >= m.id) other = ids[size_t(std::find(ids.begin(), ids.end(), other) - ids.begin()) + 1];
            for (const auto& p : m.own) {
                if (wrong >= wrong_budget) break;
                std::uint8_t& v = out.at<std::uint8_t>(p);
                if (v != m.id) continue;
                v = std::uint8_t(other);
                ++wrong;
            }
        }
    }
    return out;
}

}  // namespace

cv::Mat simulate_strokes(const cv::Mat& labels, StrokeStyle style, std::uint64_t seed,
                         const StrokeOptions& options) {
    std::string why;
    require(options.is_valid(&why), "StrokeOptions: ", why);
    require(!labels.empty() && labels.type() == CV_8UC1,
            "simulate_strokes: labels must be a non-empty 8-bit single-channel class map");
    switch (style) {
        case StrokeStyle::dashes: return dash_strokes(labels, seed, options);
        case StrokeStyle::dots: return dot_strokes(labels, seed, options);
        case StrokeStyle::sloppy: return sloppy_strokes(labels, seed, options);
        case StrokeStyle::medial: break;
    }
    return simulate_strokes(labels, options);
}

// ---- Colour-coded strokes -----------------------------------------------------------------

StrokePalette StrokePalette::fashionista_default() {
    const LabelTable& t = LabelTable::fashionista();
    const std::pair<const char*, cv::Vec3b> colours[] = {
        {"null", {0, 0, 255}},        {"skin", {255, 128, 0}},   {"hair", {128, 0, 0}},
        {"t-shirt", {255, 0, 0}},     {"top", {255, 0, 255}},    {"shirt", {128, 0, 128}},
        {"sweater", {128, 0, 255}},   {"dress", {0, 255, 0}},    {"skirt", {255, 255, 0}},
        {"pants", {0, 255, 255}},     {"shorts", {0, 128, 128}}, {"jeans", {0, 0, 128}},
        {"jacket", {0, 128, 0}},      {"bag", {128, 128, 0}},    {"belt", {255, 0, 128}},
        {"shoes", {128, 255, 0}}};
    StrokePalette p;
    for (const auto& [name, rgb] : colours) p.entries.push_back({t.id(name), rgb});
    return p;
}

std::string StrokePalette::hex(const cv::Vec3b& rgb) {
    static const char* digits = "0123456789abcdef";
    std::string s = "#";
    for (int c = 0; c < 3; ++c) {
        s += digits[rgb[c] >> 4];
        s += digits[rgb[c] & 15];
    }
    return s;
}

cv::Vec3b StrokePalette::parse_hex(const std::string& text) {
    const std::string h = !text.empty() && text[0] == '#' ? text.substr(1) : text;
    auto value = [&](char ch) -> int {
        if (ch >= '0' && ch <= '9') return ch - '0';
        if (ch >= 'a' && ch <= 'f') return ch - 'a' + 10;
        if (ch >= 'A' && ch <= 'F') return ch - 'A' + 10;
        return -1;
    };
    bool ok = h.size() == 6;
    cv::Vec3b rgb;
    for (int c = 0; ok && c < 3; ++c) {
        const int hi = value(h[size_t(2 * c)]), lo = value(h[size_t(2 * c + 1)]);
        ok = hi >= 0 && lo >= 0;
        if (ok) rgb[c] = static_cast<std::uint8_t>(16 * hi + lo);
    }
    require(ok, "colour '", text, "' is not of the form #rrggbb");
    return rgb;
}

bool StrokePalette::is_valid(std::string* why) const {
    auto fail = [&](const std::string& m) { if (why) *why = m; return false; };
    if (entries.empty()) return fail("the palette has no colour");
    if (tolerance < 0 || tolerance > 63) return fail("tolerance must be in [0, 63]");
    for (size_t i = 0; i < entries.size(); ++i) {
        const auto& a = entries[i];
        if (a.class_id < 0 || a.class_id >= kUnmarked)
            return fail("class id " + std::to_string(a.class_id) + " is outside 0..254");
        for (size_t k = 0; k < i; ++k) {
            const auto& b = entries[k];
            if (a.class_id == b.class_id)
                return fail("class id " + std::to_string(a.class_id) + " has two colours");
            int d = 0;
            for (int c = 0; c < 3; ++c) d = std::max(d, std::abs(int(a.rgb[c]) - int(b.rgb[c])));
            if (d <= 2 * tolerance)
                return fail("colours " + hex(a.rgb) + " and " + hex(b.rgb) + " differ by " + std::to_string(d) +
                            ", not more than twice the tolerance " + std::to_string(tolerance));
        }
    }
    return true;
}

cv::Mat strokes_from_colours(const cv::Mat& image, const StrokePalette& palette, StrokeDecoding* report) {
    std::string why;
    require(palette.is_valid(&why), "stroke palette: ", why);
    require(!image.empty() && (image.type() == CV_8UC3 || image.type() == CV_8UC4),
            "colour-coded strokes must be 8-bit RGB or RGBA (got OpenCV type ", image.type(), ")");
    const int ch = image.channels();
    cv::Mat out(image.size(), CV_8UC1, cv::Scalar(kUnmarked));
    StrokeDecoding r;
    long long opaque = 0;
    std::map<std::uint32_t, long long> unknown;  // packed 0xRRGGBB -> pixels
    for (int y = 0; y < image.rows; ++y) {
        const std::uint8_t* p = image.ptr<std::uint8_t>(y);
        std::uint8_t* o = out.ptr<std::uint8_t>(y);
        for (int x = 0; x < image.cols; ++x, p += ch) {
            if (ch == 4 && p[3] < 128) continue;
            ++opaque;
            const int rr = p[2], gg = p[1], bb = p[0];
            int hit = -1;
            for (const auto& e : palette.entries)
                if (std::abs(rr - e.rgb[0]) <= palette.tolerance && std::abs(gg - e.rgb[1]) <= palette.tolerance &&
                    std::abs(bb - e.rgb[2]) <= palette.tolerance) {
                    hit = e.class_id;
                    break;
                }
            if (hit >= 0) {
                o[x] = static_cast<std::uint8_t>(hit);
            } else {
                const bool canvas = (rr > 240 && gg > 240 && bb > 240) || (rr < 16 && gg < 16 && bb < 16);
                if (!canvas) ++unknown[std::uint32_t(rr << 16 | gg << 8 | bb)];
            }
        }
    }
    // Anti-aliased borders on a black or white canvas (or a layer whose colour was darkened
    // with its alpha) blend a stroke's colour towards black or white: half of red is the
    // palette's maroon, half of yellow its olive. A pixel whose colour is such a blend of
    // the colour of a neighbouring stroke pixel is that stroke's rim, not a stroke of its own.
    const size_t ne = palette.entries.size();
    std::vector<int> entry_of(256, -1);
    for (size_t i = 0; i < ne; ++i) entry_of[size_t(palette.entries[i].class_id)] = int(i);
    // blend[a * ne + b]: a's colour is b's mixed 20-80 % with black, white or a third colour
    // (where two strokes cross: red over yellow makes the palette's orange).
    std::vector<cv::Vec3d> backdrops = {{0, 0, 0}, {255, 255, 255}};
    for (const auto& e : palette.entries) backdrops.emplace_back(e.rgb[0], e.rgb[1], e.rgb[2]);
    std::vector<char> blend(ne * ne, 0);
    for (size_t a = 0; a < ne; ++a)
        for (size_t b = 0; b < ne; ++b) {
            if (a == b) continue;
            for (size_t q = 0; q < backdrops.size() && !blend[a * ne + b]; ++q) {
                if (q == a + 2 || q == b + 2) continue;
                for (int k = 2; k <= 8 && !blend[a * ne + b]; ++k) {
                    const double t = 0.1 * k;
                    int d = 0;
                    for (int c = 0; c < 3; ++c)
                        d = std::max(d, int(std::lround(std::abs(palette.entries[a].rgb[c] -
                                                                 (t * palette.entries[b].rgb[c] + (1 - t) * backdrops[q][c])))));
                    if (d <= palette.tolerance) blend[a * ne + b] = 1;
                }
            }
        }
    std::vector<cv::Point> rims;
    for (int y = 0; y < out.rows; ++y)
        for (int x = 0; x < out.cols; ++x) {
            const int v = out.at<std::uint8_t>(y, x);
            if (v == kUnmarked) continue;
            const size_t a = size_t(entry_of[size_t(v)]);
            bool rim = false;
            for (int dy = -1; dy <= 1 && !rim; ++dy)
                for (int dx = -1; dx <= 1 && !rim; ++dx) {
                    const int yy = y + dy, xx = x + dx;
                    if (yy < 0 || xx < 0 || yy >= out.rows || xx >= out.cols) continue;
                    const int w = out.at<std::uint8_t>(yy, xx);
                    if (w == kUnmarked || w == v) continue;
                    rim = blend[a * ne + size_t(entry_of[size_t(w)])];
                }
            if (rim) rims.push_back({x, y});
        }
    for (const auto& pt : rims) out.at<std::uint8_t>(pt) = kUnmarked;
    // The counts, from the final map: opaque pixels are either marked or not.
    std::vector<long long> count(256, 0);
    for (size_t i = 0; i < out.total(); ++i) ++count[out.data[i]];
    r.marked_px = static_cast<long long>(out.total()) - count[kUnmarked];
    r.unrecognised_px = opaque - r.marked_px;
    for (int id = 0; id < 255; ++id)
        if (count[size_t(id)] > 0) r.per_class.emplace_back(id, count[size_t(id)]);
    for (const auto& [rgb, n] : unknown)
        if (n > r.most_common_unrecognised_px) {
            r.most_common_unrecognised_px = n;
            r.most_common_unrecognised = cv::Vec3b(std::uint8_t(rgb >> 16), std::uint8_t(rgb >> 8), std::uint8_t(rgb));
        }
    long long off_palette = 0;  // opaque pixels of neither a palette nor a canvas colour
    for (const auto& [rgb, n] : unknown) off_palette += n;
    require(off_palette <= 0.5 * double(image.total()), "this looks like a photo, not strokes: ",
            std::lround(100.0 * double(off_palette) / double(image.total())),
            " % of its pixels have colours of no palette entry (colour-coded strokes are drawn on a "
            "transparent layer or a white or black canvas; see docs/vision.md, \"Colour-coded strokes\")");
    require(r.marked_px > 0, "no pixel of the stroke image has a palette colour (",
            r.unrecognised_px, " opaque pixels of other colours",
            r.most_common_unrecognised_px > 0 ? ", most often " + StrokePalette::hex(r.most_common_unrecognised) : "",
            "); see docs/vision.md, \"Colour-coded strokes\"");
    if (report) *report = r;
    return out;
}

cv::Mat colour_strokes(const cv::Mat& strokes, const StrokePalette& palette, std::vector<int>* missing) {
    std::string why;
    require(palette.is_valid(&why), "stroke palette: ", why);
    require(!strokes.empty() && strokes.type() == CV_8UC1, "strokes must be an 8-bit single-channel map");
    std::vector<int> colour_of(256, -1);
    for (size_t i = 0; i < palette.entries.size(); ++i) colour_of[size_t(palette.entries[i].class_id)] = int(i);
    std::vector<char> absent(256, 0);
    cv::Mat out(strokes.size(), CV_8UC4, cv::Scalar(0, 0, 0, 0));
    for (int y = 0; y < strokes.rows; ++y) {
        const std::uint8_t* s = strokes.ptr<std::uint8_t>(y);
        cv::Vec4b* o = out.ptr<cv::Vec4b>(y);
        for (int x = 0; x < strokes.cols; ++x) {
            if (s[x] == kUnmarked) continue;
            const int k = colour_of[s[x]];
            if (k < 0) { absent[s[x]] = 1; continue; }
            const cv::Vec3b& c = palette.entries[size_t(k)].rgb;
            o[x] = cv::Vec4b(c[2], c[1], c[0], 255);
        }
    }
    if (missing) {
        missing->clear();
        for (int id = 0; id < 256; ++id)
            if (absent[size_t(id)]) missing->push_back(id);
    }
    return out;
}

cv::Mat load_strokes(const std::filesystem::path& path, const StrokePalette& palette, StrokeDecoding* report) {
    const cv::Mat image = load_image_unchanged(path, "strokes");
    if (image.channels() == 1) return image;
    try {
        return strokes_from_colours(image, palette, report);
    } catch (const InvalidInput& e) {
        throw InvalidInput("strokes '" + path.string() + "': " + e.what());
    }
}

}  // namespace drape::vision
