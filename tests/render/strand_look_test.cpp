// The look of coverage-correct strands (issue 14), as image statistics on llvmpipe: the coat looks
// the same whatever the image size, the distance and zoom, and it does not crawl as the camera
// moves, on the built-in monkey and on the shared Fox and Wolf. Each creature is rendered in a
// frame of its first clip, seen from the side, with its default fur and the default look (strands
// of their width, transparency, culling by screen scale).
//
// Measures, over the creature's pixels (those that differ from the background in either image):
//  - MAD: the mean absolute difference of the sRGB channels (0..255);
//  - luminance: the mean of 0.2126 R + 0.7152 G + 0.0722 B of the sRGB values.
// Box filtering averages linear light (the coverage the filter models) and encodes the mean.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>

#include "pelage/fur/preset.h"
#include "pelage/render/renderer.h"
#include "pelage/scene/camera.h"
#include "pelage/scene/draw_list.h"
#include "pelage/scene/playback.h"
#include "pelage/util/color.h"
#include "support/gl.h"

namespace pelage::render {
namespace {

constexpr double kPi = 3.14159265358979323846;

struct Creature {
  scene::Model model;
  scene::Fur fur;
  int clip = -1;
  int frame = 0;
};

// The monkey walking (frame 5) with 100,000 hairs of the default fur, or a shared model playing
// its first clip (frame 10) with `hairs` hairs; null when the shared file is absent.
std::unique_ptr<Creature> creature(const std::string& name, double hairs) {
  const scene::Model* model = test::creature(name);
  if (!model) return nullptr;
  auto c = std::make_unique<Creature>();
  c->model = *model;
  fur::FurParams p = fur::loadFurPreset("default");
  p.setHairCount(hairs);
  c->fur = scene::growFur(c->model, p, "test");
  for (std::size_t i = 0; i < c->model.clips.size(); ++i)
    if (c->model.clips[i].name == "walk" || c->clip < 0) c->clip = static_cast<int>(i);
  c->frame = name == "monkey" ? 5 : 10;
  return c;
}

class StrandLookTest : public test::GlTest {
 protected:
  // The side camera of the creature's frame in a width x height image, moved `distance` times
  // further and its field of view narrowed so that it looks as large; then turned about the
  // vertical through the target by `turnDegrees`.
  scene::Camera camera(const Creature& c, int width, int height, float distance = 1.0f,
                       float turnDegrees = 0.0f) {
    scene::PlaybackOptions po;
    po.clip = c.clip;
    scene::Playback pb(c.model, c.fur, po);
    pb.poseFrame(c.frame);
    const scene::Framing framing = pb.framing();
    scene::Camera cam = scene::presetCamera(framing, scene::CameraPreset::Side, width, height);
    const double t = std::tan(0.5 * cam.fovYDegrees * kPi / 180.0) / distance;
    cam.fovYDegrees = static_cast<float>(2.0 * std::atan(t) * 180.0 / kPi);
    Eigen::Vector3f back = (cam.eye - cam.target) * distance;
    back = Eigen::AngleAxisf(static_cast<float>(turnDegrees * kPi / 180.0), cam.up) * back;
    cam.eye = cam.target + back;
    scene::fitClipPlanes(cam, framing);
    return cam;
  }

