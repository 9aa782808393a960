#include "pelage/util/parallel.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <mutex>
#include <utility>
#include <vector>

namespace pelage {
namespace {

TEST(Parallel, VisitsEveryIndexOnceWhateverTheThreadCount) {
  for (int threads : {1, 2, 3, 8}) {
    setThreadCount(threads);
    EXPECT_EQ(threadCount(), threads);
    std::vector<std::atomic<int>> hits(10007);
    parallelFor(10007, 100, [&](std::int64_t i) { hits[static_cast<std::size_t>(i)]++; });
    for (const auto& h : hits) ASSERT_EQ(h.load(), 1);
  }
  setThreadCount(0);
}

// The chunks are [c grain, min((c + 1) grain, n)) whatever the thread count, one included: what
// the bit-identical reductions (chunk partials summed in chunk order) rest on.
TEST(Parallel, ChunksAreFixedWhateverTheThreadCount) {
  for (const std::int64_t n : {0, 1, 63, 64, 65, 1000}) {
    std::vector<std::pair<std::int64_t, std::int64_t>> expected;
    for (std::int64_t b = 0; b < n; b += 64)
      expected.emplace_back(b, std::min<std::int64_t>(b + 64, n));
    for (const int threads : {1, 2, 3, 4, 7, 8}) {
      setThreadCount(threads);
      std::mutex m;
      std::vector<std::pair<std::int64_t, std::int64_t>> chunks;
      parallelForChunks(n, 64, [&](std::int64_t b, std::int64_t e) {
        std::lock_guard<std::mutex> lock(m);
        chunks.emplace_back(b, e);
      });
      std::sort(chunks.begin(), chunks.end());
      EXPECT_EQ(chunks, expected) << "n " << n << ", " << threads << " threads";
    }
  }
  setThreadCount(0);
}

}  // namespace
}  // namespace pelage
