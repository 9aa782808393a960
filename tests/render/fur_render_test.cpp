// Image statistics of rendered fur (llvmpipe): fur pixels carry the coat's material colour, the
// creature covers the expected area, distance culling halves the drawn hairs at twice the distance,
// and the drawing options (strands and their coverage, tubes, shadows, CPU vs GPU hairs) do what
// they say.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <vector>

#include "pelage/fur/preset.h"
#include "pelage/render/hair_vertex_buffers.h"
#include "pelage/render/renderer.h"
#include "pelage/scene/draw_list.h"
#include "pelage/scene/frame.h"
#include "support/gl.h"

namespace pelage::render {
namespace {

const scene::Model& critter() {
  return test::sceneCritter();
}

// fig9's colours with no specular term, so every lit fur pixel is Ka La + Kd t, t in [0, 1]: its
// green/red ratio is exactly the diffuse colour's (0.14 / 0.3) and it has no blue.
fur::FurParams testFur(double hairs) {
  fur::FurParams p = fur::loadFurPreset("fig9");
  p.setHairCount(hairs);
  for (fur::CoatParams& c : p.coats) c.material.specular = Eigen::Vector3f::Zero();
  p.culling.enabled = false;
  return p;
}

// The key light alone: no shadow map, no self-shadowing (the tests of those turn them on).
scene::Light plainLight(bool shadows = false, bool selfShadowing = false,
                        float fibreOpacity = 1.0f) {
  scene::Light l;
  l.shadows = shadows;
  l.selfShadowing = selfShadowing;
  l.fibreOpacity = fibreOpacity;  // opaque fibres unless asked: the shadow's geometry alone
  return l;
}

// Ambient light alone, bright enough for the coat's ambient to use 8 bits well.
scene::Light brightAmbient() {
  scene::Light l = plainLight();
  l.color.setZero();
  l.ambient = Eigen::Vector3f::Constant(3.0f);
  return l;
}

// A black skin: the pixels over it are the strands' alone.
Material blackSkin() {
  Material m;
  m.ambient = m.diffuse = m.specular = Eigen::Vector3f::Zero();
  return m;
}

// The default look's drawing options: GPU hairs, the physical fur model (transparent strands).
scene::DrawOptions physicalLook() {
  scene::DrawOptions o;
  o.hairSource = scene::HairSource::Gpu;
  o.hairShading = scene::HairShading::Physical;
  return o;
}

// The physical look's side-lit tests: pale hairs (diffuse 0.8) whose normals twist by
// normalRandomize (sec. 3.7), and the key light from the camera's side, a little above, across
// the view, with the fur's shadow (fibre opacity 0.1).
fur::FurParams paleFur(float normalRandomize) {
  fur::FurParams params = testFur(30000);
  for (fur::CoatParams& c : params.coats) {
    c.material.diffuse = Eigen::Vector3f::Constant(0.8f);
    c.normalRandomize = normalRandomize;
  }
  return params;
}
scene::Light sideLight(const scene::Camera& cam) {
  const Eigen::Vector3f toEye = (cam.eye - cam.target).normalized();
  scene::Light side = plainLight(false, true, 0.1f);
  side.direction =
      (toEye.cross(Eigen::Vector3f::UnitZ()).normalized() + 0.3f * Eigen::Vector3f::UnitZ())
          .normalized();
  return side;
}

// The share of the ambient the physical model's coat keeps (lighting.glsl's k_a).
constexpr float kCoatAmbient = 0.722f;
// The physical model's grazing ambient (renderer.cpp's k_g).
constexpr float kCoatGrazing = 0.412f;

// The physical model's coat albedo A = c^0.7 (1 - 0.2 c) (lighting.glsl's g and k_p) of a linear
// colour.
Eigen::Vector3f coatAlbedo(const Eigen::Vector3f& c) {
  return (c.array().pow(0.7f) * (1.0f - 0.2f * c.array())).matrix();
}

// Linear luminance of a linear colour, and of a read-back (sRGB-encoded) pixel.
double luminance(const Eigen::Vector3f& c) {
  return 0.2126 * c.x() + 0.7152 * c.y() + 0.0722 * c.z();
}
// A read-back (sRGB-encoded) pixel's linear colour.
Eigen::Vector3f linearPixel(const std::uint8_t* p) {
  return Eigen::Vector3f(test::decoded(p[0]), test::decoded(p[1]), test::decoded(p[2]));
}
double luminance(const std::uint8_t* p) {
  return luminance(linearPixel(p));
}

struct Shot {
  Image image;
  std::int64_t drawn = 0;
  scene::DrawList list;
};

class FurRenderTest : public test::GlTest {
 protected:
  void SetUp() override {
    test::GlTest::SetUp();
    if (HasFatalFailure()) return;
    scene::evaluateFrame(critter(), anatomy::restPose(critter().body), frame_);
  }

  Shot render(const scene::Fur* fur, const scene::Camera& cam, scene::DrawOptions opt = {},
              const scene::Light& light = plainLight(), Renderer* reuse = nullptr,
              const Material* skin = nullptr) {
    if (fur)
      scene::evaluateFur(critter(), *fur, cam, opt.hairSource == scene::HairSource::Cpu, frame_);
    Shot s;
    if (skin)
      scene::buildDrawList(critter(), frame_, fur, cam, light, opt, *skin, s.list);
    else
      scene::buildDrawList(critter(), frame_, fur, cam, light, opt, s.list);
    RendererOptions ro;
    ro.samples = 0;
    Renderer local(ro);
    Renderer& r = reuse ? *reuse : local;
    s.drawn = r.render(s.list).hairsDrawn;
    s.image = r.readPixels();
    return s;
  }

  // render()'s frame through r read back with straight alpha (0 where nothing is drawn).
  Image straight(const scene::Fur* fur, const scene::Camera& cam, const scene::DrawOptions& opt,
                 const scene::Light& light, Renderer& r, const Material* skin) {
    render(fur, cam, opt, light, &r, skin);
    return r.readPixels(FrameAlpha::Straight);
  }

  scene::Camera camera(scene::CameraPreset preset, int size, const scene::Fur& fur) {
    const scene::Framing fr =
        scene::framingOf(critter(), frame_, scene::maxHairLength(critter(), fur.params));
    return scene::presetCamera(fr, preset, size, size);
  }

  // The frames of `fur` over a black skin (the pixels are the strands' alone) lit by `on` and by
  // `off` (the same light with one term off), and the bare skin's.
  struct OnAndOff {
    Image bare, on, off;
  };
  OnAndOff onBlackSkin(const scene::Fur& fur, const scene::Camera& cam,
                       const scene::DrawOptions& opt, const scene::Light& on,
                       const scene::Light& off) {
    const Material black = blackSkin();
    RendererOptions ro;
    ro.samples = 0;
    Renderer r(ro);
    render(nullptr, cam, opt, off, &r, &black);
    OnAndOff f;
    f.bare = r.readPixels(FrameAlpha::Straight);
    f.on = render(&fur, cam, opt, on, &r, &black).image;
    f.off = render(&fur, cam, opt, off, &r, &black).image;
    return f;
  }

