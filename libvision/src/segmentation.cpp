#include <drape/vision/segmentation.hpp>

#include <drape/vision/bare_arms.hpp>
#include <drape/vision/classify_garment.hpp>
#include <drape/vision/image_io.hpp>

#include "alpha_expansion.hpp"
#include "body_layout.hpp"
#include "garment_type_model.hpp"
#include "colour_model.hpp"
#include "superpixels.hpp"

#include <drape/core/errors.hpp>

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <functional>
#include <iomanip>
#include <limits>
#include <queue>
#include <sstream>

namespace drape::vision {

bool SegmentationOptions::is_valid(std::string* why) const {
    auto fail = [&](const char* m) { if (why) *why = m; return false; };
    if (working_max_side_px < 32) return fail("working_max_side_px must be >= 32");
    if (!(smoothness >= 0)) return fail("smoothness must be >= 0");
    if (histogram_bins < 4 || histogram_bins > 64) return fail("histogram_bins must be in [4, 64]");
    if (rounds < 1) return fail("rounds must be >= 1");
    if (expansion_cycles < 1) return fail("expansion_cycles must be >= 1");
    if (!(stroke_distance_weight >= 0)) return fail("stroke_distance_weight must be >= 0");
    if (!(stroke_colour_weight >= 0)) return fail("stroke_colour_weight must be >= 0");
    if (!(background_distance_factor >= 0))
        return fail("background_distance_factor must be >= 0");
    if (!(layout_weight >= 0)) return fail("layout_weight must be >= 0");
    if (!(mark_outlier_margin >= 0)) return fail("mark_outlier_margin must be >= 0");
    if (!(mark_edge_px >= 0)) return fail("mark_edge_px must be >= 0");
    if (!(mark_edge_factor > 0)) return fail("mark_edge_factor must be > 0");
    if (!(soft_mark_weight >= 0)) return fail("soft_mark_weight must be >= 0");
    if (!(seed_growth_fraction >= 0)) return fail("seed_growth_fraction must be >= 0");
    if (!(body_prior_weight >= 0)) return fail("body_prior_weight must be >= 0");
    if (!(sparse_marks_fraction >= 0) || sparse_marks_fraction > 1)
        return fail("sparse_marks_fraction must be in [0, 1]");
    if (!(compact_marks_factor > 0) || compact_marks_factor > 1)
        return fail("compact_marks_factor must be in (0, 1]");
    if (!(compact_mark_elongation > 0)) return fail("compact_mark_elongation must be > 0");
    if (!(body_reach_fraction > 0)) return fail("body_reach_fraction must be > 0");
    if (!(stroke_layout_weight >= 0)) return fail("stroke_layout_weight must be >= 0");
    if (!(superpixel_fraction > 0)) return fail("superpixel_fraction must be > 0");
    if (!(min_piece_fraction >= 0)) return fail("min_piece_fraction must be >= 0");
    if (!(band_fraction >= 0) || band_fraction > 0.2) return fail("band_fraction must be in [0, 0.2]");
    if (!(band_smoothness >= 0)) return fail("band_smoothness must be >= 0");
    return true;
}

std::string SegmentationSummary::brief_report() const {
    static const char* names[] = {"ok", "no_garment_found", "failed"};
    std::ostringstream os;
    os << "segmentation: " << names[static_cast<int>(termination)] << ", " << labels_used
       << " classes, " << garments_found << " garment(s), " << std::fixed
       << std::setprecision(2) << seconds << " s (graph cut " << seconds_graph_cut
       << " s, refinement " << seconds_refinement << " s)";
    if (!message.empty()) os << " (" << message << ")";
    return os.str();
}

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) {
    return std::chrono::duration<double>(Clock::now() - t).count();
}

/// One multi-label problem at the working resolution.
struct Problem {
    int labels = 0;
    cv::Mat hard;                       ///< CV_8UC1 label index or 255
    std::vector<cv::Mat> prior;         ///< CV_32F per label (empty Mat = none)
    std::vector<cv::Mat> model_seed;    ///< CV_8UC1 per label: first colour model pixels
    /// Strokes mode: marks taken as soft evidence (CV_8UC1 label index or 255; empty =
    /// none): every other label costs `soft_weight` more there.
    cv::Mat soft;
    float soft_weight = 0;
};

/// Stage 1: rounds of (colour models, alpha-expansion). Returns label indices (CV_8UC1).
cv::Mat solve(const cv::Mat& small, const Problem& p, const SegmentationOptions& o) {
    const int n = small.rows * small.cols;
    const size_t L = static_cast<size_t>(p.labels);
    const cv::Mat bins = detail::colour_bins(small, o.histogram_bins);
    detail::GridEnergy e;
    e.width = small.cols;
    e.height = small.rows;
    e.labels = p.labels;
    detail::set_contrast_weights(small, o.smoothness, e);
    std::vector<std::uint8_t> lab(static_cast<size_t>(n), 0);
    const auto* hard = p.hard.ptr<std::uint8_t>(0);
    const auto* soft = p.soft.empty() ? nullptr : p.soft.ptr<std::uint8_t>(0);
    const auto* bin = bins.ptr<int>(0);
    for (int round = 0; round < o.rounds; ++round) {
        std::vector<detail::ColourHistogram> models(L, detail::ColourHistogram(o.histogram_bins));
        for (int i = 0; i < n; ++i) {
            if (round == 0) {
                for (size_t l = 0; l < L; ++l)
                    if (p.model_seed[l].data[i]) models[l].add(bin[i]);
            } else {
                models[lab[static_cast<size_t>(i)]].add(bin[i]);
            }
            if (hard[i] != 255) models[hard[i]].add(bin[i], 2.0);
            if (soft && soft[i] != 255) models[soft[i]].add(bin[i], 2.0);
        }
        for (auto& m : models) m.finish();
        e.unary.assign(static_cast<size_t>(n) * L, 0.f);
        for (int i = 0; i < n; ++i) {
            float* u = &e.unary[static_cast<size_t>(i) * L];
            for (size_t l = 0; l < L; ++l) {
                u[l] = models[l].total() > 0 ? models[l].cost(bin[i]) : 1e4f;
                if (!p.prior[l].empty()) u[l] += p.prior[l].ptr<float>(0)[i];
                if (hard[i] != 255 && hard[i] != l) u[l] = 1e5f;
                if (soft && soft[i] != 255 && soft[i] != l) u[l] += p.soft_weight;
            }
            if (round == 0)
                lab[static_cast<size_t>(i)] =
                    static_cast<std::uint8_t>(std::min_element(u, u + L) - u);
        }
        detail::alpha_expansion(e, lab, o.expansion_cycles);
    }
    cv::Mat out(small.size(), CV_8UC1);
    std::copy(lab.begin(), lab.end(), out.ptr<std::uint8_t>(0));
    return out;
}

