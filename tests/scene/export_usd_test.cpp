// USD ASCII export: the layer's structure (prims, curve counts, time samples), exact point values,
// the Bezier control points of the curve style (sec. 3.8), and write failures.
#include "pelage/scene/export_usd.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "pelage/fur/colors.h"
#include "pelage/fur/generate.h"
#include "pelage/util/error.h"
#include "support/exports.h"
#include "support/files.h"

namespace pelage::test {
namespace {

std::string exportLayer(const scene::Fur& fur, int first, int frames, const TempDir& dir,
                        std::vector<scene::FrameState>* keep = nullptr) {
  const std::string path = dir.file("critter.usda");
  scene::UsdExportOptions o;
  o.framesPerSecond = 24.0;
  o.firstFrame = first;
  o.lastFrame = first + frames - 1;
  o.comment = "test \"layer\"";
  scene::UsdaWriter w(path, sceneCritter(), fur, o);
  scene::FrameState state;
  for (int i = 0; i < frames; ++i) {
    exportFrame(fur, i, state);
    w.addFrame(first + i, state);
    if (keep) {
      keep->emplace_back();
      exportFrame(fur, i, keep->back());
    }
  }
  const scene::UsdExportCounts n = w.finish();
  EXPECT_EQ(n.frames, frames);
  EXPECT_EQ(n.curves[0], fur.roots.coats[0].size());
  EXPECT_EQ(n.curves[1], fur.roots.coats[1].size());
  return readText(path);
}

TEST(ExportUsd, LayerStructureCountsAndTimeSamples) {
  const scene::Fur fur = exportFur(fur::HairStyle::Polyline);
  TempDir dir;
  const std::string text = exportLayer(fur, 10, 3, dir);
  ASSERT_EQ(text.rfind("#usda 1.0\n", 0), 0u);
  EXPECT_NE(text.find("defaultPrim = \"critter\""), std::string::npos);
  EXPECT_NE(text.find("startTimeCode = 10\n"), std::string::npos);
  EXPECT_NE(text.find("endTimeCode = 12\n"), std::string::npos);
  EXPECT_NE(text.find("timeCodesPerSecond = 24\n"), std::string::npos);
  EXPECT_NE(text.find("upAxis = \"Z\""), std::string::npos);
  // Balanced brackets, braces and parentheses; nothing but the layer left in the directory.
  int braces = 0, brackets = 0, parens = 0;
  for (char c : text) {
    braces += c == '{' ? 1 : c == '}' ? -1 : 0;
    brackets += c == '[' ? 1 : c == ']' ? -1 : 0;
    parens += c == '(' ? 1 : c == ')' ? -1 : 0;
    ASSERT_GE(braces, 0);
    ASSERT_GE(brackets, 0);
    ASSERT_GE(parens, 0);
  }
  EXPECT_EQ(braces, 0);
  EXPECT_EQ(brackets, 0);
  EXPECT_EQ(parens, 0);
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path()),
                          std::filesystem::directory_iterator()),
            1);

  const scene::Model& m = sceneCritter();
  const std::string skin = usdBlock(text, "def Mesh \"skin\"");
  ASSERT_FALSE(skin.empty());
  EXPECT_EQ(usdArray(skin, "int[] faceVertexCounts").size(),
            static_cast<std::size_t>(m.skin.numTriangles()));
  const std::vector<double> indices = usdArray(skin, "int[] faceVertexIndices");
  ASSERT_EQ(indices.size(), m.skin.triangles.size());
  for (std::size_t i = 0; i < indices.size(); i += 997) EXPECT_EQ(indices[i], m.skin.triangles[i]);
  const auto skinPoints = usdTimeSamples(skin, "point3f[] points");
  ASSERT_EQ(skinPoints.size(), 3u);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(skinPoints[static_cast<std::size_t>(i)].first, 10 + i);
    EXPECT_EQ(skinPoints[static_cast<std::size_t>(i)].second.size(),
              static_cast<std::size_t>(m.skin.numVertices()) * 3);
  }
  EXPECT_EQ(usdTimeSamples(skin, "normal3f[] normals").size(), 3u);
  EXPECT_EQ(usdTimeSamples(skin, "float3[] extent").size(), 3u);

  for (int c = 0; c < 2; ++c) {
    const std::string curves =
        usdBlock(text, c == 0 ? "def BasisCurves \"overcoat\"" : "def BasisCurves \"undercoat\"");
    ASSERT_FALSE(curves.empty()) << c;
    EXPECT_NE(curves.find("uniform token type = \"linear\""), std::string::npos);
    EXPECT_EQ(curves.find("basis"), std::string::npos);
    const std::vector<double> counts = usdArray(curves, "int[] curveVertexCounts");
    const std::int64_t n = fur.roots.coats[static_cast<std::size_t>(c)].size();
    ASSERT_EQ(static_cast<std::int64_t>(counts.size()), n);
    for (double k : counts) ASSERT_EQ(k, 8.0);
    const auto samples = usdTimeSamples(curves, "point3f[] points");
    ASSERT_EQ(samples.size(), 3u);
    for (const auto& s : samples) EXPECT_EQ(static_cast<std::int64_t>(s.second.size()), n * 8 * 3);
    EXPECT_EQ(usdTimeSamples(curves, "float3[] extent").size(), 3u);
    // Widths per vertex, tapering from the coat's root width to its tip width (mm -> m).
    const std::vector<double> widths = usdArray(curves, "float[] widths");
    ASSERT_EQ(static_cast<std::int64_t>(widths.size()), n * 8);
    const fur::StrandWidth& w = fur.params.coats[static_cast<std::size_t>(c)].width;
    for (std::int64_t h = 0; h < n; h += 97) {
      EXPECT_FLOAT_EQ(static_cast<float>(widths[static_cast<std::size_t>(h * 8)]),
                      1e-3f * w.rootMm);
      EXPECT_NEAR(widths[static_cast<std::size_t>(h * 8 + 7)], 1e-3 * static_cast<double>(w.tipMm),
                  1e-10);
      EXPECT_GT(widths[static_cast<std::size_t>(h * 8 + 3)],
                widths[static_cast<std::size_t>(h * 8 + 4)]);
    }
    // Colours (linear): per hair, root to tip over the 8 vertices; or the coat's one colour.
    const std::vector<double> color = usdArray(curves, "color3f[] primvars:displayColor");
    const fur::CoatColors& cc = fur.colors.coats[static_cast<std::size_t>(c)];
    if (cc.perHair) {
      EXPECT_NE(curves.find("interpolation = \"vertex\""), std::string::npos);
      ASSERT_EQ(static_cast<std::int64_t>(color.size()), n * 8 * 3);
      for (std::int64_t h = 0; h < n; h += 13) {
        const Eigen::Vector3f root = fur::unpackSrgb8(cc.packed[static_cast<std::size_t>(2 * h)]);
        const Eigen::Vector3f tip =
            fur::unpackSrgb8(cc.packed[static_cast<std::size_t>(2 * h + 1)]);
        for (int j = 0; j < 3; ++j) {
          EXPECT_NEAR(color[static_cast<std::size_t>(h * 24 + j)], root[j], 1e-6);
          EXPECT_NEAR(color[static_cast<std::size_t>(h * 24 + 21 + j)], tip[j], 1e-6);
        }
      }
    } else {
      ASSERT_EQ(color.size(), 3u);
      EXPECT_FLOAT_EQ(static_cast<float>(color[0]), cc.diffuse.x());
    }
  }
}

