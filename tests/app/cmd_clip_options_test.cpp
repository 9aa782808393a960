// `pelage info` lists a glTF model's clips; `--clip NAME --time T` poses the creature in `pelage
// skin` (and every command using the shared pose options); bad clip options fail clearly. The same
// for the built-in monkey's procedural clips is in monkey_cli_test.cpp (slow: it builds the skin).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <array>
#include <sstream>

#include "support/files.h"
#include "support/gltf.h"

namespace pelage {
namespace {

using test::objVertices;
using test::runPelage;
using ::testing::HasSubstr;

TEST(ClipCli, InfoListsGltfClips) {
  PELAGE_REQUIRE_SHARED_MODELS();
  const auto r = runPelage("info --json " + test::sharedModel("Fox/Fox.glb"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const auto j = nlohmann::json::parse(r.output);
  ASSERT_EQ(j["clips"].size(), 3u);
  EXPECT_EQ(j["clips"][1]["name"], "Walk");
  EXPECT_NEAR(j["clips"][1]["durationSeconds"].get<double>(), 0.7083, 1e-3);
  EXPECT_NEAR(j["unitScale"].get<double>(), 0.01, 1e-9);
}

TEST(ClipCli, SkinIsPosedByAClipAtATime) {
  PELAGE_REQUIRE_SHARED_MODELS();
  test::TempDir dir;
  const std::string fox = test::sharedModel("Fox/Fox.glb");
  ASSERT_EQ(runPelage("skin " + fox + " --out " + dir.file("rest.obj")).exitCode, 0);
  const auto r = runPelage("skin " + fox + " --clip Walk --time 0.3 --out " + dir.file("walk.obj"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  ASSERT_EQ(runPelage("skin " + fox + " --clip Walk --time 1.0083 --out " + dir.file("loop.obj"))
                .exitCode,
            0);
  const auto rest = objVertices(dir.file("rest.obj")), walk = objVertices(dir.file("walk.obj")),
             loop = objVertices(dir.file("loop.obj"));
  ASSERT_EQ(rest.size(), walk.size());
  float moved = 0.0f, wrapped = 0.0f;
  for (std::size_t i = 0; i < rest.size(); ++i) {
    moved = std::max(moved, (walk[i] - rest[i]).norm());
    wrapped = std::max(wrapped, (loop[i] - walk[i]).norm());
  }
  EXPECT_GT(moved, 0.02f);    // the legs moved
  EXPECT_LT(wrapped, 1e-3f);  // 1.0083 s = 0.3 s after one 0.7083 s loop
}

// The furred area `pelage hair` reports ("... (N triangles, A m^2 furred)").
double furredArea(const std::string& output) {
  const auto end = output.find(" m^2 furred");
  const auto start = output.rfind(", ", end);
  EXPECT_NE(end, std::string::npos) << output;
  if (end == std::string::npos || start == std::string::npos) return -1.0;
  return std::stod(output.substr(start + 2, end - start - 2));
}

// Every shared model grows hair on its skin posed by one of its clips at a chosen time, through
// the command line (the in-process tests sample every clip of every model).
TEST(ClipCli, HairOnEveryModelPosedByAClip) {
  PELAGE_REQUIRE_SHARED_MODELS();
  test::TempDir dir;
  const std::vector<std::array<std::string, 3>> runs = {
      {"Fox/Fox.glb", "Run", "0.4"},
      {"CesiumMan/CesiumMan.glb", "clip0", "1.1"},
      {"RiggedFigure/RiggedFigure.glb", "clip0", "0.6"},
      {"RiggedSimple/RiggedSimple.glb", "clip0", "1.0"},
      {"SimpleSkin/SimpleSkin.gltf", "clip0", "2.7"},
      {"Wolf/Wolf.gltf", "Gallop", "0.3"},
      {"Husky/Husky.gltf", "Idle_2_HeadLow", "2.0"},
      {"Horse/Horse.gltf", "Attack_Kick", "0.5"},
      {"Stag/Stag.gltf", "Eating", "6.0"},
      {"Alpaca/Alpaca.gltf", "Death", "0.9"}};
  for (const auto& [file, clip, time] : runs) {
    SCOPED_TRACE(file);
    const std::string out = dir.file("hair.ply");
    const auto r = runPelage("hair " + test::sharedModel(file) + " --clip " + clip + " --time " +
                             time + " --hairs 2000 --out " + out);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_THAT(r.output, HasSubstr("polyline hairs"));
    EXPECT_GT(furredArea(r.output), 0.0);
    EXPECT_THAT(test::readText(out), HasSubstr("element vertex"));
  }
}

// Per-primitive regions (material names) are selectable as no-fur regions on the command line:
// making the Horse's body materials bare leaves a small part of its skin furred.
TEST(ClipCli, NoFurRegionsAreSelectable) {
  PELAGE_REQUIRE_SHARED_MODELS();
  test::TempDir dir;
  const std::string horse = test::sharedModel("Horse/Horse.gltf");
  const auto all = runPelage("hair " + horse + " --hairs 1000 --out " + dir.file("a.ply"));
  const auto some = runPelage(
      "hair " + horse + " --hairs 1000 --no-fur 'Main*' Hooves 'Eye*' --out " + dir.file("b.ply"));
  ASSERT_EQ(all.exitCode, 0) << all.output;
  ASSERT_EQ(some.exitCode, 0) << some.output;
  const double a = furredArea(all.output), b = furredArea(some.output);
  EXPECT_GT(b, 0.0);  // the mane ("Hair") and muzzle keep their fur
  EXPECT_LT(b, 0.25 * a) << all.output << some.output;
}

struct BadClip {
  std::string args, expect;
  bool needsModels = false;  // "<fox>" is the shared Fox model
};

void PrintTo(const BadClip& c, std::ostream* os) {
  *os << c.args;
}

class ClipCliErrors : public ::testing::TestWithParam<BadClip> {};

TEST_P(ClipCliErrors, ClearMessageAndExitCode2) {
  if (GetParam().needsModels) PELAGE_REQUIRE_SHARED_MODELS();
  test::TempDir dir;
  std::string args = GetParam().args;
  for (auto p = args.find("<dir>"); p != std::string::npos; p = args.find("<dir>"))
    args.replace(p, 5, dir.path().string());
  if (auto p = args.find("<fox>"); p != std::string::npos)
    args.replace(p, 5, test::sharedModel("Fox/Fox.glb"));
  const auto r = runPelage(args);
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr(GetParam().expect));
}

INSTANTIATE_TEST_SUITE_P(
    All, ClipCliErrors,
    ::testing::Values(
        BadClip{"skin <fox> --clip fly --out <dir>/x.obj",
                "has no clip 'fly' (its clips: Survey, Walk, Run", true},
        BadClip{"skin <fox> --time 2 --out <dir>/x.obj", "--time needs --clip", true},
        BadClip{"skin <fox> --clip Walk --time -1 --out <dir>/x.obj", "out of range [0, 1000000]",
                true},
        BadClip{"skin <fox> --clip Walk --pose <dir>/p.json --out <dir>/x.obj",
                "cannot be used together", true},
        BadClip{"skin <fox> --clip <dir>/none.json --out <dir>/x.obj", "none.json", true},
        BadClip{"info <fox> --unit-scale -3", "--unit-scale -3 is out of range", true},
        BadClip{"info --triangles 2000 --directions d.json", "glTF models (.gltf/.glb) only"}));

}  // namespace
}  // namespace pelage
