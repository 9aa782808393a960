// The GL-free draw list between the scene and the renderer (as MuJoCo's mjv_updateScene builds an
// mjvScene that mjr_render draws): camera, light, the skin and one fur item per coat, background.
// The interactive viewer and headless export fill one (through the frame owner, playback.h) and
// hand it to the same renderer, so what a frame contains is unit-testable without OpenGL.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "pelage/fur/colors.h"
#include "pelage/fur/fur_params.h"
#include "pelage/fur/hair_layout.h"
#include "pelage/fur/roots.h"
#include "pelage/scene/camera.h"
#include "pelage/scene/light.h"
#include "pelage/scene/model.h"
#include "pelage/skin/deform.h"
#include "pelage/util/material.h"

namespace pelage::scene {

struct FrameState;
struct Fur;

// How hairs are lit: the paper's Phong model with each style's shading normals, Kajiya-Kay with
// the hair tangent, Marschner's three lobes (R, TT, TRT) about the tangent, or the physically based
// fur model calibrated against a path tracer's Chiang hair BSDF (the coat's multiple scattering
// about the style's normals, the fibre's lobes about the strand's tangent; lighting.glsl).
// The values are the renderer's shader codes.
enum class HairShading { Paper = 0, KajiyaKay = 1, Marschner = 2, Physical = 3 };
inline constexpr HairShading kHairShadings[] = {HairShading::Paper, HairShading::KajiyaKay,
                                                HairShading::Marschner, HairShading::Physical};
// The shading every frame gets unless asked otherwise: the physical model, the one measured
// closest to a path tracer (README, "Next to a path-traced reference").
inline constexpr HairShading kDefaultHairShading = HairShading::Physical;
// Whether `shading` lights hairs by their tangent (the renderer's shading vector) instead of the
// style's normals.
inline bool shadesWithTangents(HairShading shading) {
  return shading == HairShading::KajiyaKay || shading == HairShading::Marschner;
}
// "paper", "kajiya-kay", "marschner", "physical".
std::string_view hairShadingName(HairShading shading);
// Parses a shading name; InputError naming `field` and the accepted names.
HairShading parseHairShading(std::string_view name, std::string_view field = "shading");

// Which of the frame's light a frame shows, as a path tracer's light passes do (Cycles' Glossy and
// Diffuse passes): everything, the hairs' light alone, or one of its parts under the physical
// model (the light its fibres scatter themselves, lighting.glsl's fibre part, or the coat's light
// scattered many times: its ambient, kept and spread direct light and grazing ambient), or the
// skin's alone. Every pass draws the same coverage (hairs and skin hide what they always hide; the
// hairs of the skin's pass are black), so in linear light, premultiplied by alpha, the passes add
// up: all = hair + skin, and under the physical model hair = fibre + coat. Under the other
// shadings the hairs' light has no such parts: fibre draws them black and coat as hair.
enum class LightPass { All = 0, Hair = 1, Fibre = 2, Coat = 3, Skin = 4 };
// Whether `pass` shows the coat's light (the physical model's coat part, and the resolve's spread
// light and grazing ambient with it; under the other shadings the hairs' whole light), as
// lighting.glsl's coatShown.
inline bool showsCoatLight(LightPass pass) {
  return pass == LightPass::All || pass == LightPass::Hair || pass == LightPass::Coat;
}
// "all", "hair", "fibre", "coat", "skin".
std::string_view lightPassName(LightPass pass);
// Parses a pass name; InputError naming `field` and the accepted names.
LightPass parseLightPass(std::string_view name, std::string_view field = "pass");

// How 1-D hairs (lines, polylines, curves) are drawn: as the paper's 1-pixel lines (sec. 3.3), or
// as strands of their physical width (fur::StrandWidth, tapering root to tip): a strand narrower
// than a pixel is drawn one pixel wide with its coverage (true width / drawn width) as alpha, with
// anti-aliased edges, and a culled coat's hairs are widened by c (sec. 3.3's factor) so that the
// coat covers the same area with fewer hairs (the LOD rule of AMD TressFX). Tubes are geometry.
enum class HairWidth { Lines, Strands };

// Where a coat's hairs come from: buffers the CPU fur model wrote this frame, or the GPU, which
// regenerates them from the roots and the deformed skin (render/gpu_fur.h).
enum class HairSource { Cpu, Gpu };
// "cpu", "gpu".
std::string_view hairSourceName(HairSource source);
// Parses a hair source name; InputError naming `field` and the accepted names.
HairSource parseHairSource(std::string_view name, std::string_view field = "hair source");

// The skin: the deformed arrays of the frame (non-owning; they live in the FrameState).
struct SkinDrawItem {
  // The skin's material; with `appearance` its diffuse and ambient are the surface's own colour
  // at each point (the materials' base colour x texture x vertex colour, skin/skin_mesh.h).
  Material material;
  const skin::SkinMesh* appearance = nullptr;
  const std::vector<Eigen::Vector3f>* positions = nullptr;  // nV
  const std::vector<Eigen::Vector3f>* normals = nullptr;    // nV
  const std::vector<std::int32_t>* triangles = nullptr;     // nT x 3
  int vertices = 0;
  int triangleCount = 0;
};

// One coat (paper sec. 3.1). Non-owning pointers into the scene; valid for the frame.
struct FurDrawItem {
  int coat = 0;            // fur::kOvercoat or fur::kUndercoat
  fur::HairLayout layout;  // the coat's style's points and topology (fur/hair_layout.h)
  // The coat's material; its diffuse and ambient are the hairs' colour when they share one (tinted,
  // fur/colors.h). With per-hair colours each hair's diffuse is its colour, graded root to tip,
  // and its ambient that colour times ambientRatio.
  Material material;
  bool perHairColor = false;
  // With per-hair colours: each hair's packed pair also holds its width scale (fur/colors.h
  // packHairWidth; a groom's), by which its strand is drawn wider or narrower than `width`.
  bool perHairWidth = false;
  float ambientRatio = 0.0f;
  const std::uint32_t* colors =
      nullptr;                  // CPU source, per-hair colours: drawnHairs x 2 (root, tip)
  std::int64_t rootCount = 0;   // hairs grown on the skin
  std::int64_t drawnHairs = 0;  // after distance culling (sec. 3.3)
  float cullFactor = 1.0f;      // c of sec. 3.3 (1 = all hairs)
  fur::StrandWidth width;       // the coat's hair width (strands)
  HairSource source = HairSource::Cpu;
  // CPU source: drawnHairs * P * 3 floats each (P = layout.pointsPerHair()).
  const float* positions = nullptr;
  const float* normals = nullptr;