  scene::FrameState frame_;
};

// testFur's hairs as stiff as the paper lets them be (floppiness 0.02): they stand near the skin's
// normal.
fur::FurParams stiffFur() {
  fur::FurParams params = testFur(30000);
  for (fur::CoatParams& c : params.coats) c.stiffness = 0.98f;
  return params;
}

// Whether the whole (2 radius + 1)^2 neighbourhood of pixel (x, y) is skin in the bare frame.
bool skinAround(const Image& bare, int x, int y, int radius) {
  for (int dy = -radius; dy <= radius; ++dy)
    for (int dx = -radius; dx <= radius; ++dx) {
      const int u = std::clamp(x + dx, 0, bare.width - 1);
      const int v = std::clamp(y + dy, 0, bare.height - 1);
      if (bare.pixel(u, v)[3] == 0) return false;
    }
  return true;
}

bool samePixel(const Image& a, const Image& b, int x, int y) {
  const std::uint8_t* p = a.pixel(x, y);
  const std::uint8_t* q = b.pixel(x, y);
  return p[0] == q[0] && p[1] == q[1] && p[2] == q[2];
}

TEST_F(FurRenderTest, FurPixelsHaveTheCoatColour) {
  const scene::Fur fur = scene::growFur(critter(), testFur(30000));
  for (const scene::HairShading shading :
       {scene::HairShading::Paper, scene::HairShading::KajiyaKay}) {
    SCOPED_TRACE(scene::hairShadingName(shading));
    const scene::Camera cam = camera(scene::CameraPreset::Side, 320, fur);
    scene::DrawOptions withFur;
    withFur.hairSource = scene::HairSource::Gpu;
    withFur.hairShading = shading;
    withFur.hairWidth = scene::HairWidth::Lines;  // opaque: each fur pixel is one hair's colour
    const Shot hairy = render(&fur, cam, withFur);
    const Shot bare = render(nullptr, cam, withFur);
    EXPECT_EQ(hairy.drawn, fur.roots.total());
    // Fur pixels: where the hairy image differs from the bare one.
    const Material mat = linearMaterial(fur.params.coats[0].material);
    const scene::Light light;
    const float loR = test::encoded255(mat.ambient.x() * light.ambient.x());
    const float hiR =
        test::encoded255(std::min(mat.ambient.x() * light.ambient.x() + mat.diffuse.x(), 1.0f));
    // Green over red lies between the ambient's and the diffuse's ratios (linear: fig9's typed
    // ambient = diffuse / 2 decodes to a slightly different hue).
    const float ratioD = mat.diffuse.y() / mat.diffuse.x();
    const float ratioA = mat.ambient.y() / mat.ambient.x();
    const float lo = std::min(ratioA, ratioD), hi = std::max(ratioA, ratioD);
    int furPixels = 0, lit = 0;
    double sumR = 0, sumG = 0;
    for (int y = 0; y < hairy.image.height; ++y)
      for (int x = 0; x < hairy.image.width; ++x) {
        if (samePixel(hairy.image, bare.image, x, y)) continue;
        const std::uint8_t* p = hairy.image.pixel(x, y);
        ++furPixels;
        ASSERT_GE(p[0] + 1.5f, loR) << x << "," << y;
        ASSERT_LE(p[0] - 1.5f, hiR) << x << "," << y;
        ASSERT_GE(p[1] + 1.5f, test::encoded255(lo * test::decoded(p[0]))) << x << "," << y;
        ASSERT_LE(p[1] - 1.5f, test::encoded255(hi * test::decoded(p[0]))) << x << "," << y;
        ASSERT_LE(p[2], 1) << x << "," << y;
        sumR += test::decoded(p[0]);
        sumG += test::decoded(p[1]);
        lit += p[0] > loR + 10.0f;
      }
    // Plenty of fur, and much of it lit by the key light, not only ambient.
    EXPECT_GT(furPixels, 5000);
    EXPECT_GT(lit, furPixels / 4);
    EXPECT_GT(sumG / sumR, lo - 0.01);
    EXPECT_LT(sumG / sumR, hi + 0.01);
  }
}

TEST_F(FurRenderTest, FurCoversTheSilhouetteAndAHairLengthAroundIt) {
  const scene::Fur fur = scene::growFur(critter(), testFur(30000));
  const scene::Camera cam = camera(scene::CameraPreset::ThreeQuarter, 256, fur);
  scene::DrawOptions gpu;
  gpu.hairSource = scene::HairSource::Gpu;
  const Shot hairy = render(&fur, cam, gpu);
  const Shot bare = render(nullptr, cam);
  const float bg[3] = {bare.list.background.x(), bare.list.background.y(),
                       bare.list.background.z()};
  const double skin = test::coverage(bare.image, bg), all = test::coverage(hairy.image, bg);
  EXPECT_GT(skin, 0.05);
  // Fur adds area around the skin, but not much: hairs are at most a few pixels long here.
  EXPECT_GT(all, skin * 1.05);
  EXPECT_LT(all, skin * 2.0);
  // Every covered pixel lies within the projected longest hair of the skin silhouette.
  const float hair = scene::maxHairLength(critter(), fur.params);
  const float pixelsPerMeter =
      static_cast<float>(cam.height) /
      (2.0f * std::tan(cam.fovYDegrees * 3.14159265f / 360.0f) * (cam.distance() - 0.3f));
  const int reach = static_cast<int>(std::ceil(hair * pixelsPerMeter)) + 1;
  for (int y = 0; y < hairy.image.height; ++y)
    for (int x = 0; x < hairy.image.width; ++x) {
      if (!test::differsFrom(hairy.image, x, y, bg)) continue;
      bool nearSkin = false;
      for (int dy = -reach; dy <= reach && !nearSkin; ++dy)
        for (int dx = -reach; dx <= reach && !nearSkin; ++dx) {
          const int u = x + dx, v = y + dy;
          nearSkin = u >= 0 && v >= 0 && u < bare.image.width && v < bare.image.height &&
                     test::differsFrom(bare.image, u, v, bg);
        }
      ASSERT_TRUE(nearSkin) << x << "," << y << " reach " << reach;
    }
}

// Van Gelder & Wilhelms 1997, sec. 3.3: twice the distance, half the hairs -- counted by the GPU's
// own draw commands.
TEST_F(FurRenderTest, DistanceCullingHalvesTheDrawnHairsAtTwiceTheDistance) {
  fur::FurParams p = testFur(40000);
  p.culling.enabled = true;
  const scene::Fur fur = scene::growFur(critter(), p);
  const scene::Camera base = camera(scene::CameraPreset::Side, 128, fur);
  const Eigen::Vector3f center = fur::creatureCenter(frame_.skin);
  // The distance at which this camera (its field of view and image height) draws every hair: the
  // creature's scale on screen there is the reference camera's (fur/culling.h).
  const float ref =
      fur::referenceDistance(fur.params) *
      fur::pixelsPerMeter(1.0f, base.fovYDegrees, base.height) /
      fur::pixelsPerMeter(1.0f, fur.params.culling.fovYDegrees, fur.params.culling.referenceHeight);
  RendererOptions ro;
  ro.samples = 0;
  Renderer r(ro);
  scene::DrawOptions gpu;
  gpu.hairSource = scene::HairSource::Gpu;
  auto drawnAt = [&](float distance) {
    scene::Camera cam = base;
    cam.eye = center + (base.eye - center).normalized() * distance;
    cam.farMeters = distance * 2.0f;
    const Shot s = render(&fur, cam, gpu, plainLight(), &r);
    const std::int64_t gpuCount =
        r.coatBuffers(0).drawnHairsOnGpu() + r.coatBuffers(1).drawnHairsOnGpu();
    EXPECT_EQ(gpuCount, s.drawn);
    return gpuCount;
  };
  for (const float d : {2.0f * ref, 4.0f * ref}) {
    const double ratio = static_cast<double>(drawnAt(d)) / static_cast<double>(drawnAt(2.0f * d));
    EXPECT_NEAR(ratio, 2.0, 0.08) << d;
  }
  EXPECT_EQ(drawnAt(0.5f * ref), fur.roots.total());
}

// The summed difference from the bare skin's image over the pixels (0..255 per channel).
double ink(const Image& a, const Image& bare) {
  double sum = 0;
  for (std::size_t i = 0; i < a.rgba.size(); ++i)
    if (i % 4 != 3) sum += std::abs(int(a.rgba[i]) - int(bare.rgba[i]));
  return sum;
}

TEST_F(FurRenderTest, StrandsTubesAndShadowsDrawWhatTheySay) {
  // Sparse fur, so that hairs rarely overlap and each one's width shows.
  fur::FurParams p = testFur(3000);
  const scene::Fur fur = scene::growFur(critter(), p);
  const scene::Camera cam = camera(scene::CameraPreset::Side, 300, fur);
  // The paper's shading, whose shadow map is the light's switch (the physical model always draws
  // it: PhysicalFurIsThePalerCoatAlbedoShadedByTheBody).
  scene::DrawOptions paper;
  paper.hairShading = scene::HairShading::Paper;
  const Shot bare = render(nullptr, cam, paper);
  auto furPixels = [&](const Shot& s) {
    int n = 0;
    for (int y = 0; y < s.image.height; ++y)
      for (int x = 0; x < s.image.width; ++x) n += samePixel(s.image, bare.image, x, y) ? 0 : 1;
    return n;
  };
  scene::DrawOptions lines = paper;
  lines.hairSource = scene::HairSource::Gpu;
  lines.hairWidth = scene::HairWidth::Lines;
  const int lineCount = furPixels(render(&fur, cam, lines));
  // Opaque strands of several pixels at the root cover more than lines.
  const float metresPerPixel = (cam.eye - cam.target).norm() * 2.0f *
                               std::tan(0.5f * cam.fovYDegrees * 3.14159265f / 180.0f) /
                               static_cast<float>(cam.height);
  scene::Fur wide = fur;
  for (fur::CoatParams& c : wide.params.coats) c.width = {4e3f * metresPerPixel, 0.0f};
  scene::DrawOptions opaque = lines;
  opaque.hairWidth = scene::HairWidth::Strands;
  opaque.transparency = false;
  EXPECT_GT(furPixels(render(&wide, cam, opaque)), lineCount * 1.4);  // 4 px at the root
  // Transparent strands narrower than a pixel: alpha is the coverage, so the ink (the summed
  // difference from the bare skin) is proportional to the width: twice as wide, twice the ink
  // (the hairs of this sparse coat seldom overlap), and far less than 1-pixel lines leave.
  scene::DrawOptions transparent = opaque;
  transparent.transparency = true;
  std::array<double, 2> inks{};
  for (int k = 0; k < 2; ++k) {
    scene::Fur thin = fur;
    for (fur::CoatParams& c : thin.params.coats)
      c.width = {1e3f * metresPerPixel * 0.1f * float(k + 1),
                 1e3f * metresPerPixel * 0.1f * float(k + 1)};
    inks[static_cast<std::size_t>(k)] = ink(render(&thin, cam, transparent).image, bare.image);
  }
  EXPECT_NEAR(inks[1] / inks[0], 2.0, 0.2);
  EXPECT_LT(inks[1], 0.5 * ink(render(&fur, cam, lines).image, bare.image));
  // Tubes: triangles around each hair; visible from here.
  scene::Fur tubes = fur;
  for (fur::CoatParams& c : tubes.params.coats) {
    c.style = fur::HairStyle::Tube;
    c.width = {3.0f, 0.15f};
  }
  const Shot tubeShot = render(&tubes, cam, lines);
  EXPECT_GT(furPixels(tubeShot), lineCount / 2);
  // Shadows: the fur darkens (fur and skin shadow each other) and so does the skin.
  const Shot lit = render(&fur, cam, lines, plainLight(false));
  const Shot shadowed = render(&fur, cam, lines, plainLight(true));
  const float bg[3] = {lit.list.background.x(), lit.list.background.y(), lit.list.background.z()};
  double a = 0, b = 0;
  int darker = 0, brighter = 0;
  for (int y = 0; y < lit.image.height; ++y)
    for (int x = 0; x < lit.image.width; ++x) {
      if (!test::differsFrom(lit.image, x, y, bg)) continue;
      const int u = lit.image.pixel(x, y)[0], q = shadowed.image.pixel(x, y)[0];
      a += u;
      b += q;
      darker += q < u;
      brighter += q > u;
    }
  EXPECT_EQ(brighter, 0);  // a shadow only takes light away
  EXPECT_GT(darker, 500);
  EXPECT_LT(b, a * 0.98);
}

// The mean decoded (linear) red of the pixels where `s` differs from `bare`, and their count.
std::pair<double, int> furMean(const Image& s, const Image& bare) {
  double sum = 0;
  int n = 0;
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x)
      if (!samePixel(s, bare, x, y)) {
        sum += test::decoded(s.pixel(x, y)[0]);
        ++n;
      }
  return {n > 0 ? sum / n : 0.0, n};
}

TEST_F(FurRenderTest, SelfShadowingDarkensTheCoatInsideAndTheSkinUnderIt) {
  const scene::Fur fur = scene::growFur(critter(), testFur(30000));
  const scene::Camera cam = camera(scene::CameraPreset::Side, 320, fur);
  scene::DrawOptions lines;  // opaque 1-pixel hairs: each fur pixel is one hair's colour
  lines.hairSource = scene::HairSource::Gpu;
  lines.hairWidth = scene::HairWidth::Lines;
  lines.hairShading = scene::HairShading::Paper;  // no skin shadow map (the physical model's is on)
  const Shot bare = render(nullptr, cam, lines);
  const Shot off = render(&fur, cam, lines, plainLight(false, false));
  const Shot on = render(&fur, cam, lines, plainLight(false, true));
  // The shadow only takes key light away: no pixel gets brighter, and the coat and the skin
  // between its hairs darken.
  const float bg[3] = {bare.list.background.x(), bare.list.background.y(),
                       bare.list.background.z()};
  int brighter = 0;
  double furOff = 0, furOn = 0, skinOff = 0, skinOn = 0;
  int furN = 0, skinN = 0;
  for (int y = 0; y < on.image.height; ++y)
    for (int x = 0; x < on.image.width; ++x) {
      const int a = off.image.pixel(x, y)[0], b = on.image.pixel(x, y)[0];
      brighter += b > a + 1;
      if (samePixel(off.image, bare.image, x, y)) {
        // No hair drawn here: the bare skin (or the background), under the fur's shadow.
        if (!test::differsFrom(bare.image, x, y, bg)) continue;
        skinOff += test::decoded(static_cast<std::uint8_t>(a));
        skinOn += test::decoded(static_cast<std::uint8_t>(b));
        ++skinN;
      } else {
        furOff += test::decoded(static_cast<std::uint8_t>(a));
        furOn += test::decoded(static_cast<std::uint8_t>(b));
        ++furN;
      }
    }
  EXPECT_EQ(brighter, 0);
  ASSERT_GT(furN, 5000);
  ASSERT_GT(skinN, 500);
  std::printf("self-shadowing: fur %.3f, skin %.3f of the unshadowed light\n", furOn / furOff,
              skinOn / skinOff);
  // (This critter's coat is sparse: 30,000 hairs, 0.86 and 0.85 measured.)
  EXPECT_LT(furOn, 0.96 * furOff) << furOn / furOff;
  EXPECT_LT(skinOn, 0.95 * skinOff) << skinOn / skinOff;
  // The shadow is of the hairs' coverage: half as wide hairs cast a lighter shadow.
  scene::Fur thin = fur;
  for (fur::CoatParams& c : thin.params.coats)
    c.width = {0.5f * c.width.rootMm, 0.5f * c.width.tipMm};
  const Shot thinOn = render(&thin, cam, lines, plainLight(false, true));
  EXPECT_GT(furMean(thinOn.image, bare.image).first, furMean(on.image, bare.image).first * 1.02);
  // Fibres that pass most of the light on (the default, Light::fibreOpacity 0.1) shadow less,
  // and not at all at 0.
  const Shot translucent = render(&fur, cam, lines, plainLight(false, true, 0.1f));
  const Shot clear = render(&fur, cam, lines, plainLight(false, true, 0.0f));
  auto light = [](const Image& img) {  // the decoded red of every pixel
    double sum = 0;
    for (std::size_t i = 0; i < img.rgba.size(); i += 4) sum += test::decoded(img.rgba[i]);
    return sum;
  };
  const double shadowed = light(off.image) - light(on.image);
  const double lighter = light(off.image) - light(translucent.image);
  std::printf("fibre opacity 0.1: %.3f of the opaque fibres' shadow\n", lighter / shadowed);
  EXPECT_GT(lighter, 0.0);
  EXPECT_LT(lighter, 0.5 * shadowed);
  EXPECT_EQ(clear.image.rgba, off.image.rgba);
}

// Plain key lights 0.3 up from the camera's side of the creature (front) and from its far side
// (back).
std::pair<scene::Light, scene::Light> frontAndBackLights(const scene::Camera& cam) {
  const Eigen::Vector3f toEye = (cam.eye - cam.target).normalized();
  const Eigen::Vector3f up = Eigen::Vector3f::UnitZ();
  scene::Light front = plainLight(), back = plainLight();
  front.direction = (toEye + 0.3f * up).normalized();
  back.direction = (-toEye + 0.3f * up).normalized();
  return {front, back};
}

TEST_F(FurRenderTest, MarschnerLobesWearTheHairColourAndScatterForward) {
  // No specular colour: R and TRT vanish, TT and the scattered term wear the hair's colour.
  const scene::Fur fur = scene::growFur(critter(), testFur(30000));
  const scene::Camera cam = camera(scene::CameraPreset::Side, 320, fur);
  scene::DrawOptions opt;
  opt.hairSource = scene::HairSource::Gpu;
  opt.hairWidth = scene::HairWidth::Lines;
  const auto [front, back] = frontAndBackLights(cam);
  std::array<double, 2> ratio{};
  for (const scene::HairShading shading :
       {scene::HairShading::KajiyaKay, scene::HairShading::Marschner}) {
    SCOPED_TRACE(scene::hairShadingName(shading));
    opt.hairShading = shading;
    const Shot lit = render(&fur, cam, opt, front), bareLit = render(nullptr, cam, opt, front);
    const Shot backlit = render(&fur, cam, opt, back), bareBack = render(nullptr, cam, opt, back);
    if (shading == scene::HairShading::Marschner) {
      const Material mat = linearMaterial(fur.params.coats[0].material);
      const float lo =
          std::min(mat.ambient.y() / mat.ambient.x(), mat.diffuse.y() / mat.diffuse.x());
      const float hi =
          std::max(mat.ambient.y() / mat.ambient.x(), mat.diffuse.y() / mat.diffuse.x());
      for (const Shot* s : {&lit, &backlit})
        for (int y = 0; y < s->image.height; ++y)
          for (int x = 0; x < s->image.width; ++x) {
            if (samePixel(s->image, (s == &lit ? bareLit : bareBack).image, x, y)) continue;
            const std::uint8_t* p = s->image.pixel(x, y);
            if (p[0] == 255) continue;  // clipped
            ASSERT_GE(p[1] + 1.5f, test::encoded255(lo * test::decoded(p[0]))) << x << "," << y;
            ASSERT_LE(p[1] - 1.5f, test::encoded255(hi * test::decoded(p[0])))
                << x << "," << y << " " << int(p[0]) << " " << int(p[1]) << " " << int(p[2])
                << (s == &lit ? " front" : " back");
            ASSERT_LE(p[2], 1) << x << "," << y;
          }
    }
    const double f = furMean(lit.image, bareLit.image).first;
    const double b = furMean(backlit.image, bareBack.image).first;
    ratio[shading == scene::HairShading::Marschner ? 1 : 0] = b / f;
  }
  // Kajiya-Kay's diffuse is the same from either side (sin(T, L) is); Marschner's TT lobe sends
  // light through the hairs towards the eye when the light is behind them.
  std::printf("backlit / front-lit coat: Kajiya-Kay %.3f, Marschner %.3f\n", ratio[0], ratio[1]);
  // (The two lights mirror each other only across the vertical plane: both are 0.3 up.)
  EXPECT_NEAR(ratio[0], 1.0, 0.25);
  EXPECT_GT(ratio[1], 1.4 * ratio[0]) << ratio[1] << " vs " << ratio[0];  // 1.55 vs 0.85
}

TEST_F(FurRenderTest, PhysicalFurIsThePalerCoatAlbedoShadedByTheBody) {
  const scene::Fur fur = scene::growFur(critter(), testFur(30000));
  const scene::Camera cam = camera(scene::CameraPreset::Side, 320, fur);
  scene::DrawOptions opt = physicalLook();
  {
    // Ambient light alone, 1-pixel lines (no tangent: the coat term only): every fur pixel is
    // k_a La A exactly (lighting.glsl: k_a = 0.722, A = c^0.7 (1 - 0.2 c)), c the coat's linear
    // diffuse colour.
    SCOPED_TRACE("ambient alone");
    opt.hairWidth = scene::HairWidth::Lines;
    scene::Light dark = plainLight();
    dark.color = Eigen::Vector3f::Zero();
    const Shot s = render(&fur, cam, opt, dark), bare = render(nullptr, cam, opt, dark);
    const Material mat = linearMaterial(fur.params.coats[0].material);
    const Eigen::Vector3f albedo = coatAlbedo(mat.diffuse);
    std::array<float, 3> want{};
    for (int c = 0; c < 3; ++c)
      want[static_cast<std::size_t>(c)] =
          test::encoded255(kCoatAmbient * dark.ambient[c] * albedo[c]);
    int n = 0;
    for (int y = 0; y < s.image.height; ++y)
      for (int x = 0; x < s.image.width; ++x) {
        if (samePixel(s.image, bare.image, x, y)) continue;
        ++n;
        const std::uint8_t* p = s.image.pixel(x, y);
        for (int c = 0; c < 3; ++c)
          ASSERT_NEAR(p[c], want[static_cast<std::size_t>(c)], 1.5) << x << "," << y << " " << c;
      }
    EXPECT_GT(n, 2000);
  }
  // Strands lit from behind the creature: the body's shadow map (always on with this model) keeps
  // the fibres' forward scattering from lighting the coat through the body, so the coat seen from
  // the light's far side is darker than front-lit, where Marschner's without the shadow map is
  // brighter (MarschnerLobesWearTheHairColourAndScatterForward).
  opt.hairWidth = scene::HairWidth::Strands;
  const auto [front, back] = frontAndBackLights(cam);
  const double f =
      furMean(render(&fur, cam, opt, front).image, render(nullptr, cam, opt, front).image).first;
  const double b =
      furMean(render(&fur, cam, opt, back).image, render(nullptr, cam, opt, back).image).first;
  std::printf("physical: backlit / front-lit coat %.3f\n", b / f);
  EXPECT_LT(b, 0.92 * f);  // 0.78 on llvmpipe; Marschner without the shadow map: 1.55
}

TEST_F(FurRenderTest, PhysicalCoatSpreadsItsLightIntoTheBodysShadow) {
  // A pale coat lit from the side, across the view: the body's shadow edge runs through the coat
  // seen, and the coat's light is mostly the key light's.
  fur::FurParams params = testFur(30000);
  for (fur::CoatParams& c : params.coats) c.material.diffuse = Eigen::Vector3f::Constant(0.8f);
  const scene::Fur fur = scene::growFur(critter(), params);
  const scene::Camera cam = camera(scene::CameraPreset::Side, 320, fur);
  const scene::DrawOptions opt = physicalLook();  // transparent strands: the default
  scene::Light side = sideLight(cam);
  side.coatSpreadSkinNormal = 0.0f;  // the spread alone (the next test has the skin's normal)
  const Shot bare = render(nullptr, cam, opt, side);
  scene::Light still = side;
  still.coatSpread = 0.0f;
  const Shot a = render(&fur, cam, opt, still), b = render(&fur, cam, opt, side);
  // Linear luminance of the fur pixels (those the coat changes), with and without the spread.
  const auto lum = [](const Image& im, int x, int y) { return luminance(im.pixel(x, y)); };
  std::vector<std::pair<double, double>> pixels;
  double lapA = 0, lapB = 0;
  int inner = 0;
  const int w = a.image.width, h = a.image.height;
  for (int y = 1; y + 1 < h; ++y)
    for (int x = 1; x + 1 < w; ++x) {
      if (samePixel(a.image, bare.image, x, y)) continue;
      pixels.emplace_back(lum(a.image, x, y), lum(b.image, x, y));
      bool allFur = true;
      for (const auto& [dx, dy] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}})
        allFur = allFur && !samePixel(a.image, bare.image, x + dx, y + dy);
      if (!allFur) continue;
      const auto lap = [&](const Image& im) {
        return std::abs(4 * lum(im, x, y) - lum(im, x + 1, y) - lum(im, x - 1, y) -
                        lum(im, x, y + 1) - lum(im, x, y - 1));
      };
      lapA += lap(a.image);
      lapB += lap(b.image);
      ++inner;
    }
  ASSERT_GT(inner, 5000);
  // The darkest fifth without the spread (the coat in the body's shadow) gets light from the lit
  // coat beside it, more than the coat's mean, and the pixel-to-pixel contrast falls (llvmpipe:
  // x 1.029 against the mean's x 0.999, and x 0.79).
  std::sort(pixels.begin(), pixels.end());
  const std::size_t n = pixels.size(), k = n / 5;
  double darkA = 0, darkB = 0, allA = 0, allB = 0;
  for (std::size_t i = 0; i < n; ++i) {
    allA += pixels[i].first;
    allB += pixels[i].second;
    if (i < k) darkA += pixels[i].first, darkB += pixels[i].second;
  }
  std::printf("coat spread: darkest fifth x %.3f, mean x %.3f, Laplacian x %.3f\n", darkB / darkA,
              allB / allA, lapB / lapA);
  EXPECT_GT(darkB / darkA, 1.02 * allB / allA);
  EXPECT_LT(lapB, 0.9 * lapA);
  // The kept (0.138) and spread (0.607) shares of the coat's direct light: about as much light in
  // all.
  EXPECT_NEAR(allB / allA, 1.0, 0.15);
}