double working_scale(const cv::Mat& image, const SegmentationOptions& o) {
    return std::min(1.0, double(o.working_max_side_px) / std::max(image.cols, image.rows));
}

cv::Mat shrink(const cv::Mat& image, double s) {
    if (s >= 1.0) return image.clone();
    cv::Mat out;
    cv::resize(image, out, cv::Size(), s, s, cv::INTER_AREA);
    return out;
}

/// Merges connected pieces smaller than `min_area` into their most common neighbour.
void remove_small_pieces(cv::Mat& labels, double min_area, const cv::Mat& fixed) {
    if (min_area <= 0) return;
    bool present[256] = {};
    for (auto it = labels.begin<std::uint8_t>(); it != labels.end<std::uint8_t>(); ++it)
        present[*it] = true;
    const cv::Mat k3 = cv::getStructuringElement(cv::MORPH_RECT, {3, 3});
    for (int id = 0; id < 256; ++id) {
        if (!present[id]) continue;
        cv::Mat comp, stats, cent;
        const int n = cv::connectedComponentsWithStats(labels == id, comp, stats, cent, 8, CV_32S);
        for (int c = 1; c < n; ++c) {
            if (stats.at<int>(c, cv::CC_STAT_AREA) >= min_area) continue;
            cv::Rect box(stats.at<int>(c, cv::CC_STAT_LEFT) - 1, stats.at<int>(c, cv::CC_STAT_TOP) - 1,
                         stats.at<int>(c, cv::CC_STAT_WIDTH) + 2,
                         stats.at<int>(c, cv::CC_STAT_HEIGHT) + 2);
            box &= cv::Rect(0, 0, labels.cols, labels.rows);
            const cv::Mat piece = comp(box) == c;
            if (!fixed.empty() && cv::countNonZero((fixed(box) != 255) & piece) > 0) continue;
            cv::Mat ring;
            cv::dilate(piece, ring, k3);
            ring &= ~piece;
            int votes[256] = {};
            const cv::Mat lb = labels(box);
            for (int y = 0; y < ring.rows; ++y)
                for (int x = 0; x < ring.cols; ++x)
                    if (ring.at<std::uint8_t>(y, x)) ++votes[lb.at<std::uint8_t>(y, x)];
            const int best = int(std::max_element(votes, votes + 256) - votes);
            if (votes[best] == 0 || best == id) continue;
            labels(box).setTo(best, piece);
        }
    }
}

