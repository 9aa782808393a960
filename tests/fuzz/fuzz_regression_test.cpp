// Every saved fuzz input (fuzz/regressions/<reader>/) and seed (fuzz/corpus/<reader>/) goes through
// the reader's entry point: seeds must be accepted, regression inputs must be either accepted or
// rejected with an InputError, never crash (the ASan build runs this too).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "fuzz_entry.h"

namespace fs = std::filesystem;
using pelage::fuzz::runTarget;

namespace {

std::string readFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::vector<fs::path> filesIn(const fs::path& dir) {
  std::vector<fs::path> files;
  if (fs::is_directory(dir)) {
    for (const auto& entry : fs::directory_iterator(dir))
      if (entry.is_regular_file()) files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

bool run(const std::string& target, const std::string& bytes) {
  return runTarget(target, reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
}

const fs::path kFuzzDir = fs::path(PELAGE_SOURCE_DIR) / "fuzz";

}  // namespace

TEST(FuzzEntry, SeedCorporaAreAccepted) {
  int seeds = 0;
  for (const auto& target : pelage::fuzz::targetNames()) {
    for (const auto& file : filesIn(kFuzzDir / "corpus" / target)) {
      SCOPED_TRACE(file.string());
      EXPECT_TRUE(run(target, readFile(file)));
      ++seeds;
    }
  }
  EXPECT_GE(seeds, 8);
}

TEST(FuzzEntry, ProjectFilesAreAccepted) {
  EXPECT_TRUE(run("creature", readFile(fs::path(PELAGE_SOURCE_DIR) / "models" / "monkey.json")));
  for (const auto& file : filesIn(fs::path(PELAGE_SOURCE_DIR) / "models" / "presets")) {
    if (file.extension() != ".json") continue;
    SCOPED_TRACE(file.string());
    EXPECT_TRUE(run("preset", readFile(file)));
  }
  const fs::path simple = fs::path(PELAGE_SHARED_MODELS_DIR) / "RiggedSimple" / "RiggedSimple.glb";
  if (fs::exists(simple)) {
    EXPECT_TRUE(run("gltf", readFile(simple)));
  }
}

TEST(FuzzEntry, GroomAndStrokesSeedsAreTheExamplesAndLoad) {
  const std::string example = pelage::fuzz::groomExample();
  EXPECT_TRUE(run("groom", example));
  EXPECT_EQ(readFile(kFuzzDir / "corpus" / "groom" / "example.json"), example)
      << "the seed is groomExample()'s text";
  const std::string strokes = pelage::fuzz::strokesExample();
  EXPECT_TRUE(run("strokes", strokes));
  EXPECT_EQ(readFile(kFuzzDir / "corpus" / "strokes" / "example.json"), strokes)
      << "the seed is strokesExample()'s text";
}

TEST(FuzzEntry, BadInputsAreRejectedNotCrashed) {
  EXPECT_FALSE(run("creature", ""));
  EXPECT_FALSE(run("creature", "{\"segments\": 3}"));
  EXPECT_FALSE(run("preset", "[1, 2"));
  EXPECT_FALSE(run("clip", "{\"channels\": [{\"segment\": \"no_such_segment\"}]}"));
  EXPECT_FALSE(
      run("pose", "{\"pose\": {\"pelvis\": {\"rotate\": {\"axis\": [0, 0, 0], \"degrees\": 1}}}}"));
  EXPECT_FALSE(run("gltf", std::string("glTF\x02\x00\x00\x00\xff\xff\xff\xff", 12)));
  EXPECT_FALSE(run("mesh", pelage::fuzz::meshInput("obj", "v 0 0 0\nf 1 2 3\n")));
  EXPECT_FALSE(run("mesh", pelage::fuzz::meshInput("stl", std::string(84, '\0'))));
  EXPECT_FALSE(run("groom", "{\"format\": \"pelage groom\", \"version\": 1}"));
  std::string otherMesh = pelage::fuzz::groomExample();
  otherMesh.replace(otherMesh.find("\"vertices\":16"), 14, "\"vertices\":17");
  EXPECT_FALSE(run("groom", otherMesh));
  EXPECT_THROW(run("no_such_reader", "x"), std::invalid_argument);
}

TEST(FuzzEntry, RegressionInputsNeverCrash) {
  for (const auto& target : pelage::fuzz::targetNames()) {
    for (const auto& file : filesIn(kFuzzDir / "regressions" / target)) {
      SCOPED_TRACE(file.string());
      run(target, readFile(file));  // accepted or rejected cleanly; a crash fails the whole test
    }
  }
}
