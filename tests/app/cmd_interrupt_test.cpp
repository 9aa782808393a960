// Interrupts as a user and a scheduler send them (issue 25): SIGINT (Ctrl-C) or SIGTERM to
// `pelage render --video` and `pelage export` mid-run. The run says "interrupted", exits with
// 128 + the signal (130, 143), leaves no temporary file (output folder, temp dir: no ffmpeg log),
// and --resume then completes it to the bytes of a run never interrupted.
#include <gtest/gtest.h>
#include <signal.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <thread>

#include "support/files.h"
#include "support/models.h"

namespace pelage::test {
namespace {

namespace fs = std::filesystem;

struct Case {
  const char* name;
  const char* command;  // "render" or "export"
  int signal;
};

void PrintTo(const Case& c, std::ostream* os) {
  *os << c.name;
}

std::vector<std::string> listing(const fs::path& d) {
  std::vector<std::string> names;
  std::error_code ec;
  for (const fs::directory_entry& e : fs::directory_iterator(d, ec))
    names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

class InterruptCommand : public ::testing::TestWithParam<Case> {
 protected:
  void SetUp() override {
    writeText(dir.file("wag.json"), kWagClip);
    fs::create_directories(tmp());
  }
  std::string tmp() const { return dir.file("tmp"); }
  // The command's arguments writing into `out` (and `out`.mp4 for render).
  std::vector<std::string> args(const std::string& out) const {
    std::vector<std::string> a = {GetParam().command,
                                  PELAGE_TEST_CRITTER,
                                  "--clip",
                                  dir.file("wag.json"),
                                  "--fps",
                                  "24",
                                  "--frames",
                                  "0:23",
                                  "--out",
                                  out};
    if (std::string(GetParam().command) == "render") {
      for (const char* s : {"--hairs", "10000", "--size", "160x120", "--camera", "side", "--video"})
        a.emplace_back(s);
      a.push_back(out + ".mp4");
    } else {
      for (const char* s : {"--hairs", "30000", "--format", "ply"}) a.emplace_back(s);
    }
    return a;
  }
  // Runs pelage with TMPDIR set to tmp(); returns its pid.
  pid_t spawn(const std::vector<std::string>& a, const std::string& log) const {
    return spawnPelage(a, log, {"TMPDIR=" + tmp()});
  }
  TempDir dir;
};

TEST_P(InterruptCommand, StopsCleanlyAndResumeFinishesTheSameBytes) {
  const Case& c = GetParam();
  const bool render = std::string(c.command) == "render";
  const std::string out = dir.file("out"), ref = dir.file("ref");
  const std::string firstFile = out + (render ? "/frame_00001.png" : "/frame_00001.ply");
  const pid_t pid = spawn(args(out), dir.file("run.log"));
  const auto t0 = std::chrono::steady_clock::now();
  bool sent = false;
  while (std::chrono::steady_clock::now() - t0 < std::chrono::seconds(120)) {
    int status = 0;
    if (::waitpid(pid, &status, WNOHANG) == pid) break;  // finished first: the test fails below
    if (fs::exists(firstFile)) {
      ::kill(pid, c.signal);
      sent = true;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  ASSERT_TRUE(sent) << "the run ended before the signal:\n" << readText(dir.file("run.log"));
  EXPECT_EQ(waitExit(pid), 128 + c.signal) << readText(dir.file("run.log"));
  const std::string log = readText(dir.file("run.log"));
  EXPECT_NE(log.find("pelage: interrupted"), std::string::npos) << log;
  EXPECT_EQ(log.find("Broken pipe"), std::string::npos) << log;
  const std::vector<std::string> left = listing(out);
  EXPECT_LT(left.size(), 24u) << "the run was not interrupted mid-way";
  for (const std::string& f : left) EXPECT_NE(f[0], '.') << "temporary file left: " << f;
  for (const std::string& f : listing(dir.path())) EXPECT_NE(f[0], '.') << "left: " << f;
  EXPECT_TRUE(listing(tmp()).empty()) << "left in the temp dir: " << listing(tmp()).front();
  EXPECT_FALSE(fs::exists(out + ".mp4"));

  std::vector<std::string> again = args(out);
  again.emplace_back("--resume");
  EXPECT_EQ(waitExit(spawn(again, dir.file("resume.log"))), 0) << readText(dir.file("resume.log"));
  EXPECT_EQ(waitExit(spawn(args(ref), dir.file("ref.log"))), 0) << readText(dir.file("ref.log"));
  ASSERT_EQ(listing(out), listing(ref));
  for (const std::string& f : listing(ref))
    EXPECT_EQ(readText(out + "/" + f), readText(ref + "/" + f)) << f;
  if (render) {
    ASSERT_TRUE(fs::exists(out + ".mp4"));
    EXPECT_EQ(readText(out + ".mp4"), readText(ref + ".mp4"));
  }
  EXPECT_TRUE(listing(tmp()).empty());
}

INSTANTIATE_TEST_SUITE_P(Signals, InterruptCommand,
                         ::testing::Values(Case{"render_sigint", "render", SIGINT},
                                           Case{"render_sigterm", "render", SIGTERM},
                                           Case{"export_sigint", "export", SIGINT},
                                           Case{"export_sigterm", "export", SIGTERM}),
                         [](const ::testing::TestParamInfo<Case>& p) {
                           return std::string(p.param.name);
                         });

// A killed run (SIGKILL: nothing can be cleaned then) leaves ffmpeg's temporary video and log;
// the next run for the same video removes them.
TEST(InterruptLeftovers, TheNextRunRemovesAKilledRunsVideoAndLog) {
  TempDir dir;
  writeText(dir.file("wag.json"), kWagClip);
  fs::create_directories(dir.file("tmp"));
  // Leftovers of a process that no longer runs (pid 999999999 cannot exist).
  writeText(dir.file(".clip.mp4.tmp-999999999-0"), "half a video");
  writeText(dir.file("tmp/.pelage-ffmpeg.log.tmp-999999999-0"), "ffmpeg log");
  const RunResult r = runShell("TMPDIR=" + dir.file("tmp") + " " + PELAGE_BIN_DIR +
                               "/pelage render " PELAGE_TEST_CRITTER " --clip " +
                               dir.file("wag.json") + " --hairs 500 --size 64x48 --frames 0:1 " +
                               "--out " + dir.file("f") + " --video " + dir.file("clip.mp4"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_FALSE(fs::exists(dir.file(".clip.mp4.tmp-999999999-0")));
  EXPECT_FALSE(fs::exists(dir.file("tmp/.pelage-ffmpeg.log.tmp-999999999-0")));
  EXPECT_TRUE(fs::exists(dir.file("clip.mp4")));
  EXPECT_TRUE(listing(dir.file("tmp")).empty());
}

}  // namespace
}  // namespace pelage::test
