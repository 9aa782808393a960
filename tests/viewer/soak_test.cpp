// Soak (issue 8): the viewer's update path and the exporter's frame loop run many frames with a
// parameter change every frame (lengths, stiffness, styles, hair counts that regrow the roots,
// clips, dynamics, culling, shadows, the hair source), on the built-in monkey. Frames come from
// PELAGE_SOAK_FRAMES (default 200: a quick pass in every test run). The memory check needs a long
// run: from PELAGE_SOAK_FRAMES >= 2000 on, the resident set at the end must be within 48 MB of the
// one after the first tenth (run by `make soak`: 10,000 frames under ASan + UBSan + LSan with a
// small ASan quarantine; it prints the RSS and peak at start and end).
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

#include "pelage/fur/hair_ply.h"
#include "pelage/fur/preset.h"
#include "pelage/scene/export_gltf.h"
#include "pelage/scene/frame.h"
#include "support/files.h"
#include "support/gl.h"
#include "viewer_session.h"

namespace pelage::viewer::detail {
namespace {

int soakFrames() {
  const char* env = std::getenv("PELAGE_SOAK_FRAMES");
  const int n = env ? std::atoi(env) : 200;
  return n > 0 ? n : 200;
}

// VmRSS and VmHWM (peak) of this process, MB.
struct Memory {
  double rss = 0.0, peak = 0.0;
};
Memory memory() {
  std::ifstream in("/proc/self/status");
  Memory m;
  std::string key;
  double kb = 0.0;
  while (in >> key) {
    if (key == "VmRSS:" && (in >> kb))
      m.rss = kb / 1024.0;
    else if (key == "VmHWM:" && (in >> kb))
      m.peak = kb / 1024.0;
  }
  return m;
}

void report(const char* what, int frame, const Memory& m) {
  std::printf("soak %s: frame %d: RSS %.1f MB, peak %.1f MB\n", what, frame, m.rss, m.peak);
  std::fflush(stdout);
}

void checkFlat(const char* what, int frames, const Memory& early, const Memory& end) {
  if (frames < 2000) return;  // too short to tell growth from warm-up
  EXPECT_LT(end.rss - early.rss, 48.0)
      << what << ": resident memory grew from " << early.rss << " MB to " << end.rss << " MB over "
      << frames << " frames";
}

const scene::Model& monkey() {
  return test::defaultMonkey();
}

class Soak : public test::GlTest {};

TEST_F(Soak, ViewerUpdatePathWithAChangeEveryFrame) {
  const int frames = soakFrames();
  ViewerOptions o;
  o.fur = fur::loadFurPreset("default");
  o.fur.setHairCount(8000);
  o.width = 128;
  o.height = 96;
  o.samples = 0;
  ViewerSession s(o, monkey());
  ASSERT_GE(s.model().clips.size(), 2u);
  const fur::HairStyle styles[] = {fur::HairStyle::Polyline, fur::HairStyle::Line,
                                   fur::HairStyle::Curve, fur::HairStyle::Tube};
  Memory early;
  report("viewer", 0, memory());
  for (int i = 0; i < frames; ++i) {
    s.edit.lengthScale = 0.5f + 0.1f * static_cast<float>(i % 10);
    s.edit.coats[0].stiffness = static_cast<float>(i % 7) / 7.0f;
    s.edit.coats[1].normalRandomize = static_cast<float>(i % 5) / 5.0f;
    if (i % 50 == 0) s.edit.coats[0].style = styles[(i / 50) % 4];
    if (i % 250 == 0) s.edit.setHairCount(6000.0 + 2000.0 * ((i / 250) % 3));
    if (i % 400 == 0) s.selectClip((s.clip() + 1) % static_cast<int>(s.model().clips.size()));
    if (i % 300 == 150) s.dynamics = !s.dynamics;
    if (i % 100 == 0) {
      s.shadows = !s.shadows;
      s.edit.culling.enabled = !s.edit.culling.enabled;
      s.hairSource =
          s.hairSource == scene::HairSource::Gpu ? scene::HairSource::Cpu : scene::HairSource::Gpu;
    }
    s.orbitBy(1.0f, 0.0f);
    s.frame(1.0 / 30.0, o.width, o.height);
    ASSERT_TRUE(s.editError.empty()) << "frame " << i << ": " << s.editError;
    if (i == frames / 10) report("viewer", i, early = memory());
  }
  s.renderer().finish();
  EXPECT_GT(s.hairsDrawn(), 0);
  const Memory end = memory();
  report("viewer", frames, end);
  checkFlat("viewer", frames, early, end);
}

TEST_F(Soak, ExportFrameLoopWithAChangeEveryFrame) {
  const int frames = soakFrames();
  test::TempDir dir;
  const scene::Model& model = monkey();
  fur::FurParams params = fur::loadFurPreset("default");
  params.setHairCount(10000);
  params.culling.enabled = false;
  scene::Fur fur = scene::growFur(model, params);
  scene::FrameState state;
  Memory early;
  report("export", 0, memory());
  for (int i = 0; i < frames; ++i) {
    if (i % 500 == 499) {  // new roots: another count and seed
      params.setHairCount(8000.0 + 1000.0 * ((i / 500) % 5));
      params.seed = static_cast<std::uint64_t>(i);
      fur = scene::growFur(model, params);
    }
    fur.params.coats[0].style = i % 3 == 0 ? fur::HairStyle::Curve : fur::HairStyle::Polyline;
    fur.params.coats[0].stiffness = static_cast<float>(i % 9) / 9.0f;
    const int clip = (i / 200) % static_cast<int>(model.clips.size());
    scene::evaluateClipFrame(model, clip, i / 30.0, state);
    scene::evaluateFur(model, fur, fur::FurView{}, true, state);
    ASSERT_EQ(state.fur.drawn(), fur.roots.total());
    fur::writeHairPly(dir.file("frame.ply"), state.fur, fur.params, "soak");
    if (i % 10 == 0) scene::writeFrameGlb(dir.file("frame.glb"), model, fur, state, "soak");
    if (i == frames / 10) report("export", i, early = memory());
  }
  const Memory end = memory();
  report("export", frames, end);
  checkFlat("export", frames, early, end);
}

}  // namespace
}  // namespace pelage::viewer::detail
