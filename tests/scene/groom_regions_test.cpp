// Fur grooming by region (fur/groom.h, scene::growFur) on the shared Fox: the coat issue's
// acceptance (b_Tail* 2.0x, b_Head* 0.4x where those joints' weights are 1, unchanged away from
// them, a monotone blend between), density and tint by region, lengths in mm, and the errors; a
// length stroke (fur/groom_strokes.h), the grooming issue's acceptance.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "pelage/fur/generate.h"
#include "pelage/fur/groom.h"
#include "pelage/fur/groom_strokes.h"
#include "pelage/fur/hair_ply.h"
#include "pelage/fur/preset.h"
#include "pelage/skin/deform.h"
#include "pelage/util/color.h"
#include "support/files.h"
#include "support/models.h"

namespace pelage {
namespace {

const scene::Model* fox() {
  return test::creature("Fox");
}

fur::FurParams foxParams() {
  fur::FurParams p = fur::loadFurPreset("default");
  p.setHairCount(30000);
  return p;
}

// Each overcoat root's rest-pose hair length (sec. 3.2's interpolated length).
std::vector<float> restLengths(const scene::Model& m, const fur::FurRoots& roots) {
  skin::DeformedSkin rest;
  skin::restSkin(m.skin, rest);
  std::vector<float> out(static_cast<std::size_t>(roots.coats[0].size()));
  for (std::int64_t k = 0; k < roots.coats[0].size(); ++k)
    out[static_cast<std::size_t>(k)] = fur::rootInput(m.skin, roots, rest, 0, k).length;
  return out;
}

// The weight of root k's three vertices in `w`, and its barycentric blend.
struct RootWeights {
  float v[3];
  float blend;
};
RootWeights rootWeights(const scene::Model& m, const fur::FurRoots& roots, std::int64_t k,
                        const std::vector<float>& w) {
  const fur::CoatRoots& cr = roots.coats[0];
  const auto ks = static_cast<std::size_t>(k);
  const std::int32_t* tv = m.skin.triangles.data() + 3 * static_cast<std::size_t>(cr.triangle[ks]);
  const float* b = roots.barycentric.data() + 4 * cr.tableIndex[ks];
  RootWeights r{};
  for (int i = 0; i < 3; ++i) r.v[i] = w[static_cast<std::size_t>(tv[i])];
  r.blend = b[0] * r.v[0] + b[1] * r.v[1] + b[2] * r.v[2];
  return r;
}

TEST(GroomRegions, FoxTailTwiceHeadShorterUnchangedAwayBlendedBetween) {
  const scene::Model* m = fox();
  if (!m) GTEST_SKIP() << "shared Fox model absent";
  const fur::FurParams plain = foxParams();
  fur::FurParams groomed = plain;
  groomed.regions = {{.match = "b_Tail*", .lengthScale = 2.0f},
                     {.match = "b_Head*", .lengthScale = 0.4f}};
  const scene::Fur a = scene::growFur(*m, plain, "test");
  const scene::Fur b = scene::growFur(*m, groomed, "test");
  // The same roots: lengths change, where hairs grow does not.
  ASSERT_EQ(a.roots.coats[0].triangle, b.roots.coats[0].triangle);
  ASSERT_EQ(a.roots.coats[0].tableIndex, b.roots.coats[0].tableIndex);
  const std::vector<float> la = restLengths(*m, a.roots), lb = restLengths(*m, b.roots);
  const std::vector<float> tail = fur::regionWeights(m->skin, m->body, "b_Tail*");
  const std::vector<float> head = fur::regionWeights(m->skin, m->body, "b_Head*");
  int inTail = 0, inHead = 0, away = 0, between = 0;
  std::vector<std::pair<float, float>> blend;  // (tail weight at the root, length ratio)
  for (std::int64_t k = 0; k < b.roots.coats[0].size(); ++k) {
    const auto ks = static_cast<std::size_t>(k);
    const RootWeights t = rootWeights(*m, b.roots, k, tail), h = rootWeights(*m, b.roots, k, head);
    const float ratio = lb[ks] / la[ks];
    if (t.v[0] == 1.0f && t.v[1] == 1.0f && t.v[2] == 1.0f) {
      EXPECT_NEAR(ratio, 2.0f, 1e-6f) << "root " << k;
      ++inTail;
    } else if (h.v[0] == 1.0f && h.v[1] == 1.0f && h.v[2] == 1.0f) {
      EXPECT_NEAR(ratio, 0.4f, 1e-6f) << "root " << k;
      ++inHead;
    } else if (std::max({t.v[0], t.v[1], t.v[2], h.v[0], h.v[1], h.v[2]}) == 0.0f) {
      EXPECT_EQ(std::memcmp(&la[ks], &lb[ks], sizeof(float)), 0) << "root " << k;
      ++away;
    } else if (h.blend == 0.0f) {
      // The Fox's vertex lengths are all equal, so the blend is exactly 1 + the tail weight.
      EXPECT_NEAR(ratio, 1.0f + t.blend, 1e-5f) << "root " << k;
      blend.emplace_back(t.blend, ratio);
      ++between;
    }
  }
  EXPECT_GT(inTail, 200);
  EXPECT_GT(inHead, 200);
  EXPECT_GT(away, 5000);
  EXPECT_GT(between, 200);
  std::sort(blend.begin(), blend.end());
  for (std::size_t i = 1; i < blend.size(); ++i)
    EXPECT_GE(blend[i].second, blend[i - 1].second - 1e-5f) << "the blend is not monotone";
}

TEST(GroomRegions, DensityTintAndLengthInMillimetres) {
  const scene::Model* m = fox();
  if (!m) GTEST_SKIP() << "shared Fox model absent";
  fur::FurParams p = foxParams();
  p.coats[0].color.source = fur::ColorSource::Material;
  p.coats[0].color.hueVariation = p.coats[0].color.valueVariation = 0.0f;
  p.coats[0].color.tipLightness = 1.0f;
  p.coats[0].color.hasTipColor = false;
  p.regions = {{.match = "*", .lengthMm = 10.0f},
               {.match = "b_Head*", .densityScale = 0.0f},
               {.match = "b_Tail*", .tint = {0.5f, 0.5f, 0.5f}}};
  const scene::Fur f = scene::growFur(*m, p, "test");
  // Random rounding over the skin's triangles: within 5 standard deviations (at most 0.5 sqrt(nT)
  // per coat).
  EXPECT_NEAR(static_cast<double>(f.roots.total()), 30000.0,
              5.0 * std::sqrt(2.0 * 0.25 * m->skin.numTriangles()))
      << "a density region moves hairs, it keeps the total";
  const std::vector<float> len = restLengths(*m, f.roots);
  const std::vector<float> head = fur::regionWeights(m->skin, m->body, "b_Head*");
  const std::vector<float> tail = fur::regionWeights(m->skin, m->body, "b_Tail*");
  const fur::CoatColors& cc = f.colors.coats[0];
  ASSERT_TRUE(cc.perHair);
  int tinted = 0;
  for (std::int64_t k = 0; k < f.roots.coats[0].size(); ++k) {
    const auto ks = static_cast<std::size_t>(k);
    EXPECT_NEAR(len[ks], 0.010f, 1e-7f) << "root " << k;
    const RootWeights h = rootWeights(*m, f.roots, k, head);
    EXPECT_FALSE(h.v[0] == 1.0f && h.v[1] == 1.0f && h.v[2] == 1.0f)
        << "root " << k << " grew where the density is 0";
    const RootWeights t = rootWeights(*m, f.roots, k, tail);
    if (t.v[0] == 1.0f && t.v[1] == 1.0f && t.v[2] == 1.0f) {
      // Half the coat's linear diffuse, within the 8-bit sRGB code's step.
      const Eigen::Vector3f c = fur::hairColorAt(cc, k, 0.0f);
      const Eigen::Vector3f d = srgbToLinear(p.coats[0].material.diffuse) * 0.5f;
      EXPECT_LT((c - d).cwiseAbs().maxCoeff(), 0.01f) << "root " << k;
      ++tinted;
    }
  }
  EXPECT_GT(tinted, 100);
}

// The grooming issue's length acceptance: a length stroke along the Fox's back from the shoulders
// to the tail, radius 6 cm, strength 1.5 (a strokes file, as `pelage groom` reads it): the hairs
// rooted within 3 cm of the stroke have a median length ratio in [1.3, 1.6]; those farther than
// 15 cm are bit-identical; the roots are the same.
TEST(GroomStrokes, FoxLengthStrokeAlongTheBack) {
  const scene::Model* m = fox();
  if (!m) GTEST_SKIP() << "shared Fox model absent";
  const std::vector<fur::GroomStroke> strokes = fur::parseGroomStrokes(R"({"strokes": [
      {"tool": "length", "radius": 0.06, "strength": 1.5,
       "points": [[0.2, 0, 0.669], [0.1, 0, 0.65], [0.0, 0, 0.643], [-0.1, 0, 0.649],
                  [-0.2, 0, 0.651], [-0.3, 0, 0.642], [-0.4, 0, 0.613]]}]})",
                                                                       "back.json");
  fur::FurParams p = foxParams();
  fur::VertexGroom g = fur::resolveVertexGroom(m->skin, m->body, m->name, p, "test");
  fur::applyGroomStrokes(m->skin, strokes, g);
  test::TempDir dir;
  fur::writeGroomFile(dir.file("back.groom.json"), m->skin, g);
  const scene::Fur before = scene::growFur(*m, p, "test");
  p.groom = dir.file("back.groom.json");
  const scene::Fur after = scene::growFur(*m, p, "test");
  ASSERT_EQ(after.roots.coats[0].triangle, before.roots.coats[0].triangle);
  ASSERT_EQ(after.roots.coats[0].tableIndex, before.roots.coats[0].tableIndex);
  const std::vector<float> a = restLengths(*m, before.roots), b = restLengths(*m, after.roots);
  skin::DeformedSkin rest;
  skin::restSkin(m->skin, rest);
  const std::vector<Eigen::Vector3f>& line = strokes[0].points;
  std::vector<float> ratios;
  int far = 0;
  for (std::int64_t k = 0; k < before.roots.coats[0].size(); ++k) {
    const fur::Vec3<float> h = fur::rootInput(m->skin, before.roots, rest, 0, k).root;
    const Eigen::Vector3f r(h.x, h.y, h.z);
    float d = 1e9f;
    for (std::size_t i = 1; i < line.size(); ++i) {
      const Eigen::Vector3f ab = line[i] - line[i - 1];
      const float t = std::clamp((r - line[i - 1]).dot(ab) / ab.squaredNorm(), 0.0f, 1.0f);
      d = std::min(d, (line[i - 1] + t * ab - r).norm());
    }
    const auto ks = static_cast<std::size_t>(k);
    if (d <= 0.03f && a[ks] > 0.0f) ratios.push_back(b[ks] / a[ks]);
    if (d > 0.15f) {
      EXPECT_EQ(b[ks], a[ks]) << "root " << k << ", " << d << " m from the stroke";
      ++far;
    }
  }
  ASSERT_GT(ratios.size(), 50u);
  EXPECT_GT(far, 10000);
  std::nth_element(ratios.begin(), ratios.begin() + static_cast<std::ptrdiff_t>(ratios.size() / 2),
                   ratios.end());
  const float median = ratios[ratios.size() / 2];
  EXPECT_GE(median, 1.3f);
  EXPECT_LE(median, 1.6f);
  std::printf("length stroke: %zu hairs within 3 cm, median ratio %.4f; %d hairs beyond 15 cm\n",
              ratios.size(), static_cast<double>(median), far);
}

