#include "pelage/util/random.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace pelage {
namespace {

TEST(Random, SameInputsSameValueAndRange) {
  for (std::uint64_t i = 0; i < 1000; ++i) {
    const float u = uniform01(42, kStreamHairEnd, i);
    EXPECT_EQ(u, uniform01(42, kStreamHairEnd, i));
    EXPECT_GE(u, 0.0f);
    EXPECT_LT(u, 1.0f);
  }
}

// Chi-square test of uniformity over 64 bins (df = 63; the 99.9% quantile is 103.4).
TEST(Random, UniformByChiSquare) {
  constexpr int kBins = 64, kN = 200000;
  for (std::uint64_t stream : {kStreamAllocation, kStreamCulling}) {
    std::vector<int> bins(kBins, 0);
    for (int i = 0; i < kN; ++i)
      ++bins[static_cast<std::size_t>(uniform01(7, stream, static_cast<std::uint64_t>(i)) * kBins)];
    double chi2 = 0.0;
    const double expected = static_cast<double>(kN) / kBins;
    for (int b : bins) chi2 += (b - expected) * (b - expected) / expected;
    EXPECT_LT(chi2, 103.4) << "stream " << stream;
  }
}

// Different streams and seeds are uncorrelated: the sample correlation of 100k pairs is ~0
// (standard error 1/sqrt(n) = 0.0032; we allow 5 sigma).
TEST(Random, StreamsAndSeedsIndependent) {
  constexpr int kN = 100000;
  auto corr = [&](auto fa, auto fb) {
    double sa = 0, sb = 0, sab = 0, saa = 0, sbb = 0;
    for (int i = 0; i < kN; ++i) {
      const double a = fa(static_cast<std::uint64_t>(i)), b = fb(static_cast<std::uint64_t>(i));
      sa += a;
      sb += b;
      sab += a * b;
      saa += a * a;
      sbb += b * b;
    }
    const double n = kN;
    return (sab / n - sa / n * sb / n) /
           std::sqrt((saa / n - sa * sa / n / n) * (sbb / n - sb * sb / n / n));
  };
  EXPECT_LT(std::abs(corr([](std::uint64_t i) { return uniform01(1, 1, i); },
                          [](std::uint64_t i) { return uniform01(1, 2, i); })),
            0.016);
  EXPECT_LT(std::abs(corr([](std::uint64_t i) { return uniform01(1, 1, i); },
                          [](std::uint64_t i) { return uniform01(2, 1, i); })),
            0.016);
  EXPECT_LT(std::abs(corr([](std::uint64_t i) { return uniform01(1, 1, i); },
                          [](std::uint64_t i) { return uniform01(1, 1, i + 1); })),
            0.016);
}

}  // namespace
}  // namespace pelage
