// `pelage view` as a user runs it: the window with its full UI path under a virtual X display
// (xvfb-run, installed by scripts/install-deps.sh), the headless fallback, the benchmark mode, and
// clear errors for bad options and a missing display.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "pelage/render/image.h"
#include "support/files.h"

namespace pelage::render {
namespace {

using test::runPelage;
using test::TempDir;

// A small static model (a UV sphere, 0.2 m radius, 960 triangles) so each run starts in well under
// a second, also under the sanitizers; returns " FILE --hairs 20000 ".
std::string smallModel(const TempDir& dir) {
  const std::string path = dir.file("ball.obj");
  std::string obj;
  const int rings = 16, sectors = 32;
  for (int i = 0; i <= rings; ++i)
    for (int j = 0; j < sectors; ++j) {
      const double th = M_PI * i / rings, ph = 2 * M_PI * j / sectors;
      obj += "v " + std::to_string(0.2 * std::sin(th) * std::cos(ph)) + " " +
             std::to_string(0.2 * std::sin(th) * std::sin(ph)) + " " +
             std::to_string(0.2 + 0.2 * std::cos(th)) + "\n";
    }
  auto idx = [&](int i, int j) { return std::to_string(i * sectors + (j % sectors) + 1); };
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < sectors; ++j) {
      if (i > 0) obj += "f " + idx(i, j) + " " + idx(i + 1, j) + " " + idx(i, j + 1) + "\n";
      if (i + 1 < rings)
        obj += "f " + idx(i, j + 1) + " " + idx(i + 1, j) + " " + idx(i + 1, j + 1) + "\n";
    }
  test::writeText(path, obj);
  return " " + path + " --hairs 20000 ";
}

bool hasXvfb() {
  return std::system("command -v xvfb-run >/dev/null 2>&1") == 0;
}

using test::runShell;

// Pixels whose colour is close to `rgb` (0..255).
int countNear(const Image& img, int r, int g, int b, int tol) {
  int n = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const std::uint8_t* p = img.pixel(x, y);
      n += std::abs(p[0] - r) <= tol && std::abs(p[1] - g) <= tol && std::abs(p[2] - b) <= tol;
    }
  return n;
}

TEST(ViewCommand, WindowUnderXvfbRendersTheFullUiPath) {
  // CI installs xvfb (scripts/install-deps.sh); elsewhere the window test is skipped, saying why.
  if (!hasXvfb())
    GTEST_SKIP() << "xvfb-run is missing: the window backend is not tested (Debian: apt-get "
                    "install xvfb xauth)";
  TempDir dir;
  const std::string shot = dir.file("window.png");
  const auto r = runShell(std::string("xvfb-run -a -s \"-screen 0 1280x1024x24\" ") +
                          PELAGE_BIN_DIR + "/pelage view" + smallModel(dir) +
                          "--size 640x480 --frames 4 --debug-gl --screenshot " + shot);
  const std::string& out = r.output;
  ASSERT_EQ(r.exitCode, 0) << out;
  EXPECT_NE(out.find("(glfw)"), std::string::npos) << out;
  EXPECT_EQ(out.find("GL error"), std::string::npos) << out;
  const Image img = readPng(shot);
  ASSERT_EQ(img.width, 640);
  ASSERT_EQ(img.height, 480);
  // The scene's background, the dark ImGui panel beside the view and the creature are all there.
  const int background = countNear(img, 204, 209, 219, 3);
  const int panel = countNear(img, 15, 15, 16, 12);
  EXPECT_GT(background, 640 * 480 / 10);
  EXPECT_GT(panel, 640 * 480 / 5);
  EXPECT_GT(640 * 480 - background - panel, 640 * 480 / 40);  // creature and widgets
}

TEST(ViewCommand, WithoutADisplayItSaysSoAndExitsNonZero) {
  TempDir dir;
  const auto r = runShell(std::string("env -u DISPLAY -u WAYLAND_DISPLAY ") + PELAGE_BIN_DIR +
                          "/pelage view" + smallModel(dir));
  const std::string& out = r.output;
  EXPECT_EQ(r.exitCode, 2) << out;
  EXPECT_NE(out.find("cannot open a window"), std::string::npos) << out;
  EXPECT_NE(out.find("--headless"), std::string::npos) << out;
}

TEST(ViewCommand, HeadlessRendersAScreenshot) {
  TempDir dir;
  const std::string shot = dir.file("headless.png");
  const auto r = runPelage(std::string("view") + smallModel(dir) +
                           "--headless --size 320x240 --frames 2 --debug-gl --shadows "
                           "--screenshot " +
                           shot);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("egl"), std::string::npos) << r.output;
  const Image img = readPng(shot);
  EXPECT_EQ(img.width, 320);
  EXPECT_EQ(img.height, 240);
  EXPECT_LT(countNear(img, 204, 209, 219, 3), 320 * 240 * 98 / 100);  // not just background
}