/// Stage 2b: alpha-expansion at full resolution over the pixels within `band_px` of a
/// class border; the others keep their class (hard constraints), as do stroked pixels.
/// Colour models per class from its pixels outside the band (all its pixels if none).
void refine_band(const cv::Mat& image, const cv::Mat& fixed, int band_px, double gamma,
                 int bins, cv::Mat& labels) {
    const cv::Mat k3 = cv::getStructuringElement(cv::MORPH_RECT, {3, 3});
    cv::Mat hi, lo, band;
    cv::dilate(labels, hi, k3);
    cv::erode(labels, lo, k3);
    band = hi != lo;
    if (cv::countNonZero(band) == 0) return;
    cv::dilate(band, band,
               cv::getStructuringElement(cv::MORPH_ELLIPSE, {2 * band_px + 1, 2 * band_px + 1}));
    cv::Rect roi = cv::boundingRect(band);
    roi = cv::Rect(roi.x - 1, roi.y - 1, roi.width + 2, roi.height + 2) &
          cv::Rect(0, 0, labels.cols, labels.rows);
    int index_of[256];
    std::fill(index_of, index_of + 256, -1);
    std::vector<int> ids;
    cv::Mat lr = labels(roi);  // a view: written back below
    for (int y = 0; y < lr.rows; ++y)
        for (int x = 0; x < lr.cols; ++x) {
            const int id = lr.at<std::uint8_t>(y, x);
            if (index_of[id] < 0) {
                index_of[id] = int(ids.size());
                ids.push_back(id);
            }
        }
    if (ids.size() < 2) return;
    const size_t L = ids.size();
    auto bin_of = [&](int y, int x) { return detail::colour_bin(image.at<cv::Vec3b>(y, x), bins); };
    std::vector<detail::ColourHistogram> inner(L, detail::ColourHistogram(bins)),
        all(L, detail::ColourHistogram(bins));
    for (int y = 0; y < labels.rows; ++y)
        for (int x = 0; x < labels.cols; ++x) {
            const int k = index_of[labels.at<std::uint8_t>(y, x)];
            if (k < 0) continue;
            const int b = bin_of(y, x);
            all[size_t(k)].add(b);
            if (!band.at<std::uint8_t>(y, x)) inner[size_t(k)].add(b);
        }
    for (size_t k = 0; k < L; ++k) {
        inner[k].finish();
        all[k].finish();
    }
    // Graph over the free pixels only (band, not stroked); fixed neighbours fold into the
    // unary terms, so the cost follows the band's size, not the photo's.
    const cv::Mat img = image(roi);
    cv::Mat node(roi.size(), CV_32S, cv::Scalar(-1));
    std::vector<cv::Point> where;
    for (int y = 0; y < roi.height; ++y)
        for (int x = 0; x < roi.width; ++x)
            if (band.at<std::uint8_t>(y + roi.y, x + roi.x) &&
                (fixed.empty() || fixed.at<std::uint8_t>(y + roi.y, x + roi.x) == 255)) {
                node.at<int>(y, x) = int(where.size());
                where.emplace_back(x, y);
            }
    if (where.empty()) return;
    detail::GraphEnergy e;
    e.nodes = int(where.size());
    e.labels = int(L);
    e.unary.assign(where.size() * L, 0.f);
    std::vector<std::uint8_t> lab(where.size());
    const double beta = detail::contrast_beta(img);
    const int dxs[8] = {1, -1, 0, 0, 1, 1, -1, -1}, dys[8] = {0, 0, 1, -1, 1, -1, 1, -1};
    for (size_t i = 0; i < where.size(); ++i) {
        const cv::Point q = where[i];
        lab[i] = static_cast<std::uint8_t>(index_of[lr.at<std::uint8_t>(q)]);
        const int b = bin_of(q.y + roi.y, q.x + roi.x);
        float* u = &e.unary[i * L];
        for (size_t k = 0; k < L; ++k) u[k] = inner[k].total() > 0 ? inner[k].cost(b) : all[k].cost(b);
        const cv::Vec3b c = img.at<cv::Vec3b>(q);
        for (int d = 0; d < 8; ++d) {
            const cv::Point r(q.x + dxs[d], q.y + dys[d]);
            if (r.x < 0 || r.y < 0 || r.x >= roi.width || r.y >= roi.height) continue;
            const cv::Vec3b cn = img.at<cv::Vec3b>(r);
            double d2 = 0;
            for (int ch = 0; ch < 3; ++ch) d2 += (double(c[ch]) - cn[ch]) * (double(c[ch]) - cn[ch]);
            const float w = float(gamma * std::exp(-beta * d2) / (d < 4 ? 1.0 : std::sqrt(2.0)));
            const int j = node.at<int>(r);
            if (j < 0) {
                const int fixed_label = index_of[lr.at<std::uint8_t>(r)];
                for (size_t k = 0; k < L; ++k)
                    if (int(k) != fixed_label) u[k] += w;
            } else if (j > int(i)) {
                e.edge_from.push_back(int(i));
                e.edge_to.push_back(j);
                e.edge_weight.push_back(w);
            }
        }
    }
    detail::alpha_expansion(e, lab, 1);
    for (size_t i = 0; i < where.size(); ++i)
        lr.at<std::uint8_t>(where[i]) = static_cast<std::uint8_t>(ids[lab[i]]);
}

/// Stage 2 and cleanup, at full resolution. `small_ids` holds class ids.
cv::Mat refine(const cv::Mat& image, const cv::Mat& small_ids, const cv::Mat& fixed,
               double body_height_px, const SegmentationOptions& o, double& seconds) {
    const auto t0 = Clock::now();
    cv::Mat labels;
    cv::resize(small_ids, labels, image.size(), 0, 0, cv::INTER_NEAREST);
    if (o.refine_boundaries) {
        const int size = std::max(3, int(std::lround(o.superpixel_fraction * body_height_px)));
        cv::Mat index;
        const int count = detail::slic_superpixels(image, size, 10.0, 4, index);
        detail::majority_vote(index, count, fixed, labels);
    } else if (!fixed.empty()) {
        fixed.copyTo(labels, fixed != 255);
    }
    if (o.band_fraction > 0) {
        const int band = std::max(1, int(std::lround(o.band_fraction * body_height_px)));
        refine_band(image, fixed, band, o.band_smoothness, o.histogram_bins, labels);
    }
    remove_small_pieces(labels, o.min_piece_fraction * double(labels.total()), fixed);
    seconds = since(t0);
    return labels;
}

/// Geodesic distance (px) from the set pixels of `seed` over the 8-connected grid of
/// `image`: a step costs its length x (1 + colour_weight |dc| / <|dc|>), where |dc| is the
/// RGB difference of the two pixels and <|dc|> its mean over the image's neighbours, so a
/// path that crosses a colour edge is long (colour_weight 0: Euclidean-like chamfer).
cv::Mat geodesic_distance(const cv::Mat& image, const cv::Mat& seed, double colour_weight,
                          double mean_step) {
    const int w = image.cols, h = image.rows;
    cv::Mat dist(image.size(), CV_32F, cv::Scalar(std::numeric_limits<float>::max()));
    using Item = std::pair<float, int>;
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            if (seed.at<std::uint8_t>(y, x)) {
                dist.at<float>(y, x) = 0;
                queue.emplace(0.f, y * w + x);
            }
    const float k = float(colour_weight / std::max(1e-6, mean_step));
    const int dxs[8] = {1, -1, 0, 0, 1, 1, -1, -1}, dys[8] = {0, 0, 1, -1, 1, -1, 1, -1};
    auto* d = dist.ptr<float>(0);
    while (!queue.empty()) {
        const auto [dv, i] = queue.top();
        queue.pop();
        if (dv > d[i]) continue;
        const int x = i % w, y = i / w;
        const cv::Vec3b c = image.at<cv::Vec3b>(y, x);
        for (int n = 0; n < 8; ++n) {
            const int xn = x + dxs[n], yn = y + dys[n];
            if (xn < 0 || yn < 0 || xn >= w || yn >= h) continue;
            const cv::Vec3b cn = image.at<cv::Vec3b>(yn, xn);
            const float db = float(c[0]) - cn[0], dg = float(c[1]) - cn[1], dr = float(c[2]) - cn[2];
            const float step = (n < 4 ? 1.f : 1.41421356f) *
                               (1.f + k * std::sqrt(db * db + dg * dg + dr * dr));
            const int j = yn * w + xn;
            if (dv + step < d[j]) {
                d[j] = dv + step;
                queue.emplace(d[j], j);
            }
        }
    }
    return dist;
}

