// The pelage command line as a user meets it: outputs, and clear errors with non-zero exits for
// bad input (never a crash: exit codes >= 128 would mean a signal).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "test_support.h"

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
        BadCase{"MissingOut", "", "skin", "--out is required"}),
    [](const auto& p) { return p.param.name; });

}  // namespace
}  // namespace pelage