TEST(ViewCommand, ClipsPlayAtTheirTimes) {
  TempDir dir;
  // A model without clips says so when asked for one.
  const auto none = runPelage("view" + smallModel(dir) + "--headless --clip walk");
  EXPECT_EQ(none.exitCode, 2);
  EXPECT_NE(none.output.find("it has no clips"), std::string::npos) << none.output;
  const std::string fox = std::string(PELAGE_SHARED_MODELS_DIR) + "/Fox/Fox.glb";
  if (!std::filesystem::exists(fox)) GTEST_SKIP() << "shared models absent: " << fox;
  auto shot = [&](const std::string& args, const std::string& name) {
    const auto r =
        runPelage("view " + fox + " --hairs 5000 --headless --size 160x120 --camera side " + args +
                  " --screenshot " + dir.file(name));
    EXPECT_EQ(r.exitCode, 0) << r.output;
    return readPng(dir.file(name));
  };
  auto differing = [](const Image& a, const Image& b) {
    int n = 0;
    for (std::size_t i = 0; i < a.rgba.size(); i += 4)
      n += a.rgba[i] != b.rgba[i] || a.rgba[i + 1] != b.rgba[i + 1];
    return n;
  };
  const Image start = shot("--clip Survey --time 0", "a.png");
  const Image again = shot("--clip Survey --time 0", "b.png");
  const Image later = shot("--clip Survey --time 1.7", "c.png");
  EXPECT_EQ(differing(start, again), 0);  // deterministic
  EXPECT_GT(differing(start, later), 160 * 120 / 50);
  const auto unknown = runPelage("view " + fox + " --headless --clip moonwalk");
  EXPECT_EQ(unknown.exitCode, 2);
  EXPECT_NE(unknown.output.find("its clips: Survey, Walk, Run"), std::string::npos)
      << unknown.output;
}

TEST(ViewCommand, BenchmarkPrintsMsPerFrame) {
  TempDir dir;
  const auto r =
      runPelage(std::string("view") + smallModel(dir) + "--benchmark --benchmark-hairs 3000 8000 " +
                "--benchmark-frames 2 --size 128x96 --samples 0");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("ms/frame"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("        3000"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("        8000"), std::string::npos) << r.output;
}

TEST(ViewCommand, BadOptionsGetClearMessages) {
  struct Case {
    std::string args, expect;
    bool ownModel = false;  // the case names its own model and hair count
  };
  TempDir dir;
  const Case cases[] = {
      {"--headless --size 10x10", "--size 10x10 is out of range"},
      {"--headless --size big", "is not WIDTHxHEIGHT"},
      {"--headless --hair-source tpu", "accepted: gpu, cpu"},
      {"--headless --camera top", "accepted: front, side, three-quarter, face, follow"},
      {"--headless --shading pbr", "accepted: paper, kajiya-kay, marschner, physical"},
      {"--headless --fur " + dir.file("missing.json"), "missing.json"},
      {"--headless --frames -1", "--frames -1 is out of range"},
      {"--headless --style fuzzy", "accepted: line, polyline, curve, tube"},
      {"--headless --skin-color 0.5 2 0.5", "--skin-color G = 2 is out of range [0, 1]"},
      {"--headless --ambient 0.3 0.3 20", "--ambient B = 20 is out of range [0, 16]"},
      {dir.file("missing.obj") + " --headless", "missing.obj", true},
      {"--headless --screenshot " + dir.file("no/such/dir/x.png"), "x.png"},
  };
  // An absurd hair count is refused up front, with the memory it would need and the accepted range.
  const std::string model = smallModel(dir);
  const auto huge =
      runPelage("view " + model.substr(0, model.find("--hairs")) + "--headless --hairs 1e12");
  EXPECT_EQ(huge.exitCode, 2) << huge.output;
  EXPECT_NE(huge.output.find("1e+12 hairs need"), std::string::npos) << huge.output;
  EXPECT_NE(huge.output.find("accepted: 0 to 2e+07 hairs"), std::string::npos) << huge.output;
  for (const Case& c : cases) {
    const auto r = runPelage("view " + (c.ownModel ? "" : smallModel(dir)) + c.args);
    EXPECT_EQ(r.exitCode, 2) << c.args << "\n" << r.output;
    EXPECT_NE(r.output.find(c.expect), std::string::npos) << c.args << "\n" << r.output;
    EXPECT_EQ(r.output.find("terminate"), std::string::npos) << r.output;
  }
}

}  // namespace
}  // namespace pelage::render
