// Fold detection and wrinkle density (docs/vision.md, "Wrinkle density").
#include <drape/vision/wrinkle_density.hpp>

#include <drape/vision/image_io.hpp>

#include "print_suppression.hpp"
#include "thinning.hpp"

#include <drape/core/errors.hpp>

#include <Eigen/Dense>
#include <opencv2/imgproc.hpp>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace drape::vision {

bool WrinkleOptions::is_valid(std::string* why) const {
    auto fail = [&](const char* m) { if (why) *why = m; return false; };
    if (!(person_height_m > 0)) return fail("person_height_m must be > 0");
    if (scale_fractions.empty()) return fail("scale_fractions must not be empty");
    for (double s : scale_fractions)
        if (!(s > 0 && s < 0.2)) return fail("scale_fractions must lie in (0, 0.2)");
    if (!(ridge_threshold > 0)) return fail("ridge_threshold must be > 0");
    if (!(working_body_height_px >= 100)) return fail("working_body_height_px must be >= 100");
    if (!(min_edge_fraction >= 0)) return fail("min_edge_fraction must be >= 0");
    if (!(merge_gap_fraction >= 0)) return fail("merge_gap_fraction must be >= 0");
    if (!(merge_angle_deg >= 0 && merge_angle_deg <= 90)) return fail("merge_angle_deg must be in [0, 90]");
    if (!(max_curvature_fraction > 0)) return fail("max_curvature_fraction must be > 0");
    if (!(pair_min_gap_fraction >= 0 && pair_max_gap_fraction > pair_min_gap_fraction))
        return fail("need 0 <= pair_min_gap_fraction < pair_max_gap_fraction");
    if (!(pair_angle_deg >= 0 && pair_angle_deg <= 90)) return fail("pair_angle_deg must be in [0, 90]");
    if (!(pair_min_overlap >= 0 && pair_min_overlap <= 1)) return fail("pair_min_overlap must be in [0, 1]");
    if (!(border_fraction >= 0)) return fail("border_fraction must be >= 0");
    if (!(full_fold_fraction >= 0)) return fail("full_fold_fraction must be >= 0");
    if (resolution_ensemble < 1) return fail("resolution_ensemble must be >= 1");
    if (!(source_blur_px >= 0)) return fail("source_blur_px must be >= 0");
    if (phase_ensemble != 1 && phase_ensemble != 2 && phase_ensemble != 4)
        return fail("phase_ensemble must be 1, 2 or 4");
    if (threads < 0) return fail("threads must be >= 0");
    if (!(min_garment_area_fraction >= 0)) return fail("min_garment_area_fraction must be >= 0");
    if (!(min_fold_count >= 0)) return fail("min_fold_count must be >= 0");
    if (!(max_step_ratio >= 0)) return fail("max_step_ratio must be >= 0");
    if (!(print_step_threshold > 0)) return fail("print_step_threshold must be > 0");
    if (!(print_chroma_threshold > 0)) return fail("print_chroma_threshold must be > 0");
    if (!(print_edge_sigma_px >= 0.7 && print_edge_sigma_px < 100)) return fail("print_edge_sigma_px must lie in [0.7, 100)");
    return true;
}

std::string WrinkleSummary::brief_report() const {
    static const char* names[] = {"ok", "garment_too_small", "failed"};
    std::ostringstream os;
    os << "wrinkles: " << names[static_cast<int>(termination)] << ", " << edges_detected
       << " edges, " << edges_merged << " after merging, " << folds << " folds (" << std::setprecision(3)
       << fold_count << " length-weighted) on "
       << std::setprecision(3) << garment_area_m2 << " m^2 -> P = " << density_per_m2
       << " /m^2, " << std::fixed << std::setprecision(2) << seconds << " s";
    if (!message.empty()) os << " (" << message << ")";
    return os.str();
}

namespace {

using Vec = Eigen::Vector2d;

/// A fitted edge: quadric v = a + b u + c u^2 in a frame (origin, axis), u in [u0, u1].
struct Edge {
    Vec origin, axis;  ///< axis unit
    double a = 0, b = 0, c = 0, u0 = 0, u1 = 0;
    bool bright = false;
    std::vector<Vec> pts;  ///< the raw pixels (image frame, pixel centres)
    bool alive = true;

