// The pelage command line as a user meets it: outputs, and clear errors with non-zero exits for
// bad input (never a crash: exit codes >= 128 would mean a signal).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <filesystem>

#include "support/files.h"

namespace pelage {
namespace {

using test::runPelage;
using ::testing::HasSubstr;

TEST(Cli, InfoJsonDescribesTheBuiltInMonkey) {
  const auto r = runPelage("info --json --triangles 20000");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const auto j = nlohmann::json::parse(r.output);
  EXPECT_EQ(j["name"], "monkey");
  EXPECT_NEAR(j["triangles"].get<double>(), 20000, 1000);
  EXPECT_EQ(j["boundaryEdges"], 0);
  EXPECT_GT(j["areaSquareMeters"].get<double>(), 0.2);
  EXPECT_GE(j["segments"].size(), 20u);
  EXPECT_TRUE(j["segments"][0]["parent"].is_null());
}

TEST(Cli, InfoCountsAWidthGroomInTheCoverage) {
  // A width groom of 2 over the whole monkey: each coat's mean width and optical depth, as `info`
  // reports them, double; the hair count (the preset's coverage) stays.
  const auto plain = runPelage("info --json --triangles 2000");
  const auto wide = runPelage(
      R"(info --json --triangles 2000 --fur-set 'regions=[{"match": "*", "widthScale": 2}]')");
  ASSERT_EQ(plain.exitCode, 0) << plain.output;
  ASSERT_EQ(wide.exitCode, 0) << wide.output;
  const auto a = nlohmann::json::parse(plain.output)["fur"];
  const auto b = nlohmann::json::parse(wide.output)["fur"];
  for (std::size_t c = 0; c < 2; ++c) {
    EXPECT_EQ(b["coats"][c]["hairs"], a["coats"][c]["hairs"]);
    EXPECT_NEAR(b["coats"][c]["meanWidthMm"].get<double>(),
                2.0 * a["coats"][c]["meanWidthMm"].get<double>(), 1e-6);
    EXPECT_NEAR(b["coats"][c]["opticalDepth"].get<double>(),
                2.0 * a["coats"][c]["opticalDepth"].get<double>(), 1e-6);
  }
  EXPECT_GT(b["hiddenShare"].get<double>(), a["hiddenShare"].get<double>());
}

TEST(Cli, SkinWritesAPosedObj) {
  test::TempDir dir;
  test::writeText(dir.file("pose.json"),
                  R"({"pose": {"l_forearm": {"rotate": {"axis": [0, 1, 0], "degrees": -80}}}})");
  const auto r = runPelage("skin --triangles 20000 --pose " + dir.file("pose.json") + " --out " +
                           dir.file("m.obj"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const std::string obj = test::readText(dir.file("m.obj"));
  EXPECT_THAT(obj, HasSubstr("\nv "));
  EXPECT_THAT(obj, HasSubstr("\nf "));
}

struct BadCase {
  std::string name;
  std::string fileText;  // written to <tmp>/c.json when non-empty
  std::string args;      // "{}" is replaced by that file's path
  std::string expect;    // a part of the message
};

void PrintTo(const BadCase& c, std::ostream* os) {
  *os << c.name;
}

class CliBadInput : public ::testing::TestWithParam<BadCase> {};

TEST_P(CliBadInput, ClearMessageAndNonZeroExit) {
  const BadCase& c = GetParam();
  test::TempDir dir;
  std::string args = c.args;
  const std::string file = dir.file("c.json");
  if (!c.fileText.empty()) test::writeText(file, c.fileText);
  if (auto p = args.find("{}"); p != std::string::npos) args.replace(p, 2, file);
  if (auto p = args.find("<dir>"); p != std::string::npos) args.replace(p, 5, dir.path().string());
  // A tetrahedron stands in for a creature where the case is about something else.
  test::writeText(dir.file("tet.obj"),
                  "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
  if (auto p = args.find("<tet>"); p != std::string::npos) args.replace(p, 5, dir.file("tet.obj"));
  const auto r = runPelage(args);
  EXPECT_NE(r.exitCode, 0) << r.output;
  EXPECT_LT(r.exitCode, 128) << "crashed: " << r.output;
  EXPECT_THAT(r.output, HasSubstr(c.expect));
}

const std::string kOneSegment = R"("segments": [{"name": "a", "joint": [0, 0, 0]}])";

INSTANTIATE_TEST_SUITE_P(
    Cases, CliBadInput,
    ::testing::Values(
        BadCase{"MissingFile", "", "info /nonexistent/creature.json", "/nonexistent/creature.json"},
        BadCase{"MalformedJson", "{ \"segments\": [", "info {}", "malformed JSON"},
        BadCase{
            "Cycle",
            R"({"segments": [{"name": "a", "parent": "b", "joint": [0,0,0]}, {"name": "b", "parent": "a", "joint": [0,0,0]}],
                            "shapes": [{"segment": "a", "type": "capsule", "from": [0,0,0], "to": [1,0,0], "radius": 0.1}]})",
            "info {}", "cycle"},
        BadCase{"UnknownParent",
                R"({"segments": [{"name": "a", "parent": "q", "joint": [0,0,0]}], "shapes": []})",
                "info {}", "unknown parent 'q'"},
        BadCase{"NaN", R"({"segments": [{"name": "a", "joint": [0, NaN, 0]}], "shapes": []})",
                "info {}", "malformed JSON"},
        BadCase{"Overflow",
                R"({"segments": [{"name": "a", "joint": [0, 1e500, 0]}], "shapes": []})", "info {}",
                "number overflow"},
        BadCase{
            "ZeroSizeShape",
            "{" + kOneSegment +
                R"(, "shapes": [{"segment": "a", "type": "ellipsoid", "center": [0,0,0], "radii": [0.1, 0, 0.1]}]})",
            "info {}", "zero-size shape"},
        BadCase{"TrianglesOutOfRange", "", "info --triangles 50", "out of range [2000, 2000000]"},
        BadCase{"UnknownModel", "", "info gorilla", "gorilla"},
        BadCase{"UnsupportedOutput", "", "skin <tet> --out <dir>/skin.stl",
                "unsupported output format"},
        BadCase{"UnwritableOutput", "", "skin <tet> --out /proc/pelage/skin.obj", "cannot write"},
        BadCase{"BadPose", R"({"pose": {"nosuch": {}}})", "skin <tet> --pose {} --out <dir>/s.obj",
                "unknown segment 'nosuch'"},
        BadCase{"MissingOut", "", "skin", "--out is required"},
        // The command line's rough edges (issue 25), one case each.
        BadCase{"HairOutNotPly", "", "hair <tet> --hairs 10 --out <dir>/x.obj",
                "x.obj: hairs are written as binary PLY; the file must end in .ply"},
        BadCase{"NoFurOnTheMonkeyNamesIt", "", "hair --no-fur face --out <dir>/x.ply",
                "error: monkey: no-fur regions"},
        BadCase{"DidYouMean", "", "render --frame 3 --out <dir>/f",
                "unknown option --frame (did you mean --frames?)"},
        BadCase{"DidYouMeanHairs", "", "hair --hair 3 --out <dir>/f.ply",
                "unknown option --hair (did you mean --hairs?)"},
        BadCase{"CameraTwice", R"({"eye": [1, 1, 1], "target": [0, 0, 0]})",
                "render <tet> --camera-file {} --camera side --frames 0 --out <dir>/f",
                "--camera-file and --camera both set the camera"},
        BadCase{"VideoUnwritable", "", "render <tet> --frames 0 --video /proc/x.mp4 --out <dir>/f",
                "--video /proc/x.mp4: cannot write"},
        BadCase{"BackgroundWord", "", "render <tet> --background clear --frames 0 --out <dir>/f",
                "--background 'clear': give R G B"},
        BadCase{"BackgroundTwoValues", "",
                "render <tet> --background 0.5 0.5 --frames 0 --out <dir>/f",
                "--background takes R G B (3 values) or transparent"},
        BadCase{"BackgroundRange", "", "render <tet> --background 0 2 0 --frames 0 --out <dir>/f",
                "--background G = '2' is not a number in [0, 1]"},
        // Grooming (issue 27): groom files, regions, subdivision.
        BadCase{"GroomMissing", "",
                "hair <tet> --hairs 10 --groom /nonexistent/g.json --out <dir>/x.ply",
                "groom: /nonexistent/g.json: cannot open file"},
        BadCase{"GroomNotAGroom", R"({"regions": []})",
                "hair <tet> --hairs 10 --groom {} --out <dir>/x.ply", "not a groom file"},
        BadCase{"RegionMatchesNothing", R"({"regions": [{"match": "tial*", "lengthScale": 2}]})",
                "hair <tet> --hairs 10 --fur {} --out <dir>/x.ply",
                "regions[0].match 'tial*' matches no region or joint"},
        BadCase{"SubdivideRange", "", "info <tet> --subdivide 4",
                "--subdivide '4' is not auto or a level in [0, 3]"},
        // Grooming strokes (issue 28): the file and field named, nothing written.
        BadCase{"StrokesMissing", "",
                "groom <tet> --strokes /nonexistent/s.json --out <dir>/g.json",
                "/nonexistent/s.json: cannot open file"},
        BadCase{"StrokeRadius",
                R"({"strokes": [{"tool": "length", "points": [[0, 0, 0]], "radius": 20,
                                 "strength": 2}]})",
                "groom <tet> --strokes {} --out <dir>/g.json", "strokes[0].radius"},
        BadCase{"UnknownBrush",
                R"({"strokes": [{"tool": "smudge", "points": [[0, 0, 0]], "radius": 1}]})",
                "groom <tet> --strokes {} --out <dir>/g.json",
                "unknown brush 'smudge' (accepted: length, density, color, comb, cut, clump)"},
        BadCase{"CutWithoutLength",
                R"({"strokes": [{"tool": "cut", "points": [[0, 0, 0]], "radius": 1}]})",
                "groom <tet> --strokes {} --out <dir>/g.json", "strokes[0]"},
        BadCase{"CombWithoutDirection",
                R"({"strokes": [{"tool": "comb", "points": [[0, 0, 0]], "radius": 1}]})",
                "groom <tet> --strokes {} --out <dir>/g.json",
                "field 'strokes[0].points': a comb stroke needs at least two distinct points"},
        BadCase{"GroomOutNotJson", "", "groom <tet> --strokes {} --out <dir>/g.ply",
                "a groom file is JSON"},
        // The viewer's brushing session starts from a strokes file only when it reads.
        BadCase{"ViewStrokesRadius",
                R"({"strokes": [{"tool": "length", "points": [[0, 0, 0]], "radius": 0,
                                 "strength": 2}]})",
                "view <tet> --headless --strokes {} --screenshot <dir>/v.png", "strokes[0].radius"},
        // Input quoted in a message is cut to a few dozen characters, with its length.
        BadCase{"LongFramesQuoted", "",
                "render <tet> --out <dir>/f --frames 1:" + std::string(5000, '9') + "x",
                "(5003 bytes)"},
        BadCase{"LongCameraQuoted", "",
                "render <tet> --out <dir>/f --frames 0 --camera " + std::string(3000, 'c'),
                "(3000 bytes)"},
        BadCase{"LongPresetQuoted", "",
                "hair <tet> --out <dir>/x.ply --fur " + std::string(900, 'p'), "(900 bytes)"}),
    [](const auto& p) { return p.param.name; });

