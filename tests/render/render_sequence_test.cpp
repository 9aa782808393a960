// Frame sequences (issue 6): complete PNG frames, frames that depend only on their number,
// --resume after a killed run, write failures, video through ffmpeg, cameras.
#include "pelage/render/render_sequence.h"
#include "pelage/render/video_encoder.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

#include "pelage/util/atomic_file.h"
#include "pelage/util/error.h"
#include "support/files.h"
#include "support/gl.h"
#include "support/models.h"

namespace pelage::test {
namespace {

namespace fs = std::filesystem;

class RenderSequenceTest : public GlTest {
 protected:
  render::SequenceOptions options(const TempDir& dir, int first = 0, int last = 5) const {
    render::SequenceOptions o;
    o.playback.clip = 0;
    o.frames = {first, last};
    o.playback.clock.fps = 12.0;
    o.width = 96;
    o.height = 72;
    o.samples = 0;
    o.outDir = dir.path().string();
    o.encoderThreads = 2;
    return o;
  }
  static std::string frame(const TempDir& dir, int f) {
    return dir.file(scene::frameFileName(f, ".png"));
  }
  static const float* background() {
    static const float bg[3] = {scene::kDefaultBackground.x(), scene::kDefaultBackground.y(),
                                scene::kDefaultBackground.z()};
    return bg;
  }
};

TEST_F(RenderSequenceTest, FramesAreCompletePngsShowingTheCreature) {
  TempDir dir;
  std::vector<int> reported;
  const render::SequenceReport r = render::renderSequence(wagCritter(), wagFur(), options(dir),
                                                          [&](const render::SequenceProgress& p) {
                                                            reported.push_back(p.done);
                                                            EXPECT_EQ(p.total, 6);
                                                            EXPECT_GE(p.framesPerSecond, 0.0);
                                                          });
  EXPECT_EQ(r.rendered, 6);
  EXPECT_EQ(r.skipped, 0);
  EXPECT_GT(r.hairsDrawn, 0);
  EXPECT_EQ(reported, (std::vector<int>{1, 2, 3, 4, 5, 6}));
  for (int f = 0; f < 6; ++f) {
    ASSERT_TRUE(render::isCompletePng(frame(dir, f))) << f;
    const render::Image img = render::readPng(frame(dir, f));
    EXPECT_EQ(img.width, 96);
    EXPECT_EQ(img.height, 72);
    const double cov = coverage(img, background());
    EXPECT_GT(cov, 0.05) << f;
    EXPECT_LT(cov, 0.9) << f;
  }
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.path()), fs::directory_iterator()),
            6);                                                 // no temporaries
  EXPECT_NE(readText(frame(dir, 0)), readText(frame(dir, 3)));  // the clip moves
}

TEST_F(RenderSequenceTest, AFrameDependsOnlyOnItsNumber) {
  TempDir dir;
  render::Image afterOthers, alone;
  {
    render::SequenceRenderer s(wagCritter(), wagFur(), options(dir));
    render::Image scratch;
    for (int f : {0, 1, 2, 3}) s.render(f, scratch);
    s.render(4, afterOthers);
  }
  {
    render::SequenceRenderer s(wagCritter(), wagFur(), options(dir));
    s.render(4, alone);
  }
  ASSERT_EQ(afterOthers.rgba.size(), alone.rgba.size());
  EXPECT_TRUE(sameImage(afterOthers, alone));
}

