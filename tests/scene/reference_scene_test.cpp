// The reference scene (scene/reference_scene.h): a frame's draw list read back from its bytes, as
// scripts/reference/cycles_render.py reads it: the camera and light as drawn, the skin's vertices,
// triangles and corner colours, and each coat's hairs (centre lines, widths, root and tip colours).
#include "pelage/scene/reference_scene.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdint>
#include <cstring>

#include "pelage/fur/colors.h"
#include "pelage/scene/frame.h"
#include "support/files.h"
#include "support/models.h"

namespace pelage::scene {
namespace {

struct Read {
  nlohmann::json header;
  std::string bytes;
  std::size_t base = 0;
  template <class T>
  T at(const nlohmann::json& spec, std::size_t i) const {
    EXPECT_LT(i, spec["count"].get<std::size_t>());
    T v;
    std::memcpy(&v, bytes.data() + base + spec["offset"].get<std::size_t>() + 4 * i, 4);
    return v;
  }
};

Read parse(const std::string& bytes) {
  Read r;
  r.bytes = bytes;
  EXPECT_EQ(bytes.substr(0, 8), "PLGSCN01");
  std::uint64_t length = 0;
  std::memcpy(&length, bytes.data() + 8, 8);
  r.header = nlohmann::json::parse(bytes.substr(16, length));
  r.base = 16 + length;
  return r;
}

TEST(ReferenceScene, HoldsTheFrameAsDrawn) {
  const Model& m = test::sceneCritter();
  const Fur& fur = test::sceneFur();
  FrameState f;
  evaluateFrame(m, anatomy::restPose(m.body), f);
  const Framing fr = framingOf(m, f, maxHairLength(m, fur.params));
  const Camera cam = presetCamera(fr, CameraPreset::ThreeQuarter, 320, 240);
  evaluateFur(m, fur, cam, true, f);
  DrawList list;
  buildDrawList(m, f, &fur, cam, Light{}, DrawOptions{}, list);
  const Read r = parse(referenceSceneBytes(list, f.fur));
  const nlohmann::json& h = r.header;
  EXPECT_EQ(h["format"], "pelage reference scene");
  EXPECT_EQ(h["version"], kReferenceSceneVersion);
  EXPECT_EQ(h["camera"]["width"], 320);
  EXPECT_EQ(h["camera"]["height"], 240);
  EXPECT_EQ(h["camera"]["fovYDegrees"].get<float>(), cam.fovYDegrees);
  for (int a = 0; a < 3; ++a) {
    EXPECT_EQ(h["camera"]["eye"][a].get<float>(), cam.eye[a]);
    EXPECT_EQ(h["camera"]["target"][a].get<float>(), cam.target[a]);
    EXPECT_EQ(h["background"][a].get<float>(), list.background[a]);
    EXPECT_EQ(h["light"]["ambient"][a].get<float>(), list.light.ambient[a]);
  }
  EXPECT_NEAR(h["light"]["direction"][0].get<float>() * list.light.direction.norm(),
              list.light.direction.x(), 1e-6f);
  // The skin: the deformed positions, the triangles, and each corner's colour.
  const nlohmann::json& s = h["skin"];
  ASSERT_EQ(s["vertices"], m.skin.numVertices());
  ASSERT_EQ(s["triangles"], m.skin.numTriangles());
  for (int v = 0; v < m.skin.numVertices(); v += 97)
    for (int a = 0; a < 3; ++a)
      EXPECT_EQ(r.at<float>(s["positions"], 3 * static_cast<std::size_t>(v) + a),
                f.skin.positions[static_cast<std::size_t>(v)][a]);
  for (std::size_t k = 0; k < m.skin.triangles.size(); k += 31)
    EXPECT_EQ(r.at<std::uint32_t>(s["indices"], k),
              static_cast<std::uint32_t>(m.skin.triangles[k]));
  const float corner[3] = {1.0f, 0.0f, 0.0f};
  const Eigen::Vector3f c0 = list.skin.appearance
                                 ? Eigen::Vector3f(m.skin.surfaceColorAt(5, corner).head<3>())
                                 : list.skin.material.diffuse;
  for (int a = 0; a < 3; ++a) EXPECT_EQ(r.at<float>(s["cornerColors"], 45 + a), c0[a]);
  // The coats: every drawn hair's points (centre lines), widths and colours.
  ASSERT_EQ(h["coats"].size(), list.fur.size());
  ASSERT_FALSE(list.fur.empty());
  for (std::size_t i = 0; i < list.fur.size(); ++i) {
    const nlohmann::json& c = h["coats"][i];
    const FurDrawItem& item = list.fur[i];
    const fur::HairBuffers& b = f.fur.coats[static_cast<std::size_t>(item.coat)];
    ASSERT_EQ(c["hairs"], b.drawn);
    ASSERT_GT(b.drawn, 100);
    const int K = b.layout.strandPoints;
    ASSERT_EQ(c["points"], K);
    EXPECT_EQ(c["cullFactor"].get<float>(), item.cullFactor);
    EXPECT_EQ(r.at<float>(c["widths"], 0), 1e-3f * item.width.rootMm);
    EXPECT_EQ(r.at<float>(c["widths"], static_cast<std::size_t>(K - 1)),
              item.width.metersAt(b.layout.along((K - 1) * b.layout.ringSides)));
    EXPECT_NEAR(r.at<float>(c["widths"], static_cast<std::size_t>(K - 1)), 1e-3f * item.width.tipMm,
                1e-9f);
    for (std::int64_t hair = 0; hair < b.drawn; hair += 37) {
      const auto hs = static_cast<std::size_t>(hair);
      if (b.layout.ringSides == 1) {
        for (int k = 0; k < 3 * K; ++k)
          ASSERT_EQ(r.at<float>(c["positions"],
                                hs * static_cast<std::size_t>(3 * K) + static_cast<std::size_t>(k)),
                    b.positions.data()[hs * static_cast<std::size_t>(b.layout.pointsPerHair() * 3) +
                                       static_cast<std::size_t>(k)]);
      }
      for (int end = 0; end < 2; ++end) {
        const Eigen::Vector3f expected =
            item.perHairColor
                ? fur::unpackSrgb8(item.colors[2 * hs + static_cast<std::size_t>(end)])
                : item.material.diffuse;
        for (int a = 0; a < 3; ++a)
          ASSERT_EQ(r.at<float>(c["colors"], 6 * hs + 3 * static_cast<std::size_t>(end) +
                                                 static_cast<std::size_t>(a)),
                    expected[a]);
      }
    }
  }
  // The file holds the same bytes.
  test::TempDir dir;
  writeReferenceScene(dir.file("f.pelscene"), list, f.fur);
  EXPECT_EQ(test::readText(dir.file("f.pelscene")), referenceSceneBytes(list, f.fur));
}

}  // namespace
}  // namespace pelage::scene
