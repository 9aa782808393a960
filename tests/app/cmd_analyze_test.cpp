// `pelage analyze` run as a user would (issue 7): the CSV and plot on a small monkey, and clear
// errors with exit code 2 for bad options.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "support/files.h"

namespace pelage {
namespace {

using test::runPelage;
using ::testing::HasSubstr;

TEST(AnalyzeCommand, WritesTheCsvAndPlotOfAQuasiStaticAndADynamicRun) {
  test::TempDir dir;
  const std::string base =
      "analyze monkey --triangles 4000 --hairs 3000 --clip tumble --frames 40:46 ";
  auto r = runPelage(base + "--dynamics on --hold 0.2 --out " + dir.file("a.csv") + " --plot " +
                     dir.file("a.png"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("13 frames of clip tumble"));
  EXPECT_THAT(r.output, HasSubstr("after the body stops at 1.533 s"));
  const std::string csv = test::readText(dir.file("a.csv"));
  EXPECT_THAT(csv.substr(0, csv.find('\n')), HasSubstr("frame,time_s,held,"));
  EXPECT_THAT(csv, HasSubstr("dyn_droop_mean_deg"));
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 14);
  EXPECT_GT(test::readText(dir.file("a.png")).size(), 10000u);
  r = runPelage(base + "--sweep stiffness=0.2:0.8:3 --out " + dir.file("s.csv"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_THAT(test::readText(dir.file("s.csv")), HasSubstr("droop_mean_deg[stiffness=0.5]"));
}

TEST(AnalyzeCommand, BadOptionsAreClearErrors) {
  test::TempDir dir;
  const std::string out = " --out " + dir.file("x.csv");
  const struct {
    std::string args, message;
  } cases[] = {
      {"--clip tumble --sweep stiffness=0:2:3",
       "--sweep 'stiffness=0:2:3': stiffness 2 is out of range [0, 1]"},
      {"--clip tumble --sweep mass=1:2:3", "unknown parameter 'mass'"},
      {"--clip tumble --frames 9:3", "--frames 9:3 is out of range"},
      {"--clip tumble --hold -1", "--hold -1 is out of range [0, 1000]"},
      {"--clip tumble --dynamics on --frequency 0",
       "dynamics frequency 0 Hz is out of range (0, 100]"},
      {"--clip tumble --damping 11", "damping ratio 11 is out of range [0, 10]"},
      {"--clip tumble --fps 0", "--fps 0 is out of range [1, 1000]"},
      {"--clip tumble --plot p.jpg", "must name a .png file"},
      {"--triangles 4000 --clip nosuch", "has no clip 'nosuch'"},
  };
  for (const auto& c : cases) {
    const auto r = runPelage("analyze " + c.args + out);
    EXPECT_EQ(r.exitCode, 2) << c.args << "\n" << r.output;
    EXPECT_THAT(r.output, HasSubstr(c.message)) << c.args;
  }
  EXPECT_FALSE(std::filesystem::exists(dir.file("x.csv")));
}

}  // namespace
}  // namespace pelage
