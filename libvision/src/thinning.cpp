#include "thinning.hpp"

#include <vector>

namespace drape::vision::detail {

void thin(cv::Mat& img) {
    std::vector<cv::Point> del;
    bool changed = true;
    while (changed) {
        changed = false;
        for (int pass = 0; pass < 2; ++pass) {
            del.clear();
            for (int y = 1; y < img.rows - 1; ++y) {
                const auto* up = img.ptr<std::uint8_t>(y - 1);
                const auto* row = img.ptr<std::uint8_t>(y);
                const auto* dn = img.ptr<std::uint8_t>(y + 1);
                for (int x = 1; x < img.cols - 1; ++x) {
                    if (!row[x]) continue;
                    const int p2 = up[x], p3 = up[x + 1], p4 = row[x + 1], p5 = dn[x + 1],
                              p6 = dn[x], p7 = dn[x - 1], p8 = row[x - 1], p9 = up[x - 1];
                    const int b = p2 + p3 + p4 + p5 + p6 + p7 + p8 + p9;
                    if (b < 2 || b > 6) continue;
                    const int a = (!p2 && p3) + (!p3 && p4) + (!p4 && p5) + (!p5 && p6) +
                                  (!p6 && p7) + (!p7 && p8) + (!p8 && p9) + (!p9 && p2);
                    if (a != 1) continue;
                    if (pass == 0 ? (p2 * p4 * p6 == 0 && p4 * p6 * p8 == 0)
                                  : (p2 * p4 * p8 == 0 && p2 * p6 * p8 == 0))
                        del.emplace_back(x, y);
                }
            }
            for (const auto& p : del) img.at<std::uint8_t>(p) = 0;
            changed = changed || !del.empty();
        }
    }
}

}  // namespace drape::vision::detail
