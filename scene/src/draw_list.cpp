#include "pelage/scene/draw_list.h"

#include "pelage/scene/frame.h"
#include "pelage/util/color.h"
#include "pelage/util/enum_names.h"
#include "pelage/util/error.h"

namespace pelage::scene {

namespace {

constexpr auto kHairShadingNames =
    makeEnumNames<HairShading>({{HairShading::Paper, "paper"},
                                {HairShading::KajiyaKay, "kajiya-kay"},
                                {HairShading::Marschner, "marschner"},
                                {HairShading::Physical, "physical"}});
constexpr auto kLightPassNames = makeEnumNames<LightPass>({{LightPass::All, "all"},
                                                           {LightPass::Hair, "hair"},
                                                           {LightPass::Fibre, "fibre"},
                                                           {LightPass::Coat, "coat"},
                                                           {LightPass::Skin, "skin"}});
constexpr auto kHairSourceNames =
    makeEnumNames<HairSource>({{HairSource::Gpu, "gpu"}, {HairSource::Cpu, "cpu"}});

}  // namespace

std::string_view hairShadingName(HairShading shading) {
  return kHairShadingNames.name(shading);
}

HairShading parseHairShading(std::string_view name, std::string_view field) {
  if (const auto s = kHairShadingNames.find(name)) return *s;
  fieldError(std::string(field), ": unknown hair shading '", excerpt(name),
             "' (accepted: ", kHairShadingNames.list(), ")");
}

std::string_view lightPassName(LightPass pass) {
  return kLightPassNames.name(pass);
}

LightPass parseLightPass(std::string_view name, std::string_view field) {
  if (const auto s = kLightPassNames.find(name)) return *s;
  fieldError(std::string(field), ": unknown light pass '", excerpt(name),
             "' (accepted: ", kLightPassNames.list(), ")");
}

std::string_view hairSourceName(HairSource source) {
  return kHairSourceNames.name(source);
}

HairSource parseHairSource(std::string_view name, std::string_view field) {
  if (const auto s = kHairSourceNames.find(name)) return *s;
  fieldError(std::string(field), "'", excerpt(name), "' (accepted: ", kHairSourceNames.list(), ")");
}

std::int64_t DrawList::drawnHairs() const {
  std::int64_t n = 0;
  for (const FurDrawItem& f : fur) n += f.drawnHairs;
  return n;
}

void buildDrawList(const Model& model, const FrameState& frame, const Fur* fur,
                   const Camera& camera, const Light& light, const DrawOptions& options,
                   DrawList& list) {
  buildDrawList(model, frame, fur, camera, light, options, skinMaterial(model.skin.color), list);
  if (list.skin.positions && (model.skin.hasSurfaceColor() || model.skin.hasUv()))
    list.skin.appearance = &model.skin;
}

void buildDrawList(const Model& model, const FrameState& frame, const Fur* fur,
                   const Camera& camera, const Light& light, const DrawOptions& options,
                   const Material& skin, DrawList& list) {
  list.camera = camera;
  list.light = light;
  list.background = options.background;
  list.hairShading = options.hairShading;
  list.lightPass = options.lightPass;
  list.hairWidth = options.hairWidth;
  list.transparency = options.transparency;
  list.bounds = frame.skinBounds;
  list.hairLength = 0.0f;
  list.skin = SkinDrawItem{};
  if (options.drawSkin) {
    list.skin.material = skin;
    list.skin.positions = &frame.skin.positions;
    list.skin.normals = &frame.skin.normals;
    list.skin.triangles = &model.skin.triangles;
    list.skin.vertices = model.skin.numVertices();
    list.skin.triangleCount = model.skin.numTriangles();
  }
  list.fur.clear();
  list.gpuFur = GpuFurInputs{};
  if (!fur || !options.drawFur) return;
  const bool cpu = options.hairSource == HairSource::Cpu;
  PELAGE_CHECK(!cpu || frame.cpuFur, "CPU hair source without evaluateFur(..., cpuHairs = true)");
  if (!cpu) {
    list.gpuFur = GpuFurInputs{&fur->params,         &fur->roots, fur->generation, &fur->colors,
                               fur->colorGeneration, &model.skin, &frame.skin};
    if (fur::clumps(fur->params)) list.gpuFur.clumpCentres = &frame.furWorkspace.clumpCentres;
  }
  const float pad = maxHairLength(model, fur->params);
  list.hairLength = pad;
  list.bounds.extend(frame.skinBounds.min() - Eigen::Vector3f::Constant(pad));
  list.bounds.extend(frame.skinBounds.max() + Eigen::Vector3f::Constant(pad));
  for (int c = 0; c < fur::kCoatCount; ++c) {
    const auto ci = static_cast<std::size_t>(c);
    const std::int64_t roots = fur->roots.coats[ci].size();
    if (roots == 0) continue;
    const fur::CoatParams& cp = fur->params.coats[ci];
    FurDrawItem item;
    item.coat = c;
    item.layout = fur::coatLayout(fur->params, fur->roots, c);
    const fur::CoatColors& colors = fur->colors.coats[ci];
    item.material = linearMaterial(cp.material);
    item.perHairColor = colors.perHair;
    item.perHairWidth = colors.perHairWidth;
    item.ambientRatio = colors.ambientRatio;
    if (!colors.perHair) {
      item.material.diffuse = colors.diffuse;
      item.material.ambient = colors.ambient;
    }
    item.rootCount = roots;
    item.drawnHairs = frame.drawnHairs[ci];
    item.cullFactor = frame.cullFactor;
    item.width = cp.width;
    item.source = options.hairSource;
    if (cpu) {
      const fur::HairBuffers& hb = frame.fur.coats[ci];
      PELAGE_CHECK(hb.layout == item.layout, "CPU hairs of coat ", c, " have ",
                   hb.layout.pointsPerHair(), " points, the parameters ", item.pointsPerHair());
      item.positions = hb.positions.data();
      item.normals = hb.normals.data();
      if (colors.perHair) {
        PELAGE_CHECK(hb.colors.size() == static_cast<std::size_t>(2 * hb.drawn), "coat ", c,
                     " has per-hair colours but the frame's are not filled");
        item.colors = hb.colors.data();
      }
    }
    list.fur.push_back(item);
  }
}

}  // namespace pelage::scene
