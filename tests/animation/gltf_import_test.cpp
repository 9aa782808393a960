// glTF import on the shared models: every model loads with its clips; the bind pose reproduces the
// mesh as stored (converted to Z up, metres); every clip keeps the skin finite and near the body; a
// joint turned by 90 degrees turns exactly its vertices; the Stag's rigid antlers follow its head;
// regions, fur lengths, bindings, unit scale and head-to-tail directions are as documented.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "pelage/animation/gltf_import.h"
#include "pelage/scene/model.h"
#include "pelage/skin/deform.h"
#include "pelage/util/color.h"
#include "pelage/util/error.h"
#include "support/files.h"
#include "support/gltf.h"

namespace pelage::animation {
namespace {

using test::sharedModel;

struct ModelFacts {
  std::string file;
  int triangles;  // after dropping degenerate ones (the Alpaca has 4 of its README's 2060)
  float unitScale;
  std::map<std::string, float> clips;  // name -> duration (README)
};

const std::vector<ModelFacts>& facts() {
  static const std::vector<ModelFacts> f = {
      {"Fox/Fox.glb", 576, 0.01f, {{"Survey", 3.4167f}, {"Walk", 0.7083f}, {"Run", 1.1583f}}},
      {"CesiumMan/CesiumMan.glb", 4672, 1.0f, {{"clip0", 2.0f}}},
      {"RiggedFigure/RiggedFigure.glb", 256, 1.0f, {{"clip0", 1.25f}}},
      {"RiggedSimple/RiggedSimple.glb", 188, 1.0f, {{"clip0", 2.0833f}}},
      {"SimpleSkin/SimpleSkin.gltf", 8, 1.0f, {{"clip0", 5.5f}}},
      {"Wolf/Wolf.gltf",
       1962,
       1.0f,
       {{"Attack", 1.3333f},
        {"Death", 1.0667f},
        {"Eating", 2.5333f},
        {"Gallop", 0.5667f},
        {"Gallop_Jump", 0.9333f},
        {"Idle", 3.3333f},
        {"Idle_2", 3.3333f},
        {"Idle_2_HeadLow", 4.0f},
        {"Idle_HitReact_Left", 0.6667f},
        {"Idle_HitReact_Right", 0.6667f},
        {"Jump_ToIdle", 1.3333f},
        {"Walk", 1.0667f}}},
      {"Husky/Husky.gltf",
       1920,
       1.0f,
       {{"Attack", 1.2f},
        {"Death", 1.0667f},
        {"Eating", 2.6667f},
        {"Gallop", 0.5667f},
        {"Gallop_Jump", 0.9333f},
        {"Idle", 3.3333f},
        {"Idle_2", 3.3333f},
        {"Idle_2_HeadLow", 4.0f},
        {"Idle_HitReact_Left", 0.6667f},
        {"Idle_HitReact_Right", 0.6667f},
        {"Jump_ToIdle", 1.3333f},
        {"Walk", 1.0667f}}},
      {"Horse/Horse.gltf",
       2182,
       1.0f,
       {{"Attack_Headbutt", 1.0333f},
        {"Attack_Kick", 1.0f},
        {"Death", 1.0f},
        {"Eating", 6.0f},
        {"Gallop", 0.6f},
        {"Gallop_Jump", 1.4667f},
        {"Idle", 3.3333f},
        {"Idle_2", 3.3333f},
        {"Idle_Headlow", 3.3333f},
        {"Idle_HitReact_Left", 0.6667f},
        {"Idle_HitReact_Right", 0.6667f},
        {"Jump_toIdle", 1.7333f},
        {"Walk", 1.1667f}}},
      {"Stag/Stag.gltf",
       3670,
       1.0f,
       {{"Attack_Headbutt", 0.8f},
        {"Attack_Kick", 0.8f},
        {"Death", 1.1f},
        {"Eating", 12.1f},
        {"Gallop", 0.5333f},
        {"Gallop_Jump", 1.4f},
        {"Idle", 3.3333f},
        {"Idle_2", 3.3333f},
        {"Idle_Headlow", 3.3333f},
        {"Idle_HitReact_Left", 0.4667f},
        {"Idle_HitReact_Right", 0.5333f},
        {"Jump_toIdle", 1.5333f},
        {"Walk", 1.1667f}}},
      {"Alpaca/Alpaca.gltf",
       2056,
       1.0f,
       {{"Attack_Headbutt", 1.0f},
        {"Attack_Kick", 1.0f},
        {"Death", 1.0417f},
        {"Eating", 7.5f},
        {"Gallop", 0.6667f},
        {"Gallop_Jump", 1.75f},
        {"Idle", 4.1667f},
        {"Idle_2", 4.1667f},
        {"Idle_Headlow", 4.1667f},
        {"Idle_HitReact_Left", 0.5833f},
        {"Idle_HitReact_Right", 0.6667f},
        {"Jump_toIdle", 1.9167f},
        {"Walk", 1.4583f}}},
  };
  return f;
}

// The load options of these tests: the skin as the file has it (no subdivision, skin/subdivide.h).
scene::LoadOptions asInFile() {
  scene::LoadOptions opt;
  opt.subdivide = 0;
  return opt;
}

// Every shared model, loaded once per test binary, as in its file.
const scene::Model& model(const std::string& file) {
  static std::map<std::string, scene::Model> cache;
  auto it = cache.find(file);
  if (it == cache.end())
    it = cache.emplace(file, scene::loadModel(sharedModel(file), asInFile())).first;
  return it->second;
}

std::vector<Eigen::Vector3f> deform(const scene::Model& m, const anatomy::Pose& pose) {
  anatomy::BodyState st;
  anatomy::forwardKinematics(m.body, pose, st);
  skin::DeformedSkin d;
  skin::deformSkin(m.skin, st, d);
  return d.positions;
}

std::vector<Eigen::Vector3f> restPositions(const scene::Model& m) {
  std::vector<Eigen::Vector3f> p(static_cast<std::size_t>(m.skin.numVertices()));
  for (std::size_t v = 0; v < p.size(); ++v)
    p[v] = Eigen::Map<const Eigen::Vector3f>(m.skin.restPositions() + 3 * v);
  return p;
}

Eigen::AlignedBox3f bounds(const std::vector<Eigen::Vector3f>& pts) {
  Eigen::AlignedBox3f b;
  for (const auto& p : pts) b.extend(p);
  return b;
}

TEST(GltfImport, EveryModelLoadsWithItsClips) {
  PELAGE_REQUIRE_SHARED_MODELS();
  for (const ModelFacts& f : facts()) {
    SCOPED_TRACE(f.file);
    const scene::Model& m = model(f.file);
    EXPECT_EQ(m.skin.numTriangles(), f.triangles);
    EXPECT_FLOAT_EQ(m.unitScale, f.unitScale);
    ASSERT_EQ(m.clips.size(), f.clips.size());
    for (const Clip& c : m.clips) {
      ASSERT_TRUE(f.clips.count(c.name)) << c.name;
      EXPECT_NEAR(c.duration, f.clips.at(c.name), 1e-3) << c.name;
      EXPECT_TRUE(c.loop);
      EXPECT_FALSE(c.channels.empty()) << c.name;
      checkClip(c, m.body);
    }
    anatomy::checkBody(m.body);
  }
}

// Z up, metres, facing +X: the animals stand on z = 0 (to 1% of their height); the Fox, 155 file
// units long, becomes 1.55 m; the head is in front (+X) of the tail.
TEST(GltfImport, CreaturesStandOnTheGroundFacingPlusX) {
  PELAGE_REQUIRE_SHARED_MODELS();
  for (const char* file : {"Fox/Fox.glb", "Wolf/Wolf.gltf", "Horse/Horse.gltf", "Stag/Stag.gltf",
                           "Alpaca/Alpaca.gltf", "Husky/Husky.gltf", "CesiumMan/CesiumMan.glb"}) {
    SCOPED_TRACE(file);
    const scene::Model& m = model(file);
    const Eigen::AlignedBox3f b = bounds(restPositions(m));
    EXPECT_NEAR(b.min().z(), 0.0f, 0.01f * b.sizes().z());
    if (std::string(file).find("Cesium") == std::string::npos) {
      EXPECT_GT(b.sizes().x(), b.sizes().y());
    }
  }
  const Eigen::AlignedBox3f fox = bounds(restPositions(model("Fox/Fox.glb")));
  EXPECT_NEAR(fox.sizes().x(), 1.547f, 0.01f);
  EXPECT_NEAR(fox.sizes().z(), 0.790f, 0.01f);
  auto jointX = [](const scene::Model& m, const char* name) {
    const int s = m.body.find(name);
    EXPECT_GE(s, 0) << name;
    return m.body.inverseBind[static_cast<std::size_t>(std::max(s, 0))].inverse().translation().x();
  };
  EXPECT_GT(jointX(model("Fox/Fox.glb"), "b_Head_05"),
            jointX(model("Fox/Fox.glb"), "b_Tail03_014") + 1.0f);
  EXPECT_GT(jointX(model("Horse/Horse.gltf"), "Head"),
            jointX(model("Horse/Horse.gltf"), "Tail7") + 2.0f);
}

// The bind-pose skin is the stored mesh, converted: every stored POSITION p of the skinned meshes,
// placed by the mesh node and then by s C (x, y, z) -> s (z, x, y), is a skin vertex, and the bind
// pose deforms the skin onto itself. (The node rest transforms of several files - RiggedSimple,
// the Quaternius animals - are not their bind pose, so the rest pose moves the skin a little.)
TEST(GltfImport, BindPoseReproducesTheStoredMesh) {
  PELAGE_REQUIRE_SHARED_MODELS();
  for (const ModelFacts& f : facts()) {
    SCOPED_TRACE(f.file);
    const scene::Model& m = model(f.file);
    const test::GltfParts parts = test::GltfParts::read(sharedModel(f.file));
    const std::vector<Eigen::Vector3f> rest = restPositions(m);
    const float diag = bounds(rest).diagonal().norm();
    // The mesh node's global transform: the product of node matrices/TRS up its parents.
    const auto& nodes = parts.json["nodes"];
    std::vector<int> parent(nodes.size(), -1);
    for (std::size_t i = 0; i < nodes.size(); ++i)
      for (const auto& c : nodes[i].value("children", nlohmann::json::array()))
        parent[c.get<std::size_t>()] = static_cast<int>(i);
    auto local = [&](std::size_t i) {
      Eigen::Affine3d t = Eigen::Affine3d::Identity();
      const auto& n = nodes[i];
      if (n.contains("matrix"))
        for (int k = 0; k < 16; ++k)
          t.matrix()(k % 4, k / 4) = n["matrix"][static_cast<std::size_t>(k)].get<double>();
      if (n.contains("translation"))
        t.translate(Eigen::Vector3d(n["translation"][0], n["translation"][1], n["translation"][2]));
      if (n.contains("rotation"))
        t.rotate(Eigen::Quaterniond(n["rotation"][3], n["rotation"][0], n["rotation"][1],
                                    n["rotation"][2]));
      if (n.contains("scale"))
        t.scale(Eigen::Vector3d(n["scale"][0], n["scale"][1], n["scale"][2]));
      return t;
    };
    std::size_t checked = 0;
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      if (!nodes[i].contains("mesh") || !nodes[i].contains("skin")) continue;
      Eigen::Affine3d g = Eigen::Affine3d::Identity();
      for (int n = static_cast<int>(i); n >= 0; n = parent[static_cast<std::size_t>(n)])
        g = local(static_cast<std::size_t>(n)) * g;
      for (const auto& prim :
           parts.json["meshes"][nodes[i]["mesh"].get<std::size_t>()]["primitives"])
        for (const Eigen::Vector3f& p : parts.vec3(prim["attributes"]["POSITION"].get<int>())) {
          const Eigen::Vector3d w = g * p.cast<double>();
          const Eigen::Vector3f expect =
              (f.unitScale * Eigen::Vector3d(w.z(), w.x(), w.y())).cast<float>();
          float best = 1e30f;
          for (const auto& r : rest) best = std::min(best, (r - expect).squaredNorm());
          ASSERT_LT(std::sqrt(best), 1e-5f * diag)
              << "stored vertex " << expect.transpose() << " not in the skin";
          ++checked;
        }
    }
    EXPECT_GT(checked, 0u);
    const std::vector<Eigen::Vector3f> posed = deform(m, bindPose(m.body));
    float worst = 0.0f;
    for (std::size_t v = 0; v < rest.size(); ++v)
      worst = std::max(worst, (posed[v] - rest[v]).norm());
    EXPECT_LT(worst, 1e-4f * diag);
  }
}

// Every clip of every model, sampled over its cycle, keeps the skin finite and within the rest
// bounds grown by one bounding-box diagonal on every side.
TEST(GltfImport, EveryClipKeepsTheSkinFiniteAndNear) {
  PELAGE_REQUIRE_SHARED_MODELS();
  for (const ModelFacts& f : facts()) {
    const scene::Model& m = model(f.file);
    const Eigen::AlignedBox3f restBox = bounds(restPositions(m));
    const float diag = restBox.diagonal().norm();
    Eigen::AlignedBox3f allowed = restBox;
    allowed.min().array() -= diag;
    allowed.max().array() += diag;
    anatomy::Pose pose;
    for (const Clip& c : m.clips)
      for (int i = 0; i <= 8; ++i) {
        sampleClip(c, m.body, c.duration * i / 8.0, pose);
        for (const auto& p : deform(m, pose)) {
          ASSERT_TRUE(p.allFinite()) << f.file << " " << c.name;
          ASSERT_TRUE(allowed.contains(p))
              << f.file << " " << c.name << " at " << c.duration * i / 8.0 << ": " << p.transpose();
        }
      }
  }
}

// Turning one joint by 90 degrees about an axis turns the vertices bound only to it by 90 degrees
// about that axis through the joint (in world space), and leaves unbound vertices where they were.
TEST(GltfImport, AJointTurnedNinetyDegreesTurnsItsVertices) {
  PELAGE_REQUIRE_SHARED_MODELS();
  const scene::Model& m = model("Fox/Fox.glb");
  const int head = m.body.find("b_Head_05");
  ASSERT_GE(head, 0);
  const anatomy::Pose rest = anatomy::restPose(m.body);
  anatomy::BodyState st;
  anatomy::forwardKinematics(m.body, rest, st);
  const Eigen::Affine3f W = st.world[static_cast<std::size_t>(head)];
  const Eigen::Vector3f axisLocal = Eigen::Vector3f(0.3f, 1.0f, -0.2f).normalized();
  anatomy::Pose turned = rest;
  turned.local[static_cast<std::size_t>(head)].rotation =
      rest.local[static_cast<std::size_t>(head)].rotation *
      Eigen::Quaternionf(Eigen::AngleAxisf(static_cast<float>(M_PI / 2), axisLocal));
  const Eigen::Vector3f axisWorld = (W.linear() * axisLocal).normalized();
  const Eigen::Vector3f pivot = W.translation();
  const Eigen::AngleAxisf R(static_cast<float>(M_PI / 2), axisWorld);
  const std::vector<Eigen::Vector3f> before = deform(m, rest), after = deform(m, turned);
  const skin::Binding* bind = m.skin.bindings();
  int moved = 0, still = 0;
  for (std::size_t v = 0; v < before.size(); ++v) {
    float w = 0.0f;
    for (int k = 0; k < 4; ++k)
      if (bind[v].segment[static_cast<std::size_t>(k)] == head)
        w += bind[v].weight[static_cast<std::size_t>(k)];
    if (w > 0.9999f) {
      EXPECT_LT((after[v] - (pivot + R * (before[v] - pivot))).norm(), 1e-5f);
      ++moved;
    } else if (w == 0.0f) {
      EXPECT_EQ(after[v], before[v]);
      ++still;
    }
  }
  EXPECT_GT(moved, 10);
  EXPECT_GT(still, 100);
}

// The antlers are a separate unskinned mesh under the Head joint: bound rigidly to their own
// segment, they keep their shape and their distance to the head joint while the head moves.
TEST(GltfImport, StagAntlersFollowTheHead) {
  PELAGE_REQUIRE_SHARED_MODELS();
  const scene::Model& m = model("Stag/Stag.gltf");
  const auto& names = m.skin.regionNames;
  const auto it = std::find(names.begin(), names.end(), "Stag_Horns");
  ASSERT_NE(it, names.end());
  const int region = static_cast<int>(it - names.begin());
  const int horns = m.body.find("Stag_Horns"), head = m.body.find("Head");
  ASSERT_GE(horns, 0);
  ASSERT_EQ(m.body.segments[static_cast<std::size_t>(horns)].parent, head);
  std::vector<int> hornVerts;
  for (int v = 0; v < m.skin.numVertices(); ++v)
    if (m.skin.regions()[v] == region) {
      hornVerts.push_back(v);
      EXPECT_EQ(m.skin.bindings()[v].segment[0], horns);
      EXPECT_EQ(m.skin.bindings()[v].weight[0], 1.0f);
      EXPECT_EQ(m.skin.furLengths()[v], 0.0f);  // *Horn* is a default no-fur region
    }
  ASSERT_GT(hornVerts.size(), 100u);
  const Clip& eat = m.clips[static_cast<std::size_t>(m.findClip("Eating"))];
  anatomy::Pose pose;
  anatomy::BodyState st;
  std::vector<float> dist0;
  Eigen::Vector3f tip0;
  float headTravel = 0.0f;
  for (int i = 0; i <= 10; ++i) {
    sampleClip(eat, m.body, eat.duration * i / 10.0, pose);
    anatomy::forwardKinematics(m.body, pose, st);
    const std::vector<Eigen::Vector3f> p = deform(m, pose);
    const Eigen::Vector3f h = st.world[static_cast<std::size_t>(head)].translation();
    for (std::size_t k = 0; k < hornVerts.size(); k += 7) {
      const float d = (p[static_cast<std::size_t>(hornVerts[k])] - h).norm();
      if (i == 0) {
        dist0.push_back(d);
      } else {
        EXPECT_NEAR(d, dist0[k / 7], 1e-4f * (1.0f + d));
      }
    }
    if (i == 0) tip0 = p[static_cast<std::size_t>(hornVerts[0])];
    headTravel = std::max(headTravel, (p[static_cast<std::size_t>(hornVerts[0])] - tip0).norm());
  }
  EXPECT_GT(headTravel, 0.1f);  // the antlers do move with the eating head
}

TEST(GltfImport, RegionsAndFurLengths) {
  PELAGE_REQUIRE_SHARED_MODELS();
  const scene::Model& m = model("Horse/Horse.gltf");
  EXPECT_THAT(m.skin.regionNames,
              ::testing::IsSupersetOf({"Main", "Main_Dark", "Main_Light", "Hooves", "Hair",
                                       "Muzzle", "Eye_White", "Eye_Black"}));
  const float diag = bounds(restPositions(m)).diagonal().norm();
  std::map<std::string, std::pair<int, int>> counts;  // region -> (furred, bare) vertices
  for (int v = 0; v < m.skin.numVertices(); ++v) {
    const std::string& r = m.skin.regionNames[static_cast<std::size_t>(m.skin.regions()[v])];
    const float len = m.skin.furLengths()[v];
    if (len > 0.0f) {
      EXPECT_NEAR(len, 0.02f * diag, 1e-4f * diag);
      ++counts[r].first;
    } else {
      ++counts[r].second;
    }
  }
  for (const char* bare : {"Hooves", "Eye_White", "Eye_Black"}) {
    EXPECT_EQ(counts[bare].first, 0) << bare;
    EXPECT_GT(counts[bare].second, 0) << bare;
  }
  for (const char* furred : {"Main", "Main_Light", "Hair", "Muzzle"}) {
    EXPECT_GT(counts[furred].first, 0) << furred;
    EXPECT_EQ(counts[furred].second, 0) << furred;
  }
  // LoadOptions replace the defaults.
  scene::LoadOptions opt;
  opt.noFurRegions = std::vector<std::string>{"main*"};
  const scene::Model bare = scene::loadModel(sharedModel("Horse/Horse.gltf"), opt);
  for (int v = 0; v < bare.skin.numVertices(); ++v) {
    const std::string& r = bare.skin.regionNames[static_cast<std::size_t>(bare.skin.regions()[v])];
    if (r == "Hooves") {
      EXPECT_GT(bare.skin.furLengths()[v], 0.0f);
    }
  }
  int mainBare = 0;
  for (int v = 0; v < bare.skin.numVertices(); ++v)
    mainBare += bare.skin.regionNames[static_cast<std::size_t>(bare.skin.regions()[v])] == "Main" &&
                bare.skin.furLengths()[v] == 0.0f;
  EXPECT_GT(mainBare, 100);
}

// Skin colour: an untextured material's base colour (the Wolf's largest furred region "Main";
// glTF's linear factor, sRGB-encoded as skin.color is typed); a textured one (the Fox: factor 1,
// colour in its texture) keeps the default skin colour rather than turning white.
TEST(GltfImport, SkinColourFromUntexturedMaterialsOnly) {
  PELAGE_REQUIRE_SHARED_MODELS();
  EXPECT_TRUE(
      model("Wolf/Wolf.gltf")
          .skin.color.isApprox(Eigen::Vector3f(linearToSrgb(0.18424858f), linearToSrgb(0.19017477f),
                                               linearToSrgb(0.16846527f)),
                               1e-5f));
  const skin::SkinMesh untouched;
  EXPECT_TRUE(model("Fox/Fox.glb").skin.color.isApprox(untouched.color));
}

TEST(GltfImport, BindingsAreNormalisedLargestFirst) {
  PELAGE_REQUIRE_SHARED_MODELS();
  for (const ModelFacts& f : facts()) {
    const scene::Model& m = model(f.file);
    for (int v = 0; v < m.skin.numVertices(); ++v) {
      const skin::Binding& b = m.skin.bindings()[v];
      float sum = 0.0f;
      for (std::size_t k = 0; k < 4; ++k) {
        sum += b.weight[k];
        ASSERT_GE(b.weight[k], 0.0f);
        ASSERT_TRUE(b.segment[k] >= 0 && b.segment[k] < m.body.size());
        if (k > 0) {
          ASSERT_LE(b.weight[k], b.weight[k - 1]) << f.file;
        }
      }
      ASSERT_NEAR(sum, 1.0f, 1e-5f) << f.file;
    }
  }
}

// Head to tail: on the Wolf the back's fur points to the tail (-X), the legs' down (-Z) and the
// tail's along the tail (away from the body, -X).
TEST(GltfImport, SegmentDirectionsRunHeadToTail) {
  PELAGE_REQUIRE_SHARED_MODELS();
  const scene::Model& m = model("Wolf/Wolf.gltf");
  auto dir = [&](const char* name) {
    const int s = m.body.find(name);
    EXPECT_GE(s, 0) << name;
    return m.body.segments[static_cast<std::size_t>(std::max(s, 0))].direction;
  };
  for (const char* back : {"Torso", "Torso2", "Neck2"})
    EXPECT_LT(dir(back).x(), -0.5f) << back << dir(back).transpose();
  for (const char* leg : {"FrontLowerLeg.L", "BackLowerLeg.R", "FrontUpperLeg.R"})
    EXPECT_LT(dir(leg).z(), -0.5f) << leg << dir(leg).transpose();
  EXPECT_LT(dir("Tail3").x(), 0.0f);
  for (const char* s : {"Torso", "FrontLowerLeg.L", "Tail3", "Head"})
    EXPECT_NEAR(dir(s).norm(), 1.0f, 1e-5f) << s;
  // Each vertex carries its closest (largest-weight) segment's direction.
  for (int v = 0; v < m.skin.numVertices(); v += 13) {
    const Eigen::Vector3f d = Eigen::Map<const Eigen::Vector3f>(m.skin.segmentDirections() + 3 * v);
    EXPECT_TRUE(d.isApprox(
        m.body.segments[static_cast<std::size_t>(m.skin.bindings()[v].segment[0])].direction));
  }
}

TEST(GltfImport, DirectionSideFileOverridesPerJoint) {
  PELAGE_REQUIRE_SHARED_MODELS();
  test::TempDir dir;
  test::writeText(dir.file("wolf.directions.json"),
                  R"({ "directions": { "Torso": [0, 0, 2], "Head": [0, 0, 0] } })");
  scene::LoadOptions opt = asInFile();
  opt.segmentDirections = dir.file("wolf.directions.json");
  const scene::Model m = scene::loadModel(sharedModel("Wolf/Wolf.gltf"), opt);
  EXPECT_EQ(m.body.segments[static_cast<std::size_t>(m.body.find("Torso"))].direction,
            Eigen::Vector3f(0, 0, 1));
  EXPECT_EQ(m.body.segments[static_cast<std::size_t>(m.body.find("Head"))].direction,
            Eigen::Vector3f::Zero());
  const int torso = m.body.find("Torso");
  int n = 0;
  for (int v = 0; v < m.skin.numVertices(); ++v)
    if (m.skin.bindings()[v].segment[0] == torso) {
      EXPECT_EQ(Eigen::Map<const Eigen::Vector3f>(m.skin.segmentDirections() + 3 * v),
                Eigen::Vector3f(0, 0, 1));
      ++n;
    }
  EXPECT_GT(n, 10);
  test::writeText(dir.file("bad.json"), R"({ "directions": { "Tosro": [0, 0, 1] } })");
  opt.segmentDirections = dir.file("bad.json");
  try {
    scene::loadModel(sharedModel("Wolf/Wolf.gltf"), opt);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("unknown segment 'Tosro'"));
    EXPECT_THAT(e.what(), ::testing::HasSubstr("bad.json"));
  }
}