/// Mean RGB distance between 4-neighbours of `image`.
double mean_colour_step(const cv::Mat& image) {
    double sum = 0;
    long n = 0;
    for (int y = 0; y < image.rows; ++y)
        for (int x = 0; x < image.cols; ++x) {
            const cv::Vec3b c = image.at<cv::Vec3b>(y, x);
            for (const cv::Point q : {cv::Point(x + 1, y), cv::Point(x, y + 1)}) {
                if (q.x >= image.cols || q.y >= image.rows) continue;
                const cv::Vec3b cn = image.at<cv::Vec3b>(q);
                const double db = double(c[0]) - cn[0], dg = double(c[1]) - cn[1],
                             dr = double(c[2]) - cn[2];
                sum += std::sqrt(db * db + dg * dg + dr * dr);
                ++n;
            }
        }
    return n > 0 ? sum / double(n) : 1.0;
}

/// Per-pixel colour-edge strength of `image`: the largest RGB difference to a 4-neighbour.
cv::Mat colour_edge_strength(const cv::Mat& image) {
    cv::Mat out(image.size(), CV_32F, cv::Scalar(0));
    for (int y = 0; y < image.rows; ++y)
        for (int x = 0; x < image.cols; ++x) {
            const cv::Vec3b c = image.at<cv::Vec3b>(y, x);
            float best = 0;
            for (const cv::Point q : {cv::Point(x + 1, y), cv::Point(x - 1, y), cv::Point(x, y + 1), cv::Point(x, y - 1)}) {
                if (q.x < 0 || q.y < 0 || q.x >= image.cols || q.y >= image.rows) continue;
                const cv::Vec3b cn = image.at<cv::Vec3b>(q);
                const float db = float(c[0]) - cn[0], dg = float(c[1]) - cn[1], dr = float(c[2]) - cn[2];
                best = std::max(best, std::sqrt(db * db + dg * dg + dr * dr));
            }
            out.at<float>(y, x) = best;
        }
    return out;
}

/// How far each mark is to be trusted (docs/vision.md, "Segmentation", strokes): a mark
/// whose colour is far likelier under another marked class's colour model than under its
/// own is dropped (a slip of the pen, a stroke past a border); a mark within
/// `edge_px` of a strong colour edge is soft evidence; the others are hard.
struct MarkTrust {
    cv::Mat hard;   ///< CV_8UC1 label index or 255
    cv::Mat soft;   ///< CV_8UC1 label index or 255
    long long dropped = 0;
    std::vector<detail::ColourHistogram> models;  ///< per label, from the kept marks (outlier test on)
    cv::Mat edge_distance;                        ///< CV_32F px to a strong colour edge (edge test on)

    /// Whether a mark of label `k` with colour bin `bin` passes the outlier test.
    bool consistent(int k, int bin, double margin) const {
        if (models.empty() || models[size_t(k)].total() <= 0) return true;
        float other = std::numeric_limits<float>::max();
        for (size_t l = 0; l < models.size(); ++l)
            if (int(l) != k && models[l].total() > 0) other = std::min(other, models[l].cost(bin));
        return models[size_t(k)].cost(bin) - other <= margin;
    }
};

MarkTrust trust_marks(const cv::Mat& small, const cv::Mat& marks, int labels,
                      const SegmentationOptions& o, double mean_step) {
    MarkTrust t;
    t.hard = marks.clone();
    t.soft = cv::Mat(marks.size(), CV_8UC1, cv::Scalar(255));
    const size_t L = size_t(labels);
    if (o.mark_outlier_margin > 0 && L > 1) {
        const cv::Mat bins = detail::colour_bins(small, o.histogram_bins);
        const int n = int(marks.total());
        cv::Mat keep = marks.clone();
        // Two passes: the models of the second leave out the first's outliers.
        for (int pass = 0; pass < 2; ++pass) {
            t.models.assign(L, detail::ColourHistogram(o.histogram_bins));
            for (int i = 0; i < n; ++i)
                if (keep.data[i] != 255) t.models[keep.data[i]].add(bins.ptr<int>(0)[i]);
            for (auto& m : t.models) m.finish();
            keep = marks.clone();
            for (int i = 0; i < n; ++i) {
                const int k = marks.data[i];
                if (k != 255 && !t.consistent(k, bins.ptr<int>(0)[i], o.mark_outlier_margin)) keep.data[i] = 255;
            }
        }
        for (int i = 0; i < n; ++i)
            if (marks.data[i] != 255 && keep.data[i] == 255) ++t.dropped;
        t.hard = keep;
    }
    if (o.mark_edge_px > 0) {
        const cv::Mat strong = colour_edge_strength(small) > float(o.mark_edge_factor * mean_step);
        cv::Mat& d = t.edge_distance;
        cv::distanceTransform(~strong, d, cv::DIST_L2, 3, CV_32F);
        for (size_t i = 0; i < t.hard.total(); ++i)
            if (t.hard.data[i] != 255 && d.ptr<float>(0)[i] < float(o.mark_edge_px)) {
                t.soft.data[i] = t.hard.data[i];
                t.hard.data[i] = 255;
            }
    }
    return t;
}

}  // namespace

double compact_mark_share(const cv::Mat& strokes, double max_elongation) {
    require(!strokes.empty() && strokes.type() == CV_8UC1,
            "compact_mark_share: strokes must be an 8-bit single-channel class map");
    cv::Mat comp, stats, centres;
    const int n = cv::connectedComponentsWithStats(strokes != kUnmarked, comp, stats, centres, 8, CV_32S);
    double all = 0, compact = 0;
    for (int c = 1; c < n; ++c) {
        const double a = stats.at<int>(c, cv::CC_STAT_AREA);
        const double side = std::max(stats.at<int>(c, cv::CC_STAT_WIDTH), stats.at<int>(c, cv::CC_STAT_HEIGHT));
        all += a;
        if (side * side < max_elongation * a) compact += a;
    }
    return all > 0 ? compact / all : 0.0;
}