  int pointsPerHair() const { return layout.pointsPerHair(); }
};

// What the GPU hair source reads (shared by the coats; not owned).
struct GpuFurInputs {
  const fur::FurParams* params = nullptr;
  const fur::FurRoots* roots = nullptr;
  std::uint64_t rootsGeneration = 0;
  const fur::FurColors* colors = nullptr;  // each root's colours (copied per drawn hair on the GPU)
  std::uint64_t colorGeneration = 0;
  const skin::SkinMesh* skin = nullptr;
  const skin::DeformedSkin* deformed = nullptr;
  // When a coat clumps: this frame's strand points of its clump centres (fur::FurWorkspace::
  // clumpCentres, from evaluateFur); null otherwise.
  const std::array<std::vector<float>, fur::kCoatCount>* clumpCentres = nullptr;
};

// The background colour of every frame (linear RGB; sRGB 0.80, 0.82, 0.86: a pale blue-grey).
inline const Eigen::Vector3f kDefaultBackground{0.604f, 0.637f, 0.708f};

// Everything one frame draws.
struct DrawList {
  Camera camera;
  Light light;
  Eigen::Vector3f background = kDefaultBackground;
  SkinDrawItem skin;
  std::vector<FurDrawItem> fur;  // 0, 1 or 2 coats
  HairShading hairShading = kDefaultHairShading;
  LightPass lightPass = LightPass::All;
  HairWidth hairWidth = HairWidth::Strands;
  // Strands blended in any order (weighted blended order-independent transparency); off: drawn
  // opaque at their drawn width.
  bool transparency = true;
  Eigen::AlignedBox3f bounds;  // everything drawn (fits the shadow map)
  float hairLength = 0.0f;     // the longest hair, metres (the depth scale of the fur's shadow)
  GpuFurInputs gpuFur;         // for fur items with HairSource::Gpu

  std::int64_t drawnHairs() const;
};

// How a frame is drawn (the draw list's look).
struct DrawOptions {
  HairSource hairSource = HairSource::Cpu;
  HairShading hairShading = kDefaultHairShading;
  LightPass lightPass = LightPass::All;
  HairWidth hairWidth = HairWidth::Strands;
  bool transparency = true;
  bool drawFur = true;
  bool drawSkin = true;
  Eigen::Vector3f background = kDefaultBackground;
};

// Fills `list` for one evaluated frame: skin item from the frame's deformed skin drawn in the
// model's own colours (its appearance when it has materials, textures or vertex colours, else
// skinMaterial(model.skin.color)), one fur item per coat with roots (when `fur` is given and
// options.drawFur), camera and light as given. With the CPU source the fur items point at the
// frame's hair buffers (evaluateFur must have run with cpuHairs); with the GPU source, at the roots
// and parameters in `fur`.
void buildDrawList(const Model& model, const FrameState& frame, const Fur* fur,
                   const Camera& camera, const Light& light, const DrawOptions& options,
                   DrawList& list);
// The same with the skin drawn in one material (a colour the user chose) instead of the model's
// own colours.
void buildDrawList(const Model& model, const FrameState& frame, const Fur* fur,
                   const Camera& camera, const Light& light, const DrawOptions& options,
                   const Material& skinMaterial, DrawList& list);

}  // namespace pelage::scene