TEST_F(FurRenderTest, PhysicalCoatSpreadLightFollowsTheSkinsNormal) {
  // Pale hairs whose own normals are twisted every way about them (sec. 3.7, normalRandomize 1),
  // lit from the side as above: the light the coat spreads takes the skin's N.L
  // (Light::coatSpreadSkinNormal = 1) instead of the hairs' own, so the coat's light fades beyond
  // the body's terminator as the skin's does. Over a black skin (the pixels are the strands'
  // alone); the bare skin lit alike (white) gives each pixel the skin's light.
  const scene::Fur fur = scene::growFur(critter(), paleFur(1.0f));
  const scene::Camera cam = camera(scene::CameraPreset::Side, 320, fur);
  const scene::DrawOptions opt = physicalLook();
  scene::Light skin = sideLight(cam);
  skin.ambient.setZero();
  scene::Light own = skin;
  own.coatSpreadSkinNormal = 0.0f;
  Material white = blackSkin();
  white.diffuse.setOnes();
  const Material black = blackSkin();
  const Shot bare = render(nullptr, cam, opt, skin, nullptr, &white);
  const Shot a = render(&fur, cam, opt, own, nullptr, &black);
  const Shot b = render(&fur, cam, opt, skin, nullptr, &black);
  // The strands' light where the skin faces the light (the white skin's light over 0.6) and beyond
  // its terminator (under 0.02), where the skin's normal turns from the light and the hairs' own
  // normals, twisted every way, still catch it.
  double facingA = 0, facingB = 0, edgeA = 0, edgeB = 0;
  int facing = 0, edge = 0;
  for (int y = 0; y < a.image.height; ++y)
    for (int x = 0; x < a.image.width; ++x) {
      const double l = luminance(bare.image.pixel(x, y));
      if (bare.image.pixel(x, y)[3] != 255 || (l >= 0.02 && l < 0.6)) continue;
      const double la = luminance(a.image.pixel(x, y)), lb = luminance(b.image.pixel(x, y));
      if (l >= 0.6)
        facingA += la, facingB += lb, ++facing;
      else
        edgeA += la, edgeB += lb, ++edge;
    }
  ASSERT_GT(facing, 1000);
  ASSERT_GT(edge, 1000);
  const double ratioA = (facingA / facing) / (edgeA / edge);
  const double ratioB = (facingB / facing) / (edgeB / edge);
  std::printf(
      "coat spread by the skin's normal: facing the light / beyond the terminator x %.3f "
      "(hairs' normals) -> x %.3f; facing x %.3f, beyond the terminator x %.3f\n",
      ratioA, ratioB, facingB / facingA, edgeB / edgeA);
  // llvmpipe: x 27.5 -> x 34.2; facing x 1.000, beyond the terminator x 0.806.
  EXPECT_GT(ratioB, 1.1 * ratioA);
  EXPECT_LT(edgeB, 0.9 * edgeA);
  EXPECT_NEAR(facingB / facingA, 1.0, 0.1);
}

