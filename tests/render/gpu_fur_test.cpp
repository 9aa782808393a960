// GPU fur against the CPU fur model: the same roots and deformed skin must give the same drawn
// hairs, in the same order, with points and shading vectors within 1e-4 relative, for every style,
// both coats, with culling on and off, with frizz, clumps (and a groom's clump scale) and a groom's
// comb on half the body; and the splitting into bindings must not change anything.
#include "pelage/render/gpu_fur.h"
#include "pelage/render/gl_context.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include "pelage/fur/preset.h"
#include "pelage/fur/roots.h"
#include "pelage/render/hair_vertex_buffers.h"
#include "pelage/render/renderer.h"
#include "pelage/scene/draw_list.h"
#include "pelage/scene/frame.h"
#include "pelage/skin/deform.h"
#include "support/gl.h"

namespace pelage::render {
namespace {

const scene::Model& critter() {
  return test::sceneCritter();
}

// A pose that bends the body (so the skin is not the bind pose) and turns it a little.
anatomy::Pose bentPose(const anatomy::Body& body) {
  anatomy::Pose p = anatomy::restPose(body);
  auto bend = [&](const char* name, const Eigen::Vector3f& axis, float deg) {
    const int s = body.find(name);
    ASSERT_GE(s, 0) << name;
    p.local[static_cast<std::size_t>(s)].rotation =
        p.local[static_cast<std::size_t>(s)].rotation *
        Eigen::Quaternionf(Eigen::AngleAxisf(deg * 3.14159265f / 180.0f, axis));
  };
  bend("head", Eigen::Vector3f::UnitY(), -25.0f);
  bend("tail", Eigen::Vector3f::UnitX(), 40.0f);
  bend("body", Eigen::Vector3f::UnitZ(), 20.0f);
  return p;
}

struct StyleCase {
  std::string name;
  fur::HairStyle over;
  fur::HairStyle under;
  float curl;  // helix radius fraction (curve/tube)
};

void PrintTo(const StyleCase& c, std::ostream* os) {
  *os << c.name;
}

fur::FurParams paramsFor(const StyleCase& sc, double hairs) {
  fur::FurParams p = fur::loadFurPreset("fig9");
  p.setHairCount(hairs);
  p.undercoatShare = 0.35f;
  p.seed = 77;
  for (int c = 0; c < fur::kCoatCount; ++c) {
    fur::CoatParams& cp = p.coats[static_cast<std::size_t>(c)];
    cp.style = c == 0 ? sc.over : sc.under;
    cp.normalRandomize = 0.5f;   // polyline twist table in use
    cp.hairEndRandomize = 0.3f;  // per-root jitter in use
    cp.segmentDirectionWeight = 0.4f;
    cp.curvePoints = 7;
    cp.tubeSides = 5;
    cp.curlRadius = sc.curl;
    cp.curlTurns = sc.curl > 0.0f ? 2.5f : 0.0f;
    cp.frizz = {.amplitudeMm = c == 0 ? 0.8f : 0.3f, .frequency = 3.3f, .tipWeight = 2.0f};
    // Clumps (fur_params.h Clump): the GPU pulls each clumped hair toward its centre's strand
    // points, which the CPU computes for the frame (fur::generateClumpCentres); then the frizz.
    cp.clump = {.density = c == 0 ? 0.5f : 1.0f,
                .strength = c == 0 ? 0.7f : 0.4f,
                .shape = c == 0 ? 1.0f : 2.5f,
                .radiusMm = 12.0f};
    // Per-hair colours (fur/colors.h): the GPU copies each drawn hair's root and tip colour.
    cp.color.hueVariation = c == 0 ? 12.0f : 0.0f;
    cp.color.valueVariation = 0.2f;
    cp.color.tipLightness = 1.4f;
  }
  // The 3D length region: a sphere around the head doubles its hairs.
  p.lengthRegion.shape = fur::LengthRegion::Shape::Sphere;
  p.lengthRegion.center = Eigen::Vector3f(0.25f, 0.0f, 0.38f);
  p.lengthRegion.radius = 0.08f;
  p.lengthRegion.scale = 2.0f;
  // Regions (fur/groom.h): a joint region with blended lengths, a skin region with an absolute
  // length and a tint, a denser head: the GPU reads the groomed vertex lengths.
  p.regions = {{.match = "tail", .lengthScale = 1.5f},
               {.match = "face", .lengthMm = 6.0f, .tint = {0.6f, 0.8f, 1.0f}},
               {.match = "head", .densityScale = 2.0f}};
  p.culling.referenceDistance = 0.25f;
  return p;
}

// Largest |gpu - cpu| / max(|cpu|, 0.05) over the points (3-vectors) of two arrays.
double maxRelativeError(const std::vector<float>& gpu, const float* cpu, std::size_t floats) {
  double worst = 0.0;
  for (std::size_t i = 0; i + 2 < floats; i += 3) {
    const Eigen::Vector3d g(gpu[i], gpu[i + 1], gpu[i + 2]);
    const Eigen::Vector3d c(cpu[i], cpu[i + 1], cpu[i + 2]);
    worst = std::max(worst, (g - c).norm() / std::max(c.norm(), 0.05));
  }
  return worst;
}

// Largest |gpu - cpu| over hair h's points divided by the hair's extent (largest distance of a CPU
// point from the hair's first point): an error measured against the hair itself, not against its
// distance from the world origin.
double maxHairRelativeError(const std::vector<float>& gpu, const float* cpu, std::int64_t hairs,
                            int pointsPerHair) {
  double worst = 0.0;
  for (std::int64_t h = 0; h < hairs; ++h) {
    const std::size_t first = static_cast<std::size_t>(h * pointsPerHair * 3);
    const Eigen::Vector3d c0(cpu[first], cpu[first + 1], cpu[first + 2]);
    double extent = 0.0, err = 0.0;
    for (int i = 0; i < pointsPerHair; ++i) {
      const std::size_t k = first + static_cast<std::size_t>(3 * i);
      const Eigen::Vector3d c(cpu[k], cpu[k + 1], cpu[k + 2]);
      const Eigen::Vector3d g(gpu[k], gpu[k + 1], gpu[k + 2]);
      extent = std::max(extent, (c - c0).norm());
      err = std::max(err, (g - c).norm());
    }
    worst = std::max(worst, err / std::max(extent, 1e-4));
  }
  return worst;
}

class GpuFurParity : public test::GlTest, public ::testing::WithParamInterface<StyleCase> {};
class GpuFurRandom : public test::GlTest {};

TEST_P(GpuFurParity, MatchesTheCpuModel) {
  const scene::Model& model = critter();
  scene::Fur fur = scene::growFur(model, paramsFor(GetParam(), 12000));
  {
    // A groom's comb (fur/groom.h) on the front half (x > 0): +X in the tangent plane, amount
    // 0.8, so the GPU reads packed combs beside uncombed hairs. The roots stay the same.
    skin::DeformedSkin rest;
    skin::restSkin(model.skin, rest);
    fur.groom.vertex.comb.assign(static_cast<std::size_t>(model.skin.numVertices()),
                                 Eigen::Vector3f::Zero());
    for (std::size_t v = 0; v < fur.groom.vertex.comb.size(); ++v) {
      const Eigen::Vector3f& n = rest.normals[v];
      const Eigen::Vector3f t = Eigen::Vector3f::UnitX() - n.x() * n;
      if (model.skin.restPositions()[3 * v] > 0.0f && t.norm() > 1e-3f)
        fur.groom.vertex.comb[v] = 0.8f * t.normalized();
    }
    // And a clump scale (groom.h): half strength behind the middle.
    fur.groom.vertex.clump.resize(fur.groom.vertex.comb.size());
    for (std::size_t v = 0; v < fur.groom.vertex.clump.size(); ++v)
      fur.groom.vertex.clump[v] = model.skin.restPositions()[3 * v] > 0.0f ? 1.0f : 0.5f;
    // And each coat's stiffness and segment direction weight per vertex (groom.h), varying along
    // x: per-hair floppiness and w.
    for (std::size_t v = 0; v < fur.groom.vertex.clump.size(); ++v) {
      const float x = model.skin.restPositions()[3 * v];
      const float s = std::clamp(0.5f + 1.5f * x, 0.0f, 1.0f);
      fur.groom.vertex.stiffness.emplace_back(s, 1.0f - s);
      fur.groom.vertex.segmentDirectionWeight.emplace_back(1.0f - s, s);
      // And a helix per vertex (curve and tube coats wind by it).
      fur.groom.vertex.curlRadius.emplace_back(0.3f * s, 0.1f);
      fur.groom.vertex.curlTurns.emplace_back(1.0f + 4.0f * s, 2.5f);
      // And a width scale per vertex (tubes grow that thick; every hair's colours carry it).
      fur.groom.vertex.widthScale.emplace_back(0.5f + 2.0f * s, 1.5f - s);
    }
    const std::vector<std::int32_t> triangles = fur.roots.coats[0].triangle;
    fur.roots = fur::growRoots(model.skin, fur.params, fur.groom);
    fur.colors = fur::colorRoots(model.skin, fur.roots, fur.params, fur.groom);
    ASSERT_EQ(fur.roots.coats[0].triangle, triangles);
    ASSERT_FALSE(fur.roots.coats[0].comb.empty());
    for (const fur::CoatRoots& cr : fur.roots.coats) {
      ASSERT_GT(cr.clumpCentres.size(), 20u);
      ASSERT_FALSE(cr.clumpScale.empty());
      ASSERT_FALSE(cr.floppiness.empty());
      ASSERT_FALSE(cr.segmentWeight.empty());
      ASSERT_FALSE(cr.curlRadius.empty());
      ASSERT_FALSE(cr.widthScale.empty());
    }
    for (const fur::CoatColors& cc : fur.colors.coats) ASSERT_TRUE(cc.perHairWidth);
  }
  ASSERT_GT(fur.roots.coats[0].size(), 5000);
  ASSERT_GT(fur.roots.coats[1].size(), 2500);
  scene::FrameState frame;
  scene::evaluateFrame(model, bentPose(model.body), frame);
  const scene::Framing framing =
      scene::framingOf(model, frame, scene::maxHairLength(model, fur.params));

  for (const bool culling : {false, true}) {
    // Culling on: the camera at 3x the reference distance (c = 3); off: every hair.
    scene::Camera cam = scene::presetCamera(framing, scene::CameraPreset::ThreeQuarter, 64, 64);
    cam.eye = framing.center + (cam.eye - framing.center).normalized() * 0.75f;
    fur::FurParams params = fur.params;
    scene::Fur f2 = fur;
    f2.params = params;
    f2.params.culling.enabled = culling;
    scene::evaluateFur(model, f2, cam, true, frame);
    if (culling) {
      ASSERT_GT(frame.cullFactor, 2.0f);
    } else {
      ASSERT_EQ(frame.cullFactor, 1.0f);
    }

    // The GPU's frame as a GPU run makes it: counts and clump centres only (evaluateFur without
    // CPU hairs).
    scene::FrameState gpuFrame;
    scene::evaluateFrame(model, bentPose(model.body), gpuFrame);
    scene::evaluateFur(model, f2, cam, false, gpuFrame);
    ASSERT_FALSE(gpuFrame.cpuFur);
    for (int c = 0; c < fur::kCoatCount; ++c) {
      const auto ci = static_cast<std::size_t>(c);
      ASSERT_EQ(gpuFrame.furWorkspace.clumpCentres[ci], frame.furWorkspace.clumpCentres[ci]);
    }

    for (const scene::HairShading shading :
         {scene::HairShading::Paper, scene::HairShading::KajiyaKay}) {
      scene::DrawOptions opt;
      opt.hairSource = scene::HairSource::Gpu;
      opt.hairShading = shading;
      scene::DrawList list;
      scene::buildDrawList(model, gpuFrame, &f2, cam, scene::Light{}, opt, list);
      ASSERT_NE(list.gpuFur.clumpCentres, nullptr);
      ASSERT_EQ(list.fur.size(), 2u);
      for (const bool split : {false, true}) {
        RendererOptions ro;
        ro.samples = 0;
        // Split: every binding at most 48 KiB, so outputs and root windows come in many pieces, and
        // dispatches of more than 8 groups become 2-D grids.
        if (split) {
          ro.gpuFur.maxBindingBytes = 48 * 1024;
          ro.gpuFur.maxGroupsPerDimension = 8;
        }
        Renderer renderer(ro);
        const RenderStats stats = renderer.render(list);
        EXPECT_EQ(stats.hairsDrawn, frame.drawnHairs[0] + frame.drawnHairs[1]);
        for (int c = 0; c < fur::kCoatCount; ++c) {
          SCOPED_TRACE(testing::Message()
                       << GetParam().name << " coat " << c << (culling ? " culled" : " all")
                       << (split ? " split" : "") << " " << scene::hairShadingName(shading));
          const fur::HairBuffers& cpu = frame.fur.coats[static_cast<std::size_t>(c)];
          const HairVertexBuffers& gpu = renderer.coatBuffers(c);
          if (split) {
            EXPECT_GT(gpu.chunks().size(), 2u);
          }
          ASSERT_EQ(gpu.drawnHairsOnGpu(), cpu.drawn);
          ASSERT_EQ(cpu.drawn, frame.drawnHairs[static_cast<std::size_t>(c)]);
          if (culling) {
            EXPECT_LT(cpu.drawn, fur.roots.coats[static_cast<std::size_t>(c)].size() / 2);
          }
          // Colours: the CPU frame's, exactly (the same packed words, culled or not).
          ASSERT_EQ(cpu.colors.size(), static_cast<std::size_t>(2 * cpu.drawn));
          std::vector<std::uint32_t> gc;
          gpu.readBackColors(gc);
          EXPECT_EQ(gc, cpu.colors);
          std::vector<float> gp, gs;
          gpu.readBack(gp, gs);
          const std::size_t floats =
              static_cast<std::size_t>(cpu.drawn * cpu.layout.pointsPerHair() * 3);
          ASSERT_EQ(gp.size(), floats);
          EXPECT_LT(maxRelativeError(gp, cpu.positions.data(), floats), 1e-4);
          // Also against each hair's own size: a 0.1% error in a 1 cm hair is far below 1e-4 of its
          // distance from the origin. (On llvmpipe the two paths agree bit for bit.)
          EXPECT_LT(
              maxHairRelativeError(gp, cpu.positions.data(), cpu.drawn, cpu.layout.pointsPerHair()),
              1e-4);
          if (shading == scene::HairShading::Paper) {
            EXPECT_LT(maxRelativeError(gs, cpu.normals.data(), floats), 1e-4);
          } else {
            std::vector<float> tangents;
            strandTangents(cpu.positions.data(), cpu.drawn, gpu.layout(), tangents);
            EXPECT_LT(maxRelativeError(gs, tangents.data(), floats), 1e-3);
          }
        }
      }
    }
  }
}

// Random parameters: 24 draws, each coat a random style with random stiffness, randomness,
// segment weight, length factor, curve points, tube sides, curl, a random length region and up
// vector (every other draw random clumps), with culling off and on. Every draw's GPU hairs (points
// and the style's shading normals) equal the CPU model's within 1e-4 of each hair's size; the
// number that agree bit for bit is reported (on llvmpipe, where both run IEEE single precision
// without contraction, all).
TEST_F(GpuFurRandom, EveryStyleWithRandomParametersMatchesTheCpuModel) {
  const scene::Model& model = critter();
  scene::FrameState frame;
  scene::evaluateFrame(model, bentPose(model.body), frame);
  std::mt19937 rng(20261123);
  auto uniform = [&](float lo, float hi) {
    return std::uniform_real_distribution<float>(lo, hi)(rng);
  };
  auto integer = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
  std::int64_t points = 0, exact = 0;
  std::array<int, fur::kHairStyleCount> styleDraws{};
  for (int draw = 0; draw < 24; ++draw) {
    fur::FurParams p = fur::loadFurPreset("default");
    p.setHairCount(2500);
    p.undercoatShare = uniform(0.2f, 0.8f);
    p.seed = static_cast<std::uint64_t>(integer(1, 1 << 30));
    p.lengthScale = uniform(0.5f, 2.0f);
    for (int c = 0; c < fur::kCoatCount; ++c) {
      fur::CoatParams& cp = p.coats[static_cast<std::size_t>(c)];
      // Every style at least 6 times over the draws and the two coats.
      cp.style = fur::kHairStyles[static_cast<std::size_t>((draw + c * 2) % fur::kHairStyleCount)];
      ++styleDraws[static_cast<std::size_t>(cp.style)];
      cp.stiffness = uniform(0.0f, 0.98f);  // (floppiness >= 0.02 without the clamp warning)
      cp.normalRandomize = integer(0, 1) ? uniform(0.0f, 1.0f) : 0.0f;
      cp.hairEndRandomize = integer(0, 1) ? uniform(0.0f, 2.0f) : 0.0f;
      cp.segmentDirectionWeight = uniform(0.0f, 1.0f);
      cp.lengthFactor = uniform(0.2f, 3.0f);
      cp.curvePoints = integer(2, 16);
      cp.tubeSides = integer(3, 9);
      cp.width.rootMm = uniform(0.02f, 2.0f);
      cp.width.tipMm = uniform(0.0f, 2.0f);
      cp.curlRadius = integer(0, 1) ? uniform(0.0f, 0.5f) : 0.0f;
      cp.curlTurns = uniform(0.0f, 6.0f);
      if (draw % 2 == 1)  // clumps on every other draw
        cp.clump = {.density = uniform(0.5f, 8.0f),
                    .strength = uniform(0.05f, 1.0f),
                    .shape = uniform(0.1f, 5.0f),
                    .radiusMm = uniform(3.0f, 40.0f)};
    }
    const int region = integer(0, 2);
    p.lengthRegion.shape = static_cast<fur::RegionShape>(region);
    p.lengthRegion.center = Eigen::Vector3f(uniform(-0.3f, 0.3f), 0.0f, uniform(0.2f, 0.5f));
    p.lengthRegion.radius = uniform(0.02f, 0.2f);
    p.lengthRegion.boxMin = p.lengthRegion.center - Eigen::Vector3f::Constant(0.1f);
    p.lengthRegion.boxMax = p.lengthRegion.center + Eigen::Vector3f::Constant(0.1f);
    p.lengthRegion.scale = uniform(0.0f, 3.0f);
    p.up = Eigen::Vector3f(uniform(-0.5f, 0.5f), uniform(-0.5f, 0.5f), 1.0f);
    p.culling.referenceDistance = 0.25f;
    for (const bool culling : {false, true}) {
      p.culling.enabled = culling;
      const scene::Fur fur = scene::growFur(model, p, "random parity draw");
      const scene::Framing framing =
          scene::framingOf(model, frame, scene::maxHairLength(model, fur.params));
      scene::Camera cam = scene::presetCamera(framing, scene::CameraPreset::ThreeQuarter, 64, 64);
      cam.eye = framing.center + (cam.eye - framing.center).normalized() * 0.75f;
      scene::evaluateFur(model, fur, cam, true, frame);
      if (culling) {
        ASSERT_GT(frame.cullFactor, 2.0f);
      }
      scene::DrawOptions opt;
      opt.hairSource = scene::HairSource::Gpu;
      scene::DrawList list;
      scene::buildDrawList(model, frame, &fur, cam, scene::Light{}, opt, list);
      RendererOptions ro;
      ro.samples = 0;
      Renderer renderer(ro);
      renderer.render(list);
      for (int c = 0; c < fur::kCoatCount; ++c) {
        const fur::HairBuffers& cpu = frame.fur.coats[static_cast<std::size_t>(c)];
        SCOPED_TRACE(testing::Message()
                     << "draw " << draw << " coat " << c << " " << fur::styleName(cpu.layout.style)
                     << (culling ? " culled" : " all"));
        const HairVertexBuffers& gpu = renderer.coatBuffers(c);
        if (cpu.drawn == 0) continue;
        ASSERT_EQ(gpu.drawnHairsOnGpu(), cpu.drawn);
        std::vector<float> gp, gs;
        gpu.readBack(gp, gs);
        const std::size_t floats =
            static_cast<std::size_t>(cpu.drawn * cpu.layout.pointsPerHair() * 3);
        ASSERT_EQ(gp.size(), floats);
        EXPECT_LT(
            maxHairRelativeError(gp, cpu.positions.data(), cpu.drawn, cpu.layout.pointsPerHair()),
            1e-4);
        EXPECT_LT(maxRelativeError(gs, cpu.normals.data(), floats), 1e-4);
        for (std::size_t i = 0; i < floats; i += 3) {
          ++points;
          exact += gp[i] == cpu.positions.data()[i] && gp[i + 1] == cpu.positions.data()[i + 1] &&
                   gp[i + 2] == cpu.positions.data()[i + 2] && gs[i] == cpu.normals.data()[i] &&
                   gs[i + 1] == cpu.normals.data()[i + 1] && gs[i + 2] == cpu.normals.data()[i + 2];
        }
      }
    }
  }
  for (int s = 0; s < fur::kHairStyleCount; ++s)
    EXPECT_GE(styleDraws[static_cast<std::size_t>(s)], 6);
  std::printf("GPU/CPU parity: %lld of %lld hair points (position and normal) bit-identical\n",
              static_cast<long long>(exact), static_cast<long long>(points));
  EXPECT_GT(points, 50000);
  // llvmpipe evaluates IEEE single precision without contraction, as the CPU kernels do: there the
  // GLSL mirror must agree operation for operation (a drift of one formula fails here).
  ContextInfo info;
  queryContextInfo(info);
  if (info.software) {
    EXPECT_EQ(exact, points);
  }
}

INSTANTIATE_TEST_SUITE_P(
    Styles, GpuFurParity,
    ::testing::Values(
        StyleCase{"line_polyline", fur::HairStyle::Line, fur::HairStyle::Polyline, 0.0f},
        StyleCase{"polyline_line", fur::HairStyle::Polyline, fur::HairStyle::Line, 0.0f},
        StyleCase{"curve_tube", fur::HairStyle::Curve, fur::HairStyle::Tube, 0.0f},
        StyleCase{"helical_tube_curve", fur::HairStyle::Tube, fur::HairStyle::Curve, 0.15f}),
    [](const ::testing::TestParamInfo<StyleCase>& i) { return i.param.name; });

}  // namespace
}  // namespace pelage::render