TEST(GltfImport, UnitScaleCanBeGiven) {
  PELAGE_REQUIRE_SHARED_MODELS();
  scene::LoadOptions opt = asInFile();
  opt.unitScale = 0.02f;
  const scene::Model big = scene::loadModel(sharedModel("Fox/Fox.glb"), opt);
  EXPECT_FLOAT_EQ(big.unitScale, 0.02f);
  const Eigen::Vector3f a = bounds(restPositions(big)).sizes(),
                        b = bounds(restPositions(model("Fox/Fox.glb"))).sizes();
  EXPECT_TRUE(a.isApprox(2.0f * b, 1e-4f));
  // Clips scale with it (root translations are converted too).
  anatomy::Pose p;
  sampleClip(big.clips[0], big.body, 0.5, p);
  const Eigen::AlignedBox3f posed = bounds(deform(big, p));
  sampleClip(model("Fox/Fox.glb").clips[0], model("Fox/Fox.glb").body, 0.5, p);
  const Eigen::AlignedBox3f small = bounds(deform(model("Fox/Fox.glb"), p));
  EXPECT_TRUE(posed.min().isApprox(2.0f * small.min(), 1e-4f));
  opt.unitScale = -1.0f;
  EXPECT_THROW(scene::loadModel(sharedModel("Fox/Fox.glb"), opt), InputError);
  scene::LoadOptions notGltf;
  notGltf.unitScale = 2.0f;
  EXPECT_THROW(scene::loadModel("monkey", notGltf), InputError);
}