    Vec at(double u) const {
        const Vec n(-axis.y(), axis.x());
        return origin + u * axis + (a + b * u + c * u * u) * n;
    }
    Vec start() const { return at(u0); }
    Vec end() const { return at(u1); }
    double length() const { return u1 - u0; }
    /// Unit tangent at u.
    Vec tangent(double u) const {
        const Vec n(-axis.y(), axis.x());
        return (axis + (b + 2 * c * u) * n).normalized();
    }
    Vec direction() const { return (end() - start()).normalized(); }
};

/// Least-squares quadric fit in the points' principal frame.
bool fit(Edge& e) {
    const size_t n = e.pts.size();
    if (n < 3) return false;
    Vec mean = Vec::Zero();
    for (const auto& p : e.pts) mean += p;
    mean /= double(n);
    Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
    for (const auto& p : e.pts) cov += (p - mean) * (p - mean).transpose();
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(cov);
    e.origin = mean;
    e.axis = es.eigenvectors().col(1).normalized();
    const Vec nrm(-e.axis.y(), e.axis.x());
    Eigen::MatrixXd A(static_cast<Eigen::Index>(n), 3);
    Eigen::VectorXd v(static_cast<Eigen::Index>(n));
    e.u0 = 1e300;
    e.u1 = -1e300;
    for (size_t i = 0; i < n; ++i) {
        const double u = (e.pts[i] - mean).dot(e.axis);
        A(Eigen::Index(i), 0) = 1;
        A(Eigen::Index(i), 1) = u;
        A(Eigen::Index(i), 2) = u * u;
        v(Eigen::Index(i)) = (e.pts[i] - mean).dot(nrm);
        e.u0 = std::min(e.u0, u);
        e.u1 = std::max(e.u1, u);
    }
    const Eigen::Vector3d coef = A.colPivHouseholderQr().solve(v);
    e.a = coef(0);
    e.b = coef(1);
    e.c = coef(2);
    return std::isfinite(e.a) && std::isfinite(e.b) && std::isfinite(e.c);
}

/// Fits `pts` as low-curvature quadrics, splitting pieces that bend too much.
void fit_pieces(std::vector<Vec> pts, bool bright, double max_turn, double min_len, int depth,
                std::vector<Edge>& out) {
    Edge e;
    e.pts = std::move(pts);
    e.bright = bright;
    if (!fit(e) || e.length() < min_len) return;
    // Turning angle of the fitted curve ~ 2|c| L; quadric residual.
    double rms = 0;
    const Vec nrm(-e.axis.y(), e.axis.x());
    for (const auto& p : e.pts) {
        const double u = (p - e.origin).dot(e.axis);
        const double r = (p - e.origin).dot(nrm) - (e.a + e.b * u + e.c * u * u);
        rms += r * r;
    }
    rms = std::sqrt(rms / double(e.pts.size()));
    const double turn = 2 * std::abs(e.c) * e.length();
    if ((turn > max_turn || rms > 0.08 * e.length() + 1.0) && depth < 3) {
        const double mid = 0.5 * (e.u0 + e.u1);
        std::vector<Vec> lo, hi;
        for (const auto& p : e.pts) ((p - e.origin).dot(e.axis) < mid ? lo : hi).push_back(p);
        fit_pieces(std::move(lo), bright, max_turn, min_len, depth + 1, out);
        fit_pieces(std::move(hi), bright, max_turn, min_len, depth + 1, out);
        return;
    }
    if (turn > max_turn) return;
    out.push_back(std::move(e));
}

/// |cos| of the undirected angle between two unit directions: the angle exceeds a limit
/// exactly when this falls below the limit's cosine (no acos in the inner loops).
double abs_cos(const Vec& d1, const Vec& d2) { return std::min(1.0, std::abs(d1.dot(d2))); }

/// Merges pieces of the same polarity with close ends and similar directions.
void merge(std::vector<Edge>& edges, double gap, double max_angle, double max_turn) {
    const double min_cos = std::cos(max_angle);
    std::vector<Vec> dir(edges.size());
    for (size_t i = 0; i < edges.size(); ++i) dir[i] = edges[i].direction();
    bool merged = true;
    while (merged) {
        merged = false;
        for (size_t i = 0; i < edges.size() && !merged; ++i) {
            if (!edges[i].alive) continue;
            for (size_t k = i + 1; k < edges.size() && !merged; ++k) {
                Edge& a = edges[i];
                Edge& b = edges[k];
                if (!b.alive || a.bright != b.bright) continue;
                if (abs_cos(dir[i], dir[k]) < min_cos) continue;
                const Vec ea[2] = {a.start(), a.end()}, eb[2] = {b.start(), b.end()};
                double best = 1e300;
                Vec p = ea[0], q = eb[0];
                for (const auto& x : ea)
                    for (const auto& y : eb)
                        if ((x - y).norm() < best) { best = (x - y).norm(); p = x; q = y; }
                if (best > gap) continue;
                if (best > 1.0 && abs_cos((q - p).normalized(), dir[i]) < min_cos) continue;
                Edge m;
                m.bright = a.bright;
                m.pts = a.pts;
                m.pts.insert(m.pts.end(), b.pts.begin(), b.pts.end());
                if (!fit(m) || 2 * std::abs(m.c) * m.length() > max_turn) continue;
                a = std::move(m);
                dir[i] = a.direction();
                b.alive = false;
                merged = true;
            }
        }
    }
    edges.erase(std::remove_if(edges.begin(), edges.end(), [](const Edge& e) { return !e.alive; }),
                edges.end());
}

/// The edge as a polyline in the photo's pixels (working pixels / scale + offset).
FoldEdge sample(const Edge& e, double scale, const Vec& offset) {
    FoldEdge f;
    f.bright = e.bright;
    const int n = std::max(2, int(std::ceil(e.length() / 2.0)) + 1);
    for (int i = 0; i < n; ++i)
        f.points_px.push_back(e.at(e.u0 + (e.u1 - e.u0) * i / (n - 1)) / scale + offset);
    return f;
}

/// The garment's box (margin 3 sigma of the largest scale) cut from the photo once, as
/// float gray, with its masks; each detection of the ensemble resamples it.
struct GarmentCrop {
    cv::Rect roi;
    cv::Mat gray;       ///< CV_32F in [0, 1], the photo's resolution
    cv::Mat mask, occlusion;  ///< views of the photo-size masks (occlusion may be empty)
};

GarmentCrop crop_garment(const cv::Mat& image, const cv::Mat& mask, const cv::Mat& occlusion, double H,
                         const WrinkleOptions& o) {
    const double sigma_max = *std::max_element(o.scale_fractions.begin(), o.scale_fractions.end()) * H;
    const int margin = int(std::ceil(3 * sigma_max)) + 2;
    const cv::Rect box = cv::boundingRect(mask);
    GarmentCrop c;
    c.roi = cv::Rect(box.x - margin, box.y - margin, box.width + 2 * margin, box.height + 2 * margin) &
            cv::Rect(0, 0, image.cols, image.rows);
    c.mask = mask(c.roi);
    if (o.suppress_prints) {
        detail::ShadingOptions so;
        so.edge_sigma_px = o.print_edge_sigma_px;
        so.step_threshold = o.print_step_threshold;
        so.chroma_threshold = o.print_chroma_threshold;
        so.method = o.print_method;
        // On the working grid (the body working_body_height_px tall), so that the print's
        // edges and the folds are told apart at the same body-relative scale whatever the
        // photo's resolution; then back to the photo's grid for the ensemble.
        const double f = o.working_body_height_px / H;
        const cv::Size ws(std::max(3, int(std::lround(c.roi.width * f))), std::max(3, int(std::lround(c.roi.height * f))));
        cv::Mat bgr_w, mask_w;
        cv::resize(image(c.roi), bgr_w, ws, 0, 0, f < 1 ? cv::INTER_AREA : cv::INTER_CUBIC);
        cv::resize(c.mask, mask_w, ws, 0, 0, cv::INTER_NEAREST);
        cv::Mat edges;
        const cv::Mat shading = detail::shading_luminance(bgr_w, mask_w, so, &edges);
        if (cv::countNonZero(edges & mask_w) == 0) {
            cv::cvtColor(image(c.roi), c.gray, cv::COLOR_BGR2GRAY);
            c.gray.convertTo(c.gray, CV_32F, 1.0 / 255.0);
        } else {
            cv::resize(shading, c.gray, c.roi.size(), 0, 0, f > 1 ? cv::INTER_AREA : cv::INTER_CUBIC);
        }
    } else {
        cv::cvtColor(image(c.roi), c.gray, cv::COLOR_BGR2GRAY);
        c.gray.convertTo(c.gray, CV_32F, 1.0 / 255.0);
    }
    if (!occlusion.empty()) c.occlusion = occlusion(c.roi);
    return c;
}

/// The folds of one detection from its ridge responses: sets the edge and fold counts of `s`.
void count_folds(const cv::Mat& resp_bright, const cv::Mat& resp_dark, const cv::Mat& nx_b, const cv::Mat& ny_b,
                 const cv::Mat& nx_d, const cv::Mat& ny_d, const cv::Mat& step_b, const cv::Mat& step_d,
                 const cv::Mat& valid, double Hw,
                 double f, const Vec& offset, const WrinkleOptions& o, WrinkleSummary& s,
                 std::vector<Fold>* folds) {
    const double max_turn = o.max_curvature_fraction * 0.25;  // radians of turn
    const double min_len = o.min_edge_fraction * Hw;
    std::vector<Edge> edges;
    for (int polarity = 0; polarity < 2; ++polarity) {
        const cv::Mat& r = polarity ? resp_bright : resp_dark;
        const cv::Mat& nx = polarity ? nx_b : nx_d;
        const cv::Mat& ny = polarity ? ny_b : ny_d;
        const cv::Mat& st = polarity ? step_b : step_d;
        const bool profile = o.max_step_ratio > 0;
        cv::Mat keep = cv::Mat::zeros(r.size(), CV_8UC1);
        for (int y = 1; y < r.rows - 1; ++y)
            for (int x = 1; x < r.cols - 1; ++x) {
                const float v = r.at<float>(y, x);
                // Hysteresis: pixels down to half the threshold, kept below when their
                // piece reaches the threshold somewhere.
                if (v < 0.5 * o.ridge_threshold || !valid.at<std::uint8_t>(y, x)) continue;
                // Ridge profile: a fold's crest or crease is a luminance extremum across
                // it; the side of a step (a print edge) has the slope of the step there.
                if (profile && st.at<float>(y, x) > o.max_step_ratio) continue;
                const int dx = int(std::lround(nx.at<float>(y, x))), dy = int(std::lround(ny.at<float>(y, x)));
                if (v >= r.at<float>(y + dy, x + dx) && v >= r.at<float>(y - dy, x - dx))
                    keep.at<std::uint8_t>(y, x) = 1;
            }
        {
            cv::Mat comp;
            const int n = cv::connectedComponents(keep, comp, 8, CV_32S);
            std::vector<char> strong(static_cast<size_t>(n), 0);
            for (int y = 0; y < r.rows; ++y)
                for (int x = 0; x < r.cols; ++x)
                    if (keep.at<std::uint8_t>(y, x) && r.at<float>(y, x) >= o.ridge_threshold)
                        strong[static_cast<size_t>(comp.at<int>(y, x))] = 1;
            for (int y = 0; y < r.rows; ++y)
                for (int x = 0; x < r.cols; ++x)
                    if (keep.at<std::uint8_t>(y, x) && !strong[static_cast<size_t>(comp.at<int>(y, x))])
                        keep.at<std::uint8_t>(y, x) = 0;
        }
        keep.row(0).setTo(0); keep.row(keep.rows - 1).setTo(0);
        keep.col(0).setTo(0); keep.col(keep.cols - 1).setTo(0);
        detail::thin(keep);
        cv::Mat comp;
        const int n = cv::connectedComponents(keep, comp, 8, CV_32S);
        std::vector<std::vector<Vec>> pieces(static_cast<size_t>(n));
        for (int y = 0; y < comp.rows; ++y)
            for (int x = 0; x < comp.cols; ++x) {
                const int k = comp.at<int>(y, x);
                if (k > 0) pieces[static_cast<size_t>(k)].emplace_back(x + 0.5, y + 0.5);
            }
        for (auto& p : pieces)
            if (double(p.size()) >= 0.3 * min_len)
                fit_pieces(std::move(p), polarity == 1, max_turn, 0.3 * min_len, 0, edges);
    }
    const double rad = M_PI / 180.0;
    merge(edges, o.merge_gap_fraction * Hw, o.merge_angle_deg * rad, max_turn);
    edges.erase(std::remove_if(edges.begin(), edges.end(),
                               [&](const Edge& e) { return e.length() < min_len; }),
                edges.end());
    s.edges_merged = int(edges.size());
    s.edges_detected = s.edges_merged;
    // Pair bright ridges with dark valleys running beside them; best overlaps first.
    struct Candidate { size_t r, v; double score; };
    std::vector<Candidate> cands;
    const double pair_min_cos = std::cos(o.pair_angle_deg * rad);
    for (size_t i = 0; i < edges.size(); ++i) {
        if (!edges[i].bright) continue;
        for (size_t k = 0; k < edges.size(); ++k) {
            if (edges[k].bright) continue;
            const Edge& r = edges[i];
            const Edge& v = edges[k];
            if (abs_cos(r.direction(), v.direction()) < pair_min_cos) continue;
            const Vec d = r.direction();
            const Vec rs = r.start(), re = r.end();
            double a0 = 0, a1 = (re - rs).dot(d);
            double b0 = (v.start() - rs).dot(d), b1 = (v.end() - rs).dot(d);
            if (b0 > b1) std::swap(b0, b1);
            const double overlap = std::min(a1, b1) - std::max(a0, b0);
            const double shorter = std::min(a1 - a0, b1 - b0);
            if (shorter <= 0 || overlap < o.pair_min_overlap * shorter) continue;
            // Perpendicular gap: each edge's mid-point to the other's chord, averaged.
            const Vec nr(-d.y(), d.x());
            const Vec dv = v.direction(), nv(-dv.y(), dv.x());
            const Vec mr = r.at(0.5 * (r.u0 + r.u1)), mv = v.at(0.5 * (v.u0 + v.u1));
            const double gap = 0.5 * (std::abs((mv - rs).dot(nr)) + std::abs((mr - v.start()).dot(nv)));
            if (gap < o.pair_min_gap_fraction * Hw || gap > o.pair_max_gap_fraction * Hw) continue;
            cands.push_back({i, k, overlap});
        }
    }
    std::sort(cands.begin(), cands.end(), [](const Candidate& a, const Candidate& b) {
        return a.score > b.score;
    });
    std::vector<bool> used(edges.size(), false);
    for (const auto& c : cands) {
        if (used[c.r] || used[c.v]) continue;
        used[c.r] = used[c.v] = true;
        ++s.folds;
        // A fold shorter than full_fold_fraction x body height counts in proportion, so
        // that a fold growing past a length threshold does not make P jump.
        s.fold_count += o.full_fold_fraction > 0 ? std::min(1.0, c.score / (o.full_fold_fraction * Hw)) : 1.0;
        if (folds) folds->push_back({sample(edges[c.r], f, offset), sample(edges[c.v], f, offset)});
    }
}

/// One detection with the body resampled to Hw px: sets the edge and fold counts of `s`.
void detect_at(const GarmentCrop& crop, double H, double Hw, const Vec& phase, const WrinkleOptions& o,
               WrinkleSummary& s, std::vector<Fold>* folds) {
    // The crop is resampled so that the body is Hw px tall: every filter then sees the
    // same pixel scale whatever the photo's resolution (discrete derivatives bias small
    // sigmas).
    const cv::Rect& roi = crop.roi;
    const double f = Hw / H;
    const cv::Size work_size(std::max(3, int(std::lround(roi.width * f))),
                             std::max(3, int(std::lround(roi.height * f))));
    cv::Mat gray;
    cv::resize(crop.gray, gray, work_size, 0, 0, f < 1 ? cv::INTER_AREA : cv::INTER_CUBIC);
    if (phase.squaredNorm() > 0) {
        const cv::Matx23d shift(1, 0, phase.x(), 0, 1, phase.y());
        cv::warpAffine(gray, gray, shift, gray.size(), cv::INTER_CUBIC, cv::BORDER_REPLICATE);
    }
    cv::Mat mask_w, occ_w;
    cv::resize(crop.mask, mask_w, work_size, 0, 0, cv::INTER_NEAREST);
    if (!crop.occlusion.empty()) cv::resize(crop.occlusion, occ_w, work_size, 0, 0, cv::INTER_NEAREST);
    const Vec offset(roi.x, roi.y);
    // Valid area: the garment without a band along its border and along occlusions.
    cv::Mat valid = mask_w.clone();
    const int band = std::max(1, int(std::lround(o.border_fraction * Hw)));
    cv::erode(valid, valid, cv::getStructuringElement(cv::MORPH_ELLIPSE, {2 * band + 1, 2 * band + 1}),
              {-1, -1}, 1, cv::BORDER_CONSTANT, cv::Scalar(0));
    if (!occ_w.empty()) {
        cv::Mat occ;
        cv::dilate(occ_w, occ, cv::getStructuringElement(cv::MORPH_ELLIPSE,
                   {2 * band + 1, 2 * band + 1}));
        valid &= ~occ;
    }
    // Multi-scale Hessian: scale-normalised sigma^2 * eigenvalues; keep the strongest.
    // Responses are needed on the valid area and its 8-neighbours (non-maximum
    // suppression reads them), the normals only where a response can pass the lowest
    // hysteresis threshold.
    cv::Mat need;
    cv::dilate(valid, need, cv::Mat());
    const float floor_resp = float(0.5 * o.ridge_threshold);
    cv::Mat resp_bright = cv::Mat::zeros(gray.size(), CV_32F), resp_dark = resp_bright.clone();
    cv::Mat nx_b(gray.size(), CV_32F, cv::Scalar(0)), ny_b = nx_b.clone(), nx_d = nx_b.clone(),
            ny_d = nx_b.clone(), step_b = nx_b.clone(), step_d = nx_b.clone();
    const bool profile = o.max_step_ratio > 0;
    for (double sf : o.scale_fractions) {
        const double sigma = std::max(0.7, sf * Hw);
        // The photo's own blur, in working pixels, is part of sigma: a photo with the body
        // 250 px tall is upsampled twice as much as one with 500 px and carries twice the
        // blur, so adding the full sigma on top made its folds look coarser and weaker.
        const double sigma_src = o.source_blur_px * f;
        const double sigma_add = std::sqrt(std::max(0.49, sigma * sigma - sigma_src * sigma_src));
        cv::Mat g, dxx, dyy, dxy;
        cv::GaussianBlur(gray, g, cv::Size(), sigma_add, sigma_add, cv::BORDER_REPLICATE);
        cv::Sobel(g, dxx, CV_32F, 2, 0, 3);
        cv::Sobel(g, dyy, CV_32F, 0, 2, 3);
        cv::Sobel(g, dxy, CV_32F, 1, 1, 3);
        cv::Mat gx, gy;
        if (profile) {
            cv::Sobel(g, gx, CV_32F, 1, 0, 3);
            cv::Sobel(g, gy, CV_32F, 0, 1, 3);
        }
        const float s2 = float(sigma * sigma);
        // Eigenvector of l: (c, l - a) or (l - b, c).
        auto normal = [](float a, float b, float c, float l, float& ex, float& ey) {
            ex = c; ey = l - a;
            if (std::abs(ex) + std::abs(ey) < 1e-12f) { ex = l - b; ey = c; }
            const float nn = std::sqrt(ex * ex + ey * ey);
            if (nn < 1e-12f) { ex = 1; ey = 0; } else { ex /= nn; ey /= nn; }
        };
        for (int y = 0; y < g.rows; ++y) {
            const std::uint8_t* nd = need.ptr<std::uint8_t>(y);
            const float *pa = dxx.ptr<float>(y), *pb = dyy.ptr<float>(y), *pc = dxy.ptr<float>(y);
            float *rbp = resp_bright.ptr<float>(y), *rdp = resp_dark.ptr<float>(y);
            float *nxb = nx_b.ptr<float>(y), *nyb = ny_b.ptr<float>(y), *nxd = nx_d.ptr<float>(y),
                  *nyd = ny_d.ptr<float>(y);
            const float* pgx = profile ? gx.ptr<float>(y) : nullptr;
            const float* pgy = profile ? gy.ptr<float>(y) : nullptr;
            float *sbp = step_b.ptr<float>(y), *sdp = step_d.ptr<float>(y);
            // Step ratio: sigma |dL/dn| / (sigma^2 |d2L/dn2|) with the Sobel gains (8 and 4)
            // removed; 0 on a symmetric bump's axis, 1 on the Hessian ridge beside a step.
            auto step_ratio = [&](int x, float ex, float ey, float r) {
                return float(sigma) * std::abs(pgx[x] * ex + pgy[x] * ey) / (2.f * r);
            };
            for (int x = 0; x < g.cols; ++x) {
                if (!nd[x]) continue;
                const float a = pa[x], b = pb[x], c = pc[x];
                const float tr = 0.5f * (a + b), det = std::sqrt(0.25f * (a - b) * (a - b) + c * c);
                const float l_max = tr + det, l_min = tr - det;
                const float rb = s2 * std::max(0.f, -l_min), rd = s2 * std::max(0.f, l_max);
                if (rb > rbp[x]) {
                    rbp[x] = rb;
                    if (rb >= floor_resp) {
                        normal(a, b, c, l_min, nxb[x], nyb[x]);
                        if (profile) sbp[x] = step_ratio(x, nxb[x], nyb[x], rb);
                    }
                }
                if (rd > rdp[x]) {
                    rdp[x] = rd;
                    if (rd >= floor_resp) {
                        normal(a, b, c, l_max, nxd[x], nyd[x]);
                        if (profile) sdp[x] = step_ratio(x, nxd[x], nyd[x], rd);
                    }
                }
            }
        }
    }
    count_folds(resp_bright, resp_dark, nx_b, ny_b, nx_d, ny_d, step_b, step_d, valid, Hw, f, offset, o, s, folds);
}

}  // namespace

