// The groom (fur/groom.h): region weights from skin regions and joint weights, the regions' vertex
// values on a grid, groom files (bit-identical round trip, another mesh refused, ranges), and the
// roots a vertex groom grows.
#include "pelage/fur/groom.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <functional>
#include <random>

#include "pelage/fur/colors.h"
#include "pelage/fur/hair_ply.h"
#include "pelage/util/error.h"
#include "support/files.h"
#include "support/skins.h"

namespace pelage::fur {
namespace {

// A 4 x 4 grid (25 vertices): the left half (x < 0.02) in region "left", bound half to segment
// "a" and half to "b" along x: vertex weight on "b" = x / 0.04.
struct Grid {
  skin::SkinMesh skin = test::makeGrid(4, 0.01f, 0.01f);
  anatomy::Body body;
  Grid() {
    body.segments.resize(2);
    body.segments[0].name = "a";
    body.segments[1].name = "b";
    body.segments[1].parent = 0;
    body.inverseBind.assign(2, Eigen::Affine3f::Identity());
    skin.regionNames = {"body", "left"};
    for (auto v : skin.mesh.vertices()) {
      const float x = skin.mesh.point(v)[0];
      skin.mesh.property(skin.region, v) = x < 0.015f ? 1 : 0;
      skin::Binding b;
      b.segment = {0, 1, 0, 0};
      b.weight = {1.0f - x / 0.04f, x / 0.04f, 0.0f, 0.0f};
      skin.mesh.property(skin.binding, v) = b;
    }
  }
  float x(int v) const { return skin.restPositions()[3 * v]; }
};

TEST(Groom, RegionWeightsFromRegionsAndJoints) {
  const Grid g;
  RegionMatch m;
  const std::vector<float> left = regionWeights(g.skin, g.body, "LEFT", &m);
  EXPECT_EQ(m.regions, std::vector<std::string>{"left"});
  EXPECT_TRUE(m.joints.empty());
  const std::vector<float> b = regionWeights(g.skin, g.body, "b", &m);
  EXPECT_EQ(m.joints, std::vector<std::string>{"b"});
  const std::vector<float> all = regionWeights(g.skin, g.body, "*", &m);
  EXPECT_EQ(m.vertices, 25);
  for (int v = 0; v < 25; ++v) {
    EXPECT_EQ(left[static_cast<std::size_t>(v)], g.x(v) < 0.015f ? 1.0f : 0.0f);
    EXPECT_FLOAT_EQ(b[static_cast<std::size_t>(v)], g.x(v) / 0.04f);
    EXPECT_EQ(all[static_cast<std::size_t>(v)], 1.0f);  // body + region matched: 1
  }
}

TEST(Groom, RegionsInListOrderOnTopOfAStart) {
  const Grid g;
  FurParams p;
  p.regions = {{.match = "b", .lengthScale = 3.0f},
               {.match = "left", .lengthMm = 5.0f, .densityScale = 0.5f},
               {.match = "a", .tint = {0.5f, 1.0f, 2.0f}}};
  VertexGroom start;
  start.length.assign(25, 0.02f);
  const VertexGroom out = groomFromRegions(g.skin, g.body, p, "test", nullptr, start);
  for (int v = 0; v < 25; ++v) {
    const auto vs = static_cast<std::size_t>(v);
    const float wb = g.x(v) / 0.04f;
    float len = 0.02f + wb * (0.06f - 0.02f);
    if (wb == 1.0f) len = 0.06f;
    if (g.x(v) < 0.015f) len = 0.005f;  // weight 1 in "left": the mm length exactly
    EXPECT_FLOAT_EQ(out.length[vs], len) << v;
    EXPECT_FLOAT_EQ(out.density[vs], g.x(v) < 0.015f ? 0.5f : 1.0f) << v;
    const float wa = 1.0f - wb;
    EXPECT_FLOAT_EQ(out.tint[vs].x(), 1.0f + wa * (0.5f - 1.0f)) << v;
    EXPECT_FLOAT_EQ(out.tint[vs].z(), 1.0f + wa * (2.0f - 1.0f)) << v;
  }
  FurParams none;
  EXPECT_TRUE(groomFromRegions(g.skin, g.body, none, "test").empty());
  p.regions.push_back({.match = "tail*"});
  test::expectInputError(
      [&] { groomFromRegions(g.skin, g.body, p, "fur 'x'"); },
      {"fur 'x'", "regions[3].match 'tail*'", "regions: body, left", "joints: a, b"});
}

TEST(Groom, RegionCoatValuesBlendFromTheCoats) {
  // The stiffness and the segment direction weight move from each coat's own toward the region's
  // by the vertex's weight in it, the later region on top.
  const Grid g;
  FurParams p;
  p.coats[kOvercoat].stiffness = 0.3f;
  p.coats[kUndercoat].stiffness = 0.7f;
  p.coats[kOvercoat].segmentDirectionWeight = 0.2f;
  p.coats[kUndercoat].segmentDirectionWeight = 0.6f;
  p.regions = {{.match = "b",
                .stiffness = Eigen::Vector2f(0.9f, 0.9f),
                .segmentDirectionWeight = Eigen::Vector2f(1.0f, 0.0f)},
               {.match = "left",
                .stiffness = Eigen::Vector2f(0.1f, 0.5f),
                .curlRadius = Eigen::Vector2f(0.25f, 0.5f)}};
  const VertexGroom out = groomFromRegions(g.skin, g.body, p, "test");
  ASSERT_EQ(out.stiffness.size(), 25u);
  ASSERT_EQ(out.segmentDirectionWeight.size(), 25u);
  ASSERT_EQ(out.curlRadius.size(), 25u);
  EXPECT_TRUE(out.curlTurns.empty());
  EXPECT_TRUE(out.length.empty() && out.density.empty() && out.tint.empty());
  for (int v = 0; v < 25; ++v) {
    const auto vs = static_cast<std::size_t>(v);
    const float wb = g.x(v) / 0.04f;
    Eigen::Vector2f stiffness(0.3f + wb * (0.9f - 0.3f), 0.7f + wb * (0.9f - 0.7f));
    Eigen::Vector2f weight(0.2f + wb * (1.0f - 0.2f), 0.6f + wb * (0.0f - 0.6f));
    if (wb == 1.0f) {  // the region's exactly
      stiffness = Eigen::Vector2f(0.9f, 0.9f);
      weight = Eigen::Vector2f(1.0f, 0.0f);
    }
    if (g.x(v) < 0.015f) stiffness = Eigen::Vector2f(0.1f, 0.5f);
    // The coats' radius is 0: the left region's (weight 1 there) or none.
    const Eigen::Vector2f radius =
        g.x(v) < 0.015f ? Eigen::Vector2f(0.25f, 0.5f) : Eigen::Vector2f::Zero();
    EXPECT_EQ(out.curlRadius[vs], radius) << v;
    EXPECT_EQ(out.stiffness[vs], stiffness) << v;
    EXPECT_EQ(out.segmentDirectionWeight[vs], weight) << v;
  }
}

TEST(Groom, FileRoundTripsBitIdenticallyAndRefusesAnotherMesh) {
  const Grid g;
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  VertexGroom v;
  for (int i = 0; i < 25; ++i) {
    v.length.push_back(u(rng) * 0.1f);
    v.density.push_back(u(rng) * 3.0f);
    v.tint.emplace_back(u(rng), u(rng) * 10.0f, 1.0f / 3.0f);
    v.clump.push_back(u(rng));
    v.stiffness.emplace_back(u(rng), 1.0f / 7.0f);
    v.segmentDirectionWeight.emplace_back(1.0f / 3.0f, u(rng));
    v.curlRadius.emplace_back(0.5f * u(rng), 0.1f);
    v.curlTurns.emplace_back(20.0f * u(rng), 1.0f / 7.0f);
  }
  const std::string file = testing::TempDir() + "grid.groom.json";
  writeGroomFile(file, g.skin, v);
  const VertexGroom back = readGroomFile(file, g.skin, "grid");
  ASSERT_EQ(back.length.size(), 25u);
  EXPECT_EQ(std::memcmp(back.length.data(), v.length.data(), 25 * sizeof(float)), 0);
  EXPECT_EQ(std::memcmp(back.density.data(), v.density.data(), 25 * sizeof(float)), 0);
  EXPECT_EQ(std::memcmp(back.tint.data(), v.tint.data(), 25 * sizeof(Eigen::Vector3f)), 0);
  EXPECT_EQ(std::memcmp(back.clump.data(), v.clump.data(), 25 * sizeof(float)), 0);
  ASSERT_EQ(back.stiffness.size(), 25u);
  EXPECT_EQ(std::memcmp(back.stiffness.data(), v.stiffness.data(), 25 * sizeof(Eigen::Vector2f)),
            0);
  for (auto field :
       {&VertexGroom::segmentDirectionWeight, &VertexGroom::curlRadius, &VertexGroom::curlTurns}) {
    ASSERT_EQ((back.*field).size(), 25u);
    EXPECT_EQ(std::memcmp((back.*field).data(), (v.*field).data(), 25 * sizeof(Eigen::Vector2f)),
              0);
  }
  EXPECT_EQ(groomFileJson(g.skin, back), test::readText(file));
  // The same counts but another shape: the hash tells them apart.
  const skin::SkinMesh moved = test::makeGrid(4, 0.011f, 0.01f);
  test::expectInputError([&] { readGroomFile(file, moved, "moved grid"); },
                         {"groom", file, "another mesh", "25 vertices", "model 'moved grid'"});
  const skin::SkinMesh bigger = test::makeGrid(5, 0.01f, 0.01f);
  test::expectInputError([&] { readGroomFile(file, bigger, "bigger"); }, {"36 vertices"});
  EXPECT_THROW(readGroomFile(testing::TempDir() + "absent.json", g.skin, "grid"), MissingFileError);
}

TEST(Groom, FileValuesAreChecked) {
  const Grid g;
  VertexGroom v;
  v.density.assign(25, 1.0f);
  std::string text = groomFileJson(g.skin, v);
  const std::string good = text;
  text.replace(text.find("[1.0,"), 5, "[-1.0,");
  test::expectInputError([&] { parseGroomFile(text, "f.json", g.skin, "grid"); },
                         {"f.json", "density[0]", "[0, 100]"});
  text = good;
  text.replace(text.find("[1.0,"), 5, "[\"x\",");
  test::expectInputError([&] { parseGroomFile(text, "f.json", g.skin, "grid"); }, {"density[0]"});
  text = good;
  text.replace(text.find("\"density\""), 9, "\"densty\"");
  test::expectInputError([&] { parseGroomFile(text, "f.json", g.skin, "grid"); }, {"densty"});
  VertexGroom c;
  c.clump.assign(25, 0.5f);
  text = groomFileJson(g.skin, c);
  text.replace(text.find("[0.5,"), 5, "[1.5,");
  test::expectInputError([&] { parseGroomFile(text, "f.json", g.skin, "grid"); },
                         {"f.json", "clump[0]", "[0, 1]"});
  VertexGroom st;
  st.stiffness.assign(25, Eigen::Vector2f(0.5f, 0.25f));
  text = groomFileJson(g.skin, st);
  const std::string goodStiffness = text;
  text.replace(text.find("[0.5,0.25]"), 10, "[0.5,1.25]");
  test::expectInputError([&] { parseGroomFile(text, "f.json", g.skin, "grid"); },
                         {"f.json", "stiffness[0]", "2 numbers", "[0, 1]"});
  text = goodStiffness;
  text.replace(text.find("[0.5,0.25]"), 10, "[0.5]");
  test::expectInputError([&] { parseGroomFile(text, "f.json", g.skin, "grid"); },
                         {"stiffness[0]", "2 numbers"});
  VertexGroom sw;
  sw.segmentDirectionWeight.assign(25, Eigen::Vector2f(0.5f, 0.25f));
  text = groomFileJson(g.skin, sw);
  text.replace(text.rfind("[0.5,0.25]"), 10, "[0.5,-0.25]");
  test::expectInputError([&] { parseGroomFile(text, "f.json", g.skin, "grid"); },
                         {"f.json", "segmentDirectionWeight[24]", "2 numbers", "[0, 1]"});
  VertexGroom curl;
  curl.curlRadius.assign(25, Eigen::Vector2f(0.5f, 0.25f));
  curl.curlTurns.assign(25, Eigen::Vector2f(20.0f, 2.0f));
  text = groomFileJson(g.skin, curl);
  const std::string goodCurl = text;
  text.replace(text.find("[0.5,0.25]"), 10, "[0.75,0.25]");
  test::expectInputError([&] { parseGroomFile(text, "f.json", g.skin, "grid"); },
                         {"f.json", "curlRadius[0]", "[0, 0.5]"});
  text = goodCurl;
  text.replace(text.find("[20.0,2.0]"), 10, "[20.5,2.0]");
  test::expectInputError([&] { parseGroomFile(text, "f.json", g.skin, "grid"); },
                         {"f.json", "curlTurns[0]", "[0, 20]"});
  VertexGroom width;
  width.widthScale.assign(25, Eigen::Vector2f(2.5f, 0.5f));
  text = groomFileJson(g.skin, width);
  text.replace(text.rfind("[2.5,0.5]"), 9, "[2.5,10.5]");
  test::expectInputError([&] { parseGroomFile(text, "f.json", g.skin, "grid"); },
                         {"f.json", "widthScale[24]", "2 numbers", "[0, 10]"});
  VertexGroom sources;
  for (int s = 0; s < kColorSourceCount; ++s)
    sources.colorSourceWeight[static_cast<std::size_t>(s)].assign(
        25, Eigen::Vector2f(s == 0 ? 0.75f : (s == 2 ? 0.25f : 0.0f), s == 1 ? 1.0f : 0.0f));
  text = groomFileJson(g.skin, sources);
  const std::string goodSources = text;
  EXPECT_EQ(parseGroomFile(text, "f.json", g.skin, "grid").colorSourceWeight,
            sources.colorSourceWeight);
  text.replace(text.find("[0.75,0.0]"), 10, "[1.75,0.0]");
  test::expectInputError([&] { parseGroomFile(text, "f.json", g.skin, "grid"); },
                         {"f.json", "colorSourceWeight", "material", "[0, 1]"});
  text = goodSources;
  text.replace(text.find("[0.75,0.0]"), 10, "[0.5,0.0]");
  test::expectInputError(
      [&] { parseGroomFile(text, "f.json", g.skin, "grid"); },
      {"f.json", "colorSourceWeight", "overcoat weights of vertex 0 sum to 0.75", "accepted: 1"});
  text = goodSources;
  text.replace(text.find("\"vertex\""), 8, "\"vortex\"");
  test::expectInputError([&] { parseGroomFile(text, "f.json", g.skin, "grid"); },
                         {"f.json", "colorSourceWeight", "vortex"});
  test::expectInputError([&] { parseGroomFile("{}", "f.json", g.skin, "grid"); },
                         {"f.json", "not a groom file"});
  test::expectInputError([&] { parseGroomFile("[1,", "f.json", g.skin, "grid"); }, {"f.json"});
}

TEST(Groom, VertexLengthsAndDensityShapeTheRoots) {
  const Grid g;
  FurParams p = test::simpleParams(HairStyle::Polyline, 20000);
  Groom groom;
  // No hair on the left (length 0 there), density 3 on the far right column of triangles.
  groom.vertex.length.assign(25, 0.01f);
  groom.vertex.density.assign(25, 1.0f);
  for (int v = 0; v < 25; ++v) {
    if (g.x(v) < 0.005f) groom.vertex.length[static_cast<std::size_t>(v)] = 0.0f;
    if (g.x(v) > 0.035f) groom.vertex.density[static_cast<std::size_t>(v)] = 3.0f;
  }
  const FurRoots roots = growRoots(g.skin, p, groom);
  EXPECT_EQ(roots.vertexLength, groom.vertex.length);
  // Triangles whose three vertices have length 0: none here (each touches x = 0.01). Per-triangle
  // densities: a triangle with k vertices on the right edge has mean (3 - k + 3 k) / 3.
  std::vector<double> weight(32);
  double sum = 0.0;
  for (int t = 0; t < 32; ++t) {
    const std::int32_t* tv = g.skin.triangles.data() + 3 * t;
    double d = 0.0;
    for (int k = 0; k < 3; ++k) d += groom.vertex.density[static_cast<std::size_t>(tv[k])];
    weight[static_cast<std::size_t>(t)] = d / 3.0;
    sum += d / 3.0;
  }
  for (int t = 0; t < 32; ++t) {
    const double expected = 20000.0 * weight[static_cast<std::size_t>(t)] / sum;
    const std::int32_t n = roots.coats[0].triangleStart[static_cast<std::size_t>(t) + 1] -
                           roots.coats[0].triangleStart[static_cast<std::size_t>(t)];
    EXPECT_LE(std::abs(n - expected), 1.0) << "triangle " << t;  // random rounding
  }
}

TEST(Groom, HairsOnAGroomMatchTheReferenceOnEveryPathAndThreadCount) {
  // Vertex lengths from 0 (bare) to twice the skin's, densities, stiffness, w, helix and width,
  // on a curved skin: every
  // style, kernel target and thread count gives the scalar reference's hairs bit for bit.
  const skin::SkinMesh s = test::makeSphere(0.1f, 24, 48);
  skin::DeformedSkin d;
  skin::restSkin(s, d);
  Groom groom;
  for (int v = 0; v < s.numVertices(); ++v) {
    const float z = s.restPositions()[3 * v + 2];
    groom.vertex.length.push_back(z < -0.07f ? 0.0f : s.furLengths()[v] * (1.5f + 10.0f * z));
    groom.vertex.density.push_back(z > 0.0f ? 2.0f : 0.5f);
    groom.vertex.stiffness.emplace_back(0.5f + 5.0f * z, 1.0f - (0.5f + 5.0f * z));
    groom.vertex.segmentDirectionWeight.emplace_back(0.5f - 5.0f * z, 0.5f + 5.0f * z);
    // A helix on both coats (the undercoat's own is 0.2 radius, 2.5 turns), turns varying.
    groom.vertex.curlRadius.emplace_back(z > 0.0f ? 0.1f : 0.0f, 0.2f);
    groom.vertex.curlTurns.emplace_back(2.0f + 20.0f * z, 2.5f + 30.0f * z);
    // Tubes of a width of their own (1 to 3 times the coat's radius, thinner undercoat).
    groom.vertex.widthScale.emplace_back(2.0f + 10.0f * z, 0.7f - 3.0f * z);
  }
  test::checkStylesAgainstReference(s, d, 6000, Eigen::Vector3f(0.0f, 0.0f, 0.1f), groom);
}

// How a groom's per-coat value stands in a coat's parameters: `set` gives a coat the value (as its
// own field, or a width as a scale of the coat's), `plain` is the groom value that keeps the coat.
struct CoatValue {
  std::function<void(CoatParams&, float)> set;
  std::function<float(const CoatParams&)> plain;
};
CoatValue coatField(float CoatParams::*field) {
  return {[field](CoatParams& c, float v) { c.*field = v; },
          [field](const CoatParams& c) { return c.*field; }};
}

// A groom of one per-coat value everywhere (VertexGroom::*field = `value` for (overcoat,
// undercoat); the default preset's coats, as `prepare` changes them) gives, bit for bit, the hairs
// of coats of that value (`coat.set`; each root's own, CoatRoots::*perRoot, is the coat's); the
// plain coats' value on the lower half changes only the upper hairs.
void expectGroomGrowsAsCoatsOfItsValue(std::vector<Eigen::Vector2f> VertexGroom::*field,
                                       const CoatValue& coat,
                                       std::vector<float> CoatRoots::*perRoot,
                                       const Eigen::Vector2f& value,
                                       const std::function<void(FurParams&)>& prepare = {}) {
  const skin::SkinMesh s = test::makeSphere(0.1f, 16, 32);
  skin::DeformedSkin d;
  skin::restSkin(s, d);
  FurParams plain = loadFurPreset("default");
  plain.setHairCount(4000);
  plain.culling.enabled = false;
  if (prepare) prepare(plain);
  FurParams coats = plain;
  coat.set(coats.coats[kOvercoat], value.x());
  coat.set(coats.coats[kUndercoat], value.y());
  Groom groom;
  (groom.vertex.*field).assign(static_cast<std::size_t>(s.numVertices()), value);
  const FurRoots groomed = growRoots(s, plain, groom);
  const FurRoots ungroomed = growRoots(s, coats);
  ASSERT_EQ((groomed.coats[kOvercoat].*perRoot).size(),
            static_cast<std::size_t>(groomed.coats[kOvercoat].size()));
  EXPECT_TRUE((ungroomed.coats[kOvercoat].*perRoot).empty());
  EXPECT_TRUE(test::sameHairs(test::furFrame(s, groomed, plain, d),
                              test::furFrame(s, ungroomed, coats, d)));
  EXPECT_FALSE(test::sameHairs(test::furFrame(s, groomed, plain, d),
                               test::furFrame(s, ungroomed, plain, d)));
  // The value only on the upper half: hairs whose three vertices are all below keep the plain
  // coat's shape exactly; those all above are the groomed coat's.
  for (int v = 0; v < s.numVertices(); ++v)
    if (s.restPositions()[3 * v + 2] < 0.0f)
      (groom.vertex.*field)[static_cast<std::size_t>(v)] =
          Eigen::Vector2f(coat.plain(plain.coats[kOvercoat]), coat.plain(plain.coats[kUndercoat]));
  const FurRoots half = growRoots(s, plain, groom);
  const FurFrame mixed = test::furFrame(s, half, plain, d);
  const FurFrame allPlain = test::furFrame(s, ungroomed, plain, d);
  const FurFrame allGroomed = test::furFrame(s, ungroomed, coats, d);
  for (int c = 0; c < kCoatCount; ++c) {
    const auto cs = static_cast<std::size_t>(c);
    const HairBuffers& m = mixed.coats[cs];
    const std::size_t n = static_cast<std::size_t>(m.layout.pointsPerHair()) * 3;
    int below = 0, above = 0;
    for (std::int64_t h = 0; h < m.drawn; ++h) {
      const std::int32_t t = half.coats[cs].triangle[static_cast<std::size_t>(h)];
      int up = 0;
      for (int k = 0; k < 3; ++k) up += s.restPositions()[3 * s.triangles[3 * t + k] + 2] >= 0.0f;
      const FurFrame* same = up == 0 ? &allPlain : up == 3 ? &allGroomed : nullptr;
      if (!same) continue;
      (up == 0 ? below : above) += 1;
      EXPECT_EQ(0, std::memcmp(m.positions.data() + h * static_cast<std::int64_t>(n),
                               same->coats[cs].positions.data() + h * static_cast<std::int64_t>(n),
                               n * sizeof(float)))
          << "coat " << c << " hair " << h;
    }
    EXPECT_GT(below, c == kOvercoat ? 1000 : 200) << "coat " << c;
    EXPECT_GT(above, c == kOvercoat ? 1000 : 200) << "coat " << c;
  }
}

TEST(Groom, AStiffnessGroomDroopsEachHairAsACoatOfItsStiffness) {
  expectGroomGrowsAsCoatsOfItsValue(&VertexGroom::stiffness, coatField(&CoatParams::stiffness),
                                    &CoatRoots::floppiness, Eigen::Vector2f(0.85f, 0.05f));
}

TEST(Groom, ADirectionWeightGroomTurnsEachHairAsACoatOfItsWeight) {
  // Sec. 3.4's w per hair: the default coats' w is 0.3; 0.9 and 0.6 lean the hairs further
  // toward the sphere's segment direction (+x).
  expectGroomGrowsAsCoatsOfItsValue(&VertexGroom::segmentDirectionWeight,
                                    coatField(&CoatParams::segmentDirectionWeight),
                                    &CoatRoots::segmentWeight, Eigen::Vector2f(0.9f, 0.6f));
}

TEST(Groom, ACurlGroomWindsEachHairAsACoatOfItsHelix) {
  // Sec. 3.8's helix per hair (curve and tube coats): a radius groom on straight coats with
  // 2.5 turns, and a turns groom on coats of radius 0.1; each alone keeps the coats' other.
  const auto styled = [](HairStyle style, float radius, float turns) {
    return [=](FurParams& p) {
      for (CoatParams& c : p.coats) {
        c.style = style;
        c.curlRadius = radius;
        c.curlTurns = turns;
      }
    };
  };
  expectGroomGrowsAsCoatsOfItsValue(&VertexGroom::curlRadius, coatField(&CoatParams::curlRadius),
                                    &CoatRoots::curlRadius, Eigen::Vector2f(0.15f, 0.3f),
                                    styled(HairStyle::Curve, 0.0f, 2.5f));
  expectGroomGrowsAsCoatsOfItsValue(&VertexGroom::curlTurns, coatField(&CoatParams::curlTurns),
                                    &CoatRoots::curlTurns, Eigen::Vector2f(3.0f, 1.5f),
                                    styled(HairStyle::Tube, 0.1f, 0.0f));
}

// A coat's width as a scale of its own (root and tip); the plain coat's scale is 1.
CoatValue widthScaled() {
  return {[](CoatParams& c, float s) {
            c.width = {c.width.rootMm * s, c.width.tipMm * s};
          },
          [](const CoatParams&) { return 1.0f; }};
}

TEST(Groom, AWidthGroomThickensEachTubeAsACoatOfThatWidth) {
  // Powers of two: a tube of the coat's radius times 2 (or 0.5) is exactly the tube of a coat of
  // twice (half) the width.
  expectGroomGrowsAsCoatsOfItsValue(&VertexGroom::widthScale, widthScaled(), &CoatRoots::widthScale,
                                    Eigen::Vector2f(2.0f, 0.5f), [](FurParams& p) {
                                      for (CoatParams& c : p.coats) c.style = HairStyle::Tube;
                                    });
}

TEST(Groom, AWidthGroomKeepsStrandsInPlaceAndGivesEachItsWidth) {
  // Strands are as thin as the renderer draws them: the groom leaves their points, and hands each
  // drawn hair its root's scale (HairBuffers::widthScales; what the exports multiply by) and the
  // renderer the same in its colours' alpha bytes (colors.h packHairWidth).
  const skin::SkinMesh s = test::makeSphere(0.1f, 16, 32);
  skin::DeformedSkin d;
  skin::restSkin(s, d);
  FurParams p = loadFurPreset("default");
  p.setHairCount(4000);
  p.culling.enabled = false;
  Groom groom;
  for (int v = 0; v < s.numVertices(); ++v)  // 1 at the bottom pole to 3 at the top
    groom.vertex.widthScale.emplace_back(2.0f + 10.0f * s.restPositions()[3 * v + 2], 0.75f);
  const FurRoots plain = growRoots(s, p);
  const FurRoots groomed = growRoots(s, p, groom);
  const FurFrame a = test::furFrame(s, plain, p, d);
  const FurFrame b = test::furFrame(s, groomed, p, d);
  EXPECT_TRUE(test::sameHairs(a, b));
  const FurColors colors = colorRoots(s, groomed, p, groom);
  const FurColors plainColors = colorRoots(s, plain, p, Groom{});
  for (int c = 0; c < kCoatCount; ++c) {
    const auto cs = static_cast<std::size_t>(c);
    const HairBuffers& hb = b.coats[cs];
    EXPECT_TRUE(a.coats[cs].widthScales.empty());
    ASSERT_EQ(hb.widthScales.size(), static_cast<std::size_t>(hb.drawn));
    const std::vector<float>& own = groomed.coats[cs].widthScale;
    const auto [lo, hi] = std::minmax_element(own.begin(), own.end());
    EXPECT_GE(*lo, c == kOvercoat ? 1.0f : 0.75f);
    EXPECT_LE(*hi, c == kOvercoat ? 3.0f : 0.75f);
    if (c == kOvercoat) {
      EXPECT_GT(*hi - *lo, 1.5f);
    }
    ASSERT_TRUE(colors.coats[cs].perHair && colors.coats[cs].perHairWidth);
    for (std::int64_t i = 0; i < hb.drawn; ++i) {
      const auto r = static_cast<std::size_t>(hb.hairIds[static_cast<std::size_t>(i)]);
      ASSERT_EQ(hb.widthScaleOf(i), own[r]);
      for (int k = 0; k < hb.layout.pointsPerHair(); ++k)
        ASSERT_EQ(exportedWidth(b, p, c, i, k), exportedWidth(a, p, c, i, k) * own[r]);
      const std::uint32_t* pair = colors.coats[cs].packed.data() + 2 * r;
      EXPECT_NEAR(hairWidthScale(pair), own[r], 0.5f / kWidthScaleCodes);
      if (plainColors.coats[cs].perHair) {  // the colours themselves are the groomless ones
        for (int e = 0; e < 2; ++e)
          EXPECT_EQ(pair[e] & 0x00FFFFFFu, plainColors.coats[cs].packed[2 * r + e] & 0x00FFFFFFu);
      }
    }
  }
}

}  // namespace
}  // namespace pelage::fur