// A bad model leaves no output folder behind (the folders a failed command made are removed),
// and an output folder that does not exist is made by every command that writes files.
TEST(Cli, OutputFoldersAreMadeForAGoodRunAndRemovedAfterABadOne) {
  test::TempDir dir;
  test::writeText(dir.file("bad.glb"), "not a glb at all");
  for (const std::string line :
       {"render <bad> --frames 0 --out <dir>/r/frames", "export <bad> --format ply --out <dir>/e/x",
        "export <bad> --format usda --out <dir>/u/x.usda", "hair <bad> --out <dir>/h/x.ply"}) {
    std::string args = line;
    args.replace(args.find("<bad>"), 5, dir.file("bad.glb"));
    args.replace(args.find("<dir>"), 5, dir.path().string());
    const auto r = runPelage(args);
    EXPECT_EQ(r.exitCode, 2) << line << "\n" << r.output;
  }
  for (const char* made : {"r", "e", "u", "h"})
    EXPECT_FALSE(std::filesystem::exists(dir.file(made))) << made << " was left behind";
  test::writeText(dir.file("tet.obj"),
                  "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
  const auto r = runPelage("hair " + dir.file("tet.obj") + " --hairs 20 --out " +
                           dir.file("new/sub/x.ply") + " --quiet");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_TRUE(std::filesystem::exists(dir.file("new/sub/x.ply")));
}

// The model-size warning is a warning: printed once, and --quiet keeps it.
TEST(Cli, TheImplausibleSizeWarningIsPrintedOnceQuietOrNot) {
  test::TempDir dir;
  // A 10 m tetrahedron.
  test::writeText(dir.file("big.obj"),
                  "v 0 0 0\nv 10 0 0\nv 0 10 0\nv 0 0 10\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
  for (const std::string line : {"info <big>", "hair <big> --hairs 20 --out <dir>/x.ply --quiet",
                                 "hair <big> --hairs 20 --out <dir>/y.ply"}) {
    std::string args = line;
    args.replace(args.find("<big>"), 5, dir.file("big.obj"));
    if (const auto p = args.find("<dir>"); p != std::string::npos)
      args.replace(p, 5, dir.path().string());
    const auto r = runPelage(args);
    ASSERT_EQ(r.exitCode, 0) << line << "\n" << r.output;
    const auto first = r.output.find("implausible");
    EXPECT_NE(first, std::string::npos) << line << "\n" << r.output;
    EXPECT_EQ(r.output.find("implausible", first + 1), std::string::npos) << line << "\n"
                                                                          << r.output;
  }
}

}  // namespace
}  // namespace pelage
