// The viewer's session (what the window and the headless loop drive): live parameter edits, roots
// regrown on a worker thread without stalling the frames, playback with cross-fades, presets.
#include "viewer_session.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <thread>

#include "pelage/animation/clip.h"
#include "pelage/fur/preset.h"
#include "pelage/render/render_sequence.h"
#include "pelage/util/color.h"
#include "support/files.h"
#include "support/gl.h"

namespace pelage::viewer::detail {
namespace {

// The critter with one clip that turns its head from side to side (2 s, looping).
scene::Model critterWithClips() {
  scene::Model m = test::sceneCritter();
  const int head = m.body.find("head");
  for (const float sign : {1.0f, -1.0f}) {
    animation::Clip c;
    c.name = sign > 0 ? "look" : "lookback";
    c.duration = 2.0f;
    animation::Channel ch;
    ch.segment = head;
    ch.path = animation::ChannelPath::Rotation;
    const Eigen::Quaternionf q0 = m.body.segments[static_cast<std::size_t>(head)].rest.rotation;
    const Eigen::Quaternionf q1 =
        q0 * Eigen::Quaternionf(Eigen::AngleAxisf(sign * 1.0f, Eigen::Vector3f::UnitZ()));
    ch.times = {0.0f, 1.0f, 2.0f};
    ch.values = {q0.x(), q0.y(), q0.z(), q0.w(), q1.x(), q1.y(),
                 q1.z(), q1.w(), q0.x(), q0.y(), q0.z(), q0.w()};
    c.channels.push_back(ch);
    m.clips.push_back(c);
  }
  return m;
}

ViewerOptions smallOptions() {
  ViewerOptions o;
  o.fur = fur::loadFurPreset("default");
  o.fur.setHairCount(4000);
  o.width = 96;
  o.height = 64;
  o.samples = 0;
  return o;
}

class ViewerSessionTest : public test::GlTest {};

TEST_F(ViewerSessionTest, EditsApplyOnTheNextFrame) {
  ViewerSession s(smallOptions(), critterWithClips());
  s.frame(0.0, 96, 64);
  const std::int64_t before = s.hairsDrawn();
  EXPECT_GT(before, 0);
  s.edit.coats[0].style = fur::HairStyle::Curve;
  s.edit.coats[0].curvePoints = 5;
  s.edit.lengthScale = 2.0f;
  s.frame(0.0, 96, 64);
  EXPECT_EQ(s.fur().params.coats[0].style, fur::HairStyle::Curve);
  EXPECT_EQ(s.fur().params.lengthScale, 2.0f);
  ASSERT_FALSE(s.drawList().fur.empty());
  EXPECT_EQ(s.drawList().fur[0].layout.strandPoints, 5);
  // An invalid value is reported and not applied.
  s.edit.coats[1].stiffness = 3.0f;
  s.frame(0.0, 96, 64);
  EXPECT_NE(s.editError.find("stiffness"), std::string::npos) << s.editError;
  EXPECT_LE(s.fur().params.coats[1].stiffness, 1.0f);
  s.edit.coats[1].stiffness = 0.5f;
  s.frame(0.0, 96, 64);
  EXPECT_TRUE(s.editError.empty());
  // The skin colour: the model's, then the panel's (typed sRGB, drawn linear).
  EXPECT_TRUE(s.drawList().skin.material.diffuse.isApprox(srgbToLinear(s.model().skin.color)));
  s.skinColor = Eigen::Vector3f(0.1f, 0.2f, 0.3f);
  s.ownSkinColor = true;  // as the panel's colour edit does
  s.frame(0.0, 96, 64);
  EXPECT_TRUE(
      s.drawList().skin.material.diffuse.isApprox(srgbToLinear(Eigen::Vector3f(0.1f, 0.2f, 0.3f))));
}

// The dynamics switch: on, hairs come from the CPU's damped ends: they start on the quasi-static
// hairs, lag behind them while the head turns, and settle back onto them once the body is still.
TEST_F(ViewerSessionTest, DynamicFurStartsLagsAndSettles) {
  ViewerOptions o = smallOptions();
  // Every hair (a 64-pixel-high image would cull most of them, the head's among them).
  o.fur.culling.enabled = false;
  // The hairs are what is compared: the look's passes (deep opacity map, blending) only cost time
  // on a software rasteriser (80 frames of each session).
  o.selfShadowing = false;
  o.transparency = false;
  o.hairSource = scene::HairSource::Cpu;
  ViewerSession quasi(o, critterWithClips());
  o.hairSource = scene::HairSource::Gpu;
  o.dynamics = true;
  o.dynamicsParams.coats[0] = {20.0f, 0.7f};
  o.dynamicsParams.coats[1] = {20.0f, 0.7f};
  ViewerSession dyn(o, critterWithClips());
  // Largest distance between the two sessions' overcoat hair points (same roots, same culling).
  auto maxGap = [&] {
    const fur::HairBuffers& a = quasi.state().fur.coats[0];
    const fur::HairBuffers& b = dyn.state().fur.coats[0];
    EXPECT_EQ(a.drawn, b.drawn);
    EXPECT_GT(a.drawn, 0);
    float gap = 0.0f;
    for (std::size_t i = 0; i < static_cast<std::size_t>(a.drawn * a.layout.pointsPerHair() * 3);
         ++i)
      gap = std::max(gap, std::abs(a.positions.data()[i] - b.positions.data()[i]));
    return gap;
  };
  quasi.frame(1.0 / 30.0, 96, 64);
  dyn.frame(1.0 / 30.0, 96, 64);
  EXPECT_TRUE(dyn.state().cpuFur);
  EXPECT_EQ(dyn.drawList().fur.empty(), false);
  EXPECT_LT(maxGap(), 1e-6f);  // the first step starts on the quasi-static hairs
  float lag = 0.0f;
  for (int i = 0; i < 10; ++i) {  // the head turns: the dynamic ends trail
    quasi.frame(1.0 / 30.0, 96, 64);
    dyn.frame(1.0 / 30.0, 96, 64);
    lag = std::max(lag, maxGap());
  }
  EXPECT_GT(lag, 1e-4f);
  // Paused, the body is still: the springs settle onto the quasi-static hairs (within 15 frames;
  // 60 leave a margin).
  quasi.playing = dyn.playing = false;
  for (int i = 0; i < 60; ++i) {
    quasi.frame(1.0 / 30.0, 96, 64);
    dyn.frame(1.0 / 30.0, 96, 64);
  }
  EXPECT_LT(maxGap(), 1e-5f);
  // Invalid spring parameters from the panel are reported and not applied.
  dyn.dynamicsParams.coats[0].dampingRatio = -1.0f;
  dyn.frame(1.0 / 30.0, 96, 64);
  EXPECT_NE(dyn.editError.find("damping"), std::string::npos) << dyn.editError;
}

TEST_F(ViewerSessionTest, ANewHairCountRegrowsTheRootsWithoutStalling) {
  ViewerSession s(smallOptions(), critterWithClips());
  s.frame(0.0, 96, 64);
  const std::uint64_t generation = s.fur().generation;
  const std::int64_t roots = s.fur().roots.total();
  s.edit.setHairCount(12000);
  s.edit.coats[0].stiffness = 0.9f;  // applies at once, to the old roots
  s.frame(0.0, 96, 64);
  EXPECT_EQ(s.fur().params.coats[0].stiffness, 0.9f);
  // Frames keep coming with the old roots until the new ones are ready, then they swap in.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  int frames = 1;
  while (s.fur().generation == generation && std::chrono::steady_clock::now() < deadline) {
    if (s.regrowing()) {
      EXPECT_EQ(s.fur().roots.total(), roots);
    }
    s.frame(0.0, 96, 64);
    ++frames;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ASSERT_NE(s.fur().generation, generation) << "the roots were never regrown";
  EXPECT_NEAR(static_cast<double>(s.fur().roots.total()), 12000.0, 400.0);
  EXPECT_EQ(s.fur().params.hairs, 12000.0);
  EXPECT_EQ(s.fur().params.coats[0].stiffness, 0.9f);
  EXPECT_FALSE(s.regrowing());
  EXPECT_GE(frames, 2);
}

TEST_F(ViewerSessionTest, PlaybackPlaysScrubsLoopsAndCrossFades) {
  ViewerOptions o = smallOptions();
  o.clip = 0;  // "look"
  o.time = 0.5;
  ViewerSession s(o, critterWithClips());
  EXPECT_EQ(s.clip(), 0);
  EXPECT_DOUBLE_EQ(s.clipDuration(), 2.0);
  s.frame(0.25, 96, 64);  // shows t = 0.5, then advances
  EXPECT_DOUBLE_EQ(s.time(), 0.75);
  s.speed = 2.0f;
  s.frame(0.25, 96, 64);
  EXPECT_DOUBLE_EQ(s.time(), 1.25);
  s.playing = false;
  s.frame(0.25, 96, 64);
  EXPECT_DOUBLE_EQ(s.time(), 1.25);
  s.setTime(1.0);  // scrub: the head at its extreme
  s.frame(0.0, 96, 64);
  const int head = s.model().body.find("head");
  const Eigen::Matrix3f turned = s.state().body.world[static_cast<std::size_t>(head)].linear();
  // A switch cross-fades: the first frame after it still shows the old clip (weight 0), the next
  // ones a pose between the two clips' poses.
  s.playing = true;
  s.selectClip(1);
  EXPECT_EQ(s.clip(), 1);
  s.frame(0.1, 96, 64);
  EXPECT_TRUE(
      s.state().body.world[static_cast<std::size_t>(head)].linear().isApprox(turned, 1e-5f));
  s.frame(0.05, 96, 64);
  const Eigen::Matrix3f fading = s.state().body.world[static_cast<std::size_t>(head)].linear();
  for (int i = 0; i < 20; ++i) s.frame(0.05, 96, 64);  // 1 s: the fade (0.3 s) is over
  const Eigen::Matrix3f after = s.state().body.world[static_cast<std::size_t>(head)].linear();
  EXPECT_FALSE(fading.isApprox(turned, 1e-3f));
  EXPECT_FALSE(fading.isApprox(after, 1e-3f));
  // Without looping a clip stops on its last frame.
  s.loop = false;
  s.speed = 1.0f;
  for (int i = 0; i < 60; ++i) s.frame(0.1, 96, 64);
  EXPECT_FALSE(s.playing);
  EXPECT_DOUBLE_EQ(s.time(), 2.0);
  // The still pose.
  s.selectClip(-1);
  s.frame(0.1, 96, 64);
  EXPECT_EQ(s.clip(), -1);
}

TEST_F(ViewerSessionTest, PresetsSaveAndLoad) {
  test::TempDir dir;
  ViewerSession s(smallOptions(), critterWithClips());
  s.edit.coats[0].material.diffuse = Eigen::Vector3f(0.1f, 0.2f, 0.3f);
  s.edit.coats[1].style = fur::HairStyle::Line;
  s.frame(0.0, 96, 64);
  s.edit.setHairCount(7000);  // saved as edited, even before the new roots have grown
  s.savePreset(dir.file("mine.json"));
  EXPECT_NE(s.message.find("saved"), std::string::npos) << s.message;
  const fur::FurParams back = fur::loadFurPreset(dir.file("mine.json"));
  EXPECT_TRUE(back.coats[0].material.diffuse.isApprox(Eigen::Vector3f(0.1f, 0.2f, 0.3f)));
  EXPECT_EQ(back.coats[1].style, fur::HairStyle::Line);
  EXPECT_EQ(back.hairs, 7000.0);
  // Invalid panel values are not saved; the message says why.
  s.edit.coats[0].stiffness = 5.0f;
  s.savePreset(dir.file("bad.json"));
  EXPECT_NE(s.message.find("stiffness"), std::string::npos) << s.message;
  EXPECT_FALSE(std::filesystem::exists(dir.file("bad.json")));
  s.edit.coats[0].stiffness = 0.5f;
  s.loadPreset("fig8");
  EXPECT_NE(s.message.find("loaded"), std::string::npos);
  s.frame(0.0, 96, 64);
  EXPECT_EQ(s.fur().params.coats[0].material.shininess,
            fur::loadFurPreset("fig8").coats[0].material.shininess);
  s.loadPreset(dir.file("missing.json"));
  EXPECT_NE(s.message.find("missing.json"), std::string::npos) << s.message;
  s.savePreset(dir.file("no/such/dir/x.json"));
  EXPECT_NE(s.message.find("x.json"), std::string::npos) << s.message;
}

TEST_F(ViewerSessionTest, CameraControlsAndPresets) {
  ViewerSession s(smallOptions(), critterWithClips());
  s.frame(0.0, 96, 64);
  const scene::Orbit o = s.orbit;
  s.orbitBy(30.0f, 100.0f);
  EXPECT_NEAR(s.orbit.azimuthDegrees, o.azimuthDegrees + 30.0f, 1e-3f);
  EXPECT_FLOAT_EQ(s.orbit.elevationDegrees, 89.0f);  // clamped below the pole
  s.zoomBy(0.5f);
  EXPECT_NEAR(s.orbit.distanceMeters, o.distanceMeters * 0.5f, 1e-5f);
  s.panBy(0.1f, 0.0f);
  EXPECT_GT((s.orbit.target - o.target).norm(), 0.0f);
  s.applyPreset(scene::CameraPreset::Face);
  s.frame(0.0, 96, 64);
  EXPECT_LT(s.orbit.distanceMeters, o.distanceMeters * 0.5f);
  s.applyPreset(scene::CameraPreset::Follow);
  EXPECT_TRUE(s.follow);
}

}  // namespace
}  // namespace pelage::viewer::detail

namespace pelage::viewer::detail {
namespace {

// Mean absolute difference per channel (8-bit codes) between two images of one size.
double meanDifference(const render::Image& a, const render::Image& b) {
  double sum = 0.0;
  for (std::size_t i = 0; i < a.rgba.size(); ++i)
    if (i % 4 != 3) sum += std::abs(int(a.rgba[i]) - int(b.rgba[i]));
  return sum / (static_cast<double>(a.rgba.size()) * 0.75);
}

// What the viewer shows is what `pelage render` writes: the Fox (orange, white chest, from its
// texture) through the session and through the sequence renderer, same frame and camera.
TEST_F(ViewerSessionTest, TheViewerDrawsTheFrameRenderDraws) {
  const scene::Model* shared = test::creature("Fox");
  if (!shared) GTEST_SKIP() << "shared models absent: " << PELAGE_SHARED_MODELS_DIR;
  const scene::Model& fox = *shared;
  ViewerOptions vo = smallOptions();
  vo.fur.setHairCount(30000);
  vo.width = 320;
  vo.height = 200;
  vo.camera = scene::CameraPreset::Side;
  ViewerSession session(vo, fox);
  session.frame(0.0, vo.width, vo.height);
  const render::Image viewed = session.renderer().readPixels();

  const scene::Fur fur = scene::growFur(fox, vo.fur, "test");
  render::SequenceOptions so;
  so.playback.clip = 0;
  so.playback.hairSource = vo.hairSource;
  so.frames = {0, 0};
  so.width = vo.width;
  so.height = vo.height;
  so.samples = 0;
  so.outDir = ".";
  so.camera.preset = scene::CameraPreset::Side;
  render::SequenceRenderer sequence(fox, fur, so);
  render::Image rendered;
  sequence.render(0, rendered);
  const double same = meanDifference(viewed, rendered);
  EXPECT_LT(same, 0.5) << "the viewer's frame differs from render's";

  // The viewer's old skin (the model's one base colour instead of its texture) is visibly
  // different: the comparison can tell.
  session.ownSkinColor = true;
  session.frame(0.0, vo.width, vo.height);
  const double old = meanDifference(session.renderer().readPixels(), rendered);
  EXPECT_GT(old, 4.0 * std::max(same, 0.25)) << "same " << same << ", old " << old;
  std::printf("viewer vs render, Fox: mean difference %.3f codes (with the old skin: %.2f)\n", same,
              old);
}

// The brushes as the panel and the mouse drive them (ViewerSession::brushAt / endBrush / undo /
// files): a stroke lands on the skin under the cursor, the fur regrows with the new groom while the
// old one draws, undo gives back the first groom bit for bit, and the saved strokes replayed by
// `pelage groom` write the very groom file the viewer saved.
TEST_F(ViewerSessionTest, BrushesGroomTheSkinUnderTheCursorUndoAndSaveFilesThatReplay) {
  const auto same = [](const std::vector<float>& a, const std::vector<float>& b) {
    return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](float x, float y) {
             return std::memcmp(&x, &y, sizeof x) == 0;
           });
  };
  const auto waitForGroom = [](ViewerSession& s) {
    for (int i = 0; i < 500 && !s.groomShown(); ++i) {
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
      s.frame(0.0, 96, 64);
    }
    return s.groomShown();
  };
  ViewerOptions o = smallOptions();
  o.selfShadowing = false;
  o.fur.culling.enabled = false;  // every hair, but for the brush preview
  ViewerSession s(o, test::sceneCritter());
  s.brushPreviewHairs = 1000;
  s.frame(0.0, 96, 64);
  EXPECT_FALSE(s.previewing());
  EXPECT_EQ(s.hairsDrawn(), s.fur().roots.total());
  const std::vector<float> start = s.groomEditor().groom().length;
  EXPECT_FALSE(s.brushAt(0.5f, 0.5f));  // the corner looks past the critter
  EXPECT_FALSE(s.brushing());
  s.brush.stroke.tool = fur::BrushTool::Length;
  s.brush.stroke.strength = 2.0f;
  s.brush.radius = 0.03f;
  s.brush.stroke.mirrorAxis = 1;
  ASSERT_TRUE(s.brushAt(48.0f, 32.0f));
  EXPECT_TRUE(s.brushing());
  // While brushing, the preview draws about 1,000 of the 4,000 hairs.
  s.frame(0.0, 96, 64);
  EXPECT_TRUE(s.previewing());
  EXPECT_GT(s.hairsDrawn(), 700);
  EXPECT_LT(s.hairsDrawn(), 1300);
  EXPECT_TRUE(s.brushAt(52.0f, 33.0f));
  s.endBrush();
  ASSERT_EQ(s.groomEditor().strokes().size(), 1u);
  const fur::GroomStroke stroke = s.groomEditor().strokes()[0];
  EXPECT_EQ(stroke.mirrorAxis, 1);
  EXPECT_FLOAT_EQ(stroke.radius, 0.03f);
  const std::vector<float>& brushed = s.groomEditor().groom().length;
  int longer = 0;
  for (std::size_t v = 0; v < start.size(); ++v) {
    EXPECT_GE(brushed[v], start[v]);
    longer += brushed[v] > start[v];
  }
  EXPECT_GT(longer, 0);
  ASSERT_TRUE(waitForGroom(s));
  EXPECT_TRUE(same(s.fur().groom.vertex.length, brushed));
  s.frame(0.0, 96, 64);
  EXPECT_FALSE(s.previewing());  // the stroke's fur has grown: every hair again
  EXPECT_EQ(s.hairsDrawn(), s.fur().roots.total());

