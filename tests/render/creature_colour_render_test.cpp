// The Fox's fur in its own colours, as image statistics (llvmpipe): the Fox's texture is orange
// with a white chest and tail tip; rendered from the side with the default fur (colour source
// "texture" for a textured glTF creature), the fur pixels over the chest and the tail tip are
// lighter than those over the back. Regions are chosen in 3D from the hairs' roots in the rest
// pose (the Fox faces +X, Z up), then found in the image at the projected middle of each hair.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <vector>

#include "pelage/anatomy/pose.h"
#include "pelage/fur/preset.h"
#include "pelage/render/renderer.h"
#include "pelage/scene/camera.h"
#include "pelage/scene/draw_list.h"
#include "pelage/scene/frame.h"
#include "support/gl.h"

namespace pelage::render {
namespace {

class CreatureColourRenderTest : public test::GlTest {};

enum class Region { Other, Back, Chest, TailTip };

struct Shot {
  Image image;
  Eigen::Matrix4f viewProjection;
};

TEST_F(CreatureColourRenderTest, FoxChestAndTailTipFurIsLighterThanItsBack) {
  const scene::Model* shared = test::creature("Fox");
  if (!shared) GTEST_SKIP() << "shared models absent: " << PELAGE_SHARED_MODELS_DIR;
  const scene::Model& fox = *shared;
  fur::FurParams params = fur::loadFurPreset("default");
  params.setHairCount(30000);
  params.culling.enabled = false;
  const scene::Fur fur = scene::growFur(fox, params, "test");
  ASSERT_EQ(fur.params.coats[0].color.source, fur::ColorSource::Creature);  // -> its texture
  ASSERT_EQ(fox.skin.textures.size(), 1u);

  scene::FrameState frame;
  scene::evaluateFrame(fox, anatomy::restPose(fox.body), frame);
  const scene::Framing framing = scene::framingOf(fox, frame, scene::maxHairLength(fox, params));
  const scene::Camera cam = scene::presetCamera(framing, scene::CameraPreset::Side, 480, 360);
  auto render = [&](const scene::Fur* f) {
    if (f) scene::evaluateFur(fox, *f, fur::FurView{}, true, frame);
    scene::DrawList list;
    scene::DrawOptions opt;
    opt.hairSource = scene::HairSource::Cpu;
    opt.hairWidth = scene::HairWidth::Lines;  // opaque: each fur pixel is one hair's colour
    // The paper's shading, linear in the hair's colour: the test is of the colours, not of the
    // physical model's coat albedo (which takes pale colours down most, lighting.glsl's k_p).
    opt.hairShading = scene::HairShading::Paper;
    scene::buildDrawList(fox, frame, f, cam, scene::Light{}, opt, list);
    RendererOptions ro;
    ro.samples = 0;
    Renderer r(ro);
    r.render(list);
    return r.readPixels();
  };
  const Image bare = render(nullptr);
  const Image hairy = render(&fur);

  // Each drawn hair's region from its root; the regions' bounds in fractions of the roots' extent
  // along x (tail at 0, nose at 1), found from the Fox's texture layout (see the README's render).
  float x0 = 1e9f, x1 = -1e9f;
  struct Hair {
    Eigen::Vector3f root, middle;
  };
  std::vector<Hair> hairs;
  for (const fur::HairBuffers& hb : frame.fur.coats) {
    const int P = hb.layout.pointsPerHair();
    for (std::int64_t i = 0; i < hb.drawn; ++i) {
      const float* p = hb.positions.data() + 3 * i * P;
      const int mid = hb.layout.strandPoints / 2;  // a point half-way along the centre line
      hairs.push_back({Eigen::Vector3f(p[0], p[1], p[2]),
                       Eigen::Vector3f(p[3 * mid], p[3 * mid + 1], p[3 * mid + 2])});
      x0 = std::min(x0, p[0]);
      x1 = std::max(x1, p[0]);
    }
  }
  ASSERT_GT(hairs.size(), 20000u);
  const float L = x1 - x0;
  auto slabZ = [&](float a, float b, float q) {  // the q-quantile of root z in x slab [a, b]
    std::vector<float> z;
    for (const Hair& h : hairs)
      if (h.root.x() >= x0 + a * L && h.root.x() < x0 + b * L) z.push_back(h.root.z());
    std::sort(z.begin(), z.end());
    return z[static_cast<std::size_t>(q * static_cast<float>(z.size() - 1))];
  };
  const float backZ = slabZ(0.45f, 0.62f, 0.85f);   // the top of the middle of the body
  const float chestZ = slabZ(0.75f, 0.85f, 0.15f);  // the underside behind the head
  auto regionOf = [&](const Eigen::Vector3f& r) {
    const float a = (r.x() - x0) / L;
    if (a < 0.06f) return Region::TailTip;
    if (a >= 0.45f && a < 0.62f && r.z() > backZ) return Region::Back;
    if (a >= 0.75f && a < 0.85f && r.z() < chestZ) return Region::Chest;
    return Region::Other;
  };

  // Mean luminance (Rec. 709 on the sRGB codes) of the fur pixels at the projected middles of each
  // region's hairs; a pixel that equals the bare render's is no fur pixel and is not counted.
  const Eigen::Matrix4f vp = cam.viewProjection();
  double sum[4] = {0, 0, 0, 0};
  int count[4] = {0, 0, 0, 0};
  for (const Hair& h : hairs) {
    const Region region = regionOf(h.root);
    if (region == Region::Other) continue;
    const Eigen::Vector4f c = vp * h.middle.homogeneous();
    const int x = static_cast<int>((c.x() / c.w() * 0.5f + 0.5f) * static_cast<float>(cam.width));
    const int y = static_cast<int>((0.5f - c.y() / c.w() * 0.5f) * static_cast<float>(cam.height));
    if (x < 0 || y < 0 || x >= cam.width || y >= cam.height) continue;
    const std::uint8_t* p = hairy.pixel(x, y);
    const std::uint8_t* q = bare.pixel(x, y);
    if (p[0] == q[0] && p[1] == q[1] && p[2] == q[2]) continue;
    const auto k = static_cast<std::size_t>(region);
    sum[k] += 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
    ++count[k];
  }
  for (const Region r : {Region::Back, Region::Chest, Region::TailTip})
    ASSERT_GT(count[static_cast<std::size_t>(r)], 100) << "region " << static_cast<int>(r);
  const double back = sum[1] / count[1], chest = sum[2] / count[2], tail = sum[3] / count[3];
  RecordProperty("back", std::to_string(back));
  RecordProperty("chest", std::to_string(chest));
  RecordProperty("tail_tip", std::to_string(tail));
  EXPECT_GT(chest, back + 25.0) << "chest " << chest << " back " << back;
  EXPECT_GT(tail, back + 25.0) << "tail tip " << tail << " back " << back;
}

}  // namespace
}  // namespace pelage::render