TEST(ExportUsd, PointsAreTheFramesHairsExactly) {
  const scene::Fur fur = exportFur(fur::HairStyle::Polyline, 500.0);
  TempDir dir;
  std::vector<scene::FrameState> frames;
  const std::string text = exportLayer(fur, 0, 2, dir, &frames);
  const auto samples =
      usdTimeSamples(usdBlock(text, "def BasisCurves \"overcoat\""), "point3f[] points");
  ASSERT_EQ(samples.size(), 2u);
  for (int f = 0; f < 2; ++f) {
    const fur::HairBuffers& b = frames[static_cast<std::size_t>(f)].fur.coats[0];
    const std::vector<double>& v = samples[static_cast<std::size_t>(f)].second;
    ASSERT_EQ(v.size(), static_cast<std::size_t>(b.drawn * 8 * 3));
    for (std::size_t i = 0; i < v.size(); ++i)
      ASSERT_EQ(static_cast<float>(v[i]), b.positions.data()[i]) << "frame " << f << " value " << i;
  }
  // The frames differ (the pose changes), so the samples are per frame.
  EXPECT_NE(samples[0].second, samples[1].second);
  const auto skin = usdTimeSamples(usdBlock(text, "def Mesh \"skin\""), "point3f[] points");
  ASSERT_EQ(skin.size(), 2u);
  for (std::size_t v = 0; v < frames[1].skin.positions.size(); v += 101)
    for (int a = 0; a < 3; ++a)
      ASSERT_EQ(static_cast<float>(skin[1].second[v * 3 + static_cast<std::size_t>(a)]),
                frames[1].skin.positions[v][a]);
}

