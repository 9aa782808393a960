// The GL-free draw list (scene/draw_list.h): one frame for a camera and light, and the shadings.
#include "pelage/scene/draw_list.h"

#include <gtest/gtest.h>

#include "pelage/scene/frame.h"
#include "pelage/util/color.h"
#include "pelage/util/error.h"
#include "support/models.h"

namespace pelage::scene {
namespace {

using test::sceneCritter;
using test::sceneFur;

FrameState restFrame() {
  FrameState f;
  evaluateFrame(sceneCritter(), anatomy::restPose(sceneCritter().body), f);
  return f;
}

TEST(Names, ShadingsParseAndRejectUnknownNames) {
  EXPECT_EQ(parseHairShading("kajiya-kay"), HairShading::KajiyaKay);
  EXPECT_EQ(parseHairShading("paper"), HairShading::Paper);
  EXPECT_EQ(parseHairShading("marschner"), HairShading::Marschner);
  EXPECT_EQ(parseHairShading("physical"), HairShading::Physical);
  for (HairShading s : kHairShadings) EXPECT_EQ(parseHairShading(hairShadingName(s)), s);
  EXPECT_FALSE(shadesWithTangents(HairShading::Paper));
  EXPECT_TRUE(shadesWithTangents(HairShading::KajiyaKay));
  EXPECT_TRUE(shadesWithTangents(HairShading::Marschner));
  EXPECT_FALSE(shadesWithTangents(HairShading::Physical));  // style normals; tangents from strands
  EXPECT_THROW(parseHairShading("pbr"), InputError);
}

TEST(Names, LightPassesParseAndRejectUnknownNames) {
  const std::pair<LightPass, const char*> passes[] = {{LightPass::All, "all"},
                                                      {LightPass::Hair, "hair"},
                                                      {LightPass::Fibre, "fibre"},
                                                      {LightPass::Coat, "coat"},
                                                      {LightPass::Skin, "skin"}};
  for (const auto& [pass, name] : passes) {
    EXPECT_EQ(parseLightPass(name), pass);
    EXPECT_EQ(lightPassName(pass), name);
  }
  EXPECT_THROW(parseLightPass("glossy"), InputError);
  EXPECT_THROW(parseLightPass(""), InputError);
}

TEST(BuildDrawList, SkinAndOneItemPerCoat) {
  const Model& m = sceneCritter();
  const Fur& fur = sceneFur();
  FrameState f = restFrame();
  const Framing fr = framingOf(m, f, maxHairLength(m, fur.params));
  const Camera cam = presetCamera(fr, CameraPreset::Side, 640, 480);
  evaluateFur(m, fur, cam, true, f);
  Light light;
  light.shadows = true;
  DrawList list;
  DrawOptions o;
  o.lightPass = LightPass::Coat;
  buildDrawList(m, f, &fur, cam, light, o, list);
  EXPECT_EQ(list.camera.width, 640);
  EXPECT_EQ(list.lightPass, LightPass::Coat);
  EXPECT_TRUE(list.light.shadows);
  EXPECT_EQ(list.skin.vertices, m.skin.numVertices());
  EXPECT_EQ(list.skin.triangleCount, m.skin.numTriangles());
  EXPECT_EQ(list.skin.positions, &f.skin.positions);
  EXPECT_TRUE(list.skin.material.diffuse.isApprox(srgbToLinear(m.skin.color)));  // drawn linear
  ASSERT_EQ(list.fur.size(), 2u);
  for (int c = 0; c < 2; ++c) {
    const FurDrawItem& item = list.fur[static_cast<std::size_t>(c)];
    EXPECT_EQ(item.coat, c);
    EXPECT_EQ(item.layout.style, fur.params.coats[static_cast<std::size_t>(c)].style);
    EXPECT_EQ(item.pointsPerHair(),
              f.fur.coats[static_cast<std::size_t>(c)].layout.pointsPerHair());
    EXPECT_EQ(item.rootCount, fur.roots.coats[static_cast<std::size_t>(c)].size());
    EXPECT_EQ(item.drawnHairs, f.fur.coats[static_cast<std::size_t>(c)].drawn);
    EXPECT_EQ(item.positions, f.fur.coats[static_cast<std::size_t>(c)].positions.data());
    EXPECT_TRUE(item.material.diffuse.isApprox(
        srgbToLinear(fur.params.coats[static_cast<std::size_t>(c)].material.diffuse)));
    EXPECT_EQ(item.source, HairSource::Cpu);
  }
  EXPECT_EQ(list.drawnHairs(), f.drawnHairs[0] + f.drawnHairs[1]);
  EXPECT_EQ(list.hairLength, maxHairLength(m, fur.params));  // the fur shadow's depth scale
  // The bounds hold every hair point.
  for (const fur::HairBuffers& hb : f.fur.coats)
    for (std::int64_t i = 0; i < hb.drawn * hb.layout.pointsPerHair(); ++i)
      ASSERT_TRUE(list.bounds.contains(Eigen::Vector3f(hb.positions.data()[3 * i],
                                                       hb.positions.data()[3 * i + 1],
                                                       hb.positions.data()[3 * i + 2])));
  // The GPU source points at the roots instead.
  o.hairSource = HairSource::Gpu;
  buildDrawList(m, f, &fur, cam, light, o, list);
  ASSERT_EQ(list.fur.size(), 2u);
  EXPECT_EQ(list.fur[0].positions, nullptr);
  EXPECT_EQ(list.gpuFur.roots, &fur.roots);
  EXPECT_EQ(list.gpuFur.rootsGeneration, fur.generation);
  // No fur, no skin.
  o.drawFur = false;
  o.drawSkin = false;
  buildDrawList(m, f, &fur, cam, light, o, list);
  EXPECT_TRUE(list.fur.empty());
  EXPECT_EQ(list.skin.positions, nullptr);
  EXPECT_EQ(list.hairLength, 0.0f);
}

}  // namespace
}  // namespace pelage::scene
