#include "pelage/scene/frame.h"

#include <algorithm>
#include <atomic>

#include "pelage/animation/clip.h"
#include "pelage/fur/coverage.h"
#include "pelage/util/error.h"

namespace pelage::scene {

namespace {
std::uint64_t nextGeneration() {
  static std::atomic<std::uint64_t> next{1};
  return next.fetch_add(1);
}
}  // namespace

namespace {
Fur growOn(const Model& model, fur::FurParams params, const fur::VertexGroom* vertex,
           const std::string& source) {
  fur::validateFurParams(params, source);
  Fur f;
  f.groom = fur::loadGroomMaps(params.maps, model.skin, model.name);
  f.groom.vertex =
      vertex ? *vertex
             : fur::resolveVertexGroom(model.skin, model.body, model.name, params, source);
  params = fur::fitCoverageToBudget(model.skin, std::move(params),
                                    fur::groomedLengths(model.skin, f.groom.vertex));
  f.roots = fur::growRoots(model.skin, params, f.groom);
  f.colors = fur::colorRoots(model.skin, f.roots, params, f.groom);
  f.params = std::move(params);
  f.generation = nextGeneration();
  f.colorGeneration = nextGeneration();
  return f;
}
}  // namespace

Fur growFur(const Model& model, fur::FurParams params, const std::string& source) {
  return growOn(model, std::move(params), nullptr, source);
}

Fur growFur(const Model& model, fur::FurParams params, fur::VertexGroom vertex,
            const std::string& source) {
  return growOn(model, std::move(params), &vertex, source);
}

void recolorFur(const Model& model, Fur& fur, fur::FurParams params, const std::string& source) {
  fur::validateFurParams(params, source);
  PELAGE_CHECK(!rootsDiffer(fur.params, params), "recolorFur with parameters that need new roots");
  if (params.maps.color != fur.params.maps.color) {
    fur::GroomMapPaths colorOnly;
    colorOnly.color = params.maps.color;
    fur.groom.color = fur::loadGroomMaps(colorOnly, model.skin, model.name).color;
  }
  fur.colors = fur::colorRoots(model.skin, fur.roots, params, fur.groom);
  fur.params = std::move(params);
  fur.colorGeneration = nextGeneration();
}

namespace {
// The clump assignment (fur::assignClumps) depends on each coat's clump density and radius, and
// on whether it clumps at all.
bool clumpRootsDiffer(const fur::FurParams& a, const fur::FurParams& b) {
  for (int c = 0; c < fur::kCoatCount; ++c) {
    const fur::Clump& x = a.coats[static_cast<std::size_t>(c)].clump;
    const fur::Clump& y = b.coats[static_cast<std::size_t>(c)].clump;
    if (x.on() != y.on() || (x.on() && (x.density != y.density || x.radiusMm != y.radiusMm)))
      return true;
  }
  return false;
}

// A region's stiffness, segment direction weight, curl or colour source blends from the coats' own
// into the per-vertex values the roots' floppiness, w and helix, and the hairs' colours, are
// interpolated from (fur::groomFromRegions).
bool regionCoatValuesDiffer(const fur::FurParams& a, const fur::FurParams& b) {
  const auto anyRegion = [&](auto field) {
    for (const fur::FurParams* p : {&a, &b})
      for (const fur::FurRegion& r : p->regions)
        if (r.*field) return true;
    return false;
  };
  const auto coatsDiffer = [&](auto field) {
    for (int c = 0; c < fur::kCoatCount; ++c)
      if (a.coats[static_cast<std::size_t>(c)].*field !=
          b.coats[static_cast<std::size_t>(c)].*field)
        return true;
    return false;
  };
  // A region's curl radius or turns alone keeps the coats' other value per root too.
  const bool curlRegions =
      anyRegion(&fur::FurRegion::curlRadius) || anyRegion(&fur::FurRegion::curlTurns);
  return (anyRegion(&fur::FurRegion::stiffness) && coatsDiffer(&fur::CoatParams::stiffness)) ||
         (anyRegion(&fur::FurRegion::segmentDirectionWeight) &&
          coatsDiffer(&fur::CoatParams::segmentDirectionWeight)) ||
         (curlRegions && (coatsDiffer(&fur::CoatParams::curlRadius) ||
                          coatsDiffer(&fur::CoatParams::curlTurns))) ||
         (anyRegion(&fur::FurRegion::colorSource) &&
          (a.coats[0].color.source != b.coats[0].color.source ||
           a.coats[1].color.source != b.coats[1].color.source));
}
}  // namespace

bool rootsDiffer(const fur::FurParams& a, const fur::FurParams& b) {
  return a.hairs != b.hairs || a.densityPerM2 != b.densityPerM2 || a.coverage != b.coverage ||
         a.undercoatShare != b.undercoatShare || a.seed != b.seed ||
         a.maps.density != b.maps.density || a.maps.length != b.maps.length ||
         a.regions != b.regions || a.groom != b.groom || clumpRootsDiffer(a, b) ||
         regionCoatValuesDiffer(a, b);
}

bool colorsDiffer(const fur::FurParams& a, const fur::FurParams& b) {
  if (a.maps.color != b.maps.color) return true;
  for (int c = 0; c < fur::kCoatCount; ++c) {
    const fur::CoatParams& x = a.coats[static_cast<std::size_t>(c)];
    const fur::CoatParams& y = b.coats[static_cast<std::size_t>(c)];
    const fur::CoatColor &p = x.color, &q = y.color;
    if (p.source != q.source || p.tint != q.tint || p.tipLightness != q.tipLightness ||
        p.hasTipColor != q.hasTipColor || p.tipColor != q.tipColor ||
        p.hueVariation != q.hueVariation || p.valueVariation != q.valueVariation ||
        x.material.diffuse != y.material.diffuse || x.material.ambient != y.material.ambient)
      return true;
  }
  return false;
}

float maxHairLength(const Model& model, const fur::FurParams& params) {
  const float* len = model.skin.furLengths();
  float longest = 0.0f;
  for (int v = 0; v < model.skin.numVertices(); ++v) longest = std::max(longest, len[v]);
  float factor = 0.0f;
  for (const fur::CoatParams& c : params.coats) factor = std::max(factor, c.lengthFactor);
  const float region = params.lengthRegion.shape == fur::LengthRegion::Shape::None
                           ? 1.0f
                           : std::max(params.lengthRegion.scale, 1.0f);
  // The regions' lengths, bounded: each may set a length and scale it.
  for (const fur::FurRegion& g : params.regions)
    longest = std::max(longest, std::max(longest, 1e-3f * g.lengthMm) * g.lengthScale);
  return longest * params.lengthScale * factor * region;
}

void evaluateFrame(const Model& model, const anatomy::Pose& pose, FrameState& frame) {
  PELAGE_CHECK(static_cast<int>(pose.local.size()) == model.body.size(), "pose has ",
               pose.local.size(), " segments, body ", model.body.size());
  if (&frame.pose != &pose) frame.pose.local.assign(pose.local.begin(), pose.local.end());
  anatomy::forwardKinematics(model.body, frame.pose, frame.body);
  skin::deformSkin(model.skin, frame.body, frame.skin);
  frame.skinBounds.setEmpty();
  for (const Eigen::Vector3f& p : frame.skin.positions) frame.skinBounds.extend(p);
  frame.cpuFur = false;
  frame.drawnHairs = {0, 0};
}

void evaluateClipFrame(const Model& model, int clip, double seconds, FrameState& frame) {
  PELAGE_CHECK(clip >= 0 && clip < static_cast<int>(model.clips.size()), "clip ", clip, " of ",
               model.clips.size());
  animation::sampleClip(model.clips[static_cast<std::size_t>(clip)], model.body, seconds,
                        frame.pose);
  evaluateFrame(model, frame.pose, frame);
}

void evaluateFur(const Model& model, const Fur& fur, const Camera& camera, bool cpuHairs,
                 FrameState& frame) {
  PELAGE_CHECK(frame.skin.positions.size() == static_cast<std::size_t>(model.skin.numVertices()),
               "evaluateFur before evaluateFrame");
  evaluateFur(model, fur, fur::makeFurView(fur.params, frame.skin, viewCamera(camera)), cpuHairs,
              frame);
}

void evaluateFur(const Model& model, const Fur& fur, const fur::FurView& view, bool cpuHairs,
                 FrameState& frame) {
  PELAGE_CHECK(frame.skin.positions.size() == static_cast<std::size_t>(model.skin.numVertices()),
               "evaluateFur before evaluateFrame");
  frame.furView = view;
  frame.cullFactor = fur::cullingFactor(frame.furView);
  if (cpuHairs) {
    // Van Gelder & Wilhelms 1997, sec. 3.2 to 3.8 on the CPU (fur::generateFur).
    fur::generateFur(model.skin, fur.roots, fur.params, frame.skin, frame.furView,
                     frame.furWorkspace, frame.fur);
    fur::fillHairColors(fur.colors, frame.fur);
    for (int c = 0; c < fur::kCoatCount; ++c)
      frame.drawnHairs[static_cast<std::size_t>(c)] =
          frame.fur.coats[static_cast<std::size_t>(c)].drawn;
    frame.cpuFur = true;
    return;
  }
  // Only the counts (sec. 3.3's rule, as the GPU applies it) and, for a coat that clumps, its clump
  // centres' strand points, which the GPU's clumped hairs move toward.
  if (fur::clumps(fur.params))
    fur::generateClumpCentres(model.skin, fur.roots, fur.params, frame.skin, frame.furWorkspace);
  for (int c = 0; c < fur::kCoatCount; ++c) {
    const auto ci = static_cast<std::size_t>(c);
    const fur::CoatRoots& cr = fur.roots.coats[ci];
    frame.drawnHairs[ci] =
        frame.cullFactor > 1.0f
            ? fur::computeDrawnStart(cr, fur::coatSeed(fur.roots.seed, c), frame.cullFactor,
                                     frame.drawnStartScratch[ci])
            : cr.size();
  }
  frame.cpuFur = false;
}

}  // namespace pelage::scene