// Point k of hair h.
Eigen::Vector3f pointOf(const fur::HairBuffers& b, std::int64_t h, int k) {
  return Eigen::Map<const Eigen::Vector3f>(b.positions.data() +
                                           (h * b.layout.pointsPerHair() + k) * 3);
}

// The grooming issue's comb acceptance on the Fox: a comb stroke along the back from the shoulders
// to the tail, radius 6 cm, strength 1: at least 80 % of the overcoat hairs rooted within 3 cm of
// the stroke point along it (tip minus root against the direction of the stroke's nearest
// segment, at rest); those rooted farther than 15 cm are bit-identical; the roots are the same.
// The Fox's back hairs already lie toward the tail (the spine's segment directions and gravity),
// so the same stroke drawn from the tail to the shoulders, against the lay, must turn them.
TEST(GroomStrokes, FoxCombStrokeAlongTheBackBothWays) {
  const scene::Model* m = fox();
  if (!m) GTEST_SKIP() << "shared Fox model absent";
  std::vector<Eigen::Vector3f> line = {{0.2f, 0, 0.669f},  {0.1f, 0, 0.65f},   {0.0f, 0, 0.643f},
                                       {-0.1f, 0, 0.649f}, {-0.2f, 0, 0.651f}, {-0.3f, 0, 0.642f},
                                       {-0.4f, 0, 0.613f}};
  fur::FurParams p = foxParams();
  const scene::Fur before = scene::growFur(*m, p, "test");
  skin::DeformedSkin rest;
  skin::restSkin(m->skin, rest);
  fur::FurWorkspace ws;
  fur::FurFrame a;
  fur::generateFur(m->skin, before.roots, before.params, rest, fur::FurView{}, ws, a);
  const fur::HairBuffers& ha = a.coats[0];
  const int P = ha.layout.pointsPerHair();
  for (const bool reversed : {false, true}) {
    SCOPED_TRACE(reversed ? "tail to shoulders" : "shoulders to tail");
    if (reversed) {
      std::reverse(line.begin(), line.end());
      // The README's example strokes file is this stroke.
      const std::vector<fur::GroomStroke> example =
          fur::readGroomStrokes(PELAGE_SOURCE_DIR "/docs/examples/fox_comb_forward.json");
      ASSERT_EQ(example.size(), 1u);
      EXPECT_EQ(example[0].points, line);
      EXPECT_EQ(example[0].tool, fur::BrushTool::Comb);
    }
    fur::GroomStroke stroke;
    stroke.tool = fur::BrushTool::Comb;
    stroke.points = line;
    stroke.radius = 0.06f;
    stroke.strength = 1.0f;
    fur::VertexGroom g = fur::resolveVertexGroom(m->skin, m->body, m->name, p, "test");
    fur::applyGroomStrokes(m->skin, {stroke}, g);
    test::TempDir dir;
    fur::writeGroomFile(dir.file("comb.groom.json"), m->skin, g);
    fur::FurParams q = p;
    q.groom = dir.file("comb.groom.json");
    const scene::Fur after = scene::growFur(*m, q, "test");
    ASSERT_EQ(after.roots.coats[0].triangle, before.roots.coats[0].triangle);
    ASSERT_EQ(after.roots.coats[0].tableIndex, before.roots.coats[0].tableIndex);
    fur::FurFrame b;
    fur::generateFur(m->skin, after.roots, after.params, rest, fur::FurView{}, ws, b);
    const fur::HairBuffers& hb = b.coats[0];
    ASSERT_EQ(ha.drawn, hb.drawn);
    int near = 0, alongBefore = 0, alongAfter = 0, far = 0;
    for (std::int64_t h = 0; h < hb.drawn; ++h) {
      const Eigen::Vector3f r = pointOf(hb, h, 0);
      float d = 1e9f;
      Eigen::Vector3f along = Eigen::Vector3f::Zero();
      for (std::size_t i = 1; i < line.size(); ++i) {
        const Eigen::Vector3f ab = line[i] - line[i - 1];
        const float t = std::clamp((r - line[i - 1]).dot(ab) / ab.squaredNorm(), 0.0f, 1.0f);
        const float di = (line[i - 1] + t * ab - r).norm();
        if (di < d) d = di, along = ab;
      }
      if (d <= 0.03f) {
        ++near;
        alongBefore += (pointOf(ha, h, P - 1) - r).dot(along) > 0.0f ? 1 : 0;
        alongAfter += (pointOf(hb, h, P - 1) - r).dot(along) > 0.0f ? 1 : 0;
      }
      if (d > 0.15f) {
        ++far;
        const std::size_t n = static_cast<std::size_t>(3 * P), o = static_cast<std::size_t>(h) * n;
        ASSERT_EQ(0, std::memcmp(ha.positions.data() + o, hb.positions.data() + o, n * 4))
            << "hair " << h << ", " << d << " m from the stroke";
        ASSERT_EQ(0, std::memcmp(ha.normals.data() + o, hb.normals.data() + o, n * 4));
      }
    }
    ASSERT_GT(near, 50);
    EXPECT_GT(far, 10000);
    const double share = static_cast<double>(alongAfter) / near;
    EXPECT_GE(share, 0.8);
    if (reversed) {
      EXPECT_LT(alongBefore, near / 5) << "the lay runs toward the tail";
    }
    std::printf(
        "comb stroke %s: %d hairs within 3 cm; along the stroke %.1f %% before, %.1f %% "
        "after; %d hairs beyond 15 cm bit-identical\n",
        reversed ? "tail to shoulders" : "shoulders to tail", near, 100.0 * alongBefore / near,
        100.0 * share, far);
  }
}