TEST_F(FurRenderTest, PhysicalFibreLightStopsAtTheBodysTerminator) {
  // Lit from the side, the fibre part's light (lighting.glsl's t) fades out where the hairs'
  // normals turn from the light (N.L from 0.1 down to -0.3) over the skin: well beyond the body's
  // terminator (N.L under -0.6: the bare skin lit from the other side, -L, at 0.6 of its
  // brightest or more) the fibres keep less of the light they scatter where the skin faces the
  // light (what is left there, hairs from nearer the light seen over that skin), while the fringe
  // beyond the skin's outline keeps its light. (lighting_glsl_test.cpp checks t itself.)
  const scene::Fur fur = scene::growFur(critter(), paleFur(0.0f));
  const scene::Camera cam = camera(scene::CameraPreset::Side, 320, fur);
  scene::Light side = sideLight(cam);
  side.ambient.setZero();
  scene::DrawOptions opt = physicalLook();
  Material white = blackSkin();
  white.diffuse.setOnes();
  const Material black = blackSkin();
  RendererOptions ro;
  ro.samples = 0;
  Renderer r(ro);
  const Image bare = straight(nullptr, cam, opt, side, r, &white);
  scene::Light other = side;
  other.direction = -side.direction;
  const Image away = straight(nullptr, cam, opt, other, r, &white);
  opt.lightPass = scene::LightPass::Fibre;
  const Image fibre = straight(&fur, cam, opt, side, r, &black);
  double brightest = 0, brightestAway = 0;
  for (int y = 0; y < bare.height; ++y)
    for (int x = 0; x < bare.width; ++x)
      if (bare.pixel(x, y)[3] == 255) {
        brightest = std::max(brightest, luminance(bare.pixel(x, y)));
        brightestAway = std::max(brightestAway, luminance(away.pixel(x, y)));
      }
  double facing = 0, beyond = 0, fringe = 0;
  int nFacing = 0, nBeyond = 0, nFringe = 0;
  for (int y = 0; y < bare.height; ++y)
    for (int x = 0; x < bare.width; ++x) {
      const std::uint8_t* f = fibre.pixel(x, y);
      const double lf = luminance(f) * f[3] / 255.0;  // premultiplied
      if (bare.pixel(x, y)[3] == 0) {
        if (f[3] > 0) fringe += lf, ++nFringe;
        continue;
      }
      const double l = luminance(bare.pixel(x, y)) / brightest;
      if (l >= 0.5) facing += lf, ++nFacing;
      if (luminance(away.pixel(x, y)) >= 0.6 * brightestAway) beyond += lf, ++nBeyond;
    }
  ASSERT_GT(nFacing, 200);
  ASSERT_GT(nBeyond, 200);
  ASSERT_GT(nFringe, 200);
  const double lit = facing / nFacing, dark = beyond / nBeyond, out = fringe / nFringe;
  std::printf(
      "fibre light: beyond the terminator %.4f, fringe %.4f of where the skin faces the "
      "light (%.4f)\n",
      dark / lit, out / lit, lit);
  // llvmpipe: 0.154 and 1.72 (without t, 0.299 and 1.68).
  EXPECT_LT(dark, 0.22 * lit);
  EXPECT_GT(out, 1.2 * lit);
}

