// Frames you can trust (issue 25): a rendered frame is opaque unless asked otherwise (no halo of
// partial alpha around the fur in an image viewer), and a transparent frame is a real straight-
// alpha image: background alpha 0, the fur's fringe carrying its coverage, and composited over
// the background colour in linear light it equals the opaque frame within 1/255.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "pelage/fur/preset.h"
#include "pelage/render/render_sequence.h"
#include "pelage/scene/model.h"
#include "pelage/util/color.h"
#include "support/gl.h"

namespace pelage::render {
namespace {

struct Frames {
  Image opaque, transparent;
};

// One frame of `model`'s first clip (or its rest pose) with the default look (strands with
// transparency), read back opaque and with a transparent background.
Frames renderBoth(const scene::Model& model, const Eigen::Vector3f& background) {
  fur::FurParams params = fur::loadFurPreset("default");
  params.hairs = 40000;
  const scene::Fur fur = scene::growFur(model, params, "test");
  Frames out;
  for (const bool transparent : {false, true}) {
    SequenceOptions o;
    o.playback.clip = model.clips.empty() ? -1 : 0;
    o.frames = {3, 3};
    o.width = 320;
    o.height = 200;
    o.outDir = ".";
    o.camera.preset = scene::CameraPreset::Side;
    o.look.background = background;
    o.transparentBackground = transparent;
    SequenceRenderer r(model, fur, o);
    r.render(3, transparent ? out.transparent : out.opaque);
  }
  return out;
}

struct AlphaCounts {
  long zero = 0, partial = 0, full = 0;
};

AlphaCounts countAlpha(const Image& img) {
  AlphaCounts c;
  for (std::size_t i = 3; i < img.rgba.size(); i += 4) {
    const int a = img.rgba[i];
    (a == 0 ? c.zero : a == 255 ? c.full : c.partial) += 1;
  }
  return c;
}

// The largest difference, in 8-bit sRGB codes, between `transparent` composited over `background`
// (straight alpha, linear light) and `opaque`.
int compositeDifference(const Image& transparent, const Image& opaque,
                        const Eigen::Vector3f& background) {
  const float* lin = srgb8ToLinearTable();
  int worst = 0;
  for (std::size_t i = 0; i + 3 < opaque.rgba.size(); i += 4) {
    const float a = static_cast<float>(transparent.rgba[i + 3]) / 255.0f;
    for (int c = 0; c < 3; ++c) {
      const float over =
          a * lin[transparent.rgba[i + static_cast<std::size_t>(c)]] + (1.0f - a) * background[c];
      worst =
          std::max(worst, std::abs(static_cast<int>(linearToSrgb8(over)) -
                                   static_cast<int>(opaque.rgba[i + static_cast<std::size_t>(c)])));
    }
  }
  return worst;
}

class FrameAlphaTest : public test::GlTest {
 protected:
  void checkCreature(const scene::Model& model, const Eigen::Vector3f& background) {
    const Frames f = renderBoth(model, background);
    const long pixels = static_cast<long>(f.opaque.width) * f.opaque.height;
    const AlphaCounts opaque = countAlpha(f.opaque);
    EXPECT_EQ(opaque.full, pixels) << opaque.zero << " pixels of alpha 0, " << opaque.partial
                                   << " partial: the opaque frame has a halo";
    const AlphaCounts t = countAlpha(f.transparent);
    // Background transparent, the body opaque, the fur's fringe in between.
    EXPECT_GT(t.zero, pixels / 4);
    EXPECT_GT(t.full, pixels / 50);
    EXPECT_GT(t.partial, 100);
    EXPECT_EQ(f.transparent.pixel(0, 0)[3], 0);
    const std::uint8_t* corner = f.transparent.pixel(0, 0);
    EXPECT_EQ(corner[0] + corner[1] + corner[2], 0);
    EXPECT_LE(compositeDifference(f.transparent, f.opaque, background), 1);
  }
};

TEST_F(FrameAlphaTest, MonkeyFramesAreOpaqueAndTheTransparentOneCompositesBack) {
  checkCreature(test::defaultMonkey(), scene::kDefaultBackground);
}

TEST_F(FrameAlphaTest, FoxFramesAreOpaqueAndTheTransparentOneCompositesBackOverAnyColour) {
  const scene::Model* fox = test::creature("Fox");
  if (!fox) GTEST_SKIP() << "shared models absent: " << PELAGE_SHARED_MODELS_DIR;
  checkCreature(*fox, srgbToLinear(Eigen::Vector3f(0.1f, 0.5f, 0.2f)));
}

// unblendBackground on tiny images: exact where it can be, and the inverse of compositing.
TEST(UnblendBackground, OpaqueAndEmptyPixelsAndACoveredOne) {
  const Eigen::Vector3f bg = srgbToLinear(Eigen::Vector3f(0.8f, 0.82f, 0.86f));
  Image img;
  img.width = 3;
  img.height = 1;
  // Opaque (kept as it is), nothing drawn (all zero), half covered by pure red over bg.
  const float a = 128.0f / 255.0f;
  const std::uint8_t r = linearToSrgb8(a * 1.0f + (1.0f - a) * bg.x());
  const std::uint8_t g = linearToSrgb8((1.0f - a) * bg.y());
  const std::uint8_t b = linearToSrgb8((1.0f - a) * bg.z());
  img.rgba = {10, 20, 30, 255, 200, 201, 202, 0, r, g, b, 128};
  unblendBackground(img, bg);
  EXPECT_EQ((std::vector<std::uint8_t>(img.rgba.begin(), img.rgba.begin() + 8)),
            (std::vector<std::uint8_t>{10, 20, 30, 255, 0, 0, 0, 0}));
  // Red, recovered within the 8-bit rounding of the blend (amplified by 1 / a near black) ...
  EXPECT_GE(img.rgba[8], 250);
  EXPECT_LE(img.rgba[9], 8);
  EXPECT_LE(img.rgba[10], 8);
  EXPECT_EQ(img.rgba[11], 128);
  // ... and composited back over the background it is the blended pixel again.
  const float* lin = srgb8ToLinearTable();
  const std::uint8_t blended[3] = {r, g, b};
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(linearToSrgb8(a * lin[img.rgba[8 + static_cast<std::size_t>(c)]] + (1 - a) * bg[c]),
                blended[c], 1)
        << c;
  makeOpaque(img);
  EXPECT_EQ(img.rgba[7], 255);
  EXPECT_EQ(img.rgba[11], 255);
}

// A highlight brighter than its coverage of white (a hair's specular above 1 in linear light), and
// one whose coverage rounded to 0, keep their brightness with more coverage.
TEST(UnblendBackground, HighlightsBrighterThanTheirCoverageGetTheCoverageTheyNeed) {
  const Eigen::Vector3f bg = srgbToLinear(Eigen::Vector3f(0.1f, 0.1f, 0.1f));
  const float* lin = srgb8ToLinearTable();
  for (const int alpha : {0, 6, 60}) {
    Image img;
    img.width = img.height = 1;
    // What a highlight of 3 (linear) over `alpha` coverage draws, clamped by the framebuffer.
    const float a = static_cast<float>(alpha) / 255.0f + 0.002f;
    const std::uint8_t drawn = linearToSrgb8(std::min(a * 3.0f + (1.0f - a) * bg.x(), 1.0f));
    img.rgba = {drawn, drawn, drawn, static_cast<std::uint8_t>(alpha)};
    unblendBackground(img, bg);
    const float back = static_cast<float>(img.rgba[3]) / 255.0f;
    EXPECT_GT(img.rgba[3], alpha) << alpha;
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(
          linearToSrgb8(back * lin[img.rgba[static_cast<std::size_t>(c)]] + (1 - back) * bg[c]),
          drawn, 1)
          << alpha;
  }
}

}  // namespace
}  // namespace pelage::render