TEST(GroomRegions, ErrorsNameThePresetFileTheRegionAndTheField) {
  const scene::Model* m = fox();
  if (!m) GTEST_SKIP() << "shared Fox model absent";
  const std::string file = testing::TempDir() + "regions_typo.json";
  test::writeText(file, R"({"regions": [{"match": "b_Tail*", "lengthScale": 2},
                                        {"match": "b_Tial*", "lengthScale": 2}]})");
  fur::FurParams p = fur::loadFurPreset(file);
  p.setHairCount(1000);
  test::expectInputError(
      [&] { scene::growFur(*m, p, "fur 'regions_typo'"); },
      {file, "regions[1].match 'b_Tial*'", "matches no region or joint", "b_Tail01_012"});
  test::writeText(file, R"({"regions": [{"match": "b_Tail*", "lengthScale": 20}]})");
  test::expectInputError([&] { fur::loadFurPreset(file); },
                         {file, "regions[0].lengthScale", "[0, 10]"});
  test::writeText(file, R"({"regions": [{"match": "b_Tail*", "stiffness": 1.5}]})");
  test::expectInputError([&] { fur::loadFurPreset(file); },
                         {file, "regions[0].stiffness", "[0, 1]"});
  test::writeText(file, R"({"regions": [{"match": "b_Tail*", "stiffness": [0.5]}]})");
  test::expectInputError([&] { fur::loadFurPreset(file); },
                         {file, "regions[0].stiffness", "[overcoat, undercoat]"});
  test::writeText(file,
                  R"({"regions": [{"match": "b_Tail*", "segmentDirectionWeight": [0.5, 2]}]})");
  test::expectInputError([&] { fur::loadFurPreset(file); },
                         {file, "regions[0].segmentDirectionWeight[1]", "[0, 1]"});
  test::writeText(file, R"({"regions": [{"match": "b_Tail*", "curl": {"radius": 0.6}}]})");
  test::expectInputError([&] { fur::loadFurPreset(file); },
                         {file, "regions[0].curl.radius", "[0, 0.5]"});
  test::writeText(file, R"({"regions": [{"match": "b_Tail*", "curl": {"turns": [1, 2, 3]}}]})");
  test::expectInputError([&] { fur::loadFurPreset(file); },
                         {file, "regions[0].curl.turns", "[overcoat, undercoat]"});
  test::writeText(file, R"({"regions": [{"match": "b_Tail*", "widthScale": [2, 10.5]}]})");
  test::expectInputError([&] { fur::loadFurPreset(file); },
                         {file, "regions[0].widthScale", "[0, 10]"});
  test::writeText(file, R"({"regions": [{"match": "b_Tail*", "colorSource": "fur"}]})");
  test::expectInputError([&] { fur::loadFurPreset(file); },
                         {"regions[0].colorSource", "unknown colour source 'fur'", "texture"});
  test::writeText(file, R"({"regions": [{"match": "b_Tail*", "colorSource": ["material"]}]})");
  test::expectInputError([&] { fur::loadFurPreset(file); },
                         {file, "regions[0].colorSource", "[overcoat, undercoat]"});
  test::writeText(file, R"({"regions": [{"match": "b_Tail*", "curl": {"radus": 0.1}}]})");
  test::expectInputError([&] { fur::loadFurPreset(file); }, {file, "regions[0].curl", "radus"});
  // Coat fields a region cannot set yet are refused by name.
  test::writeText(file, R"({"regions": [{"match": "b_Tail*", "curlTurns": 2}]})");
  test::expectInputError([&] { fur::loadFurPreset(file); }, {file, "regions[0]", "curlTurns"});
  test::writeText(file, R"({"regions": [{"lengthScale": 2}]})");
  test::expectInputError([&] { fur::loadFurPreset(file); }, {file, "regions[0]", "match"});
}

