// Print edges removed from a garment's luminance (print_suppression.hpp).
#include "print_suppression.hpp"

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <unordered_map>
#include <vector>

namespace drape::vision::detail {

namespace {

constexpr float kEps = 0.02f;  // keeps log() of dark pixels from amplifying noise

/// Solves lap(S) = div with reflecting (Neumann) borders, S's mean 0: the DCT-II
/// diagonalises the 5-point Laplacian with mirrored ghost pixels.
cv::Mat solve_poisson(const cv::Mat& div) {
    // cv::dct wants even sizes: pad by replication (the extra row/column is cut again).
    const int rows = div.rows + (div.rows % 2), cols = div.cols + (div.cols % 2);
    cv::Mat f;
    cv::copyMakeBorder(div, f, 0, rows - div.rows, 0, cols - div.cols, cv::BORDER_CONSTANT, cv::Scalar(0));
    cv::Mat F;
    cv::dct(f, F);
    for (int y = 0; y < rows; ++y) {
        float* p = F.ptr<float>(y);
        const double ly = 2 * std::cos(M_PI * y / rows) - 2;
        for (int x = 0; x < cols; ++x) {
            const double l = ly + 2 * std::cos(M_PI * x / cols) - 2;
            p[x] = (x == 0 && y == 0) ? 0.f : float(p[x] / l);
        }
    }
    cv::Mat S;
    cv::idct(F, S);
    return S(cv::Rect(0, 0, div.cols, div.rows)).clone();
}

/// |gradient| of a Gaussian-blurred channel times sqrt(2 pi) sigma: the height of a step
/// whose blurred edge has this slope (an ideal step of height h gives h).
cv::Mat step_height(const cv::Mat& channel, double sigma) {
    cv::Mat b, gx, gy, mag;
    cv::GaussianBlur(channel, b, cv::Size(), sigma, sigma, cv::BORDER_REPLICATE);
    cv::Sobel(b, gx, CV_32F, 1, 0, 3, 1.0 / 8);
    cv::Sobel(b, gy, CV_32F, 0, 1, 3, 1.0 / 8);
    cv::magnitude(gx, gy, mag);
    return mag * std::sqrt(2 * M_PI) * sigma;
}


/// exp(S) back to the luminance's units (the inverse of log(gray + kEps)), clamped at 0.
cv::Mat from_log(const cv::Mat& S) {
    cv::Mat out;
    cv::exp(S, out);
    out -= kEps;
    cv::max(out, 0.0, out);
    return out;
}

/// Union-find with each element's parity relative to its root: the 2-colouring of the
/// print's regions, joined heaviest border first.
class ParityForest {
public:
    explicit ParityForest(int n) : parent_(static_cast<size_t>(n)), parity_(static_cast<size_t>(n), 0) {
        std::iota(parent_.begin(), parent_.end(), 0);
    }
    /// The root of x and x's parity relative to it.
    std::pair<int, int> find(int x) {
        int p = 0, r = x;
        while (parent_[static_cast<size_t>(r)] != r) {
            p ^= parity_[static_cast<size_t>(r)];
            r = parent_[static_cast<size_t>(r)];
        }
        for (int q = 0, y = x; parent_[static_cast<size_t>(y)] != y;) {  // path compression
            const int next = parent_[static_cast<size_t>(y)], py = parity_[static_cast<size_t>(y)];
            parent_[static_cast<size_t>(y)] = r;
            parity_[static_cast<size_t>(y)] = static_cast<std::uint8_t>(p ^ q);
            q ^= py;
            y = next;
        }
        return {r, p};
    }
    /// Asks parity(a) ^ parity(b) == want; false when a and b are joined and disagree.
    bool unite(int a, int b, int want) {
        const auto [ra, pa] = find(a);
        const auto [rb, pb] = find(b);
        if (ra == rb) return (pa ^ pb) == want;
        parent_[static_cast<size_t>(rb)] = ra;
        parity_[static_cast<size_t>(rb)] = static_cast<std::uint8_t>(pa ^ pb ^ want);
        return true;
    }

private:
    std::vector<int> parent_;
    std::vector<std::uint8_t> parity_;
};

/// The crossings of the band between two regions a < b: where each crossing starts in a
/// and ends in b, and the log luminance and chromaticity steps from a to b.
struct Border {
    std::vector<cv::Point> in_a, in_b;
    std::vector<float> dl, dc1, dc2;
};

double median(std::vector<float> v) {
    std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(v.size() / 2), v.end());
    return double(v[v.size() / 2]);
}

/// WrinkleOptions::PrintMethod::albedo_classes. Returns false (S untouched) when the garment
/// does not look like a two-colour print.
/// `log_bgr`: log(channel + kEps) of B, G, R; L, c1, c2 the log luminance and chromaticity.
bool albedo_class_shading(const cv::Mat& L, const cv::Mat& c1, const cv::Mat& c2, const std::array<cv::Mat, 3>& log_bgr,
                          const cv::Mat& edges, const cv::Mat& mask, const ShadingOptions& o, cv::Mat& S) {
    const int R = L.rows, C = L.cols;
    const cv::Mat inside = mask != 0;
    cv::Mat lab, stats, centroids;
    const int n = cv::connectedComponentsWithStats(inside & ~edges, lab, stats, centroids, 4, CV_32S);
    if (n < 3) return false;
    auto area = [&](int r) { return stats.at<int>(r, cv::CC_STAT_AREA); };
    lab.forEach<int>([&](int& l, const int*) {
        if (l > 0 && area(l) < o.min_region_px) l = 0;
    });
    // Crossings along rows and columns: the last region pixel before a run of garment band
    // pixels and the first after it, in two different regions.
    std::unordered_map<std::int64_t, Border> borders;
    auto record = [&](cv::Point p, cv::Point q) {
        int a = lab.at<int>(p), b = lab.at<int>(q);
        if (a > b) {
            std::swap(a, b);
            std::swap(p, q);
        }
        Border& e = borders[std::int64_t(a) * n + b];
        e.in_a.push_back(p);
        e.in_b.push_back(q);
        e.dl.push_back(L.at<float>(q) - L.at<float>(p));
        e.dc1.push_back(c1.at<float>(q) - c1.at<float>(p));
        e.dc2.push_back(c2.at<float>(q) - c2.at<float>(p));
    };
    auto scan = [&](int lines, int length, auto at) {
        for (int i = 0; i < lines; ++i) {
            int last = -1;
            for (int j = 0; j < length; ++j) {
                const cv::Point p = at(i, j);
                if (!inside.at<std::uint8_t>(p)) {
                    last = -1;
                    continue;
                }
                const int l = lab.at<int>(p);
                if (l == 0) continue;
                if (last >= 0 && j - last > 1 && j - last - 1 <= o.max_crossing_px && lab.at<int>(at(i, last)) != l)
                    record(at(i, last), p);
                last = j;
            }
        }
    };
    scan(R, C, [](int y, int x) { return cv::Point(x, y); });
    scan(C, R, [](int x, int y) { return cv::Point(x, y); });
    // Each border is a step between the two colours, or the same colour on both sides (a
    // region cut by a fold's sharp shading, a corner), or neither (left out).
    struct Link {
        int a, b, count;
        double dl;  ///< the median log-luminance step from a to b
        bool step;
        const Border* border;
    };
    std::vector<Link> links;
    for (const auto& [key, e] : borders) {
        if (int(e.dl.size()) < o.min_crossings) continue;
        const double dl = median(e.dl), dc = std::hypot(median(e.dc1), median(e.dc2));
        const bool step = std::abs(dl) >= 0.5 * o.step_threshold || dc >= 0.5 * o.chroma_threshold;
        const bool same = std::abs(dl) < 0.25 * o.step_threshold && dc < 0.25 * o.chroma_threshold;
        if (step || same) links.push_back({int(key / n), int(key % n), int(e.dl.size()), dl, step, &e});
    }
    std::sort(links.begin(), links.end(), [](const Link& p, const Link& q) {
        return p.count != q.count ? p.count > q.count : (p.a != q.a ? p.a < q.a : p.b < q.b);
    });
    ParityForest forest(n);
    double agree = 0, conflict = 0;
    for (const Link& e : links) (forest.unite(e.a, e.b, e.step ? 1 : 0) ? agree : conflict) += e.count;
    std::vector<char> printed(static_cast<size_t>(n), 0);
    for (const Link& e : links)
        if (e.step) printed[static_cast<size_t>(e.a)] = printed[static_cast<size_t>(e.b)] = 1;
    const int print_regions = int(std::count(printed.begin(), printed.end(), 1));
    if (agree <= 0 || conflict > o.max_conflict_fraction * (agree + conflict) || print_regions < o.min_print_regions ||
        agree < o.min_crossing_density * cv::countNonZero(inside))
        return false;
    // The classes: each tree of the forest oriented so that class 1 is the brighter colour
    // (a step's sign compares neighbours under the same light).
    std::vector<std::pair<double, double>> votes(static_cast<size_t>(n), {0.0, 0.0});  // root: down, up
    for (const Link& e : links) {
        if (!e.step) continue;
        const auto [ra, pa] = forest.find(e.a);
        const auto [rb, pb] = forest.find(e.b);
        if (ra != rb || pa == pb) continue;
        const bool b_brighter = e.dl > 0;
        ((b_brighter == (pb == 1)) ? votes[static_cast<size_t>(ra)].second : votes[static_cast<size_t>(ra)].first) += e.count;
    }
    std::vector<int> cls(static_cast<size_t>(n), -1);
    double class_area[2] = {0, 0};
    for (int r = 1; r < n; ++r) {
        if (!printed[static_cast<size_t>(r)]) continue;
        const auto [root, p] = forest.find(r);
        const auto& v = votes[static_cast<size_t>(root)];
        cls[static_cast<size_t>(r)] = v.second >= v.first ? p : 1 - p;
        class_area[cls[static_cast<size_t>(r)]] += area(r);
    }
    // The class of the larger area (a print's ground) is the reference; the other is mapped
    // onto it: log L_ref ~ w . (1, log B, log G, log R) of the other side of each crossing.
    // A linear map of log colour holds the two albedos' ratio, the light's colour (sun and
    // sky) and the tone curve's slope, which makes one ratio per print wrong by several %.
    const int ref = class_area[1] > class_area[0] ? 1 : 0;
    auto features = [&](cv::Point q) {
        return Eigen::Vector4d(1, log_bgr[0].at<float>(q), log_bgr[1].at<float>(q), log_bgr[2].at<float>(q));
    };
    // Every crossing between the two classes: (its end in the reference class, its end in
    // the mapped class, the mapped region).
    auto for_each_mapped_crossing = [&](auto&& visit) {
        for (const Link& e : links) {
            const int ca = cls[static_cast<size_t>(e.a)], cb = cls[static_cast<size_t>(e.b)];
            if (!e.step || ca < 0 || cb < 0 || ca == cb) continue;
            const bool a_is_ref = ca == ref;
            for (size_t i = 0; i < e.border->in_a.size(); ++i)
                visit(a_is_ref ? e.border->in_a[i] : e.border->in_b[i], a_is_ref ? e.border->in_b[i] : e.border->in_a[i],
                      a_is_ref ? e.b : e.a);
        }
    };
    Eigen::Matrix4d A = Eigen::Matrix4d::Zero();
    Eigen::Vector4d rhs4 = Eigen::Vector4d::Zero();
    for_each_mapped_crossing([&](cv::Point q_ref, cv::Point q_other, int) {
        const Eigen::Vector4d f = features(q_other);
        A += f * f.transpose();
        rhs4 += f * double(L.at<float>(q_ref));
    });
    const Eigen::LDLT<Eigen::Matrix4d> fit(A);
    if (fit.info() != Eigen::Success) return false;
    const Eigen::Vector4d w = fit.solve(rhs4);
    if (!w.allFinite()) return false;
    // Then each mapped region's own correction: the median of what the map leaves across its
    // crossings, shrunk towards 0 as if region_offset_prior more crossings had left 0 (the
    // light's colour and the tone curve's slope vary over the garment; one map per print
    // left a few % in whole stripes, enough for a ridge at the detector's threshold).
    std::vector<float> region_offset(static_cast<size_t>(n), 0.f);
    {
        std::vector<std::vector<float>> res(static_cast<size_t>(n));
        for_each_mapped_crossing([&](cv::Point q_ref, cv::Point q_other, int other) {
            res[static_cast<size_t>(other)].push_back(float(L.at<float>(q_ref) - w.dot(features(q_other))));
        });
        for (int r = 1; r < n; ++r) {
            auto& v = res[static_cast<size_t>(r)];
            if (v.empty()) continue;
            region_offset[static_cast<size_t>(r)] =
                float(median(v) * double(v.size()) / (double(v.size()) + o.region_offset_prior));
        }
    }
    // A region left out of the graph (cut off by the outline or by occlusion) may be of
    // either colour: up to twice a print region's median area it is filled like the band.
    std::vector<int> areas;
    for (int r = 1; r < n; ++r)
        if (printed[static_cast<size_t>(r)]) areas.push_back(area(r));
    std::nth_element(areas.begin(), areas.begin() + std::ptrdiff_t(areas.size() / 2), areas.end());
    const int fill_below = 2 * areas[areas.size() / 2];
    S = L.clone();
    cv::Mat index(R, C, CV_32S, cv::Scalar(-1));
    int unknowns = 0;
    for (int y = 0; y < R; ++y)
        for (int x = 0; x < C; ++x) {
            if (!inside.at<std::uint8_t>(y, x)) continue;
            const int l = lab.at<int>(y, x);
            const int c = l > 0 ? cls[static_cast<size_t>(l)] : -1;
            if (l == 0 || (c < 0 && area(l) < fill_below))
                index.at<int>(y, x) = unknowns++;
            else if (c >= 0 && c != ref)
                S.at<float>(y, x) = float(w.dot(features({x, y}))) + region_offset[static_cast<size_t>(l)];
        }
    if (unknowns == 0) return true;
    // The band: a membrane (Laplace) between the garment pixels around it, with a weak pull
    // to the luminance so that a patch with no known neighbour stays defined. (A thin plate
    // carried the noise of the band's rim into it: 16.7 against 8.5 m^-2 on a check whose
    // plain P is 5.0, notes/vision.md 2026-12-02.)
    const double anchor = 1e-4;
    std::vector<Eigen::Triplet<double>> t;
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(unknowns);
    for (int y = 0; y < R; ++y)
        for (int x = 0; x < C; ++x) {
            if (!inside.at<std::uint8_t>(y, x)) continue;
            const int i = index.at<int>(y, x);
            if (i >= 0) {
                t.emplace_back(i, i, anchor);
                rhs[i] += anchor * L.at<float>(y, x);
            }
            for (const cv::Point q : {cv::Point(x + 1, y), cv::Point(x, y + 1)}) {
                if (q.x >= C || q.y >= R || !inside.at<std::uint8_t>(q)) continue;
                const int j = index.at<int>(q);
                if (i < 0 && j < 0) continue;
                // (S_p - S_q)^2 with the known side moved to the right-hand side.
                if (i >= 0) t.emplace_back(i, i, 1.0);
                if (j >= 0) t.emplace_back(j, j, 1.0);
                if (i >= 0 && j >= 0) {
                    t.emplace_back(i, j, -1.0);
                    t.emplace_back(j, i, -1.0);
                } else if (i >= 0) {
                    rhs[i] += S.at<float>(q);
                } else {
                    rhs[j] += S.at<float>(y, x);
                }
            }
        }
    Eigen::SparseMatrix<double> N(unknowns, unknowns);
    N.setFromTriplets(t.begin(), t.end());
    const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(N);
    if (solver.info() != Eigen::Success) return false;
    const Eigen::VectorXd v = solver.solve(rhs);
    if (solver.info() != Eigen::Success || !v.allFinite()) return false;
    for (int y = 0; y < R; ++y)
        for (int x = 0; x < C; ++x)
            if (const int i = index.at<int>(y, x); i >= 0) S.at<float>(y, x) = float(v[i]);
    return true;
}

/// The period (pixels) of a fine print: twice the mean run between the swings of its log
/// luminance about the local mean (above +swing, then below -swing; a Schmitt trigger, so
/// noise does not count) along the rows or the columns of the garment, whichever swing more
/// often (stripes swing one way only); 0 when nothing swings.
double print_period_px(const cv::Mat& L, const cv::Mat& mask) {
    constexpr double kLocalSigmaPx = 4.0;
    constexpr float kSwing = 0.05f;
    cv::Mat local, hp;
    cv::GaussianBlur(L, local, cv::Size(), kLocalSigmaPx, kLocalSigmaPx, cv::BORDER_REPLICATE);
    hp = L - local;
    long pixels = 0, swings_x = 0, swings_y = 0;
    std::vector<int> state_y(static_cast<size_t>(L.cols), 0);
    for (int y = 0; y < L.rows; ++y) {
        int state_x = 0;
        for (int x = 0; x < L.cols; ++x) {
            int& sy = state_y[static_cast<size_t>(x)];
            if (!mask.at<std::uint8_t>(y, x)) {
                state_x = sy = 0;
                continue;
            }
            ++pixels;
            const float v = hp.at<float>(y, x);
            const int now = v > kSwing ? 1 : (v < -kSwing ? -1 : 0);
            if (now != 0) {
                if (state_x != 0 && now != state_x) ++swings_x;
                if (sy != 0 && now != sy) ++swings_y;
                state_x = sy = now;
            }
        }
    }
    const long swings = std::max(swings_x, swings_y);
    return swings > 0 ? 2.0 * double(pixels) / double(swings) : 0.0;
}

/// A print finer than the edges' band: log L = log albedo + log shading, and a periodic
/// albedo's mean over one period is a constant, so the log luminance averaged over the
/// print's period is the shading up to a constant. The average: a box one period wide, twice
/// (its response sinc^2 is zero at the print's frequency and every harmonic, and falls off
/// beyond), normalised on the mask so that the background does not bleed in.
cv::Mat low_passed_shading(const cv::Mat& L, const cv::Mat& mask, double period_px) {
    const cv::Size box(std::max(1, int(std::lround(period_px))), std::max(1, int(std::lround(period_px))));
    const auto box_twice = [&](const cv::Mat& in) {
        cv::Mat out;
        cv::blur(in, out, box, cv::Point(-1, -1), cv::BORDER_CONSTANT);
        cv::blur(out, out, box, cv::Point(-1, -1), cv::BORDER_CONSTANT);
        return out;
    };
    const cv::Mat on = mask != 0;
    cv::Mat m;
    on.convertTo(m, CV_32F, 1.0 / 255.0);
    const cv::Mat den = box_twice(m);
    cv::Mat S = L.clone();
    cv::Mat(box_twice(L.mul(m)) / den).copyTo(S, on & (den > 1e-6));
    // At the level of the luminance on the garment.
    return S + cv::mean(L - S, mask)[0];
}

}  // namespace

