#include "pelage/skin/build_from_shapes.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "pelage/skin/deform.h"
#include "pelage/util/error.h"
#include "pelage/util/parallel.h"
#include "support/models.h"

namespace pelage::skin {
namespace {

using test::defaultMonkey;

Eigen::Vector3f vertex(const SkinMesh& s, int v) {
  return Eigen::Map<const Eigen::Vector3f>(s.restPositions() + 3 * v);
}

TEST(BuildSkin, DefaultMonkeyIsAClosedManifoldOfAbout130kTriangles) {
  const SkinMesh& s = defaultMonkey().skin;
  const SkinStats st = skinStats(s);
  EXPECT_NEAR(st.triangles, 130000, 130000 * 0.03);
  EXPECT_EQ(st.boundaryEdges, 0);
  EXPECT_EQ(st.nonManifoldVertices, 0);
  // Euler characteristic of a closed genus-0 surface.
  EXPECT_EQ(st.vertices - st.triangles * 3 / 2 + st.triangles, 2);
  EXPECT_GT(st.minAngleDegrees, 10.0) << "sliver triangles";
  RecordProperty("minAngleDegrees", std::to_string(st.minAngleDegrees));
}

TEST(BuildSkin, VerticesLieOnTheSurfaceAndFacesPointOutward) {
  const scene::Model& m = defaultMonkey();
  const anatomy::Creature c = scene::builtinCreature("monkey");
  const SkinMesh& s = m.skin;
  double maxDist = 0.0;
  for (int v = 0; v < s.numVertices(); v += 7)
    maxDist = std::max(maxDist, static_cast<double>(std::abs(creatureDistance(c, vertex(s, v)))));
  EXPECT_LT(maxDist, 2e-4) << "metres off the implicit surface";
  int inverted = 0, degenerate = 0;
  for (int f = 0; f < s.numTriangles(); ++f) {
    const Eigen::Vector3f a = vertex(s, s.triangles[3 * f]), b = vertex(s, s.triangles[3 * f + 1]),
                          cc = vertex(s, s.triangles[3 * f + 2]);
    const Eigen::Vector3f n = (b - a).cross(cc - a);
    if (n.norm() < 1e-10f) {
      ++degenerate;
      continue;
    }
    // Outward = along the distance gradient.
    const Eigen::Vector3f ctr = (a + b + cc) / 3.0f;
    const float e = 1e-4f;
    const Eigen::Vector3f g(creatureDistance(c, ctr + Eigen::Vector3f(e, 0, 0)) -
                                creatureDistance(c, ctr - Eigen::Vector3f(e, 0, 0)),
                            creatureDistance(c, ctr + Eigen::Vector3f(0, e, 0)) -
                                creatureDistance(c, ctr - Eigen::Vector3f(0, e, 0)),
                            creatureDistance(c, ctr + Eigen::Vector3f(0, 0, e)) -
                                creatureDistance(c, ctr - Eigen::Vector3f(0, 0, e)));
    if (n.normalized().dot(g.normalized()) <= 0.0f) ++inverted;
  }
  EXPECT_EQ(degenerate, 0);
  EXPECT_EQ(inverted, 0);
}

TEST(BuildSkin, TriangleCountFollowsTheRequest) {
  const anatomy::Creature c = scene::builtinCreature("monkey");
  for (int target : {2000, 20000, 60000}) {
    const SkinMesh s = buildSkin(c, {target});
    const SkinStats st = skinStats(s);
    EXPECT_NEAR(st.triangles, target, target * 0.05) << target;
    EXPECT_EQ(st.boundaryEdges, 0) << target;
    EXPECT_EQ(st.nonManifoldVertices, 0) << target;
    EXPECT_GT(st.minAngleDegrees, 5.0) << target;
    // The area converges: coarse meshes lose only a little of it.
    EXPECT_NEAR(st.area, defaultMonkey().skin.restArea, 0.03 * defaultMonkey().skin.restArea)
        << target;
  }
  EXPECT_THROW(buildSkin(c, {1999}), InputError);
  EXPECT_THROW(buildSkin(c, {2000001}), InputError);
}

TEST(BuildSkin, DeterministicWhateverTheThreadCount) {
  const anatomy::Creature c = scene::builtinCreature("monkey");
  setThreadCount(1);
  const SkinMesh a = buildSkin(c, {20000});
  setThreadCount(2);
  const SkinMesh b = buildSkin(c, {20000});
  setThreadCount(0);
  ASSERT_EQ(a.numVertices(), b.numVertices());
  EXPECT_EQ(a.triangles, b.triangles);
  EXPECT_EQ(0, std::memcmp(a.restPositions(), b.restPositions(),
                           sizeof(float) * 3 * static_cast<std::size_t>(a.numVertices())));
}

TEST(Binding, WeightsAreNormalisedAndTheFirstSegmentIsTheClosest) {
  const SkinMesh& s = defaultMonkey().skin;
  const anatomy::Creature c = scene::builtinCreature("monkey");
  std::set<int> used;
  int blended = 0;
  for (int v = 0; v < s.numVertices(); ++v) {
    const Binding& b = s.bindings()[v];
    float sum = 0.0f;
    for (int k = 0; k < 4; ++k) {
      EXPECT_GE(b.weight[static_cast<std::size_t>(k)], 0.0f);
      sum += b.weight[static_cast<std::size_t>(k)];
    }
    ASSERT_NEAR(sum, 1.0f, 1e-5f) << v;
    ASSERT_GT(b.weight[0], 0.0f) << v;
    used.insert(b.segment[0]);
    blended += b.weight[1] > 0.0f;
  }
  // Every segment of the monkey is the closest segment of some skin.
  EXPECT_EQ(static_cast<int>(used.size()), c.body.size());
  // Joints blend: a good share of vertices has a second influence, but the middle of a long
  // segment moves rigidly with it.
  EXPECT_GT(blended, s.numVertices() / 20);
  for (const char* name : {"l_upperarm", "l_forearm", "r_shin", "tail3"}) {
    const int seg = c.body.find(name);
    int rigid = 0;
    for (int v = 0; v < s.numVertices(); ++v)
      rigid += s.bindings()[v].segment[0] == seg && s.bindings()[v].weight[0] == 1.0f;
    EXPECT_GT(rigid, 50) << name;
  }
  // Segment directions are unit or zero.
  for (int v = 0; v < s.numVertices(); ++v) {
    const float n = Eigen::Map<const Eigen::Vector3f>(s.segmentDirections() + 3 * v).norm();
    ASSERT_TRUE(n == 0.0f || std::abs(n - 1.0f) < 1e-5f);
  }
}

TEST(Regions, FaceHandsAndFeetHaveShorterFur) {
  const SkinMesh& s = defaultMonkey().skin;
  const anatomy::Creature c = scene::builtinCreature("monkey");
  std::vector<double> sum(s.regionNames.size(), 0.0);
  std::vector<int> count(s.regionNames.size(), 0);
  for (int v = 0; v < s.numVertices(); ++v) {
    const int r = s.regions()[v];
    sum[static_cast<std::size_t>(r)] += s.furLengths()[v];
    ++count[static_cast<std::size_t>(r)];
  }
  ASSERT_EQ(s.regionNames[0], "body");
  const double body = sum[0] / count[0];
  EXPECT_NEAR(body, c.furLengthMeters, 0.05 * c.furLengthMeters);
  for (std::size_t r = 1; r < s.regionNames.size(); ++r) {
    ASSERT_GT(count[r], 0) << s.regionNames[r] << " has no vertices";
    EXPECT_LT(sum[r] / count[r], 0.6 * body) << s.regionNames[r];
  }
}

}  // namespace
}  // namespace pelage::skin