  // The files: the viewer's groom, and its strokes replayed by `pelage groom` on the same fur.
  test::TempDir dir;
  s.saveGroom(dir.file("critter.groom.json"));
  s.saveStrokes(dir.file("critter.strokes.json"));
  EXPECT_NE(s.message.find("1 strokes"), std::string::npos) << s.message;
  const test::RunResult r = test::runPelage(
      "groom " PELAGE_TEST_CRITTER " --fur default --strokes " + dir.file("critter.strokes.json") +
      " --out " + dir.file("replayed.groom.json"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_EQ(test::readText(dir.file("replayed.groom.json")),
            test::readText(dir.file("critter.groom.json")));

  // Undo: the first groom bit for bit, on the fur too; redo: the stroke again.
  s.undoStroke();
  EXPECT_TRUE(same(s.groomEditor().groom().length, start));
  ASSERT_TRUE(waitForGroom(s));
  EXPECT_TRUE(same(s.fur().groom.vertex.length, start));
  s.redoStroke();
  EXPECT_TRUE(same(s.groomEditor().groom().length, brushed));

  // Loading a groom file starts over from it; a missing one is reported by name.
  s.undoStroke();
  s.loadGroom(dir.file("critter.groom.json"));
  EXPECT_TRUE(same(s.groomEditor().groom().length, brushed));
  EXPECT_TRUE(s.groomEditor().strokes().empty());
  EXPECT_FALSE(s.groomEditor().canUndo());
  s.loadGroom(dir.file("missing.groom.json"));
  EXPECT_NE(s.message.find("missing.groom.json"), std::string::npos) << s.message;
  // A bad brush is reported, never applied.
  s.brush.stroke.strength = 0.0f;  // a length factor must be > 0
  EXPECT_TRUE(s.brushAt(48.0f, 32.0f));
  EXPECT_NE(s.editError.find("strength"), std::string::npos) << s.editError;
  EXPECT_FALSE(s.brushing());
}

}  // namespace
}  // namespace pelage::viewer::detail
