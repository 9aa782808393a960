// Skin subdivision (skin/subdivide.h): the PN-triangle edge midpoints on an octahedron exactly, a
// flat grid kept flat with its UVs, skin weights carried (normalised, at most 4), bare fur kept
// bare, and the Fox's facets smoothed (the normal jump across its edges, before and after).
#include "pelage/skin/subdivide.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <map>

#include "pelage/animation/clip.h"
#include "pelage/util/error.h"
#include "support/models.h"

namespace pelage::skin {
namespace {

SkinMesh makeMesh(const std::vector<Eigen::Vector3f>& vertices,
                  const std::vector<std::array<int, 3>>& triangles) {
  SkinMesh s;
  std::vector<TriMesh::VertexHandle> vh;
  for (const auto& v : vertices)
    vh.push_back(s.mesh.add_vertex(TriMesh::Point(v.x(), v.y(), v.z())));
  for (const auto& t : triangles)
    s.mesh.add_face(vh[static_cast<std::size_t>(t[0])], vh[static_cast<std::size_t>(t[1])],
                    vh[static_cast<std::size_t>(t[2])]);
  addSkinProperties(s);
  for (auto v : s.mesh.vertices()) s.mesh.property(s.furLength, v) = 0.01f;
  finalizeSkin(s);
  return s;
}

Eigen::Vector3f point(const SkinMesh& s, int v) {
  return Eigen::Map<const Eigen::Vector3f>(s.restPositions() + 3 * v);
}

TEST(Subdivide, OctahedronFollowsLoopsMasksExactly) {
  const SkinMesh o = makeMesh(
      {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}},
      {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}});
  const SkinMesh s = subdivideSkin(o, 1);
  ASSERT_EQ(s.numVertices(), 6 + 12);
  ASSERT_EQ(s.numTriangles(), 32);
  // The file's vertices stay; an edge vertex between (1, 0, 0) and (0, 1, 0), normals along the
  // axes: b1 = (2 P0 + P1 + N0) / 3 = (1, 1/3, 0), b2 = (1/3, 1, 0), (P0 + 3 b1 + 3 b2 + P1) / 8 =
  // (0.625, 0.625, 0).
  for (int v = 0; v < 6; ++v) EXPECT_EQ(point(s, v), point(o, v)) << v;
  for (int v = 6; v < 18; ++v) {
    const Eigen::Vector3f p = point(s, v);
    int nonzero = 0;
    for (int k = 0; k < 3; ++k) {
      if (p[k] != 0.0f) {
        EXPECT_FLOAT_EQ(std::abs(p[k]), 0.625f);
        ++nonzero;
      }
    }
    EXPECT_EQ(nonzero, 2) << v;
  }
  // Closed and consistently oriented: every face normal points outward.
  for (int t = 0; t < s.numTriangles(); ++t) {
    const std::int32_t* v = s.triangles.data() + 3 * t;
    const Eigen::Vector3f n =
        (point(s, v[1]) - point(s, v[0])).cross(point(s, v[2]) - point(s, v[0]));
    EXPECT_GT(n.dot(point(s, v[0]) + point(s, v[1]) + point(s, v[2])), 0.0f) << t;
  }
  EXPECT_EQ(autoSubdivisionLevels(8), 3);
  EXPECT_EQ(autoSubdivisionLevels(576), 2);
  EXPECT_EQ(autoSubdivisionLevels(1000), 1);
  EXPECT_EQ(autoSubdivisionLevels(4000), 0);
}

// A 4 x 4 grid of 1 cm squares (a regular triangle lattice), UVs = position / 4 cm, bound to
// segment 0 on the left (x < 2 cm), 1 on the right, half and half on the middle column; fur bare
// on the leftmost column.
SkinMesh boundGrid() {
  std::vector<Eigen::Vector3f> v;
  std::vector<std::array<int, 3>> t;
  for (int j = 0; j <= 4; ++j)
    for (int i = 0; i <= 4; ++i)
      v.emplace_back(0.01f * static_cast<float>(i), 0.01f * static_cast<float>(j), 0.0f);
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) {
      const int a = j * 5 + i, b = a + 1, c = a + 5, d = c + 1;
      t.push_back({a, b, d});
      t.push_back({a, d, c});
    }
  SkinMesh s = makeMesh(v, t);
  s.regionNames = {"body", "bare"};
  for (auto vh : s.mesh.vertices()) {
    const float x = s.mesh.point(vh)[0];
    Binding b;
    if (x < 0.015f) {
      b.segment = {0, 0, 0, 0};
    } else if (x > 0.025f) {
      b.segment = {1, 0, 0, 0};
    } else {
      b.segment = {0, 1, 0, 0};
      b.weight = {0.5f, 0.5f, 0.0f, 0.0f};
    }
    s.mesh.property(s.binding, vh) = b;
    if (x < 0.005f) {
      s.mesh.property(s.furLength, vh) = 0.0f;
      s.mesh.property(s.region, vh) = 1;
    }
  }
  std::vector<std::int32_t> corners;
  std::vector<Eigen::Vector2f> uv;
  for (const auto& tri : t)
    for (int k : tri) {
      corners.push_back(k);
      uv.emplace_back(v[static_cast<std::size_t>(k)].x() / 0.04f,
                      v[static_cast<std::size_t>(k)].y() / 0.04f);
    }
  setCornerUvs(s, corners, uv);
  return s;
}

