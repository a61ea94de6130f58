#include <drape/core/parallel_for.hpp>

#include <tbb/blocked_range.h>
#include <algorithm>
#include <tbb/parallel_for.h>

namespace drape::core {

void parallel_for_ranges(int n, int grain, const std::function<void(int begin, int end)>& body) {
    if (n <= 0) return;
#ifdef DRAPE_SERIAL_LOOPS
    // ThreadSanitizer builds (CMake option DRAPE_SERIAL_LOOPS): TBB's uninstrumented runtime
    // would make its work stealing read as races; one range on the calling thread.
    (void)grain;
    body(0, n);
#else
    tbb::parallel_for(tbb::blocked_range<int>(0, n, grain > 0 ? grain : 1),
                      [&](const tbb::blocked_range<int>& r) { body(r.begin(), r.end()); });
#endif
}

void parallel_for_chunks(int n, int chunk,
                         const std::function<void(int c, int begin, int end)>& body) {
    if (n <= 0) return;
    const int step = chunk > 0 ? chunk : 1;
    auto run = [&](int c) { body(c, c * step, std::min(n, (c + 1) * step)); };
#ifdef DRAPE_SERIAL_LOOPS
    for (int c = 0, chunks = chunk_count(n, step); c < chunks; ++c) run(c);
#else
    tbb::parallel_for(0, chunk_count(n, step), run);
#endif
}

}  // namespace drape::core