TEST(GroomRegions, TheReadmeExampleGroomsTheFox) {
  const scene::Model* m = fox();
  if (!m) GTEST_SKIP() << "shared Fox model absent";
  fur::FurParams p = fur::loadFurPreset(PELAGE_SOURCE_DIR "/docs/examples/fox_groom.json");
  EXPECT_EQ(p.regions.size(), 6u);
  EXPECT_DOUBLE_EQ(p.coverage, 0.95);  // the default's coat, from its base
  p.setHairCount(20000);
  std::vector<fur::RegionMatch> matches;
  fur::groomFromRegions(m->skin, m->body, p, "example", &matches);
  ASSERT_EQ(matches.size(), 6u);
  for (const fur::RegionMatch& r : matches) EXPECT_GT(r.vertices, 50) << r.pattern;
  EXPECT_GT(scene::growFur(*m, p, "example").roots.total(), 19000);
}

TEST(GroomRegions, PresetRoundTripAndRegrowth) {
  fur::FurParams p = foxParams();
  p.regions = {{.match = "b_Tail*",
                .lengthScale = 2.0f,
                .lengthMm = 30.0f,
                .densityScale = 1.5f,
                .tint = {0.5f, 0.25f, 1.0f}},
               {.match = "b_Head*", .stiffness = Eigen::Vector2f(0.25f, 0.75f)},
               {.match = "b_Leg*", .segmentDirectionWeight = Eigen::Vector2f(0.5f, 1.0f)},
               {.match = "b_Neck*", .curlTurns = Eigen::Vector2f(3.0f, 0.5f)},
               {.match = "b_Spine*", .widthScale = Eigen::Vector2f(2.0f, 0.5f)},
               {.match = "b_Head*",
                .colorSource = std::array{fur::ColorSource::Material, fur::ColorSource::Texture}}};
  const fur::FurParams back = fur::parseFurPreset(fur::furPresetJson(p), "round trip");
  EXPECT_EQ(back.regions, p.regions);
  fur::FurParams q = p;
  q.regions[0].lengthScale = 1.5f;
  EXPECT_TRUE(scene::rootsDiffer(p, q));
  q = p;
  q.regions.back().widthScale = Eigen::Vector2f(3.0f, 0.5f);
  EXPECT_TRUE(scene::rootsDiffer(p, q));
  // A region's width scale is of the coats' widths, whatever they are: no regrowth when they
  // change.
  q = p;
  q.coats[fur::kOvercoat].width = {1.0f, 0.5f};
  EXPECT_FALSE(scene::rootsDiffer(p, q));
  // A region's colour source blends from the coats' own sources.
  q = p;
  q.coats[fur::kUndercoat].color.source = fur::ColorSource::Material;
  EXPECT_TRUE(scene::rootsDiffer(p, q));
  // The coats' stiffness, w and helix are where such regions blend from: the roots' own values
  // change.
  for (float fur::CoatParams::*field :
       {&fur::CoatParams::stiffness, &fur::CoatParams::segmentDirectionWeight,
        &fur::CoatParams::curlRadius, &fur::CoatParams::curlTurns}) {
    q = p;
    q.coats[fur::kUndercoat].*field = 0.5f;
    EXPECT_TRUE(scene::rootsDiffer(p, q));
  }
  // Without a region of that value the coats' apply per frame: no regrowth.
  q = p;
  q.regions.pop_back();  // the colour source region goes
  q.regions.pop_back();  // the width region goes
  q.regions.pop_back();  // the curl region goes
  q.regions.pop_back();  // and the w region; the stiffness region stays
  fur::FurParams r = q;
  r.coats[fur::kOvercoat].segmentDirectionWeight = 0.9f;
  EXPECT_FALSE(scene::rootsDiffer(q, r));
  q.regions.pop_back();
  r = q;
  r.coats[fur::kUndercoat].stiffness = 0.25f;
  r.coats[fur::kOvercoat].segmentDirectionWeight = 0.9f;
  r.coats[fur::kOvercoat].curlTurns = 2.0f;
  EXPECT_FALSE(scene::rootsDiffer(q, r));
}