// Dynamic fur: frame 4 rendered alone pre-rolls the springs from frame 0 and matches frame 4 of a
// run through 0..4 pixel for pixel; it differs from the quasi-static frame.
TEST_F(RenderSequenceTest, DynamicFurFramesDependOnlyOnTheirNumber) {
  TempDir dir;
  render::SequenceOptions o = options(dir);
  o.playback.dynamics = true;
  o.playback.dynamicsParams.coats[0] = {2.0f, 0.05f};
  o.playback.dynamicsParams.coats[1] = {2.0f, 0.05f};
  render::Image afterOthers, alone, quasiStatic;
  {
    render::SequenceRenderer s(wagCritter(), wagFur(), o);
    render::Image scratch;
    for (int f : {0, 1, 2, 3}) s.render(f, scratch);
    s.render(4, afterOthers);
  }
  {
    render::SequenceRenderer s(wagCritter(), wagFur(), o);
    s.render(4, alone);
  }
  {
    render::SequenceOptions q = options(dir);
    q.playback.hairSource = scene::HairSource::Cpu;
    render::SequenceRenderer s(wagCritter(), wagFur(), q);
    s.render(4, quasiStatic);
  }
  ASSERT_EQ(afterOthers.rgba.size(), alone.rgba.size());
  EXPECT_TRUE(sameImage(afterOthers, alone));
  EXPECT_FALSE(alone.rgba == quasiStatic.rgba);
  // Without a clip there is no motion to simulate.
  o.playback.clip = -1;
  EXPECT_THROW(render::validateSequenceOptions(o), InputError);
}

TEST_F(RenderSequenceTest, ResumeSkipsCompleteFramesAndRedoesTheRest) {
  TempDir whole, resumed;
  render::renderSequence(wagCritter(), wagFur(), options(whole));
  render::renderSequence(wagCritter(), wagFur(), options(resumed));
  // What a killed run leaves: a missing frame, a stale temporary of a frame in the range and one
  // outside it; and a truncated file (as a copy by another tool could leave).
  fs::remove(frame(resumed, 2));
  const std::string full = readText(frame(resumed, 4));
  writeText(frame(resumed, 4), full.substr(0, full.size() / 2));
  writeText(resumed.file(".frame_00003.png.tmp-999999-0"), "partial");
  writeText(resumed.file(".frame_00042.png.tmp-1-0"), "another range's");
  EXPECT_FALSE(render::isCompletePng(frame(resumed, 4)));
  render::SequenceOptions o = options(resumed);
  o.resume = true;
  const render::SequenceReport r = render::renderSequence(wagCritter(), wagFur(), o);
  EXPECT_EQ(r.skipped, 4);
  EXPECT_EQ(r.rendered, 2);
  EXPECT_EQ(r.removedTemporaries, 1);
  EXPECT_FALSE(fs::exists(resumed.file(".frame_00003.png.tmp-999999-0")));
  EXPECT_TRUE(fs::exists(resumed.file(".frame_00042.png.tmp-1-0")));
  for (int f = 0; f < 6; ++f)
    EXPECT_EQ(readText(frame(resumed, f)), readText(frame(whole, f))) << f;
}

// A disk that fills up while frames are written: the error reaches the caller, and the directory
// holds only complete frames.
TEST_F(RenderSequenceTest, AFailingWriteStopsTheRunAndLeavesOnlyCompleteFrames) {
  TempDir dir;
  const std::string bad = frame(dir, 3);
  const render::FileWriter writer = [&](const std::string& path,
                                        const std::vector<std::uint8_t>& bytes) {
    if (path == bad) {
      AtomicFileWriter w(path);
      w.write(bytes.data(), bytes.size() / 2);
      throw InputError(path +
                       ": write failed (no space left on device (disk full)); no file was written");
    }
    AtomicFileWriter w(path);
    w.write(bytes.data(), bytes.size());
    w.commit();
  };
  try {
    render::renderSequence(wagCritter(), wagFur(), options(dir), {}, writer);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("frame_00003.png: write failed (no space left"),
              std::string::npos)
        << e.what();
  }
  EXPECT_FALSE(fs::exists(bad));
  for (const fs::directory_entry& e : fs::directory_iterator(dir.path())) {
    EXPECT_EQ(e.path().filename().string().rfind("frame_", 0), 0u) << e.path();  // no temporaries
    EXPECT_TRUE(render::isCompletePng(e.path().string())) << e.path();
  }
}

TEST_F(RenderSequenceTest, UnwritableOutputAndBadOptionsAreInputErrors) {
  TempDir dir;
  render::SequenceOptions o = options(dir);
  o.outDir = "/dev/null/frames";
  EXPECT_THROW(render::renderSequence(wagCritter(), wagFur(), o), InputError);
  o = options(dir);
  o.video = dir.file("clip.avi");
  EXPECT_THROW(render::renderSequence(wagCritter(), wagFur(), o), InputError);
  o = options(dir);
  o.playback.clock.fps = 0.0;
  EXPECT_THROW(render::renderSequence(wagCritter(), wagFur(), o), InputError);
  o = options(dir);
  o.width = 8;
  EXPECT_THROW(render::renderSequence(wagCritter(), wagFur(), o), InputError);
  EXPECT_TRUE(fs::is_empty(dir.path()));
}

