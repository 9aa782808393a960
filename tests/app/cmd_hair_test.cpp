// `pelage hair` and `pelage bench` refusing bad input: message, exit code, no output file. These
// fail before the model is built, so they are fast.
#include <gtest/gtest.h>

#include <filesystem>

#include "support/files.h"

namespace pelage {
namespace {

using test::runPelage;

struct BadHair {
  const char* name;
  const char* args;
  const char* expect;
};

// gtest names the case by this (not its bytes) in test names and failures.
void PrintTo(const BadHair& c, std::ostream* os) {
  *os << c.name;
}

class HairCommandBad : public ::testing::TestWithParam<BadHair> {};

TEST_P(HairCommandBad, ClearMessageNonZeroExitNoFile) {
  test::TempDir dir;
  const std::string out = dir.file("never.ply");
  const test::RunResult r = runPelage(std::string("hair ") + GetParam().args + " --out " + out);
  EXPECT_NE(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find(GetParam().expect), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(out));
}

INSTANTIATE_TEST_SUITE_P(
    Cases, HairCommandBad,
    ::testing::Values(
        BadHair{"UnknownPreset", "--fur fig99", "unknown fur preset 'fig99'"},
        BadHair{"MissingPresetFile", "--fur /nonexistent/x.json", "cannot open file"},
        BadHair{"AbsurdCount", "--hairs 2e10",
                "2e+10 hairs need 4.6 TB (polyline overcoat, polyline undercoat); accepted: 0 to "
                "2e+07 hairs"},
        BadHair{"NegativeCount", "--hairs -3", "out of range"},
        BadHair{"BadStyle", "--style spaghetti", "accepted: line, polyline, curve, tube"},
        BadHair{"Stiffness", "--stiffness 2", "stiffness = 2 is out of range [0, 1]"},
        BadHair{"Distance", "--distance -1", "--distance -1 is out of range"},
        BadHair{"Share", "--undercoat-share 1.5", "undercoatShare = 1.5 is out of range [0, 1]"}),
    [](const auto& bad) { return std::string(bad.param.name); });

}  // namespace
}  // namespace pelage