// The Fox with `region` on b_Tail* setting a per-coat value to `value` for both coats: hairs whose
// three vertices have tail weight 1 grow (ending direction e, sec. 3.5) exactly as in coats of
// that value (CoatParams::*coatField), hairs with none exactly as the plain coats', and the
// overcoat roots' own value (CoatRoots::*perRoot) moves monotonically with the tail weight between
// (rising when `rising`).
void expectFoxTailGrowsAsCoatsOfItsValue(const fur::FurRegion& region,
                                         float fur::CoatParams::*coatField, float value,
                                         std::vector<float> fur::CoatRoots::*perRoot, bool rising) {
  const scene::Model* m = fox();
  if (!m) GTEST_SKIP() << "shared Fox model absent";
  const fur::FurParams plain = foxParams();
  fur::FurParams groomed = plain;
  groomed.regions = {region};
  fur::FurParams coats = plain;
  for (auto& c : coats.coats) c.*coatField = value;
  const scene::Fur a = scene::growFur(*m, plain, "test");
  const scene::Fur b = scene::growFur(*m, groomed, "test");
  ASSERT_EQ(a.roots.coats[0].triangle, b.roots.coats[0].triangle);
  ASSERT_EQ(a.roots.coats[0].tableIndex, b.roots.coats[0].tableIndex);
  ASSERT_EQ((b.roots.coats[0].*perRoot).size(), b.roots.coats[0].triangle.size());
  skin::DeformedSkin rest;
  skin::restSkin(m->skin, rest);
  const fur::CoatShape plainShape = fur::makeCoatShape(plain, a.roots, 0);
  const fur::CoatShape coatsShape = fur::makeCoatShape(coats, a.roots, 0);
  const fur::CoatShape groomedShape = fur::makeCoatShape(groomed, b.roots, 0);
  const auto ending = [&](const fur::CoatShape& shape, const fur::FurRoots& roots, std::int64_t k) {
    fur::HairFrame<float> f;
    fur::hairFrame(shape, fur::rootInput(m->skin, roots, rest, 0, k), f);
    return Eigen::Vector3f(f.e.x, f.e.y, f.e.z);
  };
  const std::vector<float> tail = fur::regionWeights(m->skin, m->body, "b_Tail*");
  int inTail = 0, away = 0, between = 0;
  std::vector<std::pair<float, float>> blend;  // (tail weight at the root, the root's value)
  for (std::int64_t k = 0; k < b.roots.coats[0].size(); ++k) {
    const RootWeights t = rootWeights(*m, b.roots, k, tail);
    const Eigen::Vector3f e = ending(groomedShape, b.roots, k);
    if (t.v[0] == 1.0f && t.v[1] == 1.0f && t.v[2] == 1.0f) {
      EXPECT_EQ(e, ending(coatsShape, a.roots, k)) << "root " << k;
      ++inTail;
    } else if (std::max({t.v[0], t.v[1], t.v[2]}) == 0.0f) {
      EXPECT_EQ(e, ending(plainShape, a.roots, k)) << "root " << k;
      ++away;
    } else {
      blend.emplace_back(t.blend, (b.roots.coats[0].*perRoot)[static_cast<std::size_t>(k)]);
      ++between;
    }
  }
  EXPECT_GT(inTail, 200);
  EXPECT_GT(away, 5000);
  EXPECT_GT(between, 100);
  std::sort(blend.begin(), blend.end());
  for (std::size_t i = 1; i < blend.size(); ++i) {
    const float step = blend[i].second - blend[i - 1].second;
    EXPECT_GE(rising ? step : -step, -1e-6f) << "the blend is not monotone";
  }
}

