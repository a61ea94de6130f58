#include "thinning.hpp"

#include <vector>

namespace drape::vision::detail {

void thin(cv::Mat& img) {
    // Only foreground pixels can be deleted, so each sub-iteration visits the list of those
    // still set instead of scanning the whole image (a fold map is mostly empty). Every
    // sub-iteration decides on the image as it was at its start, as the raster scan did,
    // so the result is the same.
    std::vector<cv::Point> live, del;
    for (int y = 1; y < img.rows - 1; ++y) {
        const auto* row = img.ptr<std::uint8_t>(y);
        for (int x = 1; x < img.cols - 1; ++x)
            if (row[x]) live.emplace_back(x, y);
    }
    bool changed = true;
    while (changed) {
        changed = false;
        for (int pass = 0; pass < 2; ++pass) {
            del.clear();
            size_t kept = 0;
            for (const cv::Point& q : live) {
                const int x = q.x, y = q.y;
                const auto* up = img.ptr<std::uint8_t>(y - 1);
                const auto* row = img.ptr<std::uint8_t>(y);
                const auto* dn = img.ptr<std::uint8_t>(y + 1);
                const int p2 = up[x], p3 = up[x + 1], p4 = row[x + 1], p5 = dn[x + 1],
                          p6 = dn[x], p7 = dn[x - 1], p8 = row[x - 1], p9 = up[x - 1];
                const int b = p2 + p3 + p4 + p5 + p6 + p7 + p8 + p9;
                const int a = (!p2 && p3) + (!p3 && p4) + (!p4 && p5) + (!p5 && p6) +
                              (!p6 && p7) + (!p7 && p8) + (!p8 && p9) + (!p9 && p2);
                if (b >= 2 && b <= 6 && a == 1 &&
                    (pass == 0 ? (p2 * p4 * p6 == 0 && p4 * p6 * p8 == 0)
                               : (p2 * p4 * p8 == 0 && p2 * p6 * p8 == 0)))
                    del.push_back(q);
                else
                    live[kept++] = q;
            }
            live.resize(kept);
            for (const auto& p : del) img.at<std::uint8_t>(p) = 0;
            changed = changed || !del.empty();
        }
    }
}

}  // namespace drape::vision::detail
