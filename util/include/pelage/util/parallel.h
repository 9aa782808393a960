// Thread control and a deterministic parallel loop (OpenMP, static schedule). Work is split into
// fixed chunks of items; each item's result must depend only on its index, so the output is
// bit-identical whatever the thread count.
#pragma once

#include <cstdint>

namespace pelage {

// Sets the number of worker threads (>= 1); 0 means "all hardware threads".
void setThreadCount(int threads);
// The number of worker threads parallel loops will use.
int threadCount();

// Calls fn(begin, end) over [0, n) in chunks of at most `grain` items, in parallel. The chunks are
// fixed whatever the thread count: [c grain, min((c + 1) grain, n)) for c = 0, 1, ..., so a
// reduction over per-chunk partial results (summed in chunk order) is bit-identical for any
// count, one thread included.
template <typename Fn>
void parallelForChunks(std::int64_t n, std::int64_t grain, Fn&& fn) {
  if (n <= 0) return;
  if (grain < 1) grain = 1;
  const std::int64_t chunks = (n + grain - 1) / grain;
  if (chunks == 1 || threadCount() == 1) {
    for (std::int64_t c = 0; c < chunks; ++c) fn(c * grain, c + 1 < chunks ? (c + 1) * grain : n);
    return;
  }
#pragma omp parallel for schedule(dynamic, 1) num_threads(threadCount())
  for (std::int64_t c = 0; c < chunks; ++c) {
    const std::int64_t b = c * grain;
    const std::int64_t e = b + grain < n ? b + grain : n;
    fn(b, e);
  }
}

// Calls fn(i) for every i in [0, n), in parallel.
template <typename Fn>
void parallelFor(std::int64_t n, std::int64_t grain, Fn&& fn) {
  parallelForChunks(n, grain, [&](std::int64_t b, std::int64_t e) {
    for (std::int64_t i = b; i < e; ++i) fn(i);
  });
}

}  // namespace pelage
