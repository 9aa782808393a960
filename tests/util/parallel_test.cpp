#include "pelage/util/parallel.h"

#include <gtest/gtest.h>

#include <atomic>
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

TEST(Parallel, ChunksCoverRangeWithoutOverlap) {
  setThreadCount(4);
  std::vector<int> owner(1000, -1);
  std::atomic<int> chunkId{0};
  parallelForChunks(1000, 64, [&](std::int64_t b, std::int64_t e) {
    EXPECT_LE(e - b, 64);
    const int id = chunkId++;
    for (std::int64_t i = b; i < e; ++i) owner[static_cast<std::size_t>(i)] = id;
  });
  for (int o : owner) EXPECT_GE(o, 0);
  EXPECT_EQ(chunkId.load(), 16);
  setThreadCount(0);
}

}  // namespace
}  // namespace pelage
