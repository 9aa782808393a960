#include "pelage/render/renderer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "pelage/render/hair_vertex_buffers.h"
#include "pelage/scene/draw_list.h"
#include "pelage/scene/frame.h"
#include "pelage/util/error.h"
#include "support/files.h"
#include "support/gl.h"

namespace pelage::render {
namespace {

using test::coverage;
using test::differsFrom;

const scene::Model& critter() {
  return test::sceneCritter();
}

// A CPU point-in-triangle rasteriser of the projected skin: the expected silhouette (pixel
// centres).
std::vector<std::uint8_t> cpuSilhouette(const scene::Model& m, const scene::FrameState& f,
                                        const scene::Camera& cam) {
  const int W = cam.width, H = cam.height;
  std::vector<std::uint8_t> mask(static_cast<std::size_t>(W * H), 0);
  const Eigen::Matrix4f vp = cam.viewProjection();
  std::vector<Eigen::Vector2f> s(f.skin.positions.size());
  for (std::size_t v = 0; v < s.size(); ++v) {
    const Eigen::Vector4f c = vp * f.skin.positions[v].homogeneous();
    // Pixel coordinates with y down (image rows top-first).
    s[v] = Eigen::Vector2f((c.x() / c.w() * 0.5f + 0.5f) * static_cast<float>(W),
                           (0.5f - c.y() / c.w() * 0.5f) * static_cast<float>(H));
  }
  for (int t = 0; t < m.skin.numTriangles(); ++t) {
    const Eigen::Vector2f& a =
        s[static_cast<std::size_t>(m.skin.triangles[static_cast<std::size_t>(3 * t)])];
    const Eigen::Vector2f& b =
        s[static_cast<std::size_t>(m.skin.triangles[static_cast<std::size_t>(3 * t + 1)])];
    const Eigen::Vector2f& c =
        s[static_cast<std::size_t>(m.skin.triangles[static_cast<std::size_t>(3 * t + 2)])];
    const int x0 = std::max(0, static_cast<int>(std::floor(std::min({a.x(), b.x(), c.x()}))));
    const int x1 = std::min(W - 1, static_cast<int>(std::ceil(std::max({a.x(), b.x(), c.x()}))));
    const int y0 = std::max(0, static_cast<int>(std::floor(std::min({a.y(), b.y(), c.y()}))));
    const int y1 = std::min(H - 1, static_cast<int>(std::ceil(std::max({a.y(), b.y(), c.y()}))));
    auto edge = [](const Eigen::Vector2f& p, const Eigen::Vector2f& q, const Eigen::Vector2f& r) {
      return (q.x() - p.x()) * (r.y() - p.y()) - (q.y() - p.y()) * (r.x() - p.x());
    };
    const float area = edge(a, b, c);
    if (std::abs(area) < 1e-12f) continue;
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const Eigen::Vector2f p(static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f);
        const float w0 = edge(b, c, p) / area, w1 = edge(c, a, p) / area, w2 = edge(a, b, p) / area;
        if (w0 >= 0 && w1 >= 0 && w2 >= 0) mask[static_cast<std::size_t>(y * W + x)] = 1;
      }
  }
  return mask;
}

class RendererTest : public test::GlTest {
 protected:
  void SetUp() override {
    test::GlTest::SetUp();
    if (HasFatalFailure()) return;
    scene::evaluateFrame(critter(), anatomy::restPose(critter().body), frame_);
  }
  scene::DrawList skinOnly(scene::CameraPreset preset, int w, int h, bool shadows = false) {
    const scene::Framing fr = scene::framingOf(critter(), frame_, 0.0f);
    scene::Light light;
    light.shadows = shadows;
    scene::DrawList list;
    scene::buildDrawList(critter(), frame_, nullptr, scene::presetCamera(fr, preset, w, h), light,
                         {}, list);
    return list;
  }
  scene::FrameState frame_;
};

TEST_F(RendererTest, SkinSilhouetteMatchesTheCpuProjection) {
  for (scene::CameraPreset preset :
       {scene::CameraPreset::Front, scene::CameraPreset::Side, scene::CameraPreset::ThreeQuarter,
        scene::CameraPreset::Face}) {
    RendererOptions o;
    o.samples = 0;
    Renderer r(o);
    const scene::DrawList list = skinOnly(preset, 200, 160);
    const RenderStats stats = r.render(list);
    EXPECT_EQ(stats.skinTriangles, critter().skin.numTriangles());
    const Image img = r.readPixels();
    ASSERT_EQ(img.width, 200);
    ASSERT_EQ(img.height, 160);
    const std::vector<std::uint8_t> expect = cpuSilhouette(critter(), frame_, list.camera);
    const float bg[3] = {list.background.x(), list.background.y(), list.background.z()};
    std::int64_t both = 0, either = 0, expected = 0;
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x) {
        const bool gpu = differsFrom(img, x, y, bg, 2);
        const bool cpu = expect[static_cast<std::size_t>(y * img.width + x)] != 0;
        both += gpu && cpu;
        either += gpu || cpu;
        expected += cpu;
      }
    ASSERT_GT(expected, 500) << scene::cameraPresetName(preset);
    // Intersection over union of the rendered and the projected silhouettes.
    EXPECT_GT(static_cast<double>(both) / static_cast<double>(either), 0.97)
        << scene::cameraPresetName(preset);
  }
}