TEST_F(FurRenderTest, PhysicalCoatAmbientGrowsWhereTheCoatIsSeenAtAGrazingAngle) {
  // Ambient light alone on transparent strands: where no skin lies behind (the fringe) the coat is
  // all outer layer, |N.V| = 0, and gets k_a La A + k_g La A (lighting.glsl's k_a = 0.722,
  // renderer.cpp's k_g = 0.412, oit_composite.frag), 1 + k_g / k_a = 1.57 times the k_a La A of
  // coat seen face-on (a little more: the eye sees the fringe's hairs across,
  // Light::alongFibreDarkening).
  const scene::Fur fur = scene::growFur(critter(), testFur(30000));
  const scene::Camera cam = camera(scene::CameraPreset::Side, 320, fur);
  const scene::DrawOptions opt = physicalLook();
  scene::Light dark = plainLight();
  dark.color = Eigen::Vector3f::Zero();
  RendererOptions ro;
  ro.samples = 0;
  Renderer r(ro);
  render(nullptr, cam, opt, dark, &r);
  const Image bare = r.readPixels(FrameAlpha::Straight);
  render(&fur, cam, opt, dark, &r);
  const Image s = r.readPixels(FrameAlpha::Straight);
  const Material mat = linearMaterial(fur.params.coats[0].material);
  const double faceOn =
      luminance(kCoatAmbient * dark.ambient.cwiseProduct(coatAlbedo(mat.diffuse)));
  std::vector<double> fringe;
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x) {
      const std::uint8_t* p = s.pixel(x, y);
      if (bare.pixel(x, y)[3] != 0 || p[3] < 128) continue;  // skin behind, or little coverage
      fringe.push_back(luminance(p));
    }
  ASSERT_GT(fringe.size(), 200u);
  std::sort(fringe.begin(), fringe.end());
  const double median = fringe[fringe.size() / 2];
  std::printf("grazing ambient: the fringe's coat %.3f times face-on coat's k_a La A\n",
              median / faceOn);
  EXPECT_NEAR(median / faceOn, 1.0 + kCoatGrazing / kCoatAmbient, 0.15);
}

TEST_F(FurRenderTest, PhysicalCoatAmbientIsDarkerWhereTheEyeLooksAlongTheHairs) {
  // Ambient light alone, the coat's ambient k_a La A (1 + k_v (0.35 - |T.V|)) (lighting.glsl,
  // Light::alongFibreDarkening = k_v) against the same frame with k_v = 0, over a black skin (the
  // pixels are the strands' alone): every pixel's ratio lies in [1 - 0.65 k_v, 1 + 0.35 k_v].
  // Stiff hairs stand along the skin's normal: where the skin faces the eye it looks along them
  // (darker), near the outline across them (brighter).
  const scene::Fur fur = scene::growFur(critter(), stiffFur());
  const scene::Camera cam = camera(scene::CameraPreset::Side, 320, fur);
  scene::Light seen = brightAmbient(), same = brightAmbient();
  same.alongFibreDarkening = 0.0f;
  ASSERT_EQ(seen.alongFibreDarkening, 0.6f);
  const OnAndOff f = onBlackSkin(fur, cam, physicalLook(), seen, same);
  const Image &bare = f.bare, &a = f.on, &b = f.off;
  double rimA = 0, rimB = 0, innerA = 0, innerB = 0, lowest = 2, highest = 0;
  int inner = 0, bright = 0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      if (bare.pixel(x, y)[3] == 0) continue;  // the skin's pixels only (opaque)
      const double la = luminance(a.pixel(x, y)), lb = luminance(b.pixel(x, y));
      if (lb > 0.05 && lb < 0.95) {  // 8-bit rounding: at most 1.6 % there; no clipping
        ++bright;
        lowest = std::min(lowest, la / lb);
        highest = std::max(highest, la / lb);
      }
      if (skinAround(bare, x, y, 7))  // where the skin faces the eye
        innerA += la, innerB += lb, ++inner;
      else
        rimA += la, rimB += lb;
    }
  ASSERT_GT(inner, 2000);
  ASSERT_GT(bright, 1000);
  std::printf("ambient seen along the hairs: inside x%.3f, rim x%.3f, pixels x%.3f to x%.3f\n",
              innerA / innerB, rimA / rimB, lowest, highest);
  EXPECT_GT(lowest, 1.0 - 0.65 * 0.6 - 0.035);
  EXPECT_LT(highest, 1.0 + 0.35 * 0.6 + 0.035);
  EXPECT_LT(innerA / innerB, 0.9);
  EXPECT_GT(rimA / rimB, innerA / innerB + 0.1);
}