// Frames of a video file as ffprobe counts them, or -1 without ffprobe.
int videoFrames(const std::string& path) {
  if (render::findOnPath("ffprobe").empty()) return -1;
  const std::string cmd =
      "ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=nb_read_frames "
      "-of csv=p=0 '" +
      path + "'";
  return std::atoi(runShell(cmd).output.c_str());
}

TEST_F(RenderSequenceTest, VideoThroughFfmpegWithResumedFrames) {
  ASSERT_FALSE(render::findOnPath("ffmpeg").empty())
      << "ffmpeg is a dependency (scripts/install-deps.sh)";
  TempDir dir;
  render::SequenceOptions o = options(dir, 0, 3);
  render::renderSequence(wagCritter(), wagFur(),
                         o);  // frames 0..3 exist: the video run resumes them
  o.frames = {0, 5};
  o.resume = true;
  o.video = dir.file("clip.mp4");
  const render::SequenceReport r = render::renderSequence(wagCritter(), wagFur(), o);
  EXPECT_EQ(r.skipped, 4);
  EXPECT_EQ(r.rendered, 2);
  ASSERT_TRUE(fs::exists(o.video));
  const std::string mp4 = readText(o.video);
  EXPECT_EQ(mp4.substr(4, 4), "ftyp");
  const int n = videoFrames(o.video);
  if (n >= 0) {
    EXPECT_EQ(n, 6);
  }
  o.video = dir.file("clip.gif");
  render::renderSequence(wagCritter(), wagFur(), o);
  EXPECT_EQ(readText(o.video).substr(0, 6), "GIF89a");
  for (const fs::directory_entry& e : fs::directory_iterator(dir.path()))
    EXPECT_NE(e.path().filename().string()[0], '.') << "temporary left: " << e.path();
}

TEST_F(RenderSequenceTest, MissingFfmpegIsAClearError) {
  const std::string path = std::getenv("PATH") ? std::getenv("PATH") : "";
  ::setenv("PATH", "/nonexistent-bin", 1);
  TempDir dir;
  try {
    render::VideoEncoder v(dir.file("x.mp4"), 64, 64, 24.0);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(
        std::string(e.what()).find(
            "needs the ffmpeg program, which is not on PATH (Debian: apt-get install ffmpeg)"),
        std::string::npos)
        << e.what();
  }
  ::setenv("PATH", path.c_str(), 1);
  EXPECT_TRUE(fs::is_empty(dir.path()));
}

TEST_F(RenderSequenceTest, PresetCamerasAreFramedAtClipTimeZeroAndTrackTheRoot) {
  TempDir dir;
  render::SequenceOptions o = options(dir);
  render::SequenceRenderer fixed(wagCritter(), wagFur(), o);
  const scene::Camera a = fixed.camera(0), b = fixed.camera(6);
  EXPECT_TRUE(a.eye.isApprox(b.eye));
  EXPECT_TRUE(a.target.isApprox(b.target));
  o.camera.track = true;
  render::SequenceRenderer tracking(wagCritter(), wagFur(), o);
  const scene::Camera c = tracking.camera(0), d = tracking.camera(6);
  EXPECT_TRUE(c.eye.isApprox(a.eye));
  // Frame 6 at 12 fps is 0.5 s: the body moved 0.1 m along +X, and so did the camera.
  const Eigen::Vector3f moved = d.target - c.target;
  EXPECT_NEAR(moved.x(), 0.1f, 1e-4f);
  EXPECT_NEAR(moved.y(), 0.0f, 1e-5f);
  EXPECT_NEAR(moved.z(), 0.0f, 1e-6f);
  EXPECT_TRUE((d.eye - c.eye).isApprox(moved, 1e-4f));
}