TEST(GroomRegions, FoxStiffTailDroopsAsAStiffCoatUnchangedAwayBlendedBetween) {
  // Floppiness falls from the overcoat's (0.7) toward the tail's (0.05) as the tail weight grows.
  EXPECT_FLOAT_EQ(fur::floppiness(foxParams().coats[0].stiffness), 0.7f);
  expectFoxTailGrowsAsCoatsOfItsValue(
      {.match = "b_Tail*", .stiffness = Eigen::Vector2f(0.95f, 0.95f)}, &fur::CoatParams::stiffness,
      0.95f, &fur::CoatRoots::floppiness, false);
}

TEST(GroomRegions, FoxThickTailHairsAreTheirCoatsWidthTimesTheTailScale) {
  // A width scale of 2 on the tail: the hairs stay where they were (strands), and each root's
  // scale is 2 exactly where the tail's weight is 1, 1 exactly away, rising with the weight
  // between; the exported widths follow.
  const scene::Model* m = fox();
  if (!m) GTEST_SKIP() << "shared Fox model absent";
  const fur::FurParams plain = foxParams();
  fur::FurParams groomed = plain;
  groomed.regions = {{.match = "b_Tail*", .widthScale = Eigen::Vector2f(2.0f, 2.0f)}};
  const scene::Fur a = scene::growFur(*m, plain, "test");
  const scene::Fur b = scene::growFur(*m, groomed, "test");
  ASSERT_EQ(a.roots.coats[0].triangle, b.roots.coats[0].triangle);
  ASSERT_EQ(a.roots.coats[0].tableIndex, b.roots.coats[0].tableIndex);
  const std::vector<float>& scale = b.roots.coats[0].widthScale;
  ASSERT_EQ(scale.size(), b.roots.coats[0].triangle.size());
  EXPECT_TRUE(a.roots.coats[0].widthScale.empty());
  const std::vector<float> tail = fur::regionWeights(m->skin, m->body, "b_Tail*");
  int inTail = 0, away = 0;
  std::vector<std::pair<float, float>> blend;  // (tail weight at the root, its scale)
  for (std::int64_t k = 0; k < b.roots.coats[0].size(); ++k) {
    const RootWeights t = rootWeights(*m, b.roots, k, tail);
    const float s = scale[static_cast<std::size_t>(k)];
    if (t.v[0] == 1.0f && t.v[1] == 1.0f && t.v[2] == 1.0f) {
      EXPECT_EQ(s, 2.0f) << "root " << k;
      ++inTail;
    } else if (std::max({t.v[0], t.v[1], t.v[2]}) == 0.0f) {
      EXPECT_EQ(s, 1.0f) << "root " << k;
      ++away;
    } else {
      blend.emplace_back(t.blend, s);
    }
  }
  EXPECT_GT(inTail, 200);
  EXPECT_GT(away, 5000);
  EXPECT_GT(blend.size(), 100u);
  std::sort(blend.begin(), blend.end());
  for (std::size_t i = 1; i < blend.size(); ++i)
    EXPECT_GE(blend[i].second - blend[i - 1].second, -1e-6f) << "the blend is not monotone";
  skin::DeformedSkin rest;
  skin::restSkin(m->skin, rest);
  fur::FurWorkspace ws;
  fur::FurFrame fa, fb;
  fur::generateFur(m->skin, a.roots, plain, rest, {}, ws, fa);
  fur::generateFur(m->skin, b.roots, groomed, rest, {}, ws, fb);
  const fur::HairBuffers& hb = fb.coats[0];
  ASSERT_EQ(hb.drawn, fa.coats[0].drawn);
  EXPECT_EQ(0, std::memcmp(hb.positions.data(), fa.coats[0].positions.data(),
                           hb.positions.size() * sizeof(float)));
  for (std::int64_t i = 0; i < hb.drawn; i += 97)
    EXPECT_EQ(fur::exportedWidth(fb, groomed, 0, i, 0),
              fur::exportedWidth(fa, plain, 0, i, 0) *
                  scale[static_cast<std::size_t>(hb.hairIds[static_cast<std::size_t>(i)])]);
}