TEST_F(FurRenderTest, PhysicalCoatAmbientIsMoreSaturatedWhereTheEyeLooksAlongTheHairs) {
  // Ambient light alone, the coat's ambient colour A_v = Y(A) (A / Y(A))^k, k = 1 + k_c (|T.V| -
  // 0.35) (lighting.glsl, Light::alongFibreSaturation = k_c) against the same frame with k_c = 0,
  // over a black skin (the pixels are the strands' alone), both coats one orange: a pixel's
  // green/red ratio is A's to the power k (mixed with the grazing ambient's plain A and with other
  // strands: between A's to the powers of the lowest and the highest k), so log(g/r) / log(g/r
  // with k_c = 0) lies in [1 - 0.35 k_c, 1 + 0.65 k_c]. Stiff hairs stand along the skin's normal:
  // where the skin faces the eye it looks along them (more saturated), near the outline across
  // them (paler). A grey coat has nothing to saturate: the same frame to a level; lines (no
  // tangent) bit-identical.
  fur::FurParams params = stiffFur();
  for (fur::CoatParams& c : params.coats) c.material.diffuse = Eigen::Vector3f(0.6f, 0.3f, 0.1f);
  const scene::Fur fur = scene::growFur(critter(), params);
  const scene::Camera cam = camera(scene::CameraPreset::Side, 320, fur);
  scene::Light seen = brightAmbient();
  seen.ambient = Eigen::Vector3f::Ones();  // the reddest pixel below 1: no clipping
  scene::Light same = seen;
  same.alongFibreSaturation = 0.0f;
  const float kc = seen.alongFibreSaturation;
  ASSERT_EQ(kc, 1.25f);
  const OnAndOff f = onBlackSkin(fur, cam, physicalLook(), seen, same);
  // The power of the green/red ratio with k_c over that without.
  auto power = [](const Eigen::Vector3d& on, const Eigen::Vector3d& off) {
    return std::log(on.y() / on.x()) / std::log(off.y() / off.x());
  };
  Eigen::Vector3d innerA = Eigen::Vector3d::Zero(), innerB = innerA, rimA = innerA, rimB = innerA;
  double lowest = 9, highest = -9;
  int inner = 0, bright = 0;
  for (int y = 0; y < f.on.height; ++y)
    for (int x = 0; x < f.on.width; ++x) {
      if (f.bare.pixel(x, y)[3] == 0) continue;  // the skin's pixels only (opaque)
      const Eigen::Vector3d a = linearPixel(f.on.pixel(x, y)).cast<double>(),
                            b = linearPixel(f.off.pixel(x, y)).cast<double>();
      if (b.y() > 0.04 && a.y() > 0.04 && a.x() < 0.95) {  // 8 bits: log(g/r) within 0.05
        ++bright;
        const double k = power(a, b);
        lowest = std::min(lowest, k);
        highest = std::max(highest, k);
      }
      if (skinAround(f.bare, x, y, 7))  // where the skin faces the eye
        innerA += a, innerB += b, ++inner;
      else
        rimA += a, rimB += b;
    }
  ASSERT_GT(inner, 2000);
  ASSERT_GT(bright, 1000);
  const double kInner = power(innerA, innerB), kRim = power(rimA, rimB);
  std::printf("ambient's saturation by the hairs: inside ^%.3f, rim ^%.3f, pixels ^%.3f to ^%.3f\n",
              kInner, kRim, lowest, highest);
  EXPECT_GT(lowest, 1.0 - 0.35 * kc - 0.1);
  EXPECT_LT(highest, 1.0 + 0.65 * kc + 0.1);
  EXPECT_GT(kInner, 1.15);
  EXPECT_LT(kRim, kInner - 0.15);
  // A grey coat: the same frame to a level.
  for (fur::CoatParams& c : params.coats) c.material.diffuse = Eigen::Vector3f::Constant(0.5f);
  const scene::Fur grey = scene::growFur(critter(), params);
  const OnAndOff g = onBlackSkin(grey, cam, physicalLook(), seen, same);
  EXPECT_TRUE(test::sameImage(g.on, g.off, 1));
  // Lines: the same frame whatever k_c.
  scene::DrawOptions lines = physicalLook();
  lines.hairWidth = scene::HairWidth::Lines;
  const OnAndOff l = onBlackSkin(fur, cam, lines, seen, same);
  EXPECT_EQ(l.on.rgba, l.off.rgba);
}

TEST_F(FurRenderTest, PhysicalCoatDirectLightIsDarkerWhereTheLightRunsAlongTheHairs) {
  // The key light alone, from the eye: the coat's direct light A s Ld max(N.L, 0) l(T), l(T) =
  // max(1 + k_l (0.35 - |T.L|), 0) (lighting.glsl, Light::lightAlongFibreDarkening = k_l), against
  // the same frame with k_l = 0, over a black skin, on opaque strands (k_d = 1, nothing spread).
  // Stiff hairs stand near the skin's normal (fig9's lean: the ambient test above finds a mean
  // |T.V| of about 0.73 inside, 0.5 near the outline): where the skin faces the eye the light runs
  // along them, l = max(1 + 2 (0.35 - 0.73), 0) = 0.24 or less, and the fibre part (Chiang's
  // scattering, which k_l leaves alone: at least 0.37 of the frame with k_l = 0 there, by these
  // figures) is most of what is left (llvmpipe: x 0.525); near the outline the light crosses the
  // hairs more (x 0.68; with k_l ignored both would be x 1). Lines carry no tangent: l = 1, the
  // same frame.
  const scene::Fur fur = scene::growFur(critter(), stiffFur());
  const scene::Camera cam = camera(scene::CameraPreset::Side, 320, fur);
  scene::DrawOptions opt = physicalLook();
  opt.transparency = false;
  scene::Light caught = plainLight();
  caught.direction = (cam.eye - cam.target).normalized();
  caught.ambient.setZero();
  scene::Light same = caught;
  same.lightAlongFibreDarkening = 0.0f;
  ASSERT_EQ(caught.lightAlongFibreDarkening, 2.0f);
  const OnAndOff f = onBlackSkin(fur, cam, opt, caught, same);
  const Image &bare = f.bare, &a = f.on, &b = f.off;
  // Where the skin faces the eye (and the light): its whole 15 x 15 neighbourhood is skin; the
  // outline's ring, within 1 but not 3 pixels of it, where the skin turns away.
  double ringA = 0, ringB = 0, innerA = 0, innerB = 0;
  int inner = 0, ring = 0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      if (!skinAround(bare, x, y, 1)) continue;
      const double la = luminance(a.pixel(x, y)), lb = luminance(b.pixel(x, y));
      if (skinAround(bare, x, y, 7))
        innerA += la, innerB += lb, ++inner;
      else if (!skinAround(bare, x, y, 3))
        ringA += la, ringB += lb, ++ring;
    }
  ASSERT_GT(inner, 2000);
  ASSERT_GT(ring, 500);
  std::printf("key light along the hairs: inside x%.3f, the outline's ring x%.3f\n",
              innerA / innerB, ringA / ringB);
  EXPECT_LT(innerA / innerB, 0.65);
  EXPECT_GT(ringA / ringB, innerA / innerB + 0.1);
  // Lines: the same frame whatever k_l.
  opt.hairWidth = scene::HairWidth::Lines;
  const OnAndOff lines = onBlackSkin(fur, cam, opt, caught, same);
  EXPECT_EQ(lines.on.rgba, lines.off.rgba);
}

TEST_F(FurRenderTest, PhysicalCoatDirectLightIsDarkerSeenAgainstTheLight) {
  // The key light alone: the coat's direct light times b(V) = max(1 - k_b max(-L.V, 0), 0)
  // (lighting.glsl, Light::coatBacklitDarkening = k_b) against the same frame with k_b = 0, over a
  // black skin (the skin's pixels: the strands' alone), on opaque strands (k_d = 1, nothing
  // spread). Lit from behind and above (L.V about -0.5) the coat's light keeps about 1 - 0.5 k_b =
  // 0.65 of itself and the fibre part all of its own: no pixel brighter, the frame between 0.65
  // and 1 times (from above: the coat on the creature's back catches it). Against the light the
  // fibre part (Chiang's scattering, forward through the fibres) is nearly all of the frame, so
  // the frame keeps nearly all (llvmpipe: x 0.986; x 0.92 with the lobes before 2026-12-07). Lit
  // from the eye's side and above (L.V about 0.5) b = 1: the same frame, bit for bit.
  const scene::Fur fur = scene::growFur(critter(), testFur(30000));
  const scene::Camera cam = camera(scene::CameraPreset::Side, 320, fur);
  scene::DrawOptions opt = physicalLook();
  opt.transparency = false;
  const Eigen::Vector3f toEye = (cam.eye - cam.target).normalized();
  // Up, square to the line of sight (the side camera looks a little down).
  const Eigen::Vector3f up =
      (Eigen::Vector3f::UnitZ() - Eigen::Vector3f::UnitZ().dot(toEye) * toEye).normalized();
  scene::Light against = plainLight();
  against.direction = (-0.5f * toEye + 0.866f * up).normalized();
  against.ambient.setZero();
  scene::Light same = against;
  same.coatBacklitDarkening = 0.0f;
  ASSERT_EQ(against.coatBacklitDarkening, 0.7f);
  const OnAndOff f = onBlackSkin(fur, cam, opt, against, same);
  double sumOn = 0, sumOff = 0, highest = 0;
  int lit = 0;
  for (int y = 0; y < f.on.height; ++y)
    for (int x = 0; x < f.on.width; ++x) {
      if (f.bare.pixel(x, y)[3] == 0) continue;  // the skin's pixels only (opaque)
      const double on = luminance(f.on.pixel(x, y)), off = luminance(f.off.pixel(x, y));
      sumOn += on, sumOff += off;
      if (off > 0.05) ++lit, highest = std::max(highest, on / off);  // 8 bits: 1.6 % at most
    }
  ASSERT_GT(lit, 1000);
  std::printf("coat lit from behind: x%.3f of its light with k_b, pixels at most x%.3f\n",
              sumOn / sumOff, highest);
  EXPECT_LT(highest, 1.017);
  EXPECT_GT(sumOn / sumOff, 0.6);
  EXPECT_LT(sumOn / sumOff, 0.995);
  scene::Light facing = against, facingSame = same;
  facing.direction = facingSame.direction = (0.5f * toEye + 0.866f * up).normalized();
  const OnAndOff g = onBlackSkin(fur, cam, opt, facing, facingSame);
  EXPECT_EQ(g.on.rgba, g.off.rgba);
}

