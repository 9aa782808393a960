// The built-in monkey on the command line: `pelage info` lists its procedural clips, `pelage skin
// --clip tumble --time 1.5` turns it upside down, a clip .json file poses it, and an unknown clip
// lists the known ones. Labelled slow: every run builds the monkey's skin (seconds; a minute under
// the sanitizers).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <Eigen/Core>

#include <sstream>

#include "support/files.h"

namespace pelage {
namespace {

using test::objVertices;
using test::runPelage;
using ::testing::HasSubstr;

TEST(MonkeyCli, InfoListsTheMonkeysProceduralClips) {
  const auto r = runPelage("info --json --triangles 2000");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const auto j = nlohmann::json::parse(r.output);
  ASSERT_EQ(j["clips"].size(), 5u);
  const std::pair<const char*, double> expect[] = {
      {"walk", 1.0}, {"tumble", 3.0}, {"hang", 1.4}, {"shake", 1.5}, {"idle", 4.0}};
  for (std::size_t i = 0; i < 5; ++i) {
    EXPECT_EQ(j["clips"][i]["name"], expect[i].first);
    EXPECT_NEAR(j["clips"][i]["durationSeconds"].get<double>(), expect[i].second, 1e-6);
  }
  const auto text = runPelage("info --triangles 2000");
  EXPECT_THAT(text.output, HasSubstr("clips      5"));
  EXPECT_THAT(text.output, HasSubstr("tumble"));
}

TEST(MonkeyCli, MonkeyTumbleAndClipFiles) {
  test::TempDir dir;
  ASSERT_EQ(runPelage("skin --triangles 2000 --clip tumble --time 1.5 --out " + dir.file("t.obj"))
                .exitCode,
            0);
  ASSERT_EQ(runPelage("skin --triangles 2000 --out " + dir.file("r.obj")).exitCode, 0);
  // Upside down: a foot sole (the lowest vertex at rest) is in the upper half mid-tumble.
  const auto t = objVertices(dir.file("t.obj")), r = objVertices(dir.file("r.obj"));
  ASSERT_EQ(t.size(), r.size());
  std::size_t sole = 0;
  for (std::size_t i = 0; i < r.size(); ++i)
    if (r[i].z() < r[sole].z()) sole = i;
  float minZ = 1e9f, maxZ = -1e9f;
  for (const auto& p : t) minZ = std::min(minZ, p.z()), maxZ = std::max(maxZ, p.z());
  EXPECT_GT(t[sole].z(), minZ + 0.5f * (maxZ - minZ));
  test::writeText(dir.file("nod.json"), R"({ "channels": [ { "segment": "head", "path": "rotate",
      "keys": [ { "time": 0, "axis": [0, 1, 0], "degrees": 0 }, { "time": 1, "axis": [0, 1, 0], "degrees": 40 } ] } ] })");
  const auto c = runPelage("skin --triangles 2000 --clip " + dir.file("nod.json") +
                           " --time 0.5 --out " + dir.file("n.obj"));
  EXPECT_EQ(c.exitCode, 0) << c.output;
}

TEST(MonkeyCli, UnknownClipListsTheKnownOnes) {
  test::TempDir dir;
  const auto r = runPelage("skin --triangles 2000 --clip fly --out " + dir.file("x.obj"));
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("has no clip 'fly' (its clips: walk, tumble, hang, shake, idle"));
}

}  // namespace
}  // namespace pelage