  Image render(const Creature& c, const scene::Camera& cam, const scene::DrawOptions& look = {}) {
    scene::PlaybackOptions po;
    po.clip = c.clip;
    po.hairSource = look.hairSource;
    scene::Playback pb(c.model, c.fur, po);
    pb.poseFrame(c.frame);
    pb.evaluateFur(cam);
    const scene::DrawList& list = pb.drawList(cam, scene::Light{}, look);
    RendererOptions ro;
    ro.samples = 0;
    Renderer r(ro);
    r.render(list);
    return r.readPixels();
  }
};

// The image box-filtered by k x k (linear light).
Image boxFilter(const Image& a, int k) {
  Image out;
  out.width = a.width / k;
  out.height = a.height / k;
  out.rgba.assign(static_cast<std::size_t>(out.width) * static_cast<std::size_t>(out.height) * 4,
                  255);
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x)
      for (int ch = 0; ch < 3; ++ch) {
        double sum = 0;
        for (int j = 0; j < k; ++j)
          for (int i = 0; i < k; ++i)
            sum += srgbToLinear(a.pixel(x * k + i, y * k + j)[ch] / 255.0f);
        out.rgba[(static_cast<std::size_t>(y) * static_cast<std::size_t>(out.width) +
                  static_cast<std::size_t>(x)) *
                     4 +
                 static_cast<std::size_t>(ch)] =
            static_cast<std::uint8_t>(
                std::lround(255.0f * linearToSrgb(static_cast<float>(sum / (k * k)))));
      }
  return out;
}

struct Difference {
  double mad = 0;  // mean absolute difference, 0..255
  double luminanceA = 0, luminanceB = 0;
  int pixels = 0;
  double luminanceRatio() const { return luminanceA / luminanceB; }
};

bool isBackground(const Image& a, int x, int y) {
  const Eigen::Vector3f& bg = scene::kDefaultBackground;
  for (int ch = 0; ch < 3; ++ch)
    if (std::abs(a.pixel(x, y)[ch] - std::lround(255.0f * linearToSrgb(bg[ch]))) > 2) return false;
  return true;
}

double luminance(const std::uint8_t* p) {
  return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
}

Difference compare(const Image& a, const Image& b) {
  EXPECT_EQ(a.width, b.width);
  EXPECT_EQ(a.height, b.height);
  Difference d;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      if (isBackground(a, x, y) && isBackground(b, x, y)) continue;
      ++d.pixels;
      for (int ch = 0; ch < 3; ++ch) d.mad += std::abs(a.pixel(x, y)[ch] - b.pixel(x, y)[ch]);
      d.luminanceA += luminance(a.pixel(x, y));
      d.luminanceB += luminance(b.pixel(x, y));
    }
  d.mad /= 3.0 * std::max(d.pixels, 1);
  d.luminanceA /= std::max(d.pixels, 1);
  d.luminanceB /= std::max(d.pixels, 1);
  return d;
}

void print(const char* what, const Difference& d) {
  std::printf("%s: MAD %.2f/255 over %d pixels, luminance %.1f vs %.1f (ratio %.3f)\n", what, d.mad,
              d.pixels, d.luminanceA, d.luminanceB, d.luminanceRatio());
}

// The image-size acceptance: the same view at 320x320 and at 1280x1280 box-filtered to
// 320x320 differ by at most 6/255 over the creature, coat luminance within 5 %.
void expectSizeIndependent(const Image& small, const Image& large) {
  const Difference d = compare(small, boxFilter(large, 4));
  print("320 vs 1280 box-filtered", d);
  EXPECT_GT(d.pixels, 320 * 320 / 10);
  EXPECT_LE(d.mad, 6.0);
  EXPECT_NEAR(d.luminanceRatio(), 1.0, 0.05);
}

TEST_F(StrandLookTest, MonkeyLooksTheSameAtEveryImageSize) {
  const auto c = creature("monkey", 100000);
  const Image small = render(*c, camera(*c, 320, 320));
  const Image large = render(*c, camera(*c, 1280, 1280));
  expectSizeIndependent(small, large);
}

TEST_F(StrandLookTest, FoxAndWolfLookTheSameAtEveryImageSize) {
  for (const char* name : {"Fox", "Wolf"}) {
    SCOPED_TRACE(name);
    const auto c = creature(name, 100000);
    if (!c) GTEST_SKIP() << "shared models absent: " << name;
    const Image small = render(*c, camera(*c, 320, 320));
    const Image large = render(*c, camera(*c, 1280, 1280));
    expectSizeIndependent(small, large);
  }
}

TEST_F(StrandLookTest, MonkeyLooksTheSameFromFurtherAwayZoomedIn) {
  const auto c = creature("monkey", 100000);
  const Image near = render(*c, camera(*c, 480, 480));
  scene::DrawOptions bare;
  bare.drawFur = false;
  const Image nearBare = render(*c, camera(*c, 480, 480), bare);
  for (float k : {4.0f, 8.0f}) {
    const Difference d = compare(render(*c, camera(*c, 480, 480, k)), near);
    print(k == 4.0f ? "4d vs d" : "8d vs d", d);
    // The body itself changes between the views (a flatter perspective: silhouette, and the
    // angles to the eye the shading sees): the bare skin's images differ by ~16/255 (measured),
    // so the pixel comparison cannot reach the 8/255; like with like, the fur adds no
    // difference of its own to the body's, and the coat's luminance holds. (Distance culling
    // alone, the paper's rule, left the far view nearly bald: MAD 50, luminance -16 %.)
    const Difference skin = compare(render(*c, camera(*c, 480, 480, k), bare), nearBare);
    print("  bare skin", skin);
    EXPECT_LE(d.mad, skin.mad);
    EXPECT_NEAR(d.luminanceRatio(), 1.0, 0.05);
  }
}