WrinkleSummary detect_wrinkles(const cv::Mat& image, const cv::Mat& mask, const cv::Mat& occlusion,
                               const Joints& joints, const WrinkleOptions& o,
                               std::vector<Fold>* folds) {

    const auto t0 = std::chrono::steady_clock::now();
    std::string why;
    require(o.is_valid(&why), "WrinkleOptions: ", why);
    check_image(image, CV_8UC3, "photo");
    require(!mask.empty() && mask.type() == CV_8UC1 && mask.size() == image.size(),
            "detect_wrinkles: the garment mask must be CV_8UC1 of the photo's size");
    require(occlusion.empty() || (occlusion.type() == CV_8UC1 && occlusion.size() == image.size()),
            "detect_wrinkles: the occlusion mask must be empty or CV_8UC1 of the photo's size");
    joints.validate(image.cols, image.rows);
    if (folds) folds->clear();
    WrinkleSummary s;
    const double H = joints.body_height_px();
    const double px_per_m = H / o.person_height_m;
    s.garment_area_px = cv::countNonZero(mask);
    s.garment_area_m2 = s.garment_area_px / (px_per_m * px_per_m);
    auto done = [&] {
        s.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        return s;
    };
    if (s.garment_area_px < std::max(0.0005, o.min_garment_area_fraction) * H * H) {
        s.termination = WrinkleTermination::garment_too_small;
        std::ostringstream m;
        m << "garment covers " << std::setprecision(2) << 100 * s.garment_area_px / (H * H)
          << " % of body height squared, below the " << 100 * std::max(0.0005, o.min_garment_area_fraction)
          << " % that P needs";
        s.message = m.str();
        return done();
    }
    // P is the mean fold count of detections at working body heights spread around
    // working_body_height_px (resolution_ensemble of them, ±15 % geometric): one detection
    // is a threshold-laden function of the sampling grid (hysteresis, thinning, splitting,
    // merging, pairing), so a fold near a threshold comes and goes when the photo is
    // resampled; averaging over grids measures P, not one grid's luck. Each resolution also
    // runs on phase_ensemble sub-pixel shifts of its grid: the same sampling noise at a
    // fixed scale, which a spread of scales alone leaves partly correlated.
    const int n = o.resolution_ensemble;
    const GarmentCrop crop = crop_garment(image, mask, occlusion, H, o);
    const Vec phases[4] = {{0, 0}, {0.5, 0.5}, {0.5, 0}, {0, 0.5}};
    // The detections are independent: they run in parallel (WrinkleOptions::threads) and
    // are summed in a fixed order, so P does not depend on the thread count.
    const int total = n * o.phase_ensemble;
    const int nominal = (n / 2) * o.phase_ensemble;  // k = n / 2 (t = 0 when n is odd), phase 0
    std::vector<WrinkleSummary> runs(static_cast<size_t>(total));
    auto run = [&](int i) {
        const int k = i / o.phase_ensemble, j = i % o.phase_ensemble;
        const double t = n > 1 ? 2.0 * k / (n - 1) - 1.0 : 0.0;
        detect_at(crop, H, o.working_body_height_px * std::pow(1.15, t), phases[j], o,
                  runs[static_cast<size_t>(i)], i == nominal ? folds : nullptr);
    };
    if (o.threads == 1 || total == 1) {
        for (int i = 0; i < total; ++i) run(i);
    } else {
        tbb::task_arena arena(o.threads > 0 ? o.threads : tbb::task_arena::automatic);
        arena.execute([&] { tbb::parallel_for(0, total, run); });
    }
    double count_sum = 0;
    for (const auto& r : runs) count_sum += r.fold_count;
    s.edges_detected = runs[static_cast<size_t>(nominal)].edges_detected;
    s.edges_merged = runs[static_cast<size_t>(nominal)].edges_merged;
    s.folds = runs[static_cast<size_t>(nominal)].folds;
    s.fold_count = count_sum / (n * o.phase_ensemble);
    // Below the detection limit the garment has no fold: the few grids that pair two short
    // edges on a plain garment are noise, and their ratio across scales is meaningless.
    s.folds_detected = s.fold_count >= o.min_fold_count;
    s.density_per_m2 = s.folds_detected && s.garment_area_m2 > 0 ? s.fold_count / s.garment_area_m2 : 0.0;
    if (!s.folds_detected) {
        s.folds = 0;
        if (folds) folds->clear();
        std::ostringstream m;
        m << "no fold: " << std::setprecision(2) << s.fold_count << " full-length folds, below the detection limit "
          << o.min_fold_count;
        s.message = m.str();
    }
    s.termination = WrinkleTermination::ok;
    return done();
}

cv::Mat draw_folds(const cv::Mat& image, const cv::Mat& mask, const std::vector<Fold>& folds) {
    check_image(image, CV_8UC3, "photo");
    cv::Mat out = image * 0.4;
    if (!mask.empty() && mask.size() == image.size()) image.copyTo(out, mask);
    auto poly = [&](const FoldEdge& e, const cv::Scalar& colour) {
        std::vector<cv::Point> pts;
        for (const auto& p : e.points_px) pts.emplace_back(int(std::floor(p.x())), int(std::floor(p.y())));
        cv::polylines(out, pts, false, colour, 2, cv::LINE_AA);
    };
    for (const auto& f : folds) {
        poly(f.ridge, cv::Scalar(0, 230, 255));
        poly(f.valley, cv::Scalar(255, 120, 0));
        const auto& a = f.ridge.points_px[f.ridge.points_px.size() / 2];
        const auto& b = f.valley.points_px[f.valley.points_px.size() / 2];
        cv::line(out, cv::Point(int(a.x()), int(a.y())), cv::Point(int(b.x()), int(b.y())),
                 cv::Scalar(0, 0, 255), 1, cv::LINE_AA);
    }
    return out;
}

}  // namespace drape::vision
