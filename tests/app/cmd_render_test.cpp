// `pelage render` as a user and a render farm run it: two processes on disjoint frame ranges equal
// one run byte for byte; a killed run leaves only complete frames and --resume finishes it; video;
// clear errors (exit 2) for bad input.
#include <gtest/gtest.h>
#include <signal.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <thread>

#include <nlohmann/json.hpp>

#include "pelage/render/render_sequence.h"
#include "pelage/scene/light.h"
#include "support/files.h"
#include "support/models.h"

namespace pelage::test {
namespace {

namespace fs = std::filesystem;

class RenderCommand : public ::testing::Test {
 protected:
  void SetUp() override { writeText(dir.file("wag.json"), kWagClip); }
  // The critter with its clip, 5000 hairs, a small image.
  std::string args(const std::string& frames, const std::string& out,
                   const std::string& size = "128x96") const {
    return std::string(PELAGE_TEST_CRITTER " --clip ") + dir.file("wag.json") +
           " --hairs 5000 --fps 12 --camera side --track --size " + size + " --frames " + frames +
           " --out " + out;
  }
  static std::vector<std::string> frames(const fs::path& d) {
    std::vector<std::string> names;
    for (const fs::directory_entry& e : fs::directory_iterator(d))
      names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  }
  TempDir dir;
};

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::size_t at = 0;
  while (at < s.size()) {
    const std::size_t sp = s.find(' ', at);
    out.push_back(s.substr(at, sp - at));
    if (sp == std::string::npos) break;
    at = sp + 1;
  }
  return out;
}

TEST_F(RenderCommand, TwoProcessesOnDisjointRangesEqualOneRun) {
  const std::string whole = dir.file("whole"), sharded = dir.file("sharded");
  const RunResult one = runPelage("render " + args("0:7", whole));
  ASSERT_EQ(one.exitCode, 0) << one.output;
  // Not a terminal: plain log lines.
  EXPECT_NE(one.output.find("frame 8/8 (100%)"), std::string::npos) << one.output;
  EXPECT_NE(one.output.find("rendered 8 frame(s)"), std::string::npos) << one.output;
  // Two processes at once into one directory, as two render-farm tasks on shared storage.
  const pid_t a = spawnPelage(split("render " + args("0:3", sharded)), dir.file("a.log"));
  const pid_t b = spawnPelage(split("render " + args("4:7", sharded)), dir.file("b.log"));
  EXPECT_EQ(waitExit(a), 0) << readText(dir.file("a.log"));
  EXPECT_EQ(waitExit(b), 0) << readText(dir.file("b.log"));
  ASSERT_EQ(frames(whole), frames(sharded));
  ASSERT_EQ(frames(whole).size(), 8u);
  for (const std::string& f : frames(whole))
    EXPECT_EQ(readText(whole + "/" + f), readText(sharded + "/" + f)) << f << " differs";
  EXPECT_NE(readText(whole + "/frame_00000.png"), readText(whole + "/frame_00005.png"));
}

// docs/render-farm/: the Slurm job-array script and the range script of the Kubernetes Indexed Job,
// run here with the environment those engines give each task.
TEST_F(RenderCommand, RenderFarmScriptsSplitTheRangeIntoTheSameFrames) {
  const std::string whole = dir.file("whole"), slurm = dir.file("slurm"), k8s = dir.file("k8s");
  const std::string common = std::string(PELAGE_TEST_CRITTER " --clip ") + dir.file("wag.json") +
                             " --hairs 5000 --fps 12 --camera three-quarter --size 96x72";
  const RunResult one = runPelage("render " + common + " --frames 2:8 --out " + whole);
  ASSERT_EQ(one.exitCode, 0) << one.output;
  const std::string env = std::string("FIRST=2 LAST=8 PELAGE=") + PELAGE_BIN_DIR +
                          "/pelage PELAGE_ARGS='" + common + "' ";
  const std::string farm = PELAGE_SOURCE_DIR "/docs/render-farm";
  for (int task = 0; task < 2; ++task) {
    const std::string cmd =
        env + "OUT=" + slurm + " SLURM_ARRAY_TASK_ID=" + std::to_string(task + 4) +
        " SLURM_ARRAY_TASK_MIN=4 SLURM_ARRAY_TASK_COUNT=2 SLURM_CPUS_PER_TASK=1 SLURM_SUBMIT_DIR=" +
        farm + " bash " + farm + "/render.slurm";
    const test::RunResult r = test::runShell(cmd);
    const std::string& out = r.output;
    ASSERT_EQ(r.exitCode, 0) << out;
    EXPECT_NE(
        out.find(task == 0 ? "task 0/2: frames 2..5 of 2..8" : "task 1/2: frames 6..8 of 2..8"),
        std::string::npos)
        << out;
  }
  for (int task = 0; task < 3; ++task) {
    const std::string cmd = env + "OUT=" + k8s + " JOB_COMPLETION_INDEX=" + std::to_string(task) +
                            " PELAGE_TASK_COUNT=3 bash " + farm + "/render-range.sh";
    const test::RunResult r = test::runShell(cmd);
    const std::string& out = r.output;
    ASSERT_EQ(r.exitCode, 0) << out;
  }
  ASSERT_EQ(frames(whole).size(), 7u);
  ASSERT_EQ(frames(slurm), frames(whole));
  ASSERT_EQ(frames(k8s), frames(whole));
  for (const std::string& f : frames(whole)) {
    EXPECT_EQ(readText(slurm + "/" + f), readText(whole + "/" + f)) << f;
    EXPECT_EQ(readText(k8s + "/" + f), readText(whole + "/" + f)) << f;
  }
}

TEST_F(RenderCommand, AKilledRunLeavesCompleteFramesAndResumeFinishesIt) {
  const std::string out = dir.file("frames"), ref = dir.file("ref");
  const std::string a = args("0:29", out, "320x240");
  const pid_t pid = spawnPelage(split("render " + a), dir.file("run.log"));
  // Kill it (as a preempted render-farm task dies) once it has written a frame or two.
  const auto t0 = std::chrono::steady_clock::now();
  bool killed = false;
  while (std::chrono::steady_clock::now() - t0 < std::chrono::seconds(120)) {
    int status = 0;
    if (::waitpid(pid, &status, WNOHANG) == pid) break;  // finished before we could kill it
    if (fs::exists(out + "/frame_00001.png")) {
      ::kill(pid, SIGKILL);
      EXPECT_EQ(waitExit(pid), 128 + SIGKILL);
      killed = true;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  ASSERT_TRUE(killed) << "the run ended before it could be killed:\n"
                      << readText(dir.file("run.log"));
  int complete = 0;
  for (const std::string& f : frames(out)) {
    if (f.rfind("frame_", 0) != 0) continue;  // temporaries of frames being written
    EXPECT_TRUE(render::isCompletePng(out + "/" + f)) << f << " is truncated";
    ++complete;
  }
  EXPECT_GE(complete, 2);
  EXPECT_LT(complete, 30);
  const RunResult resumed = runPelage("render " + a + " --resume");
  ASSERT_EQ(resumed.exitCode, 0) << resumed.output;
  EXPECT_NE(resumed.output.find("skipped " + std::to_string(complete) + " complete"),
            std::string::npos)
      << resumed.output;
  const RunResult clean = runPelage("render " + args("0:29", ref, "320x240"));
  ASSERT_EQ(clean.exitCode, 0) << clean.output;
  ASSERT_EQ(frames(out), frames(ref));  // and no temporaries left
  for (const std::string& f : frames(ref))
    EXPECT_EQ(readText(out + "/" + f), readText(ref + "/" + f)) << f;
}

TEST_F(RenderCommand, VideoFileThroughFfmpeg) {
  const RunResult r =
      runPelage("render " + args("0:5", dir.file("f")) + " --video " + dir.file("clip.mp4"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("wrote " + dir.file("clip.mp4")), std::string::npos) << r.output;
  EXPECT_EQ(readText(dir.file("clip.mp4")).substr(4, 4), "ftyp");
}

TEST_F(RenderCommand, LightPassesAreFramesOfTheirOwnAndBadOnesSaySo) {
  // --pass draws part of the light (scene::LightPass; their sums are render_tests' business):
  // the fibre pass is another frame than the whole, the skin pass darker still.
  for (const char* pass : {"all", "fibre", "skin"}) {
    const RunResult r = runPelage("render " + args("2", dir.file(pass)) + " --pass " + pass);
    ASSERT_EQ(r.exitCode, 0) << pass << ": " << r.output;
  }
  const std::string all = readText(dir.file("all/frame_00002.png"));
  EXPECT_NE(readText(dir.file("fibre/frame_00002.png")), all);
  EXPECT_NE(readText(dir.file("skin/frame_00002.png")), all);
  // A pass that is not one, or a part of the physical model's light under another shading: exit 2
  // with the accepted values, and no output folder left behind.
  const std::pair<const char*, const char*> bad[] = {
      {"--pass glossy",
       "--pass: unknown light pass 'glossy' (accepted: all, hair, fibre, coat, skin)"},
      {"--pass coat --shading paper",
       "--pass coat is a part of the physical model's hair light: it "
       "needs --shading physical (the default), not paper"}};
  for (const auto& [options, expect] : bad) {
    const RunResult r = runPelage("render " + args("2", dir.file("bad")) + " " + options);
    EXPECT_EQ(r.exitCode, 2) << options << ": " << r.output;
    EXPECT_NE(r.output.find(expect), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir.file("bad"))) << options;
  }
}

TEST_F(RenderCommand, SceneFilesBesideTheFrames) {
  // --scene-files: each frame also as a reference scene (scene/reference_scene.h), the frames
  // themselves unchanged.
  // The key light placed by --light: the scene holds its direction.
  const std::string light = " --hair-source cpu --light -150 20";
  const RunResult plain = runPelage("render " + args("2:3", dir.file("plain")) + light);
  ASSERT_EQ(plain.exitCode, 0) << plain.output;
  const RunResult lit = runPelage("render " + args("2:3", dir.file("lit")) + " --hair-source cpu");
  ASSERT_EQ(lit.exitCode, 0) << lit.output;
  EXPECT_NE(readText(dir.file("lit/frame_00002.png")), readText(dir.file("plain/frame_00002.png")));
  const RunResult r = runPelage("render " + args("2:3", dir.file("f")) + light + " --scene-files");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_EQ(frames(dir.file("f")),
            (std::vector<std::string>{"frame_00002.pelscene", "frame_00002.png",
                                      "frame_00003.pelscene", "frame_00003.png"}));
  for (const char* f : {"frame_00002.png", "frame_00003.png"})
    EXPECT_EQ(readText(dir.file("f/") + f), readText(dir.file("plain/") + f)) << f;
  const std::string scene = readText(dir.file("f/frame_00003.pelscene"));
  EXPECT_EQ(scene.substr(0, 8), "PLGSCN01");
  std::uint64_t length = 0;
  std::memcpy(&length, scene.data() + 8, 8);
  const nlohmann::json header = nlohmann::json::parse(scene.substr(16, length));
  EXPECT_EQ(header["camera"]["width"], 128);
  const Eigen::Vector3f towards = scene::lightDirection(-150.0f, 20.0f).normalized();
  for (int a = 0; a < 3; ++a)
    EXPECT_NEAR(header["light"]["direction"][a].get<float>(), towards[a], 1e-6f) << a;
  // The key light's colour and the ambient (--light-color, --ambient) reach the scene, so the
  // path tracer renders the same light's parts (scripts/reference/views.py parts).
  const RunResult k = runPelage("render " + args("2", dir.file("k")) + light +
                                " --scene-files --light-color 2 1 0.5 --ambient 0");
  ASSERT_EQ(k.exitCode, 0) << k.output;
  const std::string keyScene = readText(dir.file("k/frame_00002.pelscene"));
  std::memcpy(&length, keyScene.data() + 8, 8);
  const nlohmann::json keyHeader = nlohmann::json::parse(keyScene.substr(16, length));
  EXPECT_EQ(keyHeader["light"]["color"], nlohmann::json({2.0, 1.0, 0.5}));
  EXPECT_EQ(keyHeader["light"]["ambient"], nlohmann::json({0.0, 0.0, 0.0}));
  EXPECT_NE(readText(dir.file("k/frame_00002.png")), readText(dir.file("plain/frame_00002.png")));
}

TEST_F(RenderCommand, MissingFfmpegFailsBeforeRendering) {
  const std::string cmd = "PATH=/nonexistent-bin " + std::string(PELAGE_BIN_DIR) +
                          "/pelage render " + args("0:1", dir.file("f")) + " --video " +
                          dir.file("clip.mp4");
  const test::RunResult r = test::runShell(cmd);
  const std::string& out = r.output;
  EXPECT_EQ(r.exitCode, 2) << out;
  EXPECT_NE(
      out.find("needs the ffmpeg program, which is not on PATH (Debian: apt-get install ffmpeg)"),
      std::string::npos)
      << out;
  EXPECT_TRUE(!fs::exists(dir.file("f")) || fs::is_empty(dir.file("f")));
}

struct BadRender {
  const char* name;
  std::string args;  // <args> = the critter and its clip into <dir>/f (add --frames, --size...)
  std::string expect;
};

// gtest names the case by this (not its bytes) in test names and failures.
void PrintTo(const BadRender& c, std::ostream* os) {
  *os << c.name;
}

class RenderCommandErrors : public RenderCommand,
                            public ::testing::WithParamInterface<BadRender> {};

TEST_P(RenderCommandErrors, ExitTwoWithAClearMessage) {
  std::string line = GetParam().args;
  const std::string base =
      std::string(PELAGE_TEST_CRITTER " --clip ") + dir.file("wag.json") + " --hairs 2000";
  if (line.find("--out") == std::string::npos) line += " --out " + dir.file("f");
  for (std::size_t at; (at = line.find("<args>")) != std::string::npos;) line.replace(at, 6, base);
  for (std::size_t at; (at = line.find("<dir>")) != std::string::npos;)
    line.replace(at, 5, dir.path().string());
  const RunResult r = runPelage("render " + line);
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find(GetParam().expect), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir.file("f/frame_00000.png")));
}

INSTANTIATE_TEST_SUITE_P(
    BadInput, RenderCommandErrors,
    ::testing::Values(
        BadRender{"reversed", "<args> --frames 9:3", "--frames 9:3 is out of range"},
        BadRender{"not_a_range", "<args> --frames 1-5", "'1-5' is not a frame range"},
        BadRender{"too_far", "<args> --frames 0:10000000", "out of range"},
        BadRender{"unknown_clip", PELAGE_TEST_CRITTER " --clip dance --frames 0:1 --out <dir>/f",
                  "has no clip 'dance' (it has no clips"},
        BadRender{"scene_files_gpu", "<args> --frames 0 --scene-files --hair-source gpu",
                  "--scene-files needs the hairs computed on the CPU (hair source cpu)"},
        BadRender{"light_azimuth", "<args> --frames 0 --light 400 10",
                  "--light azimuth 400 is out of range [-360, 360]"},
        BadRender{"light_elevation", "<args> --frames 0 --light 0 95",
                  "--light elevation 95 is out of range [-90, 90]"},
        BadRender{"light_color", "<args> --frames 0 --light-color 1 17 1",
                  "--light-color G = 17 is out of range [0, 16]"},
        BadRender{"light_color_count", "<args> --frames 0 --light-color 1 1",
                  "--light-color takes I or R G B, got 2 values"},
        BadRender{"ambient", "<args> --frames 0 --ambient -0.5",
                  "--ambient R = -0.5 is out of range [0, 16]"},
        BadRender{"camera", "<args> --frames 0:1 --camera overhead",
                  "unknown camera preset 'overhead'"},
        BadRender{"camera_file", "<args> --frames 0:1 --camera-file <dir>/none.json", "none.json"},
        BadRender{"size", "<args> --frames 0:1 --size 100", "--size '100' is not WIDTHxHEIGHT"},
        BadRender{"tiny", "<args> --frames 0:1 --size 8x8", "out of range [16, 16384]"},
        BadRender{"fps", "<args> --frames 0:1 --fps 0", "--fps 0 is out of range"},
        BadRender{"video_ext", "<args> --frames 0:1 --video <dir>/clip.avi",
                  "must end in .mp4 or .gif"},
        BadRender{"unwritable", "<args> --frames 0:1 --out /dev/null/frames", "/dev/null/frames"},
        BadRender{"hair_source", "<args> --frames 0:1 --hair-source tpu", "--hair-source 'tpu'"},
        BadRender{"fur_set", "<args> --frames 0:1 --fur-set undercoat.curvePoints=1",
                  "curvePoints"}),
    [](const ::testing::TestParamInfo<BadRender>& param) { return std::string(param.param.name); });

}  // namespace
}  // namespace pelage::test