TEST(GroomRegions, FoxTailTakesItsRegionsColourSourceBlendedAtItsBorder) {
  // The default coats colour the Fox from its texture (source creature); a region's "material"
  // source on the tail: hairs with tail weight 1 have exactly the colours of coats of the material
  // source, those away exactly the texture's, and those between a blend of the two.
  const scene::Model* m = fox();
  if (!m) GTEST_SKIP() << "shared Fox model absent";
  const fur::FurParams plain = foxParams();
  ASSERT_EQ(plain.coats[0].color.source, fur::ColorSource::Creature);
  fur::FurParams groomed = plain, coats = plain;
  groomed.regions = {
      {.match = "b_Tail*",
       .colorSource = std::array{fur::ColorSource::Material, fur::ColorSource::Material}}};
  for (fur::CoatParams& c : coats.coats) c.color.source = fur::ColorSource::Material;
  const scene::Fur a = scene::growFur(*m, plain, "test");
  const scene::Fur b = scene::growFur(*m, groomed, "test");
  const scene::Fur o = scene::growFur(*m, coats, "test");
  ASSERT_EQ(a.roots.coats[0].triangle, b.roots.coats[0].triangle);
  ASSERT_TRUE(b.groom.vertex.hasColorSourceWeights());
  // The root colour of root k as packed (the coat's one colour where every hair has it).
  const auto rootColor = [](const scene::Fur& f, std::int64_t k) {
    const fur::CoatColors& cc = f.colors.coats[0];
    return cc.perHair ? cc.packed[2 * static_cast<std::size_t>(k)] : fur::packSrgb8(cc.diffuse);
  };
  const std::vector<float> tail = fur::regionWeights(m->skin, m->body, "b_Tail*");
  int inTail = 0, away = 0, between = 0, outside = 0;
  for (std::int64_t k = 0; k < b.roots.coats[0].size(); ++k) {
    const RootWeights t = rootWeights(*m, b.roots, k, tail);
    const std::uint32_t got = rootColor(b, k);
    if (t.v[0] == 1.0f && t.v[1] == 1.0f && t.v[2] == 1.0f) {
      EXPECT_EQ(got, rootColor(o, k)) << "root " << k;
      ++inTail;
    } else if (std::max({t.v[0], t.v[1], t.v[2]}) == 0.0f) {
      EXPECT_EQ(got, rootColor(a, k)) << "root " << k;
      ++away;
    } else {
      // Each channel between the texture's and the material's (8-bit rounding aside).
      const Eigen::Vector3f c = fur::unpackSrgb8(got), x = fur::unpackSrgb8(rootColor(a, k)),
                            y = fur::unpackSrgb8(rootColor(o, k));
      for (int i = 0; i < 3; ++i)
        outside += c[i] < std::min(x[i], y[i]) - 0.01f || c[i] > std::max(x[i], y[i]) + 0.01f;
      ++between;
    }
  }
  EXPECT_GT(inTail, 200);
  EXPECT_GT(away, 5000);
  EXPECT_GT(between, 100);
  EXPECT_EQ(outside, 0);
}

TEST(GroomRegions, FoxTailAlongTheBoneTurnsAsACoatOfThatWeight) {
  // Sec. 3.4's w from the overcoat's 0.3 to 1 on the tail (hairs along the tail's bones).
  EXPECT_FLOAT_EQ(foxParams().coats[0].segmentDirectionWeight, 0.3f);
  expectFoxTailGrowsAsCoatsOfItsValue(
      {.match = "b_Tail*", .segmentDirectionWeight = Eigen::Vector2f(1.0f, 1.0f)},
      &fur::CoatParams::segmentDirectionWeight, 1.0f, &fur::CoatRoots::segmentWeight, true);
}

}  // namespace
}  // namespace pelage