// The crawl acceptance: a camera orbiting the creature by a quarter pixel per frame
// (where the creature is widest: a turn of 0.25 px x metres per pixel / r about the vertical
// through the target, r the creature's bounding radius), eight frames. The mean frame-to-frame
// change over the creature is compared with the same change in the converged image, approximated
// by rendering 4x larger and box-filtering: motion itself changes the converged image a little
// (edges move a quarter pixel); what the 1x image changes beyond it is crawling (hairs flickering
// on and off pixels). The bound: crawling adds at most one 8-bit level to the mean change (the
// output's own quantisation step: a mean flicker of one level is not seen), and at most a quarter
// of what the paper's 1-pixel lines add. Measured 2026-11-24 (llvmpipe, no MSAA): strands 1.01,
// converged 0.59, lines 3.26; the bare skin alone 0.52 vs 0.41 converged.
TEST_F(StrandLookTest, MonkeyDoesNotCrawlAsTheCameraOrbitsAQuarterPixelPerFrame) {
  const auto c = creature("monkey", 100000);
  const scene::Camera first = camera(*c, 320, 320);
  const float metresPerPixel =
      (first.eye - first.target).norm() * 2.0f *
      std::tan(0.5f * first.fovYDegrees * static_cast<float>(kPi) / 180.0f) /
      static_cast<float>(first.height);
  scene::PlaybackOptions po;
  po.clip = c->clip;
  scene::Playback pb(c->model, c->fur, po);
  pb.poseFrame(c->frame);
  const double stepDegrees = 0.25 * metresPerPixel / pb.framing().radius * 180.0 / kPi;
  scene::DrawOptions lines, bare;
  lines.hairWidth = scene::HairWidth::Lines;
  bare.drawFur = false;
  double strands = 0, converged = 0, paper = 0, skin = 0, skinConverged = 0;
  Image prev, prevRef, prevLines, prevSkin, prevSkinRef;
  constexpr int kFrames = 8;
  for (int k = 0; k < kFrames; ++k) {
    const float turn = static_cast<float>(k * stepDegrees);
    Image img = render(*c, camera(*c, 320, 320, 1.0f, turn));
    Image ref = boxFilter(render(*c, camera(*c, 1280, 1280, 1.0f, turn)), 4);
    Image lin = render(*c, camera(*c, 320, 320, 1.0f, turn), lines);
    Image sk = render(*c, camera(*c, 320, 320, 1.0f, turn), bare);
    Image skRef = boxFilter(render(*c, camera(*c, 1280, 1280, 1.0f, turn), bare), 4);
    if (k > 0) {
      strands += compare(img, prev).mad / (kFrames - 1);
      converged += compare(ref, prevRef).mad / (kFrames - 1);
      paper += compare(lin, prevLines).mad / (kFrames - 1);
      skin += compare(sk, prevSkin).mad / (kFrames - 1);
      skinConverged += compare(skRef, prevSkinRef).mad / (kFrames - 1);
    }
    prev = std::move(img);
    prevRef = std::move(ref);
    prevLines = std::move(lin);
    prevSkin = std::move(sk);
    prevSkinRef = std::move(skRef);
  }
  std::printf(
      "orbit by %.4f degrees a frame: mean change %.2f/255 (converged %.2f, 1-pixel lines "
      "%.2f; bare skin %.2f, converged %.2f)\n",
      stepDegrees, strands, converged, paper, skin, skinConverged);
  EXPECT_GT(converged, 0.0);  // the camera does move
  EXPECT_LE(strands - converged, 1.0);
  EXPECT_LE(strands - converged, 0.25 * (paper - converged));
}

}  // namespace
}  // namespace pelage::render
