#include "pelage/skin/skin_mesh.h"

#include <gtest/gtest.h>

#include <cmath>

namespace pelage::skin {
namespace {

// The tetrahedron (0,0,0), (1,0,0), (0,1,0), (0,0,1) with outward faces.
SkinMesh tetrahedron() {
  SkinMesh s;
  TriMesh& m = s.mesh;
  auto v0 = m.add_vertex({0, 0, 0}), v1 = m.add_vertex({1, 0, 0}), v2 = m.add_vertex({0, 1, 0}),
       v3 = m.add_vertex({0, 0, 1});
  m.add_face(v0, v2, v1);
  m.add_face(v0, v1, v3);
  m.add_face(v0, v3, v2);
  m.add_face(v1, v2, v3);
  addSkinProperties(s);
  finalizeSkin(s);
  return s;
}

TEST(SkinMesh, FinalizeBuildsTrianglesAdjacencyAndArea) {
  const SkinMesh s = tetrahedron();
  EXPECT_EQ(s.numVertices(), 4);
  EXPECT_EQ(s.numTriangles(), 4);
  EXPECT_EQ(s.triangles, (std::vector<std::int32_t>{0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3}));
  // Vertex 0 touches faces 0, 1, 2; vertex 3 touches faces 1, 2, 3.
  EXPECT_EQ(s.vertexFaceStart, (std::vector<std::int32_t>{0, 3, 6, 9, 12}));
  EXPECT_EQ(std::vector<std::int32_t>(s.vertexFaces.begin(), s.vertexFaces.begin() + 3),
            (std::vector<std::int32_t>{0, 1, 2}));
  EXPECT_EQ(std::vector<std::int32_t>(s.vertexFaces.begin() + 9, s.vertexFaces.end()),
            (std::vector<std::int32_t>{1, 2, 3}));
  EXPECT_NEAR(s.restArea, 1.5 + std::sqrt(3.0) / 2.0, 1e-6);
  const SkinStats st = skinStats(s);
  EXPECT_EQ(st.boundaryEdges, 0);
  EXPECT_EQ(st.nonManifoldVertices, 0);
  EXPECT_NEAR(st.minAngleDegrees, 45.0, 1e-3);
  EXPECT_TRUE(st.boundsMax.isApprox(Eigen::Vector3f(1, 1, 1)));
}

}  // namespace
}  // namespace pelage::skin
