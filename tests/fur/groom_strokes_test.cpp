// Grooming strokes (fur/groom_strokes.h) on a 4 x 4 grid: the falloff's exact values, each tool's
// change at and away from the stroke (untouched vertices bit-identical), mirrors, list order, the
// JSON round trip and the errors.
#include "pelage/fur/groom_strokes.h"

#include <gtest/gtest.h>

#include "pelage/util/error.h"
#include "support/files.h"
#include "support/skins.h"

namespace pelage::fur {
namespace {

// 5 x 5 vertices 1 cm apart in z = 0, fur 1 cm.
const skin::SkinMesh& grid() {
  static const skin::SkinMesh g = test::makeGrid(4, 0.01f, 0.01f);
  return g;
}
Eigen::Vector3f at(int v) {
  return Eigen::Map<const Eigen::Vector3f>(grid().restPositions() + 3 * v);
}
int vertexAt(float x, float y) {
  for (int v = 0; v < grid().numVertices(); ++v)
    if ((at(v) - Eigen::Vector3f(x, y, 0.0f)).norm() < 1e-6f) return v;
  return -1;
}

GroomStroke stroke(BrushTool tool, std::vector<Eigen::Vector3f> points, float radius,
                   float strength) {
  GroomStroke s;
  s.tool = tool;
  s.points = std::move(points);
  s.radius = radius;
  s.strength = strength;
  return s;
}

TEST(GroomStrokes, FalloffIsFullInsideHalfTheRadiusAndSmoothToTheEdge) {
  EXPECT_EQ(brushFalloff(0.0f, 0.02f), 1.0f);
  EXPECT_EQ(brushFalloff(0.01f, 0.02f), 1.0f);
  EXPECT_FLOAT_EQ(brushFalloff(0.015f, 0.02f), 0.5f);       // smoothstep(1/2)
  EXPECT_FLOAT_EQ(brushFalloff(0.0175f, 0.02f), 0.15625f);  // smoothstep(1/4) = 5/32
  EXPECT_EQ(brushFalloff(0.02f, 0.02f), 0.0f);
  EXPECT_EQ(brushFalloff(1.0f, 0.02f), 0.0f);
}

TEST(GroomStrokes, LengthAlongALineScalesUnderItAndNothingAway) {
  // A stroke along x = 0.02 with radius 1.5 cm: the column x = 0.02 in full, x = 0.01 and 0.03 at
  // the falloff of 1 cm (smoothstep(2/3) = 20/27), the outer columns (2 cm away) untouched.
  const std::vector<GroomStroke> s = {
      stroke(BrushTool::Length, {{0.02f, 0.0f, 0.0f}, {0.02f, 0.04f, 0.0f}}, 0.015f, 1.5f)};
  VertexGroom g;
  applyGroomStrokes(grid(), s, g);
  ASSERT_EQ(g.length.size(), 25u);
  EXPECT_TRUE(g.density.empty());
  EXPECT_TRUE(g.tint.empty());
  for (int v = 0; v < 25; ++v) {
    const float dx = std::abs(at(v).x() - 0.02f);
    const float base = grid().furLengths()[v];
    if (dx < 1e-6f)
      EXPECT_EQ(g.length[static_cast<std::size_t>(v)], base * 1.5f);
    else if (dx < 0.0101f)
      EXPECT_FLOAT_EQ(g.length[static_cast<std::size_t>(v)], base * (1.0f + 0.5f * 20.0f / 27.0f));
    else
      EXPECT_EQ(g.length[static_cast<std::size_t>(v)], base) << v;  // bit for bit
  }
}

TEST(GroomStrokes, CutTrimsTowardItsLengthAndNeverLengthens) {
  // The grid's fur is 1 cm. A cut to 4 mm along x = 0.02 (radius 1.5 cm): the column in full, x =
  // 0.01 and 0.03 at the falloff 20/27, the rest untouched; a second cut to 2 cm changes nothing
  // (it only shortens); a cut to 0 with strength 0.5 halves the core.
  GroomStroke cut =
      stroke(BrushTool::Cut, {{0.02f, 0.0f, 0.0f}, {0.02f, 0.04f, 0.0f}}, 0.015f, 1.0f);
  cut.cutLength = 0.004f;
  GroomStroke longer = cut;
  longer.cutLength = 0.02f;
  VertexGroom g;
  applyGroomStrokes(grid(), {cut, longer}, g);
  ASSERT_EQ(g.length.size(), 25u);
  for (int v = 0; v < 25; ++v) {
    const float dx = std::abs(at(v).x() - 0.02f);
    const float base = grid().furLengths()[v];
    ASSERT_EQ(base, 0.01f);
    const float got = g.length[static_cast<std::size_t>(v)];
    if (dx < 1e-6f)
      EXPECT_EQ(got, 0.004f) << v;
    else if (dx < 0.0101f)
      EXPECT_FLOAT_EQ(got, 0.01f + 20.0f / 27.0f * (0.004f - 0.01f)) << v;
    else
      EXPECT_EQ(got, base) << v;
  }
  GroomStroke shave = stroke(BrushTool::Cut, {{0.0f, 0.0f, 0.0f}}, 0.005f, 0.5f);
  VertexGroom h;
  applyGroomStrokes(grid(), {shave}, h);
  EXPECT_EQ(h.length[static_cast<std::size_t>(vertexAt(0.0f, 0.0f))], 0.005f);
  EXPECT_EQ(h.length[static_cast<std::size_t>(vertexAt(0.01f, 0.0f))], 0.01f);
}

TEST(GroomStrokes, ClumpPaintsTheClumpScaleTowardItsStrength) {
  // A dab of radius 1 cm at the centre, strength 0.25: the centre (in the core) exactly 0.25, the
  // four neighbours 1 cm away (the edge) untouched at 1, the rest 1.
  const int centre = vertexAt(0.02f, 0.02f);
  VertexGroom g;
  applyGroomStrokes(grid(), {stroke(BrushTool::Clump, {{0.02f, 0.02f, 0.0f}}, 0.01f, 0.25f)}, g);
  ASSERT_EQ(g.clump.size(), 25u);
  EXPECT_TRUE(g.length.empty());
  for (int v = 0; v < 25; ++v)
    EXPECT_EQ(g.clump[static_cast<std::size_t>(v)], v == centre ? 0.25f : 1.0f) << v;
  // Half-way out (smoothstep 1/2 at 7.5 mm from a dab 7.5 mm left of the centre): 1 + 0.5 (0 - 1).
  applyGroomStrokes(grid(), {stroke(BrushTool::Clump, {{0.0125f, 0.02f, 0.0f}}, 0.01f, 0.0f)}, g);
  EXPECT_NEAR(g.clump[static_cast<std::size_t>(centre)], 0.25f * 0.5f, 1e-6f);
}

TEST(GroomStrokes, DensityAndColourPaintTowardTheirValues) {
  const int centre = vertexAt(0.02f, 0.02f), corner = vertexAt(0.0f, 0.0f);
  GroomStroke paint = stroke(BrushTool::Color, {{0.02f, 0.02f, 0.0f}}, 0.01f, 0.5f);
  paint.color = {0.0f, 1.0f, 3.0f};
  const std::vector<GroomStroke> s = {
      stroke(BrushTool::Density, {{0.02f, 0.02f, 0.0f}}, 0.01f, 0.0f), paint};
  VertexGroom g;
  applyGroomStrokes(grid(), s, g);
  EXPECT_EQ(g.density[static_cast<std::size_t>(centre)], 0.0f);
  EXPECT_EQ(g.density[static_cast<std::size_t>(corner)], 1.0f);
  EXPECT_TRUE(g.tint[static_cast<std::size_t>(centre)].isApprox(Eigen::Vector3f(0.5f, 1.0f, 2.0f)));
  EXPECT_EQ(g.tint[static_cast<std::size_t>(corner)], Eigen::Vector3f::Ones());
  // A second pass of the same colour stroke halves the remaining difference: strokes compose in
  // order.
  applyGroomStrokes(grid(), {paint}, g);
  EXPECT_TRUE(
      g.tint[static_cast<std::size_t>(centre)].isApprox(Eigen::Vector3f(0.25f, 1.0f, 2.5f)));
}

TEST(GroomStrokes, AMirroredStrokeAppliesOnBothSidesOfThePlane) {
  // A dab 5 mm above the grid's centre vertex, mirrored in z: the same dab 5 mm below; the vertex
  // is within half the radius of both, so its length doubles twice.
  GroomStroke s = stroke(BrushTool::Length, {{0.02f, 0.02f, 0.005f}}, 0.02f, 2.0f);
  VertexGroom once, mirrored;
  applyGroomStrokes(grid(), {s}, once);
  s.mirrorAxis = 2;
  applyGroomStrokes(grid(), {s}, mirrored);
  const auto c = static_cast<std::size_t>(vertexAt(0.02f, 0.02f));
  EXPECT_EQ(once.length[c], 2.0f * grid().furLengths()[c]);
  EXPECT_EQ(mirrored.length[c], 4.0f * grid().furLengths()[c]);
}

TEST(GroomStrokes, CombTurnsTowardTheStrokeInTheTangentPlaneAndMirrors) {
  // A stroke along +X lifted 5 mm off the grid (normal +Z): the comb is the tangential +X, full
  // under the core, the falloff's share at 1 cm, nothing beyond the radius; a second stroke along
  // +Y at half strength moves it halfway: (1 - 1/2) X + 1/2 Y.
  const GroomStroke along =
      stroke(BrushTool::Comb, {{0.0f, 0.02f, 0.005f}, {0.04f, 0.02f, 0.005f}}, 0.015f, 1.0f);
  VertexGroom g;
  applyGroomStrokes(grid(), {along}, g);
  const auto centre = static_cast<std::size_t>(vertexAt(0.02f, 0.02f));
  const auto side = static_cast<std::size_t>(vertexAt(0.02f, 0.03f));
  const auto away = static_cast<std::size_t>(vertexAt(0.02f, 0.04f));
  EXPECT_EQ(g.comb[centre], Eigen::Vector3f::UnitX());
  EXPECT_TRUE(g.comb[side].isApprox(brushFalloff(std::hypot(0.01f, 0.005f), 0.015f) *
                                    Eigen::Vector3f::UnitX()));
  EXPECT_EQ(g.comb[away], Eigen::Vector3f::Zero());
  applyGroomStrokes(
      grid(), {stroke(BrushTool::Comb, {{0.02f, 0.0f, 0.0f}, {0.02f, 0.04f, 0.0f}}, 0.015f, 0.5f)},
      g);
  EXPECT_TRUE(g.comb[centre].isApprox(Eigen::Vector3f(0.5f, 0.5f, 0.0f)));
  // Mirrored across x = 0 (the grid's edge): the mirrored stroke runs along -X over x <= 0, so the
  // edge column (x = 0, within the core of both) gets X then -X: nothing left.
  GroomStroke m =
      stroke(BrushTool::Comb, {{0.005f, 0.02f, 0.0f}, {0.01f, 0.02f, 0.0f}}, 0.02f, 1.0f);
  VertexGroom once, both;
  applyGroomStrokes(grid(), {m}, once);
  m.mirrorAxis = 0;
  applyGroomStrokes(grid(), {m}, both);
  const auto edge = static_cast<std::size_t>(vertexAt(0.0f, 0.02f));
  EXPECT_EQ(once.comb[edge], Eigen::Vector3f::UnitX());
  EXPECT_EQ(both.comb[edge], -Eigen::Vector3f::UnitX());
}

TEST(GroomStrokes, JsonRoundTripAndErrorsNameTheField) {
  GroomStroke a = stroke(BrushTool::Length, {{0.1f, -0.2f, 0.3f}, {0.4f, 0.5f, 0.6f}}, 0.06f, 1.5f);
  a.mirrorAxis = 1;
  GroomStroke b = stroke(BrushTool::Color, {{0.01f, 0.02f, 0.03f}}, 0.5f, 0.25f);
  b.color = {0.3f, 0.2f, 0.1f};
  GroomStroke c = stroke(BrushTool::Cut, {{0.01f, 0.02f, 0.03f}}, 0.05f, 0.75f);
  c.cutLength = 0.015f;
  const std::vector<GroomStroke> strokes = {a, b, c};
  const std::vector<GroomStroke> back = parseGroomStrokes(groomStrokesJson(strokes), "round trip");
  ASSERT_EQ(back.size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(back[k].tool, strokes[k].tool);
    EXPECT_EQ(back[k].points, strokes[k].points);
    EXPECT_EQ(back[k].radius, strokes[k].radius);
    EXPECT_EQ(back[k].strength, strokes[k].strength);
    EXPECT_EQ(back[k].color, strokes[k].color);
    EXPECT_EQ(back[k].mirrorAxis, strokes[k].mirrorAxis);
    EXPECT_EQ(back[k].cutLength, strokes[k].cutLength);
  }
  const auto bad = [](const std::string& stroke, std::initializer_list<std::string> parts) {
    test::expectInputError([&] { parseGroomStrokes("{\"strokes\": [" + stroke + "]}", "s.json"); },
                           parts);
  };
  bad(R"({"tool": "length", "points": [[0, 0, 0]], "radius": 0, "strength": 2})",
      {"s.json", "strokes[0].radius", "out of range"});
  bad(R"({"tool": "length", "points": [], "radius": 1, "strength": 2})",
      {"strokes[0].points", "0 points; accepted: 1 to 100000"});
  bad(R"({"tool": "length", "points": [[0, 0, 0]], "radius": 1, "strength": 11})",
      {"strokes[0].strength"});
  bad(R"({"tool": "density", "points": [[0, 0, 0]], "radius": 1, "strength": 1, "color": [1, 1, 1]})",
      {"strokes[0].color", "only the color brush"});
  bad(R"({"tool": "length", "points": [[0, 0, 0]], "radius": 1, "strength": 1, "mirror": "w"})",
      {"strokes[0].mirror", "accepted: x, y, z"});
  bad(R"({"tool": "clump", "points": [[0, 0, 0]], "radius": 1, "strength": 1.5})",
      {"strokes[0].strength", "out of range"});
  bad(R"({"tool": "cut", "points": [[0, 0, 0]], "radius": 1})", {"strokes[0]", "length"});
  bad(R"({"tool": "cut", "points": [[0, 0, 0]], "radius": 1, "length": 11})",
      {"strokes[0].length", "out of range"});
  bad(R"({"tool": "length", "points": [[0, 0, 0]], "radius": 1, "strength": 1, "length": 1})",
      {"strokes[0].length", "only the cut brush"});
  bad(R"({"tool": "comb", "points": [[0, 0, 0], [0, 0, 0]], "radius": 1})",
      {"strokes[0].points", "two distinct points"});
  bad(R"({"tool": "comb", "points": [[0, 0, 0], [1, 0, 0]], "radius": 1, "strength": 2})",
      {"strokes[0].strength"});
  bad(R"({"tool": "smudge", "points": [[0, 0, 0]], "radius": 1})", {"unknown brush 'smudge'"});
  bad(R"({"tool": "length", "points": [[0, 0, 0]], "radius": 1, "strength": 1, "size": 2})",
      {"strokes[0]", "size"});
}

}  // namespace
}  // namespace pelage::fur