TEST(CameraFile, KeysInterpolateAndHoldAtTheEnds) {
  TempDir dir;
  writeText(dir.file("cam.json"), R"({ "track": true, "keys": [
      { "frame": 10, "eye": [1, 0, 0.5], "target": [0, 0, 0.3], "fovYDegrees": 30 },
      { "frame": 20, "eye": [0, 1, 0.5], "target": [0, 0, 0.5], "fovYDegrees": 50 } ] })");
  const scene::CameraPath path = scene::loadCameraFile(dir.file("cam.json"));
  EXPECT_TRUE(path.track);
  ASSERT_EQ(path.keys.size(), 2u);
  const scene::Camera before = scene::cameraOnPath(path, 0, 64, 48);
  EXPECT_TRUE(before.eye.isApprox(Eigen::Vector3f(1, 0, 0.5f)));
  EXPECT_EQ(before.width, 64);
  const scene::Camera mid = scene::cameraOnPath(path, 15, 64, 48);
  EXPECT_TRUE(mid.eye.isApprox(Eigen::Vector3f(0.5f, 0.5f, 0.5f)));
  EXPECT_TRUE(mid.target.isApprox(Eigen::Vector3f(0, 0, 0.4f)));
  EXPECT_FLOAT_EQ(mid.fovYDegrees, 40.0f);
  EXPECT_TRUE(scene::cameraOnPath(path, 99, 64, 48).eye.isApprox(Eigen::Vector3f(0, 1, 0.5f)));
  writeText(dir.file("one.json"), R"({ "eye": [2, 0, 1], "target": [0, 0, 0] })");
  const scene::CameraPath one = scene::loadCameraFile(dir.file("one.json"));
  EXPECT_FALSE(one.track);
  EXPECT_TRUE(scene::cameraOnPath(one, 1234, 64, 48).up.isApprox(Eigen::Vector3f::UnitZ()));
}

TEST(CameraFile, MalformedFilesNameTheFileAndField) {
  TempDir dir;
  const std::pair<const char*, const char*> bad[] = {
      {R"({ "eye": [1, 0, 0], "target": [1, 0, 0] })", "eye and target must differ"},
      {R"({ "eye": [1, 0, 0], "target": [0, 0, 0], "up": [1, 0, 0] })", "not parallel"},
      {R"({ "eye": [1, 0, 0] })", "target"},
      {R"({ "eye": [1, 0, 0], "target": [0, 0, 0], "fov": 30 })", "fov"},
      {R"({ "eye": [1, 0, 0], "target": [0, 0, 0], "fovYDegrees": 200 })", "fovYDegrees"},
      {R"({ "keys": [] })", "at least one key"},
      {R"({ "keys": [ { "frame": 5, "eye": [1, 0, 0], "target": [0, 0, 0] },
                      { "frame": 5, "eye": [2, 0, 0], "target": [0, 0, 0] } ] })",
       "must increase"},
      {R"([1, 2])", "JSON object"},
      {R"({ "eye": [1, 0, 0], )", "cam.json"},
  };
  for (const auto& [text, expect] : bad) {
    writeText(dir.file("cam.json"), text);
    try {
      scene::loadCameraFile(dir.file("cam.json"));
      ADD_FAILURE() << "accepted " << text;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(expect), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("cam.json"), std::string::npos) << e.what();
    }
  }
}

TEST(CompletePng, SignatureHeaderAndEndChunk) {
  TempDir dir;
  render::Image img;
  img.width = 4;
  img.height = 3;
  img.rgba.assign(48, 200);
  render::writePng(dir.file("a.png"), img);
  EXPECT_TRUE(render::isCompletePng(dir.file("a.png")));
  const std::string full = readText(dir.file("a.png"));
  writeText(dir.file("b.png"), full.substr(0, full.size() - 1));
  EXPECT_FALSE(render::isCompletePng(dir.file("b.png")));
  writeText(dir.file("c.png"), "");
  EXPECT_FALSE(render::isCompletePng(dir.file("c.png")));
  EXPECT_FALSE(render::isCompletePng(dir.file("missing.png")));
}

}  // namespace
}  // namespace pelage::test
