// `pelage hair` and `pelage bench` end to end on the monkey (each run builds the skin: labelled
// slow).
#include <gtest/gtest.h>

#include "support/files.h"

namespace pelage {
namespace {

using test::runPelage;

TEST(HairCommand, WritesAPlyOfTheRequestedHairs) {
  test::TempDir dir;
  const std::string out = dir.file("fur.ply");
  const test::RunResult r = runPelage("hair --fur fig8 --hairs 5000 --style line --out " + out);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("overcoat:"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("line hairs, 2 points each"), std::string::npos) << r.output;
  const std::string text = test::readText(out);
  ASSERT_EQ(text.rfind("ply\nformat binary_little_endian 1.0\n", 0), 0u);
  EXPECT_NE(text.find("comment model monkey, fur fig8, seed 8"), std::string::npos);
  EXPECT_NE(text.find("element edge"), std::string::npos);
}

TEST(HairCommand, DistanceCullsHairs) {
  test::TempDir dir;
  const test::RunResult r =
      runPelage("hair --hairs 20000 --distance 2 --out " + dir.file("far.ply"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("culling factor"), std::string::npos) << r.output;
}

TEST(HairCommand, TubesWriteFaces) {
  test::TempDir dir;
  const test::RunResult r = runPelage("hair --hairs 500 --style tube --out " + dir.file("t.ply"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(test::readText(dir.file("t.ply")).find("element face"), std::string::npos);
}

TEST(BenchCommand, PrintsHairsPerSecondAndMsPerFrame) {
  const test::RunResult r =
      runPelage("--threads 2 bench --hairs 20000 --style polyline --repeat 3");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("M hairs/s"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("ms/frame"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("threads 2"), std::string::npos) << r.output;
  EXPECT_NE(runPelage("bench --repeat 0").exitCode, 0);
}

// A missing folder is made (as render and export make theirs); one that cannot be made is an
// error naming it, before the model is built.
TEST(HairCommand, UnwritableOutputIsAnErrorWithoutPartialFile) {
  const test::RunResult r = runPelage("hair --hairs 100 --out /proc/pelage-test/fur.ply");
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("/proc/pelage-test"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace pelage