// A .gltf whose buffers are external .bin files next to it loads exactly like the embedded one.
TEST(GltfImport, ExternalBufferFilesLoad) {
  PELAGE_REQUIRE_SHARED_MODELS();
  test::TempDir dir;
  test::GltfParts g = test::GltfParts::read(sharedModel("SimpleSkin/SimpleSkin.gltf"));
  ASSERT_GE(g.buffers.size(), 2u);
  for (std::size_t i = 0; i < g.buffers.size(); ++i) {
    const std::string name =
        "part " + std::to_string(i) + ".bin";  // a space: URIs are percent-decoded
    test::writeBytes(dir.file(name), g.buffers[i]);
    g.json["buffers"][i]["uri"] = "part%20" + std::to_string(i) + ".bin";
  }
  g.write(dir.file("external.gltf"));
  const GltfCreature ext = importGltf(dir.file("external.gltf"));
  const GltfCreature emb = importGltf(sharedModel("SimpleSkin/SimpleSkin.gltf"));
  ASSERT_EQ(ext.skin.numVertices(), emb.skin.numVertices());
  for (int v = 0; v < 3 * ext.skin.numVertices(); ++v)
    EXPECT_EQ(ext.skin.restPositions()[v], emb.skin.restPositions()[v]);
  ASSERT_EQ(ext.clips.size(), 1u);
  EXPECT_EQ(ext.clips[0].channels.size(), emb.clips[0].channels.size());
}