TEST_F(RendererTest, RowsAreTopFirstAndTheBackgroundIsExact) {
  RendererOptions o;
  o.samples = 0;
  Renderer r(o);
  const scene::DrawList list = skinOnly(scene::CameraPreset::Side, 160, 160);
  r.render(list);
  const Image img = r.readPixels();
  // Z up: the lowest vertex lands on the lowest covered row and the highest (the tail tip) on the
  // highest, and the top-left corner is background, exactly.
  const float bg[3] = {list.background.x(), list.background.y(), list.background.z()};
  int lowest = -1, highest = img.height;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x)
      if (differsFrom(img, x, y, bg)) {
        lowest = std::max(lowest, y);
        highest = std::min(highest, y);
      }
  ASSERT_GE(lowest, 0);
  const Eigen::Matrix4f vp = list.camera.viewProjection();
  auto row = [&](const Eigen::Vector3f& p) {
    const Eigen::Vector4f c = vp * p.homogeneous();
    return (0.5f - c.y() / c.w() * 0.5f) * static_cast<float>(img.height);
  };
  float lowRow = 0.0f, highRow = 1e9f;
  for (const Eigen::Vector3f& p : frame_.skin.positions) {
    lowRow = std::max(lowRow, row(p));
    highRow = std::min(highRow, row(p));
  }
  EXPECT_NEAR(lowest, lowRow, 1.5);
  EXPECT_NEAR(highest, highRow, 1.5);
  const std::uint8_t* corner = img.pixel(0, 0);
  for (int c = 0; c < 3; ++c) EXPECT_EQ(corner[c], linearToSrgb8(bg[c]));
  EXPECT_EQ(corner[3], 255);
}