TEST_F(FurRenderTest, NearStrandsHideTheCoatsDepthsWithCoatSeenDepth) {
  // A red overcoat over a short blue undercoat (relative length 0.3) on a black skin, under ambient
  // light alone: the opaque strands (transparency off) show each pixel's nearest strand, mostly the
  // overcoat's. The transparent strands weighted by exp(d / (coatSeenDepth x hair length)), d the
  // depth in front of the skin (hair.frag), show the near strands as the opaque ones do, where
  // every strand of the coat's depth counting alike (coatSeenDepth 0) lets the undercoat's blue
  // through; the shallower the eye sees, the nearer the opaque look.
  fur::FurParams params = testFur(60000);
  params.coats[0].material.diffuse = Eigen::Vector3f(0.8f, 0.02f, 0.02f);
  params.coats[1].material.diffuse = Eigen::Vector3f(0.02f, 0.02f, 0.8f);
  ASSERT_LT(params.coats[1].lengthFactor, 0.5f);
  const scene::Fur fur = scene::growFur(critter(), params);
  const scene::Camera cam = camera(scene::CameraPreset::Side, 320, fur);
  scene::DrawOptions opt = physicalLook();
  scene::Light seen = brightAmbient(), plain = brightAmbient();
  // Dim enough that no channel of the red coat clips at 8 bits (the shares are ratios).
  seen.ambient = plain.ambient = Eigen::Vector3f::Constant(1.2f);
  plain.coatSeenDepth = 0.0f;
  ASSERT_EQ(seen.coatSeenDepth, 0.35f);
  const Material black = blackSkin();
  RendererOptions ro;
  ro.samples = 0;
  Renderer r(ro);
  const Image bare = straight(nullptr, cam, opt, plain, r, &black);
  const Image weighted = render(&fur, cam, opt, seen, &r, &black).image;
  const Image alike = render(&fur, cam, opt, plain, &r, &black).image;
  scene::Light shallow = seen;  // the eye sees a twentieth of a hair deep: nearly the opaque look
  shallow.coatSeenDepth = 0.05f;
  const Image near = render(&fur, cam, opt, shallow, &r, &black).image;
  opt.transparency = false;
  const Image opaque = render(&fur, cam, opt, seen, &r, &black).image;
  // The overcoat's share of each skin pixel's colour, red / (red + blue) in linear light, averaged.
  const auto redShare = [&](const Image& im) {
    double sum = 0;
    int n = 0;
    for (int y = 0; y < im.height; ++y)
      for (int x = 0; x < im.width; ++x) {
        if (bare.pixel(x, y)[3] == 0) continue;  // the skin's pixels: the coat's depth behind
        const std::uint8_t* p = im.pixel(x, y);
        const double red = test::decoded(p[0]), blue = test::decoded(p[2]);
        if (red + blue < 0.02) continue;
        sum += red / (red + blue);
        ++n;
      }
    EXPECT_GT(n, 2000);
    return sum / std::max(n, 1);
  };
  const double w = redShare(weighted), a = redShare(alike), o = redShare(opaque);
  const double n = redShare(near);
  std::printf(
      "the overcoat's share: opaque strands %.3f; transparent, coatSeenDepth 0.05 %.3f, "
      "0.35 %.3f, 0 %.3f\n",
      o, n, w, a);
  EXPECT_GT(o, a + 0.1);
  EXPECT_GT(w - a, 0.3 * (o - a));  // 0.39 on llvmpipe
  EXPECT_GT(n, w);
  EXPECT_LT(std::abs(n - o), 0.25 * (o - a));
}

TEST_F(FurRenderTest, CoatSeenDepthWeighsTheFringeFromTheNearestSkin) {
  // Lit from behind. Beyond the skin's outline no skin lies under a pixel; the transparent strands'
  // depth there is measured from the nearest skin within 1.5 hair lengths (renderer.cpp's
  // kFringeReach), so coatSeenDepth changes the fringe's pixels as it changes the skin's (without
  // the reach they kept the plain weights exactly, and on the reference views the light stepped at
  // the outline: a dark line along the skin's edge against the light, README).
  const scene::Fur fur = scene::growFur(critter(), testFur(60000));
  const scene::Camera cam = camera(scene::CameraPreset::Side, 320, fur);
  const scene::DrawOptions opt = physicalLook();
  scene::Light seen = frontAndBackLights(cam).second, plain = seen;
  seen.shadows = plain.shadows = true;
  seen.selfShadowing = plain.selfShadowing = true;
  seen.fibreOpacity = plain.fibreOpacity = scene::Light{}.fibreOpacity;
  plain.coatSeenDepth = 0.0f;
  RendererOptions ro;
  ro.samples = 0;
  Renderer r(ro);
  render(nullptr, cam, opt, plain, &r);
  const Image bare = r.readPixels(FrameAlpha::Straight);
  const Image a = render(&fur, cam, opt, seen, &r).image;
  const Image b = render(&fur, cam, opt, plain, &r).image;
  // Each pixel's ring about the skin's outline (4-neighbour steps): -1 the skin's edge, -2 the next
  // ring in, 1 the first ring beyond, 2 the next; 0 farther.
  const int w = bare.width, h = bare.height;
  std::vector<int> ring(static_cast<std::size_t>(w * h), 0);
  const auto at = [&](int x, int y) -> int& { return ring[static_cast<std::size_t>(y * w + x)]; };
  const auto skin = [&](int x, int y) { return bare.pixel(x, y)[3] != 0; };
  for (int k = 1; k <= 4; ++k)
    for (int y = 1; y + 1 < h; ++y)
      for (int x = 1; x + 1 < w; ++x) {
        if (at(x, y) != 0) continue;
        for (const auto& [dx, dy] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
          const bool across = skin(x + dx, y + dy) != skin(x, y);
          const int n = at(x + dx, y + dy);
          if (k == 1 ? across : (n != 0 && std::abs(n) == k - 1 && !across)) {
            at(x, y) = skin(x, y) ? -k : k;
            break;
          }
        }
      }
  // The weights' change to each ring's mean luminance: (seen - plain) per ring.
  std::array<double, 9> sum{};
  std::array<int, 9> count{};
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const int k = at(x, y);
      if (k == 0) continue;
      sum[static_cast<std::size_t>(k + 4)] += luminance(a.pixel(x, y)) - luminance(b.pixel(x, y));
      ++count[static_cast<std::size_t>(k + 4)];
    }
  std::array<double, 9> change{};
  for (std::size_t k = 0; k < 9; ++k) change[k] = count[k] ? sum[k] / count[k] : 0.0;
  std::printf("the weights' change by ring (-4 .. -1 inside, 1 .. 4 beyond):");
  for (const int k : {-4, -3, -2, -1, 1, 2, 3, 4})
    std::printf(" %+.4f", change[static_cast<std::size_t>(k + 4)]);
  std::printf("\n");
  EXPECT_GT(count[3], 300);
  EXPECT_GT(count[6], 300);
  // 0.0000 in rings 1 to 4 without the reach; -0.019 to -0.038 with it (llvmpipe).
  for (const int k : {1, 2, 3})
    EXPECT_LT(change[static_cast<std::size_t>(k + 4)], -0.005) << "ring " << k;
  EXPECT_GT(std::abs(change[3]), 0.002);  // the skin's edge, -1: +0.007
}