namespace {

/// Distance (px) of every pixel of an image of `size` to the skeleton of `j` (joints in
/// that image's pixels): the legs' chain, the arms' chain through the shoulders, the
/// torso's sides, the spine (neck to mid-hip) and the neck to the head.
cv::Mat skeleton_distance(cv::Size size, const Joints& j) {
    auto at = [](const Eigen::Vector2d& p) { return cv::Point(int(std::floor(p.x())), int(std::floor(p.y()))); };
    std::vector<std::vector<cv::Point>> chains(2);
    for (int k = 0; k < 6; ++k) {
        chains[0].push_back(at(j.px[size_t(k)]));       // right ankle ... left ankle
        chains[1].push_back(at(j.px[size_t(k + 6)]));   // right hand ... left hand
    }
    chains.push_back({at(j[Joint::head]), at(j[Joint::neck]), at(j.mid_hip())});
    chains.push_back({at(j[Joint::right_shoulder]), at(j[Joint::right_hip])});
    chains.push_back({at(j[Joint::left_shoulder]), at(j[Joint::left_hip])});
    cv::Mat not_bone(size, CV_8UC1, cv::Scalar(255));
    cv::polylines(not_bone, chains, false, cv::Scalar(0), 1, cv::LINE_8);
    cv::Mat d;
    cv::distanceTransform(not_bone, d, cv::DIST_L2, 3, CV_32F);
    return d;
}

int count_classes(const cv::Mat& labels) {
    bool present[256] = {};
    for (auto it = labels.begin<std::uint8_t>(); it != labels.end<std::uint8_t>(); ++it)
        present[*it] = true;
    return int(std::count(present, present + 256, true));
}

bool is_garment(LabelRole r) {
    return r == LabelRole::upper_garment || r == LabelRole::lower_garment ||
           r == LabelRole::full_garment;
}

int count_garments(const cv::Mat& labels, const LabelTable& t, double min_area) {
    int counts[256] = {};
    for (auto it = labels.begin<std::uint8_t>(); it != labels.end<std::uint8_t>(); ++it)
        ++counts[*it];
    int g = 0;
    for (int id = 0; id < 255; ++id)
        if (counts[id] >= min_area && is_garment(t.role(id))) ++g;
    return g;
}

void finish(Segmentation& result, const SegmentationOptions& o, SegmentationSummary& s) {
    result.occlusion = occlusion_mask(result.labels, o.table);
    s.labels_used = count_classes(result.labels);
    s.garments_found = count_garments(result.labels, o.table, 0.002 * result.labels.total());
    if (s.garments_found == 0) {
        s.termination = SegmentationTermination::no_garment_found;
        s.message = "no garment region covers 0.2 % of the image";
    } else {
        s.termination = SegmentationTermination::ok;
    }
}

}  // namespace

cv::Mat occlusion_mask(const cv::Mat& labels, const LabelTable& table) {
    require(!labels.empty() && labels.type() == CV_8UC1,
            "occlusion_mask: labels must be a non-empty 8-bit single-channel class map");
    cv::Mat out = cv::Mat::zeros(labels.size(), CV_8UC1);
    cv::Mat garments = cv::Mat::zeros(labels.size(), CV_8UC1);
    cv::Mat front = cv::Mat::zeros(labels.size(), CV_8UC1);
    for (int y = 0; y < labels.rows; ++y)
        for (int x = 0; x < labels.cols; ++x) {
            const LabelRole r = table.role(labels.at<std::uint8_t>(y, x));
            if (is_garment(r)) garments.at<std::uint8_t>(y, x) = 255;
            if (r == LabelRole::skin || r == LabelRole::hair || r == LabelRole::occluder)
                front.at<std::uint8_t>(y, x) = 255;
        }
    // Non-garment pixels enclosed by a garment's outline (holes).
    std::vector<std::vector<cv::Point>> contours;
    cv::findContours(garments.clone(), contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_SIMPLE);
    cv::Mat filled = cv::Mat::zeros(labels.size(), CV_8UC1);
    cv::drawContours(filled, contours, -1, cv::Scalar(255), cv::FILLED);
    out |= filled & ~garments;
    // Skin, hair and occluders touching a garment (within 2 px).
    cv::Mat near;
    cv::dilate(garments, near, cv::getStructuringElement(cv::MORPH_ELLIPSE, {5, 5}));
    out |= near & front & ~garments;
    return out;
}