cv::Mat shading_luminance(const cv::Mat& bgr, const cv::Mat& mask, const ShadingOptions& o, cv::Mat* edges_out) {
    cv::Mat gray;
    cv::cvtColor(bgr, gray, cv::COLOR_BGR2GRAY);
    gray.convertTo(gray, CV_32F, 1.0 / 255.0);
    cv::Mat f;
    bgr.convertTo(f, CV_32FC3, 1.0 / 255.0);
    std::vector<cv::Mat> ch;
    cv::split(f, ch);
    cv::Mat L, lb, lr, lg, c1, c2;
    cv::log(gray + kEps, L);
    cv::log(ch[0] + kEps, lb);
    cv::log(ch[1] + kEps, lg);
    cv::log(ch[2] + kEps, lr);
    c1 = lr - lg;
    c2 = lb - lg;
    const double sigma = std::max(0.7, o.edge_sigma_px);
    const cv::Mat hl = step_height(L, sigma);
    cv::Mat hc1 = step_height(c1, sigma), hc2 = step_height(c2, sigma), hc;
    cv::magnitude(hc1, hc2, hc);
    cv::Mat edges = (hl > o.step_threshold) | (hc > o.chroma_threshold);
    if (o.dilate_px > 0)
        cv::dilate(edges, edges, cv::getStructuringElement(cv::MORPH_RECT, {2 * o.dilate_px + 1, 2 * o.dilate_px + 1}));
    if (edges_out) *edges_out = edges.clone();
    if (cv::countNonZero(edges) == 0) return gray;
    const bool classes = o.method == WrinkleOptions::PrintMethod::albedo_classes;
    if (classes) {
        cv::Mat S;
        if (albedo_class_shading(L, c1, c2, {lb, lg, lr}, edges, mask, o, S)) return from_log(S);
    }
    // Edges over most of the garment are a print finer than their band: no region is left
    // between them for the classes, nor for the gradient fill (which holds the whole band
    // flat). One whose period the folds do not share is averaged over that period.
    const bool fine = cv::countNonZero(edges & (mask != 0)) >= o.fallback_band_fraction * std::max(1, cv::countNonZero(mask));
    if (classes && !fine) {
        // Not a two-colour print the graph can follow, nor a fine one: a plain garment,
        // which keeps its luminance.
        if (edges_out) edges_out->setTo(0);
        return gray;
    }
    if (fine) {
        const double period = print_period_px(L, mask);
        if (period > 0 && period <= o.fine_print_max_period_px) return from_log(low_passed_shading(L, mask, period));
    }

    // Forward differences; a difference touching an edge pixel is unknown (weight 0).
    const int R = L.rows, C = L.cols;
    cv::Mat gx = cv::Mat::zeros(R, C, CV_32F), gy = gx.clone(), wx = gx.clone(), wy = gx.clone();
    for (int y = 0; y < R; ++y) {
        const float* l = L.ptr<float>(y);
        const float* ln = y + 1 < R ? L.ptr<float>(y + 1) : nullptr;
        const std::uint8_t* e = edges.ptr<std::uint8_t>(y);
        const std::uint8_t* en = y + 1 < R ? edges.ptr<std::uint8_t>(y + 1) : nullptr;
        float *px = gx.ptr<float>(y), *py = gy.ptr<float>(y), *qx = wx.ptr<float>(y), *qy = wy.ptr<float>(y);
        for (int x = 0; x < C; ++x) {
            if (x + 1 < C) {
                px[x] = l[x + 1] - l[x];
                qx[x] = (e[x] || e[x + 1]) ? 0.f : 1.f;
            }
            if (ln) {
                py[x] = ln[x] - l[x];
                qy[x] = (e[x] || en[x]) ? 0.f : 1.f;
            }
        }
    }
    auto divergence = [&](const cv::Mat& ax, const cv::Mat& ay) {
        cv::Mat d(R, C, CV_32F);
        for (int y = 0; y < R; ++y) {
            const float *px = ax.ptr<float>(y), *py = ay.ptr<float>(y), *pyu = y > 0 ? ay.ptr<float>(y - 1) : nullptr;
            float* q = d.ptr<float>(y);
            for (int x = 0; x < C; ++x) q[x] = px[x] - (x > 0 ? px[x - 1] : 0.f) + py[x] - (pyu ? pyu[x] : 0.f);
        }
        return d;
    };
    // First the shading held flat across the edges (their gradients zero); then the edges'
    // gradients are those of that shading smoothed (fill_sigma_px), so a fold crossing a
    // stripe keeps its slope across the stripe's edge. A gradient of a function, not
    // smoothed gradients: averaging noisy gradients is not integrable, and the Poisson
    // solve turned that into blotches at every corner of a check.
    gx = gx.mul(wx);
    gy = gy.mul(wy);
    gx.col(C - 1).setTo(0);
    gy.row(R - 1).setTo(0);
    for (int pass = 0; o.fill_sigma_px > 0 && pass < o.fill_passes; ++pass) {
        cv::Mat S0 = solve_poisson(divergence(gx, gy)), Sb;
        cv::GaussianBlur(S0, Sb, cv::Size(), o.fill_sigma_px, o.fill_sigma_px, cv::BORDER_REPLICATE);
        for (int y = 0; y < R; ++y) {
            const float* b = Sb.ptr<float>(y);
            const float* bn = y + 1 < R ? Sb.ptr<float>(y + 1) : nullptr;
            float *px = gx.ptr<float>(y), *py = gy.ptr<float>(y);
            const float *qx = wx.ptr<float>(y), *qy = wy.ptr<float>(y);
            for (int x = 0; x < C; ++x) {
                if (x + 1 < C && qx[x] == 0.f) px[x] = b[x + 1] - b[x];
                if (bn && qy[x] == 0.f) py[x] = bn[x] - b[x];
            }
        }
    }
    const cv::Mat div = divergence(gx, gy);
    cv::Mat S = solve_poisson(div);
    // The level: S follows L on the garment's pixels off the edges (mean of L - S there).
    cv::Mat off_edges = mask & ~edges;
    if (cv::countNonZero(off_edges) == 0) off_edges = mask;
    const double shift = cv::countNonZero(off_edges) > 0 ? cv::mean(L - S, off_edges)[0] : cv::mean(L - S)[0];
    return from_log(S + shift);
}

}  // namespace drape::vision::detail
