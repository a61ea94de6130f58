#include <drape/core/distance_transform.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace drape::core {

namespace {

// 1D squared distance transform of f (n samples) into d (Felzenszwalb & Huttenlocher 2012).
void edt_1d(const std::vector<double>& f, std::vector<double>& d, std::vector<int>& v,
            std::vector<double>& z) {
    const int n = static_cast<int>(f.size());
    const double inf = std::numeric_limits<double>::infinity();
    int k = 0;
    v[0] = 0;
    z[0] = -inf;
    z[1] = inf;
    auto intersect = [&](int q, int p) {
        return ((f[static_cast<size_t>(q)] + double(q) * q) -
                (f[static_cast<size_t>(p)] + double(p) * p)) / (2.0 * q - 2.0 * p);
    };
    for (int q = 1; q < n; ++q) {
        double s = intersect(q, v[static_cast<size_t>(k)]);
        while (s <= z[static_cast<size_t>(k)]) {  // z[0] = -inf stops this at k = 0
            --k;
            s = intersect(q, v[static_cast<size_t>(k)]);
        }
        ++k;
        v[static_cast<size_t>(k)] = q;
        z[static_cast<size_t>(k)] = s;
        z[static_cast<size_t>(k) + 1] = inf;
    }
    k = 0;
    for (int q = 0; q < n; ++q) {
        while (z[static_cast<size_t>(k) + 1] < q) ++k;
        const int p = v[static_cast<size_t>(k)];
        d[static_cast<size_t>(q)] = double(q - p) * (q - p) + f[static_cast<size_t>(p)];
    }
}

}  // namespace

std::vector<float> distance_transform(int width, int height, const std::vector<std::uint8_t>& pixels,
                                      bool target) {
    std::vector<float> out;
    if (width <= 0 || height <= 0) return out;
    const size_t n = static_cast<size_t>(width) * static_cast<size_t>(height);
    if (pixels.size() != n) return out;
    out.assign(n, 0.0f);
    const double far = double(width + height);
    const double big = 1e20;  // "no target" marker that stays finite in the arithmetic
    std::vector<double> grid(n);
    bool any = false;
    for (size_t i = 0; i < n; ++i) {
        const bool is_target = (pixels[i] != 0) == target;
        grid[i] = is_target ? 0.0 : big;
        any = any || is_target;
    }
    if (!any) {
        std::fill(out.begin(), out.end(), static_cast<float>(far));
        return out;
    }
    const int longest = std::max(width, height);
    std::vector<double> f(static_cast<size_t>(longest)), d(static_cast<size_t>(longest));
    std::vector<int> v(static_cast<size_t>(longest));
    std::vector<double> z(static_cast<size_t>(longest) + 1);
    // Columns, then rows.
    f.resize(static_cast<size_t>(height));
    d.resize(static_cast<size_t>(height));
    for (int x = 0; x < width; ++x) {
        for (int y = 0; y < height; ++y) f[static_cast<size_t>(y)] = grid[static_cast<size_t>(y) * width + x];
        edt_1d(f, d, v, z);
        for (int y = 0; y < height; ++y) grid[static_cast<size_t>(y) * width + x] = d[static_cast<size_t>(y)];
    }
    f.resize(static_cast<size_t>(width));
    d.resize(static_cast<size_t>(width));
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) f[static_cast<size_t>(x)] = grid[static_cast<size_t>(y) * width + x];
        edt_1d(f, d, v, z);
        for (int x = 0; x < width; ++x)
            out[static_cast<size_t>(y) * width + x] =
                static_cast<float>(std::sqrt(d[static_cast<size_t>(x)]));
    }
    return out;
}

}  // namespace drape::core