SegmentationSummary segment_with_strokes(const cv::Mat& image, const cv::Mat& strokes,
                                         const Joints* joints, const SegmentationOptions& o,
                                         Segmentation& result) {
    const auto t0 = Clock::now();
    std::string why;
    require(o.is_valid(&why), "SegmentationOptions: ", why);
    check_image(image, CV_8UC3, "photo");
    require(!strokes.empty() && strokes.type() == CV_8UC1,
            "strokes must be an 8-bit single-channel map of class ids (255 = unmarked)");
    require(strokes.size() == image.size(), "strokes are ", strokes.cols, " x ", strokes.rows,
            " px but the photo is ", image.cols, " x ", image.rows, " px");
    if (joints) joints->validate(image.cols, image.rows);
    // Classes marked.
    int counts[256] = {};
    for (auto it = strokes.begin<std::uint8_t>(); it != strokes.end<std::uint8_t>(); ++it)
        ++counts[*it];
    std::vector<int> ids;
    for (int id = 0; id < kUnmarked; ++id) {
        if (!counts[id]) continue;
        require(o.table.contains(id), "strokes use class id ", id,
                " which is not in the label table (labels.txt ids 0..58)");
        ids.push_back(id);
    }
    require(!ids.empty(), "strokes mark no pixel (every pixel is 255 = unmarked)");
    require(counts[o.table.background_id()] > 0,
            "strokes must mark some background (class ", o.table.background_id(), ")");
    require(ids.size() <= 64, "strokes use ", ids.size(), " classes (at most 64)");

    const double s = working_scale(image, o);
    const cv::Mat small = shrink(image, s);
    Problem p;
    p.labels = int(ids.size());
    int index_of[256];
    std::fill(index_of, index_of + 256, 255);
    for (size_t k = 0; k < ids.size(); ++k) index_of[ids[k]] = int(k);
    cv::Mat small_strokes;
    cv::resize(strokes, small_strokes, small.size(), 0, 0, cv::INTER_NEAREST);
    // Strokes that vanished when shrinking (thin, short marks): kept from the full-size map.
    for (size_t k = 0; k < ids.size(); ++k)
        if (cv::countNonZero(small_strokes == ids[k]) == 0) {
            cv::Mat full = strokes == ids[k], sm;
            cv::resize(full, sm, small.size(), 0, 0, cv::INTER_AREA);
            small_strokes.setTo(ids[k], (sm > 0) & (small_strokes == kUnmarked));
        }
    cv::Mat marks(small.size(), CV_8UC1);
    for (size_t i = 0; i < small_strokes.total(); ++i)
        marks.data[i] = static_cast<std::uint8_t>(index_of[small_strokes.data[i]]);
    const double body_h = joints ? joints->body_height_px() : 0.9 * image.rows;
    const double mean_step = mean_colour_step(small);
    const MarkTrust trust = trust_marks(small, marks, p.labels, o, mean_step);
    p.hard = trust.hard;
    p.soft = trust.soft;
    p.soft_weight = float(o.soft_mark_weight);
    const cv::Mat trusted = (trust.hard != 255) | (trust.soft != 255);
    // Sparse marks (a few clicks) leave most pixels far from every mark, so the distance
    // prior, made for strokes through every region, would outweigh the colours: its
    // weight falls in proportion to the marked share below `sparse_marks_fraction`, to
    // a quarter at most.
    const double marked = double(cv::countNonZero(strokes != kUnmarked)) / double(strokes.total());
    const double sparse_factor =
        o.sparse_marks_fraction > 0 ? std::clamp(marked / o.sparse_marks_fraction, 0.25, 1.0) : 1.0;
    // Clicks (compact marks) say where a region is, not how far it reaches: the distance
    // weight falls with their share b, and the skeleton prior below rises as much (what
    // the marks no longer bound, the body does).
    const double compact = o.compact_marks_factor < 1 ? compact_mark_share(strokes, o.compact_mark_elongation) : 0.0;
    const double compact_factor = 1 - compact * (1 - o.compact_marks_factor);
    for (size_t k = 0; k < ids.size(); ++k) {
        cv::Mat seed = ((trust.hard == int(k)) | (trust.soft == int(k)));
        if (cv::countNonZero(seed) == 0) seed = marks == int(k);  // every mark dropped: keep them
        const cv::Mat d = geodesic_distance(small, seed, o.stroke_colour_weight, mean_step);
        // First colour model: the marks grown along their geodesic ball, so that a few
        // clicks sample their region's colours, not a dozen pixels.
        const double grow = o.seed_growth_fraction * body_h * s;
        p.model_seed.push_back(grow > 0 ? cv::Mat(d <= float(grow)) : seed);
        const double f = ids[k] == o.table.background_id() ? o.background_distance_factor : 1.0;
        p.prior.push_back(d * (f * sparse_factor * compact_factor * o.stroke_distance_weight / (body_h * s)));
    }
    // The person is where the joints are: every class but the background costs more the
    // farther a pixel lies beyond `body_reach_fraction` of the body height from the
    // skeleton (up to `body_prior_weight`, reached one reach farther out). Sparse marks
    // (a few clicks) leave most of the background far from its own marks.
    if (joints && o.body_prior_weight > 0) {
        const double H = body_h * s, r0 = o.body_reach_fraction * H;
        const cv::Mat d = skeleton_distance(small.size(), joints->scaled(s));
        cv::Mat ramp = (d - r0) / std::max(1e-6, r0);
        cv::max(ramp, 0.0, ramp);
        cv::min(ramp, 1.0, ramp);
        ramp *= o.body_prior_weight / compact_factor;
        for (size_t k = 0; k < ids.size(); ++k)
            if (ids[k] != o.table.background_id()) p.prior[k] += ramp;
    }
    // Where people wear what (the automatic mode's learned layout), through each marked
    // class's role; a dress is upper or lower, wherever its waist is.
    if (joints && o.stroke_layout_weight > 0) {
        const auto learned = detail::learned_layout(small.size(), joints->scaled(s), detail::kLayoutPseudoCount);
        for (size_t k = 0; k < ids.size(); ++k) {
            const LabelRole role = o.table.role(ids[k]);
            const cv::Mat p_role = role == LabelRole::full_garment
                                       ? cv::Mat(learned[detail::kUpper] + learned[detail::kLower])
                                       : learned[detail::auto_label_of(role, false)];
            cv::Mat log_p;
            cv::log(cv::max(p_role, 1e-6), log_p);
            p.prior[k] -= log_p * o.stroke_layout_weight;
        }
    }
    // The marks the full-resolution stages keep fixed: the same tests on each full-size
    // mark (its own colour; the edge distance of its working pixel, in working px).
    cv::Mat fixed = strokes.clone();
    if (o.mark_outlier_margin > 0 || o.mark_edge_px > 0) {
        for (int y = 0; y < strokes.rows; ++y) {
            const int ys = std::min(small.rows - 1, int(y * s));
            for (int x = 0; x < strokes.cols; ++x) {
                std::uint8_t& v = fixed.at<std::uint8_t>(y, x);
                if (v == kUnmarked) continue;
                const int xs = std::min(small.cols - 1, int(x * s));
                const int k = index_of[v];
                if (!trust.edge_distance.empty() && trust.edge_distance.at<float>(ys, xs) < float(o.mark_edge_px))
                    v = kUnmarked;
                else if (!trust.consistent(k, detail::colour_bin(image.at<cv::Vec3b>(y, x), o.histogram_bins),
                                           o.mark_outlier_margin))
                    v = kUnmarked;
            }
        }
    }
    (void)trusted;
    cv::Mat small_idx = solve(small, p, o);
    cv::Mat small_ids(small_idx.size(), CV_8UC1);
    for (size_t i = 0; i < small_idx.total(); ++i)
        small_ids.data[i] = static_cast<std::uint8_t>(ids[small_idx.data[i]]);
    SegmentationSummary summary;
    summary.seconds_graph_cut = since(t0);
    result = Segmentation{};
    result.labels = refine(image, small_ids, fixed, body_h, o, summary.seconds_refinement);
    finish(result, o, summary);
    summary.seconds = since(t0);
    return summary;
}

