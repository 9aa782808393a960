// `pelage export` as a user runs it: USD, PLY and glTF output of a clip of the test critter, and
// clear errors (exit 2, nothing left behind) for bad formats, frame ranges, clips, fur settings,
// unwritable outputs and a failing disk.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "pelage/scene/frame_range.h"
#include "support/exports.h"
#include "support/files.h"
#include "support/models.h"

namespace pelage::test {
namespace {

namespace fs = std::filesystem;

class ExportCommand : public ::testing::Test {
 protected:
  void SetUp() override { writeText(dir.file("wag.json"), kWagClip); }
  std::string base() const {
    return std::string(PELAGE_TEST_CRITTER " --clip ") + dir.file("wag.json") + " --hairs 2000";
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
      std::string("export " PELAGE_TEST_CRITTER " --hairs 100 --dynamics on --format ply --out ") +
      dir.file("rest"));
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("--dynamics on needs a clip"), std::string::npos) << r.output;
}

struct BadExport {
  const char* name;
  std::string args;    // <dir> and <base> are replaced
  std::string expect;  // in the message
};

// gtest names the case by this (not its bytes) in test names and failures.
void PrintTo(const BadExport& c, std::ostream* os) {
  *os << c.name;
}

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
        BadExport{"clip", PELAGE_TEST_CRITTER " --clip nope --format usda --out <dir>/o.usda",
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
                  "unknown field 'coat'"},
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

namespace pelage::test {
namespace {

// The JSON chunk of a .glb file.
nlohmann::json glbJson(const std::string& path) {
  const std::string bytes = readText(path);
  EXPECT_GE(bytes.size(), 20u);
  std::uint32_t length = 0;
  std::memcpy(&length, bytes.data() + 12, 4);
  return nlohmann::json::parse(bytes.substr(20, length));
}

// glTF is +Y up: the Fox (1.55 m nose to tail, 0.77 m high) stands on its feet, its height along
// Y and its length along Z, and the asset says how pelage's axes were converted.
TEST(ExportGlb, TheFoxStandsUpInGltfAxes) {
  const std::string fox = PELAGE_SHARED_MODELS_DIR "/Fox/Fox.glb";
  if (!fs::exists(fox)) GTEST_SKIP() << fox << " is absent (../shared/models)";
  TempDir dir;
  const RunResult r = runPelage("export " + fox + " --clip Walk --frames 0 --hairs 3000 " +
                                "--format glb --out " + dir.file("fox"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const nlohmann::json j = glbJson(dir.file("fox/frame_00000.glb"));
  EXPECT_EQ(j["asset"]["extras"]["up"], "+Y");
  const int position = j["meshes"][0]["primitives"][0]["attributes"]["POSITION"];
  const nlohmann::json& acc = j["accessors"][static_cast<std::size_t>(position)];
  double size[3];
  for (int a = 0; a < 3; ++a)
    size[a] = acc["max"][static_cast<std::size_t>(a)].get<double>() -
              acc["min"][static_cast<std::size_t>(a)].get<double>();
  EXPECT_NEAR(size[1], 0.77, 0.12);               // height: Y (mid-stride in the walk)
  EXPECT_NEAR(size[2], 1.55, 0.15);               // nose to tail: Z, glTF's front
  EXPECT_LT(size[0], size[1]);                    // width: X, the narrowest
  EXPECT_GT(acc["min"][1].get<double>(), -0.05);  // the paws on the ground plane, none below it
}

// Spools of a USD export killed by SIGKILL are removed by the next run for the same output; a
// SIGTERM removes them at once (the signal handler of util/atomic_file.h).
TEST_F(ExportCommand, KilledUsdExportsLeaveNoSpoolFiles) {
  const std::string out = dir.file("walk.usda");
  auto spools = [&] {
    int n = 0;
    for (const auto& e : fs::directory_iterator(dir.path()))
      n += e.path().filename().string().rfind(".walk.usda.", 0) == 0;
    return n;
  };
  for (const char* signal : {"KILL", "TERM"}) {
    SCOPED_TRACE(signal);
    const RunResult r =
        runShell("bash -c '" + std::string(PELAGE_BIN_DIR) + "/pelage export " +
                 PELAGE_TEST_CRITTER " --clip " + dir.file("wag.json") +
                 " --hairs 200000 --frames 0:400 --format usda --out " + out +
                 " > /dev/null & pid=$!; for i in $(seq 400); do ls -a " + dir.path().string() +
                 " | grep -q walk.usda.spool && break; sleep 0.05; done; kill -" + signal +
                 " $pid; wait $pid; echo status $?'");
    EXPECT_NE(r.output.find(std::string("status ") + (signal[0] == 'K' ? "137" : "143")),
              std::string::npos)
        << r.output;
    if (signal[0] == 'K') {
      EXPECT_GT(spools(), 0) << "SIGKILL cannot be caught: its spools stay until the next run";
      const RunResult next =
          runPelage("export " + base() + " --frames 0:1 --format usda --out " + out);
      ASSERT_EQ(next.exitCode, 0) << next.output;
      EXPECT_NE(next.output.find("spool file(s) of a killed run"), std::string::npos)
          << next.output;
    }
    EXPECT_EQ(spools(), 0);
  }
}

// --resume keeps complete PLY/glb frames, redoes the missing one and removes a killed run's
// temporary: the same bytes as one run, with dynamics too (the redone frame is pre-rolled).
TEST_F(ExportCommand, ResumeCompletesPerFrameExportsToTheSameBytes) {
  for (const std::string format : {"ply", "glb"}) {
    SCOPED_TRACE(format);
    const std::string whole = dir.file("whole-" + format), part = dir.file("part-" + format);
    const std::string dyn = " --dynamics on --format " + format;
    ASSERT_EQ(runPelage("export " + base() + " --frames 0:4" + dyn + " --out " + whole).exitCode,
              0);
    ASSERT_EQ(runPelage("export " + base() + " --frames 0:4" + dyn + " --out " + part).exitCode, 0);
    const std::string name = "frame_00003." + format;
    fs::remove(fs::path(part) / name);
    writeText((fs::path(part) / ("frame_00004." + format)).string(), "truncated");
    writeText((fs::path(part) / ("." + name + ".tmp-999999-0")).string(), "half");
    const auto kept = fs::last_write_time(fs::path(part) / ("frame_00001." + format));
    const RunResult r =
        runPelage("export " + base() + " --frames 0:4" + dyn + " --resume --out " + part);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("3 complete frame(s) kept by --resume"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("removed 1 temporary file(s)"), std::string::npos) << r.output;
    EXPECT_EQ(fs::last_write_time(fs::path(part) / ("frame_00001." + format)), kept);
    for (int f = 0; f <= 4; ++f) {
      const std::string n = scene::frameFileName(f, "." + format);
      EXPECT_EQ(readText((fs::path(part) / n).string()), readText((fs::path(whole) / n).string()))
          << n;
    }
    EXPECT_FALSE(fs::exists(fs::path(part) / ("." + name + ".tmp-999999-0")));
  }
}

}  // namespace
}  // namespace pelage::test

namespace pelage::test {
namespace {

// Frames past the clip's end are played (the clip loops), with one note saying so; --quiet
// drops the note.
TEST_F(ExportCommand, FramesPastTheClipsEndGetANote) {
  const RunResult r = runPelage("export " + base() +
                                " --format ply --fps 12 --frames 10:14 --out " + dir.file("f"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const std::string note =
      "pelage: note: frames 13..14 lie past the end of clip 'wag' (1 s at 12 fps): they show it "
      "looped";
  const auto at = r.output.find(note);
  EXPECT_NE(at, std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("pelage: note", at + 1), std::string::npos) << r.output;
  const RunResult inside = runPelage("export " + base() + " --format ply --fps 12 --frames 0:12 " +
                                     "--out " + dir.file("g"));
  EXPECT_EQ(inside.output.find("note"), std::string::npos) << inside.output;
  const RunResult quiet = runPelage("export " + base() + " --format ply --fps 12 --frames 10:14 " +
                                    "--quiet --out " + dir.file("h"));
  EXPECT_EQ(quiet.output.find("note"), std::string::npos) << quiet.output;
}

}  // namespace
}  // namespace pelage::test
