// `pelage export` as a user runs it: USD, PLY and glTF output of a clip of the test critter, and
// clear errors (exit 2, nothing left behind) for bad formats, frame ranges, clips, fur settings,
// unwritable outputs and a failing disk.
#include <gtest/gtest.h>

#include <filesystem>

#include "scene/export_test_support.h"
#include "test_support.h"

namespace pelage::test {
namespace {

namespace fs = std::filesystem;

// A clip for the critter: the tail wags, the head nods, the body moves forward.
const char* kWagClip = R"({ "name": "wag", "duration": 1.0, "channels": [
  { "segment": "tail", "path": "rotate", "interpolation": "cubic", "keys": [
    { "time": 0, "axis": [0, 0, 1], "degrees": -30 }, { "time": 0.5, "axis": [0, 0, 1], "degrees": 30 },
    { "time": 1, "axis": [0, 0, 1], "degrees": -30 } ] },
  { "segment": "head", "path": "rotate", "keys": [
    { "time": 0, "axis": [0, 1, 0], "degrees": 0 }, { "time": 0.5, "axis": [0, 1, 0], "degrees": 20 },
    { "time": 1, "axis": [0, 1, 0], "degrees": 0 } ] },
  { "segment": "body", "path": "translate", "keys": [
    { "time": 0, "value": [0, 0, 0] }, { "time": 1, "value": [0.2, 0, 0] } ] } ] })";

class ExportCommand : public ::testing::Test {
 protected:
  void SetUp() override { writeText(dir.file("wag.json"), kWagClip); }
  std::string base() const {
    return std::string(PELAGE_SOURCE_DIR "/tests/scene/critter.json --clip ") +
           dir.file("wag.json") + " --hairs 2000";
  }
  TempDir dir;
};

TEST_F(ExportCommand, UsdLayerWithATimeSamplePerFrame) {
  const RunResult r = runPelage("export " + base() + " --frames 0:2 --fps 24 --format usda --out " +
                                dir.file("c.usda"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("3 time samples"), std::string::npos) << r.output;
  const std::string text = readText(dir.file("c.usda"));
  const std::string over = usdBlock(text, "def BasisCurves \"overcoat\"");
  const auto samples = usdTimeSamples(over, "point3f[] points");
  ASSERT_EQ(samples.size(), 3u);
  EXPECT_NE(samples[0].second, samples[2].second);  // the clip moves the creature
  const auto skin = usdTimeSamples(usdBlock(text, "def Mesh \"skin\""), "point3f[] points");
  ASSERT_EQ(skin.size(), 3u);
  // The body translates by 0.2 m per second: 2/24 s later the skin is 1/60 m further along +X.
  double dx = 0.0;
  const std::size_t n = skin[0].second.size() / 3;
  for (std::size_t v = 0; v < n; ++v) dx += skin[2].second[v * 3] - skin[0].second[v * 3];
  EXPECT_NEAR(dx / static_cast<double>(n), 0.2 * 2.0 / 24.0, 0.2 * 2.0 / 24.0 * 0.5);
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.path()), fs::directory_iterator()),
            2);  // wag.json, c.usda
}

