// Print edges removed from a garment's luminance (print_suppression.hpp).
#include "print_suppression.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>

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
    cv::Mat out;
    cv::exp(S + shift, out);
    out -= kEps;
    cv::max(out, 0.0, out);
    return out;
}

}  // namespace drape::vision::detail