// Sec. 3.8: the curve style is written as the paper's cubic Bezier; evaluated at t_k = k / (K - 1)
// it gives the tessellated points the renderer draws.
TEST(ExportUsd, CurveStyleIsTheCubicBezierOfSection38) {
  const scene::Fur fur = exportFur(fur::HairStyle::Curve, 600.0);
  TempDir dir;
  std::vector<scene::FrameState> frames;
  const std::string text = exportLayer(fur, 0, 1, dir, &frames);
  const std::string curves = usdBlock(text, "def BasisCurves \"overcoat\"");
  EXPECT_NE(curves.find("uniform token type = \"cubic\""), std::string::npos);
  EXPECT_NE(curves.find("uniform token basis = \"bezier\""), std::string::npos);
  for (double k : usdArray(curves, "int[] curveVertexCounts")) ASSERT_EQ(k, 4.0);
  const auto samples = usdTimeSamples(curves, "point3f[] points");
  ASSERT_EQ(samples.size(), 1u);
  const fur::HairBuffers& b = frames[0].fur.coats[0];
  const int K = b.layout.pointsPerHair();
  ASSERT_EQ(K, fur.params.coats[0].curvePoints);
  double worst = 0.0;
  for (std::int64_t h = 0; h < b.drawn; ++h) {
    const double* P = samples[0].second.data() + h * 12;
    for (int k = 0; k < K; ++k) {
      const double t = k / double(K - 1), s = 1.0 - t;
      const double w[4] = {s * s * s, 3 * s * s * t, 3 * s * t * t, t * t * t};
      for (int a = 0; a < 3; ++a) {
        double x = 0.0;
        for (int j = 0; j < 4; ++j) x += w[j] * P[j * 3 + a];
        worst = std::max(
            worst, std::abs(x - static_cast<double>(b.positions.data()[(h * K + k) * 3 + a])));
      }
    }
  }
  EXPECT_LT(worst, 2e-6) << "metres";  // float rounding of critter-sized hairs (about 2 cm)
}

TEST(ExportUsd, CurledCurvesPassThroughEveryPoint) {
  const scene::Fur fur = exportFur(fur::HairStyle::Curve, 300.0, 0.2f);
  TempDir dir;
  std::vector<scene::FrameState> frames;
  const std::string text = exportLayer(fur, 0, 1, dir, &frames);
  const std::string curves = usdBlock(text, "def BasisCurves \"overcoat\"");
  const int K = fur.params.coats[0].curvePoints;
  const int V = 3 * (K - 1) + 1;
  for (double k : usdArray(curves, "int[] curveVertexCounts")) ASSERT_EQ(k, V);
  const auto samples = usdTimeSamples(curves, "point3f[] points");
  const fur::HairBuffers& b = frames[0].fur.coats[0];
  for (std::int64_t h = 0; h < b.drawn; ++h)
    for (int k = 0; k < K; ++k)
      for (int a = 0; a < 3; ++a)
        ASSERT_EQ(static_cast<float>(
                      samples[0].second[static_cast<std::size_t>((h * V + 3 * k) * 3 + a)]),
                  b.positions.data()[(h * K + k) * 3 + a]);
}

TEST(ExportUsd, TubesAreCentreCurvesWithTaperedWidths) {
  const scene::Fur fur = exportFur(fur::HairStyle::Tube, 300.0);
  TempDir dir;
  const std::string text = exportLayer(fur, 0, 1, dir);
  const std::string curves = usdBlock(text, "def BasisCurves \"overcoat\"");
  EXPECT_NE(curves.find("uniform token type = \"cubic\""), std::string::npos);
  EXPECT_NE(curves.find("interpolation = \"varying\""), std::string::npos);
  const std::vector<double> widths = usdArray(curves, "float[] widths");
  const std::int64_t n = fur.roots.coats[0].size();
  ASSERT_EQ(static_cast<std::int64_t>(widths.size()), n * 2);
  const fur::StrandWidth& w = fur.params.coats[0].width;
  EXPECT_FLOAT_EQ(static_cast<float>(widths[0]), 1e-3f * w.rootMm);
  EXPECT_NEAR(widths[1], 1e-3 * static_cast<double>(w.tipMm), 1e-9);
  // The one taper: exactly the width the PLY and glb exports write (StrandWidth::metersAt).
  for (std::int64_t h = 0; h < n; ++h) {
    EXPECT_EQ(static_cast<float>(widths[static_cast<std::size_t>(2 * h)]), w.metersAt(0.0f));
    EXPECT_EQ(static_cast<float>(widths[static_cast<std::size_t>(2 * h + 1)]), w.metersAt(1.0f));
  }
}

TEST(ExportUsd, UnwritableDirectoryAndUnfinishedLayersLeaveNothing) {
  const scene::Fur fur = exportFur(fur::HairStyle::Line, 200.0);
  scene::UsdExportOptions o;
  o.lastFrame = 1;
  try {
    scene::UsdaWriter w("/nonexistent-dir/x.usda", sceneCritter(), fur, o);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent-dir/x.usda"), std::string::npos) << e.what();
  }
  TempDir dir;
  {
    scene::UsdaWriter w(dir.file("x.usda"), sceneCritter(), fur, o);
    scene::FrameState state;
    exportFrame(fur, 0, state);
    w.addFrame(0, state);
    // Destroyed without finish(): an interrupted export.
  }
  EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
}

TEST(ExportUsd, IdentifiersAreValid) {
  EXPECT_EQ(scene::usdIdentifier("monkey"), "monkey");
  EXPECT_EQ(scene::usdIdentifier("Fox-2.glb"), "Fox_2_glb");
  EXPECT_EQ(scene::usdIdentifier("3d"), "_3d");
  EXPECT_EQ(scene::usdIdentifier(""), "_");
}

}  // namespace
}  // namespace pelage::test
