#include <drape/core/parallel_for.hpp>

#include <tbb/blocked_range.h>
#include <algorithm>
#include <tbb/parallel_for.h>

namespace drape::core {

void parallel_for_ranges(int n, int grain, const std::function<void(int begin, int end)>& body) {
    if (n <= 0) return;
    tbb::parallel_for(tbb::blocked_range<int>(0, n, grain > 0 ? grain : 1),
                      [&](const tbb::blocked_range<int>& r) { body(r.begin(), r.end()); });
}

void parallel_for_chunks(int n, int chunk,
                         const std::function<void(int c, int begin, int end)>& body) {
    if (n <= 0) return;
    const int step = chunk > 0 ? chunk : 1;
    tbb::parallel_for(0, chunk_count(n, step), [&](int c) {
        const int begin = c * step;
        body(c, begin, std::min(n, begin + step));
    });
}

}  // namespace drape::core
