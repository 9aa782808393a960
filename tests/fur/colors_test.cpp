// Hair colours and groom maps (fur/colors.h, fur/groom.h) on a unit square with texture
// coordinates u = x, v = y: exact colours from a 2x2 texture, a density map zero on half the UV
// square, a length map at mid-grey, thread-count invariance.
#include "pelage/fur/colors.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "pelage/fur/groom.h"
#include "pelage/skin/texture.h"
#include "pelage/util/color.h"
#include "pelage/util/error.h"
#include "pelage/util/image.h"
#include "support/files.h"
#include "support/skins.h"

namespace pelage::fur {
namespace {

constexpr int kCells = 16;  // the square: 16 x 16 cells of 1/16 m, 512 triangles

// The unit square with u = x, v = y at every corner.
skin::SkinMesh texturedSquare() {
  skin::SkinMesh s = test::makeGrid(kCells, 1.0f / kCells, 0.01f);
  const float* p = s.restPositions();
  s.cornerUv.resize(s.triangles.size());
  for (std::size_t i = 0; i < s.triangles.size(); ++i) {
    const auto v = static_cast<std::size_t>(s.triangles[i]);
    s.cornerUv[i] = Eigen::Vector2f(p[3 * v], p[3 * v + 1]);
  }
  return s;
}

// Writes a PNG of `w` x `h` RGB bytes.
std::string writeRgbPng(const test::TempDir& dir, const std::string& name, int w, int h,
                        const std::vector<std::uint8_t>& rgb) {
  const std::string path = dir.file(name);
  writeImageFile(path, rgb.data(), w, h, 3);
  return path;
}

// The root's (u, v) = its rest position on the square.
Eigen::Vector2f rootUv(const skin::SkinMesh& s, const FurRoots& r, int coat, std::int64_t k) {
  const CoatRoots& cr = r.coats[static_cast<std::size_t>(coat)];
  const float* b = r.barycentric.data() + 4 * cr.tableIndex[static_cast<std::size_t>(k)];
  return s.uvAt(cr.triangle[static_cast<std::size_t>(k)], b);
}

FurParams params(double hairs) {
  FurParams p = test::simpleParams(HairStyle::Line, hairs);
  p.coats[kOvercoat].stiffness = 1.0f;  // straight hairs along the normal
  p.coats[kOvercoat].normalRandomize = 0.0f;
  return p;
}

// Sec. 3.2 plus colour: every hair rooted in a quadrant of a 2x2 texture (nearest texel) takes that
// quadrant's colour exactly (8-bit sRGB in, 8-bit sRGB out); the tip too (no gradient).
TEST(HairColors, TextureQuadrantsGiveExactColours) {
  skin::SkinMesh s = texturedSquare();
  const std::vector<std::uint8_t> texels = {200, 30, 10,  255, 20,  180, 40, 255,
                                            10,  20, 220, 255, 240, 240, 40, 255};
  skin::Texture t = skin::makeTexture(Rgba8Image{2, 2, 4, texels}, "quad", true);
  t.filter = skin::Filter::Nearest;
  s.textures.push_back(t);
  s.materials.push_back(skin::SkinMaterial{"quad", Eigen::Vector4f::Ones(), 0});
  s.triangleMaterial.assign(static_cast<std::size_t>(s.numTriangles()), 0);
  FurParams p = params(4000);
  p.coats[kOvercoat].color.source = ColorSource::Texture;
  const FurRoots roots = growRoots(s, p);
  const FurColors colors = colorRoots(s, roots, p, Groom{});
  const CoatColors& cc = colors.coats[kOvercoat];
  ASSERT_TRUE(cc.perHair);
  ASSERT_EQ(cc.packed.size(), static_cast<std::size_t>(2 * roots.coats[kOvercoat].size()));
  int perQuadrant[4] = {0, 0, 0, 0};
  for (std::int64_t k = 0; k < roots.coats[kOvercoat].size(); ++k) {
    const Eigen::Vector2f uv = rootUv(s, roots, kOvercoat, k);
    const int q = (uv.y() >= 0.5f ? 2 : 0) + (uv.x() >= 0.5f ? 1 : 0);
    ++perQuadrant[q];
    const std::uint32_t want = static_cast<std::uint32_t>(texels[4 * q]) |
                               static_cast<std::uint32_t>(texels[4 * q + 1]) << 8 |
                               static_cast<std::uint32_t>(texels[4 * q + 2]) << 16 | 0xFF000000u;
    ASSERT_EQ(cc.packed[static_cast<std::size_t>(2 * k)], want) << k;
    ASSERT_EQ(cc.packed[static_cast<std::size_t>(2 * k + 1)], want) << k;
  }
  for (int n : perQuadrant) EXPECT_GT(n, 800);

  // With per-hair variation: value within +-20 %, hue within +-10 degrees of the quadrant's, and
  // not every hair the same.
  p.coats[kOvercoat].color.valueVariation = 0.2f;
  p.coats[kOvercoat].color.hueVariation = 10.0f;
  const CoatColors varied = colorRoots(s, roots, p, Groom{}).coats[kOvercoat];
  int changed = 0;
  for (std::int64_t k = 0; k < roots.coats[kOvercoat].size(); ++k) {
    const Eigen::Vector3f a = unpackSrgb8(cc.packed[static_cast<std::size_t>(2 * k)]);
    const Eigen::Vector3f b = unpackSrgb8(varied.packed[static_cast<std::size_t>(2 * k)]);
    changed += (a - b).norm() > 1e-3f;
    ASSERT_LE(b.maxCoeff(), a.maxCoeff() * 1.2f + 0.01f) << k;
    ASSERT_GE(b.maxCoeff(), a.maxCoeff() * 0.8f - 0.01f) << k;
  }
  EXPECT_GT(changed, roots.coats[kOvercoat].size() * 9 / 10);
}

TEST(HairColors, ShiftHueKeepsValueAndTurnsRedTowardsGreen) {
  const Eigen::Vector3f red(0.8f, 0.1f, 0.1f);
  const Eigen::Vector3f turned = shiftHue(red, 120.0f);
  EXPECT_NEAR(turned.maxCoeff(), 0.8f, 1e-5f);
  EXPECT_GT(turned.y(), turned.x());
  EXPECT_TRUE(shiftHue(red, 0.0f).isApprox(red, 1e-6f));
  EXPECT_TRUE(shiftHue(shiftHue(red, 40.0f), -40.0f).isApprox(red, 1e-4f));
}

// A hair's width scale rides in its colour pair's alpha bytes: the colours' bytes stay, the scale
// comes back within half a code (exactly for multiples of 1/kWidthScaleCodes), over [0, 10].
TEST(HairColors, AWidthScaleRidesInTheAlphaBytesAndLeavesTheColours) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> scale(0.0f, kMaxWidthScale);
  std::uniform_int_distribution<std::uint32_t> bits;
  for (int i = 0; i < 10000; ++i) {
    const std::uint32_t before[2] = {bits(rng), bits(rng)};
    std::uint32_t pair[2] = {before[0], before[1]};
    const float s = i == 0 ? kMaxWidthScale : (i == 1 ? 0.0f : scale(rng));
    packHairWidth(pair, s);
    ASSERT_EQ(pair[0] & 0x00FFFFFFu, before[0] & 0x00FFFFFFu);
    ASSERT_EQ(pair[1] & 0x00FFFFFFu, before[1] & 0x00FFFFFFu);
    ASSERT_NEAR(hairWidthScale(pair), s, 0.5f / kWidthScaleCodes) << s;
  }
  for (const float exact : {0.0f, 0.25f, 1.0f, 1.5f, 2.0f, 3.0009765625f, 10.0f}) {
    std::uint32_t pair[2] = {packSrgb8(Eigen::Vector3f(0.2f, 0.4f, 0.6f)), 0u};
    packHairWidth(pair, exact);
    EXPECT_EQ(hairWidthScale(pair), exact);
  }
  std::uint32_t pair[2] = {0u, 0u};
  packHairWidth(pair, 1e6f);  // clamped to the range
  EXPECT_EQ(hairWidthScale(pair), kMaxWidthScale);
}

// A density map black on the left half of the UV square: no root there, and the total is kept
// (random rounding of alpha N, sec. 3.3's allocation: within a few standard deviations).
TEST(GroomMaps, DensityMapZeroOnHalfGrowsNoRootsThereAndKeepsTheTotal) {
  test::TempDir dir;
  const skin::SkinMesh s = texturedSquare();
  FurParams p = params(20000);
  p.maps.density = writeRgbPng(dir, "density.png", 2, 1, {0, 0, 0, 255, 255, 255});
  const Groom maps = loadGroomMaps(p.maps, s, "square");
  const FurRoots roots = growRoots(s, p, maps);
  const std::int64_t n = roots.coats[kOvercoat].size();
  for (std::int64_t k = 0; k < n; ++k)
    ASSERT_GE(rootUv(s, roots, kOvercoat, k).x(), 0.5f - 1e-6f) << k;
  // 256 triangles carry the hairs; each rounds up or down at random: sd <= sqrt(256) / 2 = 8.
  EXPECT_NEAR(static_cast<double>(n), 20000.0, 40.0);
  // Without the map: the same total, over the whole square.
  const FurRoots plain = growRoots(s, p);
  EXPECT_NEAR(static_cast<double>(plain.coats[kOvercoat].size()), 20000.0, 40.0);
}

// A length map mid-grey (128) on the left and white on the right: hairs on the left are
// 128 / 255 as long as the same roots' hairs without the map; on the right, unchanged.
TEST(GroomMaps, LengthMapScalesTheInterpolatedLength) {
  test::TempDir dir;
  const skin::SkinMesh s = texturedSquare();
  FurParams p = params(3000);
  const test::RestFur plain = test::restFur(s, p);
  p.maps.length = writeRgbPng(dir, "length.png", 4, 1,
                              {128, 128, 128, 128, 128, 128, 255, 255, 255, 255, 255, 255});
  const Groom maps = loadGroomMaps(p.maps, s, "square");
  const FurRoots mapped = growRoots(s, p, maps);
  ASSERT_EQ(mapped.coats[kOvercoat].triangle, plain.roots.coats[kOvercoat].triangle);  // same roots
  const FurFrame a = test::furFrame(s, plain.roots, p, plain.rest);
  const FurFrame b = test::furFrame(s, mapped, p, plain.rest);
  int left = 0, right = 0;
  for (std::int64_t k = 0; k < mapped.coats[kOvercoat].size(); ++k) {
    // Away from the bilinear blends (texel centres at u = 1/8, 3/8, 5/8, 7/8; repeat wrap).
    const float u = rootUv(s, mapped, kOvercoat, k).x();
    const float want = u > 0.13f && u < 0.37f   ? 128.0f / 255.0f
                       : u > 0.63f && u < 0.87f ? 1.0f
                                                : -1.0f;
    if (want < 0.0f) continue;
    (want < 1.0f ? left : right) += 1;
    ASSERT_NEAR(mapped.coats[kOvercoat].lengthScale[static_cast<std::size_t>(k)], want, 1e-6f);
    const float la = (test::point(a.coats[0], k, 1) - test::point(a.coats[0], k, 0)).norm();
    const float lb = (test::point(b.coats[0], k, 1) - test::point(b.coats[0], k, 0)).norm();
    ASSERT_NEAR(lb / la, want, 1e-4f) << k;
  }
  EXPECT_GT(left, 500);
  EXPECT_GT(right, 500);
}

TEST(GroomMaps, ErrorsNameTheFieldAndTheFile) {
  test::TempDir dir;
  const skin::SkinMesh s = texturedSquare();
  GroomMapPaths paths;
  paths.density = dir.file("missing.png");
  EXPECT_THROW(
      {
        try {
          loadGroomMaps(paths, s, "square");
        } catch (const InputError& e) {
          EXPECT_NE(std::string(e.what()).find("maps.density"), std::string::npos) << e.what();
          EXPECT_NE(std::string(e.what()).find("missing.png"), std::string::npos) << e.what();
          throw;
        }
      },
      InputError);
  paths.density.clear();
  paths.length = dir.file("notes.png");
  std::ofstream(paths.length) << "not an image";
  EXPECT_THROW(loadGroomMaps(paths, s, "square"), InputError);
  // A skin without texture coordinates takes no map.
  const skin::SkinMesh bare = test::makeGrid(2, 0.5f, 0.01f);
  paths.length = writeRgbPng(dir, "ok.png", 1, 1, {255, 255, 255});
  EXPECT_THROW(loadGroomMaps(paths, bare, "bare"), InputError);
  // Nor a texture colour source.
  FurParams p = params(100);
  p.coats[kOvercoat].color.source = ColorSource::Texture;
  EXPECT_THROW(colorRoots(bare, growRoots(bare, p), p, Groom{}), InputError);
}

// Colours, density and length maps: bit-identical for any thread count.
TEST(GroomMaps, SameRootsAndColoursForAnyThreadCount) {
  test::TempDir dir;
  const skin::SkinMesh s = texturedSquare();
  FurParams p = params(20000);
  p.maps.density =
      writeRgbPng(dir, "d.png", 2, 2, {0, 0, 0, 90, 90, 90, 255, 255, 255, 30, 30, 30});
  p.maps.length = writeRgbPng(dir, "l.png", 2, 1, {60, 60, 60, 250, 250, 250});
  p.maps.color = writeRgbPng(dir, "c.png", 2, 1, {200, 100, 50, 20, 40, 90});
  p.coats[kOvercoat].color.source = ColorSource::Map;
  p.coats[kOvercoat].color.hueVariation = 8.0f;
  p.coats[kOvercoat].color.valueVariation = 0.1f;
  p.coats[kOvercoat].color.tipLightness = 1.3f;
  const Groom maps = loadGroomMaps(p.maps, s, "square");
  std::vector<std::uint32_t> first;
  std::vector<std::int32_t> triangles;
  std::vector<float> scales;
  for (int threads : {1, 2, 3}) {
    setThreadCount(threads);
    const FurRoots roots = growRoots(s, p, maps);
    const FurColors colors = colorRoots(s, roots, p, maps);
    if (first.empty()) {
      first = colors.coats[kOvercoat].packed;
      triangles = roots.coats[kOvercoat].triangle;
      scales = roots.coats[kOvercoat].lengthScale;
      ASSERT_FALSE(first.empty());
    } else {
      EXPECT_EQ(colors.coats[kOvercoat].packed, first) << threads;
      EXPECT_EQ(roots.coats[kOvercoat].triangle, triangles) << threads;
      EXPECT_EQ(roots.coats[kOvercoat].lengthScale, scales) << threads;
    }
  }
  setThreadCount(0);
}

}  // namespace
}  // namespace pelage::fur