TEST(GltfImport, UnitScaleHeuristic) {
  EXPECT_EQ(detectUnitScale(154.7f), 0.01f);
  EXPECT_EQ(detectUnitScale(5.4f), 1.0f);
  EXPECT_EQ(detectUnitScale(1.5f), 1.0f);
  EXPECT_EQ(detectUnitScale(30.0f), 1.0f);
  EXPECT_EQ(detectUnitScale(31.0f), 0.01f);
  EXPECT_EQ(detectUnitScale(4000.0f), 0.001f);
  EXPECT_EQ(detectUnitScale(0.0f), 1.0f);
  std::string why;
  detectUnitScale(154.7f, &why);
  EXPECT_THAT(why, ::testing::HasSubstr("centimetres"));
}

// A hand-made skeleton: head <- neck <- root -> tail, root -> leg (joints at unit spacing).
TEST(GltfImport, HeadToTailDirectionsOnAHandMadeSkeleton) {
  std::vector<anatomy::SegmentSpec> specs(5);
  specs[0].name = "root";
  specs[1].name = "neck";
  specs[1].parent = "root";
  specs[2].name = "my_head";
  specs[2].parent = "neck";
  specs[3].name = "tail";
  specs[3].parent = "root";
  specs[4].name = "leg";
  specs[4].parent = "root";
  const anatomy::Body body = anatomy::makeBody(specs, "test");
  std::vector<Eigen::Vector3f> pos(5);
  pos[static_cast<std::size_t>(body.find("root"))] = {0, 0, 1};
  pos[static_cast<std::size_t>(body.find("neck"))] = {1, 0, 1};
  pos[static_cast<std::size_t>(body.find("my_head"))] = {2, 0, 1};
  pos[static_cast<std::size_t>(body.find("tail"))] = {-1, 0, 1};
  pos[static_cast<std::size_t>(body.find("leg"))] = {0, 0, 0.5f};
  const std::vector<bool> all(5, true);
  const auto d = headToTailDirections(body, pos, all);
  auto at = [&](const char* n) { return d[static_cast<std::size_t>(body.find(n))]; };
  // The spine runs head -> neck -> root -> tail (the tail tip is the joint farthest from the head):
  // its segments point along it, to the tail; the leg, off the spine, points down.
  EXPECT_TRUE(at("root").isApprox(Eigen::Vector3f(-1, 0, 0)));
  EXPECT_TRUE(at("neck").isApprox(Eigen::Vector3f(-1, 0, 0)));
  EXPECT_TRUE(at("my_head").isApprox(Eigen::Vector3f(-1, 0, 0)));
  EXPECT_TRUE(at("tail").isApprox(Eigen::Vector3f(-1, 0, 0)));
  EXPECT_TRUE(at("leg").isApprox(Eigen::Vector3f(0, 0, -1)));
  // A longer leg makes the leg the spine's end: the root then averages the neck bone and the leg.
  pos[static_cast<std::size_t>(body.find("leg"))] = {0, 0, -2.0f};
  EXPECT_TRUE(
      headToTailDirections(body, pos, all)[static_cast<std::size_t>(body.find("root"))].isApprox(
          Eigen::Vector3f(-1, 0, -1).normalized()));
  pos[static_cast<std::size_t>(body.find("leg"))] = {0, 0, 0.5f};
  // Unbound segments get no direction.
  std::vector<bool> some = all;
  some[static_cast<std::size_t>(body.find("leg"))] = false;
  EXPECT_EQ(headToTailDirections(body, pos, some)[static_cast<std::size_t>(body.find("leg"))],
            Eigen::Vector3f::Zero());
  // Without a segment named *head*, the front-most joint of a long, low skeleton is the head: here
  // the tail end (moved to +X) becomes the head, and the flow reverses.
  std::vector<anatomy::SegmentSpec> renamed = specs;
  renamed[2].name = "snout";
  const anatomy::Body body2 = anatomy::makeBody(renamed, "test");
  std::vector<Eigen::Vector3f> pos2(5);
  pos2[static_cast<std::size_t>(body2.find("root"))] = {0, 0, 1};
  pos2[static_cast<std::size_t>(body2.find("neck"))] = {1, 0, 1};
  pos2[static_cast<std::size_t>(body2.find("snout"))] = {2, 0, 1};
  pos2[static_cast<std::size_t>(body2.find("tail"))] = {3.5f, 0, 1};  // front-most now
  pos2[static_cast<std::size_t>(body2.find("leg"))] = {0, 0, 0.5f};
  const auto d2 = headToTailDirections(body2, pos2, all);
  EXPECT_TRUE(d2[static_cast<std::size_t>(body2.find("tail"))].isApprox(Eigen::Vector3f(-1, 0, 0)));
  EXPECT_TRUE(d2[static_cast<std::size_t>(body2.find("neck"))].isApprox(Eigen::Vector3f(1, 0, 0)));
}

}  // namespace
}  // namespace pelage::animation