TEST_F(FurRenderTest, FrameIsTheSumOfItsKeyAndAmbientLight) {
  // Every shading term is linear in the light (Light::color, Light::ambient): a frame over black
  // equals, in linear light, the frame lit by the key light alone plus the frame lit by the
  // ambient alone (pelage render --ambient 0 / --light-color 0: the parts scripts/reference/
  // views.py measures against a path tracer's). The default look: physical fur, transparent
  // strands with the coat's spread light, the shadow map and self-shadowing.
  const scene::Fur fur = scene::growFur(critter(), testFur(30000));
  const scene::Camera cam = camera(scene::CameraPreset::ThreeQuarter, 160, fur);
  scene::DrawOptions opt = physicalLook();
  opt.background = Eigen::Vector3f::Zero();
  scene::Light both = plainLight(true, true, 0.1f);
  both.color = Eigen::Vector3f(1.2f, 1.0f, 0.8f);
  both.ambient = Eigen::Vector3f(0.3f, 0.35f, 0.45f);
  scene::Light key = both, ambient = both;
  key.ambient.setZero();
  ambient.color.setZero();
  const Image full = render(&fur, cam, opt, both).image;
  const Image k = render(&fur, cam, opt, key).image;
  const Image a = render(&fur, cam, opt, ambient).image;
  double error = 0, worst = 0, sumFull = 0, sumKey = 0, sumAmbient = 0;
  int n = 0;
  for (int y = 0; y < full.height; ++y)
    for (int x = 0; x < full.width; ++x)
      for (int c = 0; c < 3; ++c) {
        const double f = test::decoded(full.pixel(x, y)[c]);
        const double parts = test::decoded(k.pixel(x, y)[c]) + test::decoded(a.pixel(x, y)[c]);
        error += std::abs(f - parts);
        worst = std::max(worst, std::abs(f - parts));
        sumFull += f;
        sumKey += test::decoded(k.pixel(x, y)[c]);
        sumAmbient += test::decoded(a.pixel(x, y)[c]);
        ++n;
      }
  std::printf(
      "light parts: key %.3f + ambient %.3f of the frame; mean |frame - sum| %.5f, max %.4f\n",
      sumKey / sumFull, sumAmbient / sumFull, error / n, worst);
  // Both parts light the creature; their sum is the frame to within 8-bit rounding (three
  // roundings of at most half a step each: 0.006 in linear light at the top of the range).
  EXPECT_GT(sumKey, 0.2 * sumFull);
  EXPECT_GT(sumAmbient, 0.1 * sumFull);
  EXPECT_LT(error / n, 0.002);
  EXPECT_LT(worst, 0.02);
}

TEST_F(FurRenderTest, LightPassesAddUpToTheFrame) {
  // scene::LightPass: each pass draws the same coverage with part of the light, so over black, in
  // linear light, all = hair + skin and, under the physical model, hair = fibre + coat (pelage
  // render --pass). The default look, key and ambient light, shadows and self-shadowing.
  const scene::Fur fur = scene::growFur(critter(), testFur(30000));
  const scene::Camera cam = camera(scene::CameraPreset::ThreeQuarter, 160, fur);
  scene::DrawOptions opt = physicalLook();
  opt.background = Eigen::Vector3f::Zero();
  const scene::Light light = plainLight(true, true, 0.15f);
  std::array<Image, 5> pass;  // scene::LightPass's order
  std::array<Image, 5> alpha;
  RendererOptions ro;
  ro.samples = 0;
  Renderer r(ro);
  for (int i = 0; i < 5; ++i) {
    opt.lightPass = static_cast<scene::LightPass>(i);
    pass[i] = render(&fur, cam, opt, light, &r).image;
    alpha[i] = r.readPixels(FrameAlpha::Straight);
  }
  const auto at = [&](scene::LightPass p, int x, int y, int c) {
    return test::decoded(pass[static_cast<std::size_t>(p)].pixel(x, y)[c]);
  };
  using P = scene::LightPass;
  double sum[5] = {}, errorAll = 0, errorHair = 0, worst = 0;
  int n = 0, alphaDiffers = 0;
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x) {
      for (int i = 1; i < 5; ++i)
        alphaDiffers =
            std::max(alphaDiffers, std::abs(alpha[i].pixel(x, y)[3] - alpha[0].pixel(x, y)[3]));
      for (int c = 0; c < 3; ++c) {
        for (int i = 0; i < 5; ++i) sum[i] += at(static_cast<P>(i), x, y, c);
        const double a = at(P::All, x, y, c) - at(P::Hair, x, y, c) - at(P::Skin, x, y, c);
        const double h = at(P::Hair, x, y, c) - at(P::Fibre, x, y, c) - at(P::Coat, x, y, c);
        errorAll += std::abs(a);
        errorHair += std::abs(h);
        worst = std::max({worst, std::abs(a), std::abs(h)});
        ++n;
      }
    }
  std::printf(
      "light passes of the frame: hair %.3f (fibre %.3f, coat %.3f), skin %.3f; mean "
      "|all - hair - skin| %.5f, |hair - fibre - coat| %.5f, max %.4f\n",
      sum[1] / sum[0], sum[2] / sum[0], sum[3] / sum[0], sum[4] / sum[0], errorAll / n,
      errorHair / n, worst);
  EXPECT_LE(alphaDiffers, 1);  // the same coverage in every pass (to the read-back's rounding)
  // Every part lights the frame, and the parts add up to within 8-bit rounding (as the key and
  // ambient parts do above).
  EXPECT_GT(sum[2], 0.05 * sum[1]);
  EXPECT_GT(sum[3], 0.3 * sum[1]);
  EXPECT_GT(sum[4], 0.005 * sum[0]);
  EXPECT_LT(sum[4], 0.9 * sum[0]);  // this sparse coat shows much of its skin (0.71 measured)
  EXPECT_LT(errorAll / n, 0.002);
  EXPECT_LT(errorHair / n, 0.002);
  EXPECT_LT(worst, 0.02);

  // Kajiya-Kay's hair light has no fibre and coat parts: its fibre pass is black, its coat pass
  // the hairs' whole light.
  opt.hairShading = scene::HairShading::KajiyaKay;
  opt.lightPass = scene::LightPass::Hair;
  const Image hair = render(&fur, cam, opt, light, &r).image;
  opt.lightPass = scene::LightPass::Coat;
  const Image coat = render(&fur, cam, opt, light, &r).image;
  opt.lightPass = scene::LightPass::Fibre;
  const Image fibre = render(&fur, cam, opt, light, &r).image;
  EXPECT_EQ(coat.rgba, hair.rgba);
  EXPECT_EQ(std::count(fibre.rgba.begin(), fibre.rgba.end(), std::uint8_t{0}),
            static_cast<std::ptrdiff_t>(fibre.rgba.size()) / 4 * 3);
}

TEST_F(FurRenderTest, CpuAndGpuHairsGiveTheSameImage) {
  const scene::Fur fur = scene::growFur(critter(), testFur(20000));
  const scene::Camera cam = camera(scene::CameraPreset::Front, 200, fur);
  scene::DrawOptions cpu, gpu;
  cpu.hairSource = scene::HairSource::Cpu;
  gpu.hairSource = scene::HairSource::Gpu;
  const Shot a = render(&fur, cam, cpu);
  const Shot b = render(&fur, cam, gpu);
  EXPECT_EQ(a.drawn, b.drawn);
  int differ = 0;
  for (int y = 0; y < a.image.height; ++y)
    for (int x = 0; x < a.image.width; ++x) differ += samePixel(a.image, b.image, x, y) ? 0 : 1;
  // The points agree to ~1e-7 m, so at most a handful of line pixels may round differently.
  EXPECT_LT(differ, a.image.width * a.image.height / 500);
}

// A groom's width scale draws each strand at its own width, in the colour pass and the deep opacity
// map alike: scale 2 everywhere is, pixel for pixel, coats of twice the width (powers of two keep
// every product exact), on the CPU's hairs and the GPU's; and wider strands cover more.
TEST_F(FurRenderTest, AWidthGroomDrawsEachStrandAtItsOwnWidth) {
  fur::FurParams p = testFur(20000);
  for (fur::CoatParams& c : p.coats) c.color.valueVariation = 0.2f;  // colours per hair either way
  fur::FurParams groomed = p, wide = p;
  groomed.regions = {{.match = "*", .widthScale = Eigen::Vector2f(2.0f, 2.0f)}};
  for (fur::CoatParams& c : wide.coats) c.width = {2.0f * c.width.rootMm, 2.0f * c.width.tipMm};
  const scene::Fur plainFur = scene::growFur(critter(), p);
  const scene::Fur groomedFur = scene::growFur(critter(), groomed);
  const scene::Fur wideFur = scene::growFur(critter(), wide);
  ASSERT_TRUE(groomedFur.colors.coats[0].perHairWidth);
  const scene::Camera cam = camera(scene::CameraPreset::Side, 240, plainFur);
  const Shot bare = render(nullptr, cam);
  for (const scene::HairSource source : {scene::HairSource::Cpu, scene::HairSource::Gpu}) {
    SCOPED_TRACE(scene::hairSourceName(source));
    scene::DrawOptions opt;
    opt.hairSource = source;
    const scene::Light light = plainLight(false, true);  // the deep opacity map takes widths too
    const Shot g = render(&groomedFur, cam, opt, light);
    const Shot w = render(&wideFur, cam, opt, light);
    const Shot n = render(&plainFur, cam, opt, light);
    EXPECT_EQ(g.image.rgba, w.image.rgba);
    const double inkWide = ink(g.image, bare.image), inkPlain = ink(n.image, bare.image);
    std::printf("width scale 2: ink %.0f against %.0f at the coats' width\n", inkWide, inkPlain);
    EXPECT_GT(inkWide, 1.2 * inkPlain);
  }
}

}  // namespace
}  // namespace pelage::render
