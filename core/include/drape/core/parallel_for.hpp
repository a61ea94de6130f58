// Parallel loops over an index range (TBB underneath, kept out of this header).
#pragma once

#include <functional>
#include <vector>

namespace drape::core {

/// Runs body(begin, end) over sub-ranges covering [0, n) exactly once, on TBB's threads,
/// with sub-ranges of about `grain` indices (TBB's auto partitioner decides the split). The
/// schedule is not deterministic: use it when body writes only the slots of its own indices.
/// \pre grain >= 1. \throw whatever body throws (TBB rethrows one of them on this thread).
void parallel_for_ranges(int n, int grain, const std::function<void(int begin, int end)>& body);

/// Runs f(i) for every i in [0, n) in parallel (see parallel_for_ranges); deterministic when
/// f(i) writes only slot i.
template <class F>
void parallel_for(int n, F&& f, int grain = 256) {
    parallel_for_ranges(n, grain, [&f](int begin, int end) {
        for (int i = begin; i < end; ++i) f(i);
    });
}

/// The number of fixed chunks of `chunk` indices that cover [0, n): ceil(n / chunk).
inline int chunk_count(int n, int chunk) { return (n + chunk - 1) / chunk; }

/// Runs body(c, begin, end) for the fixed chunks c = 0 .. chunk_count(n, chunk) − 1, chunk c
/// covering [c · chunk, min(n, (c + 1) · chunk)), in parallel. The chunk boundaries do not
/// depend on the schedule, so per-chunk results combined in chunk order are deterministic
/// (sums, concatenations).
/// \pre chunk >= 1.
void parallel_for_chunks(int n, int chunk,
                         const std::function<void(int c, int begin, int end)>& body);

/// Runs body(i, out) for i in [0, n) in parallel; each fixed chunk appends to its own vector
/// and the chunks are concatenated in index order, so the result does not depend on the
/// schedule.
template <class T, class Body>
std::vector<T> parallel_collect(int n, int chunk, Body&& body) {
    std::vector<std::vector<T>> parts(static_cast<std::size_t>(chunk_count(n, chunk)));
    parallel_for_chunks(n, chunk, [&](int c, int begin, int end) {
        for (int i = begin; i < end; ++i) body(i, parts[static_cast<std::size_t>(c)]);
    });
    std::vector<T> all;
    for (auto& part : parts) all.insert(all.end(), part.begin(), part.end());
    return all;
}

}  // namespace drape::core