SegmentationSummary segment_automatic(const cv::Mat& image, const Joints& joints,
                                      const SegmentationOptions& o, Segmentation& result) {
    using namespace detail;
    const auto t0 = Clock::now();
    std::string why;
    require(o.is_valid(&why), "SegmentationOptions: ", why);
    check_image(image, CV_8UC3, "photo");
    joints.validate(image.cols, image.rows);
    const double s = working_scale(image, o);
    const cv::Mat small = shrink(image, s);
    const BodyLayout layout = body_layout(small.size(), joints.scaled(s));
    Problem p;
    p.labels = kAutoLabels;
    p.hard = layout.hard;
    p.model_seed.assign(layout.seed.begin(), layout.seed.end());
    // Spatial costs: layout_weight x -ln p(label | body-frame cell), p learned from hand
    // labels (tools/derive_layout_prior.cpp). "Other" (shoes, tights, bags, outerwear) has
    // no hand-placed seed: its first colour model comes from where the layout expects it
    // more than anything else (above all the feet).
    const auto learned = learned_layout(small.size(), joints.scaled(s), kLayoutPseudoCount);
    for (int l = 0; l < kAutoLabels; ++l) {
        cv::Mat log_p;
        cv::log(learned[size_t(l)], log_p);
        p.prior.push_back(log_p * -o.layout_weight);
    }
    // ... without the colours of where the layout expects the lower garment or skin most
    // (thighs and hips; face, arms): a maxi skirt or trousers cover the feet, and a seed
    // on them would give "other" the garment's colours. A colour is theirs when their
    // histogram gives it more than a uniform one would (cost < 0). (A guard: no change
    // measured on the tuning photos, docs/notes/vision.md.)
    {
        const cv::Mat bins = colour_bins(small, o.histogram_bins);
        std::array<ColourHistogram, 2> known{ColourHistogram(o.histogram_bins),
                                             ColourHistogram(o.histogram_bins)};
        const cv::Mat lower_region = learned[kLower] > kOtherSeedProbability;
        const cv::Mat skin_region = learned[kSkin] > kOtherSeedProbability;
        for (size_t i = 0; i < bins.total(); ++i) {
            if (lower_region.data[i]) known[0].add(bins.ptr<int>(0)[i]);
            if (skin_region.data[i]) known[1].add(bins.ptr<int>(0)[i]);
        }
        cv::Mat seed = learned[kOther] > kOtherSeedProbability;
        for (auto& h : known) {
            if (h.total() <= 0) continue;
            h.finish();
            for (size_t i = 0; i < bins.total(); ++i)
                if (seed.data[i] && h.cost(bins.ptr<int>(0)[i]) < 0) seed.data[i] = 0;
        }
        p.model_seed[kOther] = seed;
    }
    // "Other" only where the layout finds it at least as likely as the lower garment
    // (feet, lower legs of most people): elsewhere, once its colour model has a garment's
    // colours, it takes the garment (002149's maxi skirt, whose thigh seeds lie on a clutch:
    // lower IoU 0.00 without this rule, 0.84 with it).
    p.prior[kOther].setTo(1e4, learned[kLower] > learned[kOther]);
    const cv::Mat idx = solve(small, p, o);

    // Dress or two pieces: one colour model for the upper and lower regions?
    // A fixed 16 bins per channel, whatever histogram_bins: the 0.75 threshold on the
    // Bhattacharyya coefficient depends on the binning.
    constexpr int kDressBins = 16;
    // Belts, sashes and waistbands sit at the natural waist (62 % shoulder -> hip, as in
    // body_layout) and are up to ~10 cm wide: they are not the dress's fabric, so pixels
    // within kWaistBandFraction x body height of the waist line are left out of both
    // histograms (a gold sash between two white halves made 001630 two garments).
    constexpr double kWaistBandFraction = 0.06;
    const cv::Mat bins = colour_bins(small, kDressBins);
    const Joints js = joints.scaled(s);
    const Eigen::Vector2d waist_r = js[Joint::right_shoulder] + 0.62 * (js[Joint::right_hip] - js[Joint::right_shoulder]),
                          waist_l = js[Joint::left_shoulder] + 0.62 * (js[Joint::left_hip] - js[Joint::left_shoulder]);
    const Eigen::Vector2d waist_dir = (waist_l - waist_r).normalized();
    const double waist_band = kWaistBandFraction * js.body_height_px();
    auto colour_similarity = [&](bool skip_waist) {
        ColourHistogram hu(kDressBins), hl(kDressBins);
        for (int y = 0; y < idx.rows; ++y)
            for (int x = 0; x < idx.cols; ++x) {
                const int l = idx.at<std::uint8_t>(y, x);
                if (l != kUpper && l != kLower) continue;
                const Eigen::Vector2d d = Eigen::Vector2d(x + 0.5, y + 0.5) - waist_r;
                if (skip_waist && std::abs(d.x() * waist_dir.y() - d.y() * waist_dir.x()) < waist_band) continue;
                (l == kUpper ? hu : hl).add(bins.at<int>(y, x));
            }
        hu.finish();
        hl.finish();
        return std::pair{(hu.total() > 0 && hl.total() > 0) ? hu.similarity(hl) : 0.0,
                         std::min(hu.total(), hl.total())};
    };
    auto [similarity, kept] = colour_similarity(true);
    // A part left smaller than a garment's minimum area (0.2 % of the image) outside the
    // band: compare the whole regions.
    if (kept < 0.002 * double(idx.total())) similarity = colour_similarity(false).first;
    bool dress = similarity > 0.75;
    if (o.hint) dress = part_of(*o.hint) == GarmentPart::full;

    const int skin = o.table.skin_id() >= 0 ? o.table.skin_id() : 41;
    const int hair = o.table.hair_id() >= 0 ? o.table.hair_id() : 19;
    const int kUpperTmp = 250, kLowerTmp = 251;
    const std::vector<int> occluders = o.table.ids_with_role(LabelRole::occluder);
    const int other = occluders.empty() ? o.table.background_id() : occluders.front();
    const std::array<int, kAutoLabels> to_id = {o.table.background_id(), skin, hair, kUpperTmp,
                                                kLowerTmp, other};
    cv::Mat small_ids(idx.size(), CV_8UC1);
    for (size_t i = 0; i < idx.total(); ++i)
        small_ids.data[i] = static_cast<std::uint8_t>(to_id[idx.data[i]]);
    SegmentationSummary summary;
    summary.seconds_graph_cut = since(t0);
    result = Segmentation{};
    result.labels = refine(image, small_ids, cv::Mat(), joints.body_height_px(), o,
                           summary.seconds_refinement);

    // Bare arms the cut gave to the upper garment (a pale or over-exposed arm beside a
    // white top) would read as sleeves: garment pixels along an arm with the skin's
    // chromaticity rather than the torso fabric's go back to skin (bare_arms.hpp).
    const cv::Mat hair_mask = result.labels == hair;  // unchanged below
    result.labels.setTo(skin, bare_arm_pixels(image, result.labels == kUpperTmp,
                                              result.labels == skin, joints, hair_mask));

    // Classify and write the garments' class ids.
    const double min_area = 0.002 * double(result.labels.total());
    auto assign = [&](const cv::Mat& mask, GarmentType t) {
        result.labels.setTo(label_id_of(t), mask);
        result.garment_types.emplace_back(label_id_of(t), t);
    };
    const cv::Mat mu = result.labels == kUpperTmp, ml = result.labels == kLowerTmp;
    // The learned decision (garment_type_model.hpp) replaces the colour-similarity rule
    // when both regions are garments and the model is trained.
    std::optional<bool> learned_dress;
    if (!o.hint && cv::countNonZero(mu) >= min_area && cv::countNonZero(ml) >= min_area)
        learned_dress = detail::learned_is_dress(image, mu, ml, joints);
    if (learned_dress) dress = *learned_dress;
    if (dress) {
        const cv::Mat both = mu | ml;
        if (cv::countNonZero(both) >= min_area) assign(both, GarmentType::dress);
        else result.labels.setTo(o.table.background_id(), both);
    } else {
        for (const auto& [mask, part] : {std::pair{mu, GarmentPart::upper},
                                         std::pair{ml, GarmentPart::lower}}) {
            if (cv::countNonZero(mask) < min_area) {
                result.labels.setTo(o.table.background_id(), mask);
                continue;
            }
            const GarmentShapeCues cues = measure_shape_cues(mask, joints, hair_mask);
            GarmentType t = part == GarmentPart::upper ? classify_upper(cues) : classify_lower(cues);
            if (part == GarmentPart::lower)
                if (const auto lt = detail::learned_lower_type(image, mask, joints, hair_mask)) t = *lt;
            if (o.hint && part_of(*o.hint) == part) t = *o.hint;
            assign(mask, t);
        }
    }
    finish(result, o, summary);
    std::ostringstream msg;
    msg << "upper/lower colour similarity " << std::fixed << std::setprecision(2) << similarity
        << (learned_dress ? ", learned model" : "") << (dress ? " -> dress" : " -> two pieces");
    if (!summary.message.empty()) msg << "; " << summary.message;
    summary.message = msg.str();
    summary.seconds = since(t0);
    return summary;
}

}  // namespace drape::vision

