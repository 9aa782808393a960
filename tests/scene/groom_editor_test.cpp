// Brushing (scene/groom_editor.h): the skin under a pixel, and the editor's groom, which is always
// its strokes replayed on its start bit for bit, through live points, undo, redo and checkpoints.
#include "pelage/scene/groom_editor.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "pelage/anatomy/pose.h"
#include "pelage/fur/preset.h"
#include "pelage/util/error.h"
#include "support/models.h"

namespace pelage::scene {
namespace {

// The critter at rest and a camera from the three-quarter preset, 320x240.
struct Picking {
  FrameState frame;
  Camera camera;
  Picking() {
    evaluateFrame(test::sceneCritter(), anatomy::restPose(test::sceneCritter().body), frame);
    camera = presetCamera(framingOf(test::sceneCritter(), frame, 0.02f), CameraPreset::ThreeQuarter,
                          320, 240);
  }
};

// Where a world point lands in the camera's viewport (pixels from the top-left).
Eigen::Vector2f project(const Camera& c, const Eigen::Vector3f& p) {
  const Eigen::Vector4f q = c.viewProjection() * p.homogeneous();
  return {(q.x() / q.w() + 1.0f) * 0.5f * static_cast<float>(c.width),
          (1.0f - q.y() / q.w()) * 0.5f * static_cast<float>(c.height)};
}

TEST(PickSkin, TheHitProjectsBackToThePixelAndLiesOnItsTriangle) {
  const Picking p;
  const Model& m = test::sceneCritter();
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> ux(0.0f, 320.0f), uy(0.0f, 240.0f);
  int hits = 0;
  for (int i = 0; i < 200; ++i) {
    const float x = ux(rng), y = uy(rng);
    const std::optional<SkinHit> h = pickSkin(m, p.frame, p.camera, x, y);
    if (!h) continue;
    ++hits;
    const Eigen::Vector2f back = project(p.camera, h->position);
    EXPECT_NEAR(back.x(), x, 2e-3f);
    EXPECT_NEAR(back.y(), y, 2e-3f);
    EXPECT_NEAR((h->position - p.camera.eye).norm(), h->distance, 1e-5f);
    EXPECT_GE(h->barycentric.minCoeff(), 0.0f);
    EXPECT_NEAR(h->barycentric.sum(), 1.0f, 1e-6f);
    // At rest the deformed skin is the rest skin: the same point twice.
    EXPECT_LT((h->rest - h->position).norm(), 1e-5f);
  }
  EXPECT_GT(hits, 20);  // the preset frames the critter in the middle of the image
  EXPECT_LT(hits, 200);
  // The image's corner looks past the creature.
  EXPECT_FALSE(pickSkin(m, p.frame, p.camera, 0.5f, 0.5f));
}

TEST(PickSkin, TheNearestSurfaceWinsAndAPosedHitKeepsItsRestPoint) {
  const Picking p;
  const Model& m = test::sceneCritter();
  const std::optional<SkinHit> h = pickSkin(m, p.frame, p.camera, 160.0f, 120.0f);
  ASSERT_TRUE(h);
  // The ray continues through the creature: just behind the first hit, a second pick from there
  // finds a farther surface, never a nearer one.
  Camera behind = p.camera;
  const Eigen::Vector3f dir = (h->position - p.camera.eye).normalized();
  behind.eye = h->position + 1e-4f * dir;
  behind.target = behind.eye + dir;
  const std::optional<SkinHit> far = pickSkin(m, p.frame, behind, 160.0f, 120.0f);
  ASSERT_TRUE(far);  // a closed body has a back
  EXPECT_GT((far->position - p.camera.eye).norm(), h->distance);
  // Moved whole, the skin's hit moves along while its rest point stays.
  FrameState moved;
  moved.skin.positions = p.frame.skin.positions;
  for (Eigen::Vector3f& q : moved.skin.positions) q += Eigen::Vector3f(0.0f, 0.0f, 0.01f);
  Camera up = p.camera;
  up.eye.z() += 0.01f;
  up.target.z() += 0.01f;
  const std::optional<SkinHit> g = pickSkin(m, moved, up, 160.0f, 120.0f);
  ASSERT_TRUE(g);
  EXPECT_EQ(g->triangle, h->triangle);
  EXPECT_LT((g->rest - h->rest).norm(), 1e-5f);
  EXPECT_LT((g->position - h->position - Eigen::Vector3f(0.0f, 0.0f, 0.01f)).norm(), 1e-5f);
}

TEST(PickSkin, PixelsToMetersIsTheViewHeightAtThatDistance) {
  Camera c;
  c.fovYDegrees = 90.0f;
  c.height = 200;
  // At distance 1 a 90 degree view is 2 m high: 200 px span 2 m.
  EXPECT_FLOAT_EQ(pixelsToMeters(c, 200.0f, 1.0f), 2.0f);
  EXPECT_FLOAT_EQ(pixelsToMeters(c, 10.0f, 3.0f), 0.3f);
}

bool sameGroom(const fur::VertexGroom& a, const fur::VertexGroom& b) {
  const auto same = [](const auto& x, const auto& y) {
    return x.size() == y.size() &&
           (x.empty() || std::memcmp(x.data(), y.data(), x.size() * sizeof x[0]) == 0);
  };
  return same(a.length, b.length) && same(a.density, b.density) && same(a.tint, b.tint) &&
         same(a.comb, b.comb) && same(a.clump, b.clump);
}

fur::VertexGroom replayed(const GroomEditor& e) {
  fur::VertexGroom g = e.start();
  fur::applyGroomStrokes(test::sceneCritter().skin, e.strokes(), g);
  return g;
}

// A random stroke of a random tool over the critter's rest skin.
fur::GroomStroke randomBrush(std::mt19937& rng) {
  std::uniform_int_distribution<int> tool(0, 5), axis(-1, 2);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  fur::GroomStroke s;
  s.tool = static_cast<fur::BrushTool>(tool(rng));
  s.radius = 0.01f + 0.05f * u(rng);
  const fur::StrengthRange r = fur::brushStrengthRange(s.tool);
  s.strength = r.lo + (std::min(r.hi, 3.0f) - r.lo) * u(rng);
  s.color = Eigen::Vector3f(u(rng), u(rng), u(rng));
  s.cutLength = 0.01f * u(rng);
  s.mirrorAxis = axis(rng);
  return s;
}

TEST(GroomEditor, TheGroomIsAlwaysItsStrokesReplayedThroughUndoRedoAndCheckpoints) {
  const Model& m = test::sceneCritter();
  const fur::FurParams params = fur::loadFurPreset("default");
  GroomEditor e(m, startingGroom(m, params, "test"));
  const int nv = m.skin.numVertices();
  const float* rest = m.skin.restPositions();
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> vertex(0, nv - 1), action(0, 9);
  std::vector<fur::VertexGroom> history{e.groom()};  // the groom after each kept stroke
  for (int step = 0; step < 70; ++step) {
    const int a = action(rng);
    if (a < 2 && e.canUndo()) {
      const std::uint64_t rev = e.revision();
      e.undo();
      EXPECT_NE(e.revision(), rev);
      history.pop_back();
      ASSERT_TRUE(sameGroom(e.groom(), history.back())) << "undo at step " << step;
    } else if (a < 3 && e.canRedo()) {
      e.redo();
      history.push_back(e.groom());
    } else {
      e.beginStroke(randomBrush(rng));
      const Eigen::Vector3f p0 = Eigen::Map<const Eigen::Vector3f>(rest + 3 * vertex(rng));
      const Eigen::Vector3f p1 = Eigen::Map<const Eigen::Vector3f>(rest + 3 * vertex(rng));
      for (int k = 0; k <= 4; ++k) {
        e.addPoint(p0 + (p1 - p0) * (0.25f * static_cast<float>(k)));
        // Live: the groom so far is the strokes so far replayed (at the last point and at one
        // more that moves with the step: every replay is all the strokes again, from the start).
        if (k == 4 || k == step % 4) {
          ASSERT_TRUE(sameGroom(e.groom(), replayed(e))) << "live point at step " << step;
        }
      }
      e.endStroke();
      history.push_back(e.groom());
    }
    ASSERT_EQ(history.size(), e.strokes().size() + 1);
    ASSERT_TRUE(sameGroom(e.groom(), replayed(e))) << "step " << step;
  }
  EXPECT_GT(e.strokes().size(), 16u);  // past a checkpoint
  // Undo everything: the start, bit for bit; redo everything: the same groom as before.
  const fur::VertexGroom all = e.groom();
  while (e.canUndo()) e.undo();
  EXPECT_TRUE(sameGroom(e.groom(), e.start()));
  while (e.canRedo()) e.redo();
  EXPECT_TRUE(sameGroom(e.groom(), all));
}

TEST(GroomEditor, SpacingCombsOfOnePointNewStrokesAndReset) {
  const Model& m = test::sceneCritter();
  GroomEditor e(m, startingGroom(m, fur::loadFurPreset("default"), "test"));
  const Eigen::Vector3f p = Eigen::Map<const Eigen::Vector3f>(m.skin.restPositions());
  fur::GroomStroke comb;
  comb.tool = fur::BrushTool::Comb;
  comb.radius = 0.03f;
  e.beginStroke(comb);
  EXPECT_FALSE(e.addPoint(p));  // a comb has no direction yet
  EXPECT_FALSE(e.addPoint(p + Eigen::Vector3f(0.001f, 0, 0), 0.005f));  // closer than the spacing
  EXPECT_TRUE(e.strokes().empty());
  e.endStroke();
  EXPECT_TRUE(e.strokes().empty());  // no trace
  EXPECT_FALSE(e.canUndo());
  e.beginStroke(comb);
  e.addPoint(p);
  EXPECT_TRUE(e.addPoint(p + Eigen::Vector3f(0.01f, 0, 0), 0.005f));
  e.endStroke();
  ASSERT_EQ(e.strokes().size(), 1u);
  EXPECT_EQ(e.strokes()[0].points.size(), 2u);
  e.undo();
  EXPECT_TRUE(e.canRedo());
  e.beginStroke(comb);  // a new stroke drops the redo history
  EXPECT_FALSE(e.canRedo());
  e.endStroke();
  fur::VertexGroom other = e.start();
  other.density.assign(static_cast<std::size_t>(m.skin.numVertices()), 0.5f);
  e.reset(other);
  EXPECT_TRUE(sameGroom(e.groom(), other));
  EXPECT_FALSE(e.canUndo());
  EXPECT_FALSE(e.canRedo());
}

TEST(GroomEditor, BadBrushesNameTheField) {
  const Model& m = test::sceneCritter();
  GroomEditor e(m, startingGroom(m, fur::loadFurPreset("default"), "test"));
  const auto message = [&](fur::GroomStroke s) {
    try {
      e.beginStroke(s, "brush");
    } catch (const InputError& err) {
      return std::string(err.what());
    }
    return std::string();
  };
  fur::GroomStroke s;
  s.radius = 0.0f;
  EXPECT_NE(message(s).find("brush: radius = 0 m is out of range (0, 10]"), std::string::npos)
      << message(s);
  s.radius = 0.02f;
  s.strength = std::nanf("");
  EXPECT_NE(message(s).find("strength = nan is out of range"), std::string::npos) << message(s);
  s.tool = fur::BrushTool::Cut;
  s.strength = 1.0f;
  s.cutLength = -1.0f;
  EXPECT_NE(message(s).find("length = -1 m is out of range [0, 10]"), std::string::npos)
      << message(s);
  s.tool = fur::BrushTool::Density;
  s.mirrorAxis = 3;
  EXPECT_NE(message(s).find("mirror"), std::string::npos) << message(s);
  EXPECT_FALSE(e.drawing());
  // A finished stroke needs its points.
  fur::GroomStroke none;
  EXPECT_THROW(fur::validateGroomStroke(none, "brush"), InputError);
  none.points = {Eigen::Vector3f(0, 0, std::nanf(""))};
  EXPECT_THROW(fur::validateGroomStroke(none, "brush", false), InputError);
}

}  // namespace
}  // namespace pelage::scene