TEST_F(ExportCommand, PlyAndGlbFilesPerFrame) {
  RunResult r =
      runPelage("export " + base() + " --frames 3:4 --format ply --out " + dir.file("ply"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  for (const char* f : {"frame_00003.ply", "frame_00004.ply"})
    EXPECT_EQ(readText((dir.path() / "ply" / f).string())
                  .rfind("ply\nformat binary_little_endian 1.0\n", 0),
              0u)
        << f;
  EXPECT_FALSE(fs::exists(dir.path() / "ply" / "frame_00002.ply"));
  r = runPelage("export " + base() + " --frames 0:1 --format glb --style curve --out " +
                dir.file("glb"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  for (const char* f : {"frame_00000.glb", "frame_00001.glb"})
    EXPECT_EQ(readText((dir.path() / "glb" / f).string()).substr(0, 4), "glTF") << f;
}

// Dynamic fur in export: a range exported on its own pre-rolls the springs from frame 0, so its
// files are byte-identical to the same frames of a whole run, and differ from the quasi-static
// ones.
TEST_F(ExportCommand, DynamicFurRangesMatchAWholeRun) {
  const std::string dyn = " --format ply --dynamics on --frequency 3 --damping 0.1";
  RunResult r =
      runPelage("export " + base() + " --frames 0:5" + dyn + " --out " + dir.file("whole"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("(dynamic)"), std::string::npos) << r.output;
  r = runPelage("export " + base() + " --frames 4:5" + dyn + " --out " + dir.file("part"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  r = runPelage("export " + base() + " --frames 4:5 --format ply --out " + dir.file("static"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  for (const char* f : {"frame_00004.ply", "frame_00005.ply"}) {
    const std::string whole = readText((dir.path() / "whole" / f).string());
    EXPECT_EQ(readText((dir.path() / "part" / f).string()), whole) << f;
    EXPECT_NE(readText((dir.path() / "static" / f).string()), whole) << f;
  }
  // A short pre-roll is allowed (approximate), and the rest pose has nothing to simulate.
  r = runPelage("export " + base() + " --frames 4:4 --preroll 2" + dyn + " --out " +
                dir.file("short"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  r = runPelage(
      std::string("export " PELAGE_SOURCE_DIR
                  "/tests/scene/critter.json --hairs 100 --dynamics on --format ply --out ") +
      dir.file("rest"));
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("--dynamics on needs a clip"), std::string::npos) << r.output;
}

struct BadExport {
  const char* name;
  std::string args;    // <dir> and <base> are replaced
  std::string expect;  // in the message
};

class ExportCommandErrors : public ExportCommand,
                            public ::testing::WithParamInterface<BadExport> {};

TEST_P(ExportCommandErrors, ExitTwoWithAClearMessageAndNoOutput) {
  std::string args = GetParam().args;
  for (std::size_t at; (at = args.find("<base>")) != std::string::npos;)
    args.replace(at, 6, base());
  for (std::size_t at; (at = args.find("<dir>")) != std::string::npos;)
    args.replace(at, 5, dir.path().string());
  const RunResult r = runPelage("export " + args);
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find(GetParam().expect), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("Segmentation"), std::string::npos);
  EXPECT_FALSE(fs::exists(dir.path() / "o.usda"));
  EXPECT_FALSE(fs::exists(dir.path() / "o") && !fs::is_empty(dir.path() / "o"));
}

INSTANTIATE_TEST_SUITE_P(
    BadInput, ExportCommandErrors,
    ::testing::Values(
        BadExport{"format", "<base> --format obj --out <dir>/o",
                  "--format 'obj' (accepted: usda, ply, glb)"},
        BadExport{"reversed", "<base> --frames 5:2 --format ply --out <dir>/o",
                  "--frames 5:2 is out of range"},
        BadExport{"words", "<base> --frames a:b --format ply --out <dir>/o",
                  "is not a frame range"},
        BadExport{"negative", "<base> --frames=-3:2 --format ply --out <dir>/o",
                  "--frames -3:2 is out of range"},
        BadExport{"clip",
                  PELAGE_SOURCE_DIR
                  "/tests/scene/critter.json --clip nope --format usda --out <dir>/o.usda",
                  "has no clip 'nope'"},
        BadExport{"usda name", "<base> --format usda --out <dir>/o.usd", "must end in .usda"},
        BadExport{"unwritable usda", "<base> --format usda --out /proc/o.usda", "/proc"},
        BadExport{"unwritable dir", "<base> --format glb --out /dev/null/o", "/dev/null/o"},
        BadExport{"fur range",
                  "<base> --fur-set overcoat.stiffness=7 --format usda --out <dir>/o.usda",
                  "stiffness"},
        BadExport{"fur field",
                  "<base> --fur-set overcoat.stifness=0.5 --format usda --out <dir>/o.usda",
                  "stifness"},
        BadExport{"fur group",
                  "<base> --fur-set coat.stiffness=0.5 --format usda --out <dir>/o.usda",
                  "no field group 'coat'"},
        BadExport{"fur syntax", "<base> --fur-set stiffness --format usda --out <dir>/o.usda",
                  "is not FIELD=VALUE"},
        BadExport{"damping", "<base> --dynamics on --damping 20 --format ply --out <dir>/o",
                  "damping"},
        BadExport{"preroll", "<base> --dynamics on --preroll=-5 --format ply --out <dir>/o",
                  "--preroll -5 is out of range"}),
    [](const ::testing::TestParamInfo<BadExport>& param) {
      std::string n = param.param.name;
      for (char& c : n)
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
      return n;
    });

// A disk that fails mid-write (the file-size limit makes every write past 64 KiB fail with EFBIG,
// as a full disk fails with ENOSPC): a clear error, and neither the layer nor its spools remain.
TEST_F(ExportCommand, FailingDiskLeavesNoPartialFiles) {
  const RunResult r = runShell("bash -c \"trap '' XFSZ; ulimit -f 64; exec " +
                               std::string(PELAGE_BIN_DIR) + "/pelage export " + base() +
                               " --frames 0:2 --format usda --out " + dir.file("big.usda") + "\"");
  const std::string& out = r.output;
  EXPECT_EQ(r.exitCode, 2) << out;
  EXPECT_NE(out.find("big.usda: write failed (File too large); no file was written"),
            std::string::npos)
      << out;
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.path()), fs::directory_iterator()),
            1);  // wag.json only
}

}  // namespace
}  // namespace pelage::test