TEST_F(RendererTest, SkinIsLitWithItsMaterialColour) {
  RendererOptions o;
  o.samples = 0;  // no edge pixels blended with the background
  Renderer r(o);
  const scene::DrawList list = skinOnly(scene::CameraPreset::ThreeQuarter, 128, 128);
  r.render(list);
  const Image img = r.readPixels();
  const float bg[3] = {list.background.x(), list.background.y(), list.background.z()};
  // Every skin pixel lies between ambient-only and fully lit (diffuse + specular), channel by
  // channel; their mean hue follows the skin colour (red > green > blue for the critter).
  const Eigen::Vector3f k = srgbToLinear(critter().skin.color);
  double sum[3] = {0, 0, 0};
  int n = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      if (!differsFrom(img, x, y, bg, 30)) continue;
      const std::uint8_t* p = img.pixel(x, y);
      for (int c = 0; c < 3; ++c) {
        const float lo = k[c] * list.light.ambient[c];
        const float hi = k[c] * list.light.ambient[c] + k[c] + list.skin.material.specular[c];
        EXPECT_GE(p[c] + 2, std::floor(test::encoded255(lo))) << x << "," << y;
        EXPECT_LE(p[c] - 2, std::ceil(test::encoded255(std::min(hi, 1.0f)))) << x << "," << y;
        sum[c] += p[c];
      }
      ++n;
    }
  ASSERT_GT(n, 1000);
  EXPECT_GT(sum[0], sum[1]);
  EXPECT_GT(sum[1], sum[2]);
}

TEST_F(RendererTest, ShadowsDarkenTheSkin) {
  RendererOptions o;
  o.samples = 0;
  Renderer r(o);
  // Light from the front, low: the head shadows the front of the body, the body the tail's base.
  auto shot = [&](bool shadows, scene::HairShading shading) {
    scene::DrawList list = skinOnly(scene::CameraPreset::Side, 200, 200, shadows);
    list.light.direction = Eigen::Vector3f(1.0f, 0.4f, 0.3f);
    list.hairShading = shading;
    r.render(list);
    return std::pair{r.readPixels(), list};
  };
  // The light's switch under the paper's shading; the physical model always draws the shadow map.
  const auto [lit, list] = shot(false, scene::HairShading::Paper);
  const auto [shadowed, unused] = shot(true, scene::HairShading::Paper);
  EXPECT_EQ(shot(false, scene::HairShading::Physical).first.rgba, shadowed.rgba);
  const float bg[3] = {list.background.x(), list.background.y(), list.background.z()};
  int skin = 0, darker = 0, brighter = 0;
  double a = 0, b = 0;
  for (int y = 0; y < lit.height; ++y)
    for (int x = 0; x < lit.width; ++x) {
      if (!differsFrom(lit, x, y, bg)) continue;
      const int p = lit.pixel(x, y)[0], q = shadowed.pixel(x, y)[0];
      ++skin;
      darker += q < p;
      brighter += q > p;
      a += test::decoded(static_cast<std::uint8_t>(p));  // light adds up in linear values
      b += test::decoded(static_cast<std::uint8_t>(q));
    }
  ASSERT_GT(skin, 2000);
  EXPECT_EQ(brighter, 0);  // a shadow only takes the key light away
  EXPECT_GT(darker, skin / 50);
  EXPECT_LT(b, a * 0.99);
  EXPECT_GT(b, a * 0.5);  // ambient remains, and most of the skin is lit
}

TEST_F(RendererTest, RenderingIsDeterministic) {
  Renderer r;
  const scene::DrawList list = skinOnly(scene::CameraPreset::Front, 96, 96, true);
  r.render(list);
  const Image a = r.readPixels();
  r.render(list);
  const Image b = r.readPixels();
  Renderer r2;
  r2.render(list);
  const Image c = r2.readPixels();
  EXPECT_TRUE(test::sameImage(a, b));
  EXPECT_TRUE(test::sameImage(a, c));
}

TEST_F(RendererTest, PngRoundTrip) {
  Renderer r;
  r.render(skinOnly(scene::CameraPreset::Front, 64, 48));
  const Image a = r.readPixels();
  test::TempDir dir;
  writePng(dir.file("a.png"), a);
  const Image b = readPng(dir.file("a.png"));
  EXPECT_EQ(b.width, 64);
  EXPECT_EQ(b.height, 48);
  EXPECT_TRUE(test::sameImage(a, b));
  EXPECT_THROW(readPng(dir.file("missing.png")), InputError);
  EXPECT_THROW(writePng(dir.file("no/such/dir/a.png"), a), InputError);
}

}  // namespace
}  // namespace pelage::render