TEST(Subdivide, FlatGridStaysFlatWithItsUvsWeightsAndBareFur) {
  const SkinMesh g = boundGrid();
  const SkinMesh s = subdivideSkin(g, 2);
  ASSERT_EQ(s.numTriangles(), 32 * 16);
  EXPECT_NEAR(s.restArea, g.restArea, 1e-9);
  for (int t = 0; t < s.numTriangles(); ++t)
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3f p = point(s, s.triangles[static_cast<std::size_t>(3 * t + k)]);
      EXPECT_EQ(p.z(), 0.0f);
      // Flat: the edge curves are straight, new vertices at the midpoints where the UVs (split
      // linearly) also are.
      const Eigen::Vector2f uv = s.cornerUv[static_cast<std::size_t>(3 * t + k)];
      EXPECT_NEAR(uv.x(), p.x() / 0.04f, 1e-5f);
      EXPECT_NEAR(uv.y(), p.y() / 0.04f, 1e-5f);
    }
  for (int v = 0; v < s.numVertices(); ++v) {
    const Binding& b = s.bindings()[v];
    float sum = 0.0f;
    for (int k = 0; k < 4; ++k) sum += b.weight[static_cast<std::size_t>(k)];
    EXPECT_NEAR(sum, 1.0f, 1e-6f);
    EXPECT_GE(b.weight[0], b.weight[1]);
    const float x = point(s, v).x();
    if (x < 0.0099f) {  // both ends of every edge it came from on segment 0 alone
      EXPECT_EQ(b.segment[0], 0);
      EXPECT_EQ(b.weight[0], 1.0f);
    }
    // Bare stays bare: on the leftmost cells (x < 1 cm, an end on the bare column) no fur.
    const float len = s.furLengths()[v];
    if (x < 0.0049f) {
      EXPECT_EQ(len, 0.0f) << v;
      EXPECT_EQ(s.regions()[v], 1) << v;
    }
    if (x > 0.0151f) {
      EXPECT_FLOAT_EQ(len, 0.01f) << v;
    }
  }
}

// The mean angle between the face normals of the two triangles on each edge with fur (degrees).
double meanFacetJump(const SkinMesh& s) {
  std::map<std::pair<int, int>, std::vector<Eigen::Vector3f>> edges;
  for (int t = 0; t < s.numTriangles(); ++t) {
    const std::int32_t* v = s.triangles.data() + 3 * t;
    const Eigen::Vector3f n =
        (point(s, v[1]) - point(s, v[0])).cross(point(s, v[2]) - point(s, v[0])).normalized();
    for (int k = 0; k < 3; ++k) {
      const int a = v[k], b = v[(k + 1) % 3];
      if (s.furLengths()[a] > 0.0f && s.furLengths()[b] > 0.0f)
        edges[{std::min(a, b), std::max(a, b)}].push_back(n);
    }
  }
  double sum = 0.0;
  int n = 0;
  for (const auto& [e, normals] : edges) {
    if (normals.size() != 2) continue;
    sum += std::acos(std::clamp(static_cast<double>(normals[0].dot(normals[1])), -1.0, 1.0));
    ++n;
  }
  return n ? sum / n * 180.0 / 3.14159265358979323846 : 0.0;
}

TEST(Subdivide, FoxFacetsSmoothedAndItStillDeforms) {
  scene::LoadOptions raw;
  raw.subdivide = 0;
  const std::string file = std::string(PELAGE_SHARED_MODELS_DIR) + "/Fox/Fox.glb";
  if (!std::filesystem::exists(file)) GTEST_SKIP() << "shared Fox model absent";
  const scene::Model flat = scene::loadModel(file, raw);
  const scene::Model smooth = scene::loadModel(file);  // auto: 2 levels
  ASSERT_EQ(flat.skin.numTriangles(), 576);
  ASSERT_EQ(smooth.skin.numTriangles(), 576 * 16);
  const double before = meanFacetJump(flat.skin), after = meanFacetJump(smooth.skin);
  std::printf(
      "Fox: mean normal jump across furred edges %.2f deg (576 triangles), %.2f deg (9216)\n",
      before, after);
  EXPECT_LT(after, 0.4 * before);
  // The surface stays close: the file's vertices stay, the edges bow out a little.
  EXPECT_NEAR(smooth.skin.restArea, flat.skin.restArea, 0.05 * flat.skin.restArea);
  // It deforms with the creature: a clip frame moves the subdivided skin like the file's skin.
  scene::FrameState a, b;
  anatomy::Pose pose;
  animation::sampleClip(flat.clips[0], flat.body, 0.3, pose);
  scene::evaluateFrame(flat, pose, a);
  scene::evaluateFrame(smooth, pose, b);
  EXPECT_LT((a.skinBounds.min() - b.skinBounds.min()).norm(), 0.01f);
  EXPECT_LT((a.skinBounds.max() - b.skinBounds.max()).norm(), 0.01f);
  scene::LoadOptions once;
  once.subdivide = 1;
  EXPECT_THROW(scene::loadModel("monkey", once), InputError);
}

}  // namespace
}  // namespace pelage::skin
