// The hair PLY file: header, vertex records, edges and tube faces, read back byte by byte.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "pelage/fur/hair_ply.h"
#include "pelage/util/color.h"
#include "pelage/util/error.h"
#include "support/files.h"
#include "support/skins.h"

namespace pelage::fur {
namespace {

struct Ply {
  std::vector<std::string> header;
  std::int64_t vertices = 0, edges = -1, faces = -1;
  std::string body;  // binary payload
};

Ply readPly(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  Ply p;
  std::string line;
  while (std::getline(in, line)) {
    p.header.push_back(line);
    std::istringstream ls(line);
    std::string w, what;
    std::int64_t n = 0;
    ls >> w;
    if (w == "element" && (ls >> what >> n)) {
      if (what == "vertex") p.vertices = n;
      if (what == "edge") p.edges = n;
      if (what == "face") p.faces = n;
    }
    if (line == "end_header") break;
  }
  p.body.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  return p;
}

template <class T>
T at(const std::string& s, std::size_t offset) {
  T v;
  std::memcpy(&v, s.data() + offset, sizeof(T));
  return v;
}

// With colours: red, green, blue after the coat, each point's colour graded from its hair's root
// colour to its tip colour (uniform coat: the material's diffuse, encoded), and still complete.
TEST(HairPly, ColoursPerVertexReadBackEqual) {
  const skin::SkinMesh s = test::makeGrid(6, 0.01f, 0.02f);
  FurParams p = test::simpleParams(HairStyle::Polyline, 400);
  p.undercoatShare = 0.5f;
  p.coats[kOvercoat].color.valueVariation = 0.3f;  // per hair
  p.coats[kOvercoat].color.tipLightness = 2.0f;
  p.coats[kUndercoat].style = HairStyle::Line;  // uniform
  const test::RestFur rf = test::restFur(s, p);
  FurFrame f = test::furFrame(s, rf.roots, p, rf.rest);
  const FurColors colors = colorRoots(s, rf.roots, p, Groom{});
  fillHairColors(colors, f);
  test::TempDir dir;
  const HairPlyCounts n = writeHairPly(dir.file("c.ply"), f, p, "", &colors);
  EXPECT_TRUE(isCompleteHairPly(dir.file("c.ply")));
  const Ply ply = readPly(dir.file("c.ply"));
  for (const char* name : {"property uchar red", "property uchar green", "property uchar blue"})
    EXPECT_NE(std::find(ply.header.begin(), ply.header.end(), name), ply.header.end()) << name;
  ASSERT_EQ(ply.body.size(), static_cast<std::size_t>(n.vertices * 36 + n.edges * 8));
  std::int64_t v = 0;
  int graded = 0;
  for (int c = 0; c < kCoatCount; ++c) {
    const HairBuffers& hb = f.coats[static_cast<std::size_t>(c)];
    const int P = hb.layout.pointsPerHair();
    const CoatColors& cc = colors.coats[static_cast<std::size_t>(c)];
    EXPECT_EQ(cc.perHair, c == kOvercoat);
    for (std::int64_t h = 0; h < hb.drawn; ++h)
      for (int k = 0; k < P; ++k, ++v) {
        const auto o = static_cast<std::size_t>(v * 36 + 33);
        const Eigen::Vector3f want =
            cc.perHair ? unpackSrgb8(hb.colors[static_cast<std::size_t>(2 * h)]) +
                             hb.layout.along(k) *
                                 (unpackSrgb8(hb.colors[static_cast<std::size_t>(2 * h + 1)]) -
                                  unpackSrgb8(hb.colors[static_cast<std::size_t>(2 * h)]))
                       : cc.diffuse;
        for (int j = 0; j < 3; ++j)
          ASSERT_EQ(at<std::uint8_t>(ply.body, o + static_cast<std::size_t>(j)),
                    linearToSrgb8(want[j]))
              << c << " " << h << " " << k;
        graded += cc.perHair && k == P - 1 &&
                  at<std::uint8_t>(ply.body, o) != at<std::uint8_t>(ply.body, o - (P - 1) * 36);
      }
  }
  EXPECT_GT(graded, 50);  // tips lighter than roots
}

TEST(HairPly, VerticesAndEdgesOfBothCoats) {
  const skin::SkinMesh s = test::makeGrid(6, 0.01f, 0.02f);
  FurParams p = test::simpleParams(HairStyle::Polyline, 400);
  p.undercoatShare = 0.5f;
  p.coats[kUndercoat].style = HairStyle::Line;
  const test::RestFur rf = test::restFur(s, p);
  const FurRoots& r = rf.roots;
  const skin::DeformedSkin& d = rf.rest;
  const FurFrame f = test::furFrame(s, r, p, d);
  test::TempDir dir;
  const HairPlyCounts n = writeHairPly(dir.file("h.ply"), f, p, "fur: test");
  const std::int64_t over = f.coats[0].drawn, under = f.coats[1].drawn;
  EXPECT_EQ(n.vertices, over * 8 + under * 2);
  EXPECT_EQ(n.edges, over * 7 + under * 1);
  EXPECT_EQ(n.faces, 0);
  const Ply ply = readPly(dir.file("h.ply"));
  ASSERT_GE(ply.header.size(), 3u);
  EXPECT_EQ(ply.header[0], "ply");
  EXPECT_EQ(ply.header[1], "format binary_little_endian 1.0");
  EXPECT_NE(std::find(ply.header.begin(), ply.header.end(), "comment fur: test"), ply.header.end());
  EXPECT_NE(std::find(ply.header.begin(), ply.header.end(), "property int hair"), ply.header.end());
  EXPECT_NE(std::find(ply.header.begin(), ply.header.end(), "property uchar coat"),
            ply.header.end());
  EXPECT_NE(std::find(ply.header.begin(), ply.header.end(), "property float width"),
            ply.header.end());
  EXPECT_EQ(ply.vertices, n.vertices);
  EXPECT_EQ(ply.edges, n.edges);
  EXPECT_EQ(ply.faces, -1) << "no face element without tubes";
  ASSERT_EQ(ply.body.size(), static_cast<std::size_t>(n.vertices * 33 + n.edges * 8));
  // Vertex v: the frame's point, normal, hair id and coat.
  std::int64_t v = 0;
  for (int c = 0; c < 2; ++c) {
    const HairBuffers& hb = f.coats[static_cast<std::size_t>(c)];
    for (std::int64_t h = 0; h < hb.drawn; ++h)
      for (int k = 0; k < hb.layout.pointsPerHair(); ++k, ++v) {
        const auto o = static_cast<std::size_t>(v * 33);
        for (int q = 0; q < 3; ++q) {
          ASSERT_EQ(at<float>(ply.body, o + 4 * static_cast<std::size_t>(q)),
                    test::point(hb, h, k)[q]);
          ASSERT_EQ(at<float>(ply.body, o + 12 + 4 * static_cast<std::size_t>(q)),
                    test::normal(hb, h, k)[q]);
        }
        ASSERT_EQ(at<std::int32_t>(ply.body, o + 24), hb.hairIds[static_cast<std::size_t>(h)]);
        ASSERT_EQ(static_cast<int>(ply.body[o + 28]), c);
        // The coat's width at the point: root width at k = 0, tip width at the last point,
        // linear between (the frame is not culled).
        const StrandWidth& w = p.coats[static_cast<std::size_t>(c)].width;
        const int P = hb.layout.pointsPerHair();
        ASSERT_NEAR(at<float>(ply.body, o + 29),
                    1e-3f * (w.rootMm + (w.tipMm - w.rootMm) * static_cast<float>(k) /
                                            static_cast<float>(P - 1)),
                    1e-9f);  // a nanometre: float rounding of the interpolation
      }
  }
  // Edges join consecutive points of each hair: (0,1) .. (6,7), (8,9) ...
  const std::size_t e0 = static_cast<std::size_t>(n.vertices * 33);
  std::int64_t e = 0;
  std::int32_t base = 0;
  for (int c = 0; c < 2; ++c) {
    const int P = f.coats[static_cast<std::size_t>(c)].layout.pointsPerHair();
    for (std::int64_t h = 0; h < f.coats[static_cast<std::size_t>(c)].drawn; ++h, base += P)
      for (int k = 0; k + 1 < P; ++k, ++e) {
        ASSERT_EQ(at<std::int32_t>(ply.body, e0 + static_cast<std::size_t>(8 * e)), base + k);
        ASSERT_EQ(at<std::int32_t>(ply.body, e0 + static_cast<std::size_t>(8 * e + 4)),
                  base + k + 1);
      }
  }
}

TEST(HairPly, TubesWriteFaces) {
  const skin::SkinMesh s = test::makeGrid(3, 0.01f, 0.02f);
  FurParams p = test::simpleParams(HairStyle::Tube, 30);
  p.coats[0].curvePoints = 4;
  p.coats[0].tubeSides = 3;
  const test::RestFur rf = test::restFur(s, p);
  const FurRoots& r = rf.roots;
  const skin::DeformedSkin& d = rf.rest;
  const FurFrame f = test::furFrame(s, r, p, d);
  test::TempDir dir;
  const HairPlyCounts n = writeHairPly(dir.file("t.ply"), f, p);
  const std::int64_t hairs = f.coats[0].drawn;
  EXPECT_EQ(n.vertices, hairs * 12);
  EXPECT_EQ(n.faces, hairs * 3 * 3 * 2);
  const Ply ply = readPly(dir.file("t.ply"));
  EXPECT_EQ(ply.edges, -1) << "tubes write faces instead of edges";
  EXPECT_EQ(ply.faces, n.faces);
  EXPECT_NE(
      std::find(ply.header.begin(), ply.header.end(), "property list uchar int vertex_indices"),
      ply.header.end());
  ASSERT_EQ(ply.body.size(), static_cast<std::size_t>(n.vertices * 33 + n.faces * 13));
  // Every point of ring k carries the tube's diameter there: 2 r_k = the coat's width at k / 3.
  for (std::int64_t v = 0; v < n.vertices; ++v) {
    const int k = static_cast<int>(v % 12) / 3;
    ASSERT_FLOAT_EQ(at<float>(ply.body, static_cast<std::size_t>(v * 33 + 29)),
                    p.coats[0].width.metersAt(static_cast<float>(k) / 3.0f))
        << v;
  }
  const std::vector<std::int32_t> pattern = tubeTriangles(4, 3);
  const std::size_t f0 = static_cast<std::size_t>(n.vertices * 33);
  for (std::int64_t t = 0; t < n.faces; ++t) {
    const std::size_t o = f0 + static_cast<std::size_t>(13 * t);
    ASSERT_EQ(ply.body[o], 3);
    const std::int64_t hair = t / 18;
    for (int k = 0; k < 3; ++k)
      ASSERT_EQ(at<std::int32_t>(ply.body, o + 1 + 4 * static_cast<std::size_t>(k)),
                hair * 12 + pattern[static_cast<std::size_t>((t % 18) * 3 + k)]);
  }
}

TEST(HairPly, CulledStrandsAreWidenedTubesKeepTheirDiameter) {
  const skin::SkinMesh s = test::makeGrid(3, 0.01f, 0.02f);
  FurParams p = test::simpleParams(HairStyle::Polyline, 30);
  p.undercoatShare = 0.5f;
  p.coats[kUndercoat].style = HairStyle::Tube;
  const test::RestFur rf = test::restFur(s, p);
  FurFrame f = test::furFrame(s, rf.roots, p, rf.rest);
  f.cullingFactor = 3.0f;  // a third of the hairs drawn: strands three times as wide
  const int P = f.coats[kOvercoat].layout.pointsPerHair();
  for (int k = 0; k < P; ++k)
    EXPECT_FLOAT_EQ(exportedWidth(f, p, kOvercoat, 0, k),
                    3.0f * p.coats[kOvercoat].width.metersAt(static_cast<float>(k) /
                                                             static_cast<float>(P - 1)));
  const HairLayout& tube = f.coats[kUndercoat].layout;
  for (int k = 0; k < tube.pointsPerHair(); ++k)
    EXPECT_FLOAT_EQ(exportedWidth(f, p, kUndercoat, 0, k),
                    p.coats[kUndercoat].width.metersAt(tube.along(k)));
  f.cullingFactor = 0.5f;  // closer than the reference: every hair, at its own width
  EXPECT_FLOAT_EQ(exportedWidth(f, p, kOvercoat, 0, 0), p.coats[kOvercoat].width.metersAt(0.0f));
}

TEST(HairPly, UnwritableDestinationLeavesNoFile) {
  const skin::SkinMesh s = test::makeGrid(2, 0.01f, 0.02f);
  const FurParams p = test::simpleParams(HairStyle::Line, 10);
  const test::RestFur rf = test::restFur(s, p);
  const FurRoots& r = rf.roots;
  const skin::DeformedSkin& d = rf.rest;
  const FurFrame f = test::furFrame(s, r, p, d);
  EXPECT_THROW(writeHairPly("/nonexistent-dir/h.ply", f, p), InputError);
  EXPECT_FALSE(std::filesystem::exists("/nonexistent-dir/h.ply"));
}

}  // namespace
}  // namespace pelage::fur
