#include "alpha_expansion.hpp"

#include <opencv2/imgproc/detail/gcgraph.hpp>

#include <algorithm>
#include <cmath>

namespace drape::vision::detail {

namespace {

double colour_diff2(const cv::Mat& image_bgr, int x0, int y0, int x1, int y1) {
    const cv::Vec3b a = image_bgr.at<cv::Vec3b>(y0, x0), b = image_bgr.at<cv::Vec3b>(y1, x1);
    double s = 0;
    for (int c = 0; c < 3; ++c) s += (double(a[c]) - b[c]) * (double(a[c]) - b[c]);
    return s;
}

}  // namespace

double contrast_beta(const cv::Mat& image_bgr) {
    const int w = image_bgr.cols, h = image_bgr.rows;
    double sum = 0;
    long count = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            if (x + 1 < w) { sum += colour_diff2(image_bgr, x, y, x + 1, y); ++count; }
            if (y + 1 < h) { sum += colour_diff2(image_bgr, x, y, x, y + 1); ++count; }
        }
    return sum > 0 ? count / (2.0 * sum) : 0.0;
}

void set_contrast_weights(const cv::Mat& image_bgr, double gamma, GridEnergy& e) {
    const int w = e.width, h = e.height;
    const size_t n = static_cast<size_t>(w) * static_cast<size_t>(h);
    auto diff2 = [&](int x0, int y0, int x1, int y1) {
        return colour_diff2(image_bgr, x0, y0, x1, y1);
    };
    const double beta = contrast_beta(image_bgr);
    e.w_right.assign(n, 0.f);
    e.w_down.assign(n, 0.f);
    e.w_down_right.assign(n, 0.f);
    e.w_down_left.assign(n, 0.f);
    const double diag = gamma / std::sqrt(2.0);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const size_t i = static_cast<size_t>(y) * w + x;
            if (x + 1 < w) e.w_right[i] = float(gamma * std::exp(-beta * diff2(x, y, x + 1, y)));
            if (y + 1 < h) {
                e.w_down[i] = float(gamma * std::exp(-beta * diff2(x, y, x, y + 1)));
                if (x + 1 < w)
                    e.w_down_right[i] = float(diag * std::exp(-beta * diff2(x, y, x + 1, y + 1)));
                if (x > 0)
                    e.w_down_left[i] = float(diag * std::exp(-beta * diff2(x, y, x - 1, y + 1)));
            }
        }
}

namespace {

template <class F>
void for_each_edge(const GridEnergy& e, F f) {
    const int w = e.width, h = e.height;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const int i = y * w + x;
            if (x + 1 < w) f(i, i + 1, e.w_right[static_cast<size_t>(i)]);
            if (y + 1 < h) {
                f(i, i + w, e.w_down[static_cast<size_t>(i)]);
                if (x + 1 < w) f(i, i + w + 1, e.w_down_right[static_cast<size_t>(i)]);
                if (x > 0) f(i, i + w - 1, e.w_down_left[static_cast<size_t>(i)]);
            }
        }
}

}  // namespace

double energy(const GridEnergy& e, const std::vector<std::uint8_t>& labels) {
    double s = 0;
    for (size_t i = 0; i < labels.size(); ++i)
        s += e.unary[i * static_cast<size_t>(e.labels) + labels[i]];
    for_each_edge(e, [&](int i, int j, float w) {
        if (labels[static_cast<size_t>(i)] != labels[static_cast<size_t>(j)]) s += w;
    });
    return s;
}

double energy(const GraphEnergy& e, const std::vector<std::uint8_t>& labels) {
    double s = 0;
    for (size_t i = 0; i < labels.size(); ++i)
        s += e.unary[i * static_cast<size_t>(e.labels) + labels[i]];
    for (size_t k = 0; k < e.edge_from.size(); ++k)
        if (labels[static_cast<size_t>(e.edge_from[k])] != labels[static_cast<size_t>(e.edge_to[k])])
            s += e.edge_weight[k];
    return s;
}

double alpha_expansion(const GridEnergy& e, std::vector<std::uint8_t>& labels, int cycles) {
    GraphEnergy g;
    g.nodes = e.width * e.height;
    g.labels = e.labels;
    g.unary = e.unary;
    for_each_edge(e, [&](int i, int j, float w) {
        g.edge_from.push_back(i);
        g.edge_to.push_back(j);
        g.edge_weight.push_back(w);
    });
    return alpha_expansion(g, labels, cycles);
}

double alpha_expansion(const GraphEnergy& e, std::vector<std::uint8_t>& labels, int cycles) {
    const int n = e.nodes;
    const size_t L = static_cast<size_t>(e.labels);
    const size_t m = e.edge_from.size();
    double best = energy(e, labels);
    for (int cycle = 0; cycle < cycles; ++cycle) {
        bool improved = false;
        for (int a = 0; a < e.labels; ++a) {
            // x_p = 1 (source side) takes alpha, x_p = 0 keeps the current label.
            cv::detail::GCGraph<double> g(static_cast<unsigned>(n), static_cast<unsigned>(2 * m));
            std::vector<double> c1(static_cast<size_t>(n)), c0(static_cast<size_t>(n));
            for (int i = 0; i < n; ++i) {
                g.addVtx();
                const size_t k = static_cast<size_t>(i);
                c1[k] = e.unary[k * L + static_cast<size_t>(a)];
                c0[k] = e.unary[k * L + labels[k]];
            }
            for (size_t k = 0; k < m; ++k) {
                const int i = e.edge_from[k], j = e.edge_to[k];
                const double w = e.edge_weight[k];
                const int fi = labels[static_cast<size_t>(i)], fj = labels[static_cast<size_t>(j)];
                // E(x_i, x_j): E00 = w[fi != fj], E01 = w[fi != a], E10 = w[a != fj], E11 = 0.
                const double e00 = fi != fj ? w : 0, e01 = fi != a ? w : 0,
                             e10 = a != fj ? w : 0;
                // E = E00 + (E10 - E00) x_i + (E11 - E10) x_j + (E01 + E10 - E00) (1 - x_i) x_j
                // (the constant E00 dropped).
                c1[static_cast<size_t>(i)] += e10 - e00;
                c1[static_cast<size_t>(j)] += -e10;
                const double pair = e01 + e10 - e00;
                // (1 - x_i) x_j: j on the source side, i on the sink side -> edge j -> i.
                if (pair > 0) g.addEdges(j, i, pair, 0);
            }
            for (int i = 0; i < n; ++i) {
                const size_t k = static_cast<size_t>(i);
                // cost(x=1) is paid when cut from the sink (sink weight), cost(x=0) the source.
                const double s1 = c1[k], s0 = c0[k];
                const double mn = std::min(s0, s1);
                g.addTermWeights(i, s0 - mn, s1 - mn);
            }
            g.maxFlow();
            std::vector<std::uint8_t> next = labels;
            for (int i = 0; i < n; ++i)
                if (g.inSourceSegment(i)) next[static_cast<size_t>(i)] = static_cast<std::uint8_t>(a);
            const double en = energy(e, next);
            if (en < best - 1e-9) {
                best = en;
                labels.swap(next);
                improved = true;
            }
        }
        if (!improved) break;
    }
    return best;
}

}  // namespace drape::vision::detail