namespace drape::vision {

cv::Mat draw_segmentation(const cv::Mat& image, const cv::Mat& labels) {
    check_image(image, CV_8UC3, "photo");
    require(labels.type() == CV_8UC1 && labels.size() == image.size(),
            "draw_segmentation: labels must be CV_8UC1 of the photo's size");
    cv::Mat out = image.clone();
    for (int y = 0; y < image.rows; ++y)
        for (int x = 0; x < image.cols; ++x) {
            const int id = labels.at<std::uint8_t>(y, x);
            if (id == 0) continue;
            // A fixed, well-spread colour per id (golden-ratio hue steps).
            const double h = std::fmod(id * 0.618034, 1.0) * 6.0;
            const double f = h - std::floor(h);
            const double rgb[6][3] = {{1, f, 0}, {1 - f, 1, 0}, {0, 1, f},
                                      {0, 1 - f, 1}, {f, 0, 1}, {1, 0, 1 - f}};
            const auto& c = rgb[int(h) % 6];
            cv::Vec3b& p = out.at<cv::Vec3b>(y, x);
            for (int k = 0; k < 3; ++k)
                p[k] = cv::saturate_cast<std::uint8_t>(0.5 * p[k] + 0.5 * 255 * c[2 - k]);
        }
    cv::Mat edges;
    cv::Mat dx, dy;
    cv::Mat l16;
    labels.convertTo(l16, CV_16S);
    cv::Sobel(l16, dx, CV_16S, 1, 0, 1);
    cv::Sobel(l16, dy, CV_16S, 0, 1, 1);
    edges = (dx != 0) | (dy != 0);
    out.setTo(cv::Scalar(255, 255, 255), edges);
    return out;
}

}  // namespace drape::vision
