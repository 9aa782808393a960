// Degenerate geometry through the whole pipeline (issue 8): a mesh file with a zero-area triangle,
// a sliver, duplicate vertices, a triangle repeating a vertex, a non-manifold edge, an isolated
// vertex and open boundaries. It loads with warnings saying what was skipped, fur grows where there
// is area, and no NaN or infinity reaches a hair buffer in any style.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "pelage/fur/generate.h"
#include "pelage/fur/preset.h"
#include "pelage/fur/roots.h"
#include "pelage/skin/deform.h"
#include "pelage/skin/mesh_io.h"
#include "pelage/util/log.h"
#include "support/files.h"

namespace pelage::fur {
namespace {

// Vertices 1-9: a 2 x 2 quad grid in z = 0 (open: all of its border is a boundary);
// 10-12: three collinear points (a zero-area triangle); 13-15: a sliver 1e-7 m high;
// 16: a copy of vertex 5's position (a duplicate used by its own triangle); 17: isolated;
// 18: the apex of a third triangle on the grid's edge 1-2 (non-manifold: skipped).
const char* kDegenerateObj = R"(v 0 0 0
v 0.1 0 0
v 0.2 0 0
v 0 0.1 0
v 0.1 0.1 0
v 0.2 0.1 0
v 0 0.2 0
v 0.1 0.2 0
v 0.2 0.2 0
v 0.3 0 0
v 0.4 0 0
v 0.5 0 0
v 0.3 0.3 0
v 0.5 0.3 0
v 0.4 0.3000001 0
v 0.1 0.1 0
v 9 9 9
v 0.05 0 0.1
f 1 2 5 4
f 2 3 6 5
f 4 5 8 7
f 5 6 9 8
f 10 11 12
f 13 14 15
f 16 9 6
f 1 1 2
f 1 2 18
f 2 1 18
)";

bool allFinite(const FloatSpan& b) {
  for (std::size_t i = 0; i < b.size(); ++i)
    if (!std::isfinite(b.data()[i])) return false;
  return true;
}

TEST(DegenerateSkin, LoadsWithWarningsAndGrowsFiniteFurInEveryStyle) {
  test::TempDir dir;
  test::writeText(dir.file("bad.obj"), kDegenerateObj);
  std::vector<std::string> warnings;
  const WarningSink previous = setWarningSink([&](const std::string& w) { warnings.push_back(w); });
  const skin::SkinMesh s = skin::readStaticMesh(dir.file("bad.obj"), 0.02f);
  setWarningSink(previous);
  // 8 grid triangles, the zero-area one, the sliver, the duplicate's, one of the two on edge 1-2.
  EXPECT_EQ(s.numTriangles(), 12);
  EXPECT_EQ(s.numVertices(), 17);  // the isolated vertex is gone
  ASSERT_EQ(warnings.size(), 2u);
  EXPECT_NE(warnings[0].find("skipped 2 triangles (repeated vertices or non-manifold edges)"),
            std::string::npos)
      << warnings[0];
  EXPECT_NE(warnings[1].find("removed 1 isolated vertices"), std::string::npos) << warnings[1];

  skin::DeformedSkin d;
  skin::restSkin(s, d);
  for (const auto& p : d.positions) ASSERT_TRUE(p.allFinite());
  for (const auto& n : d.normals) ASSERT_TRUE(n.allFinite());
  for (HairStyle style :
       {HairStyle::Line, HairStyle::Polyline, HairStyle::Curve, HairStyle::Tube}) {
    FurParams p = loadFurPreset("default");
    p.setHairCount(20000);
    p.densityPerM2 = 0.0;
    p.culling.enabled = false;
    for (CoatParams& c : p.coats) c.style = style;
    const FurRoots roots = growRoots(s, p);
    // Roots only where there is area: none on the zero-area triangle, about none on the sliver.
    const double area = s.restArea;
    EXPECT_NEAR(area, 0.04 + 0.5 * 0.1 * 0.1 + 0.5 * 0.2 * 1e-7 + 0.005, 1e-6);
    for (int c = 0; c < kCoatCount; ++c) {
      const CoatRoots& r = roots.coats[static_cast<std::size_t>(c)];
      for (std::int64_t k = 0; k < r.size(); ++k) {
        const int t = r.triangle[static_cast<std::size_t>(k)];
        const int* tri = &s.triangles[3 * static_cast<std::size_t>(t)];
        const Eigen::Vector3f a = d.positions[static_cast<std::size_t>(tri[0])];
        const Eigen::Vector3f e1 = d.positions[static_cast<std::size_t>(tri[1])] - a;
        const Eigen::Vector3f e2 = d.positions[static_cast<std::size_t>(tri[2])] - a;
        ASSERT_GT(e1.cross(e2).norm(), 0.0f) << "a root on a zero-area triangle";
      }
    }
    FurWorkspace ws;
    FurFrame frame;
    generateFur(s, roots, p, d, FurView{}, ws, frame);
    EXPECT_GT(frame.drawn(), 15000) << static_cast<int>(style);
    for (const HairBuffers& b : frame.coats) {
      EXPECT_TRUE(allFinite(b.positions)) << static_cast<int>(style);
      EXPECT_TRUE(allFinite(b.normals)) << static_cast<int>(style);
    }
  }
}

}  // namespace
}  // namespace pelage::fur
