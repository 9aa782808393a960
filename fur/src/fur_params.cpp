#include "pelage/fur/fur_params.h"

#include <array>
#include <cmath>
#include <limits>
#include <utility>

#include "pelage/fur/roots.h"
#include "pelage/util/enum_names.h"
#include "pelage/util/error.h"
#include "pelage/util/log.h"

namespace pelage::fur {
namespace {

void checkRange(const std::string& source, const std::string& field, double v, double lo,
                double hi) {
  if (!std::isfinite(v) || v < lo || v > hi)
    inputError(source, ": ", field, " = ", v, " is out of range [", lo, ", ", hi, "]");
}

void checkColor(const std::string& source, const std::string& field, const Eigen::Vector3f& c) {
  for (int k = 0; k < 3; ++k) checkRange(source, str(field, "[", k, "]"), c[k], 0.0, 1.0);
}

constexpr auto kColorSources = makeEnumNames<ColorSource>({{ColorSource::Material, "material"},
                                                           {ColorSource::Creature, "creature"},
                                                           {ColorSource::Texture, "texture"},
                                                           {ColorSource::Vertex, "vertex"},
                                                           {ColorSource::Map, "map"}});

void checkCoat(const std::string& source, const std::string& name, const CoatParams& c) {
  checkRange(source, name + ".stiffness", c.stiffness, 0.0, 1.0);
  checkRange(source, name + ".normalRandomize", c.normalRandomize, 0.0, 1.0);
  checkRange(source, name + ".hairEndRandomize", c.hairEndRandomize, 0.0, 2.0);
  checkRange(source, name + ".segmentDirectionWeight", c.segmentDirectionWeight, 0.0, 1.0);
  checkRange(source, name + ".relativeLength", c.lengthFactor, 0.0, 10.0);
  checkRange(source, name + ".curvePoints", c.curvePoints, 2, 64);
  checkRange(source, name + ".tubeSides", c.tubeSides, 3, 32);
  checkRange(source, name + ".width.root", c.width.rootMm, 0.001, 20.0);
  checkRange(source, name + ".width.tip", c.width.tipMm, 0.0, 20.0);
  checkRange(source, name + ".curl.radius", c.curlRadius, 0.0, kMaxCurlRadius);
  checkRange(source, name + ".curl.turns", c.curlTurns, 0.0, kMaxCurlTurns);
  checkRange(source, name + ".frizz.amplitude", c.frizz.amplitudeMm, 0.0, 100.0);
  checkRange(source, name + ".frizz.frequency", c.frizz.frequency, 0.1, 64.0);
  checkRange(source, name + ".frizz.tipWeight", c.frizz.tipWeight, 1.0, 8.0);
  checkRange(source, name + ".clump.density", c.clump.density, 0.0, 100.0);
  checkRange(source, name + ".clump.strength", c.clump.strength, 0.0, 1.0);
  checkRange(source, name + ".clump.shape", c.clump.shape, 0.1, 10.0);
  checkRange(source, name + ".clump.radius", c.clump.radiusMm, 0.1, 1000.0);
  checkColor(source, name + ".ambient", c.material.ambient);
  checkColor(source, name + ".diffuse", c.material.diffuse);
  checkColor(source, name + ".specular", c.material.specular);
  checkRange(source, name + ".shininess", c.material.shininess, 1.0, 1000.0);
  for (int k = 0; k < 3; ++k)
    checkRange(source, str(name, ".color.tint[", k, "]"), c.color.tint[k], 0.0, 10.0);
  checkRange(source, name + ".color.tipLightness", c.color.tipLightness, 0.0, 10.0);
  checkColor(source, name + ".color.tipColor", c.color.tipColor);
  checkRange(source, name + ".color.hueVariation", c.color.hueVariation, 0.0, 180.0);
  checkRange(source, name + ".color.valueVariation", c.color.valueVariation, 0.0, 1.0);
}

}  // namespace

std::string_view colorSourceName(ColorSource source) {
  return kColorSources.name(source);
}

std::string colorSourceNames() {
  return kColorSources.list();
}

std::optional<ColorSource> findColorSource(std::string_view name) {
  return kColorSources.find(name);
}

ColorSource parseColorSource(std::string_view name, const std::string& where) {
  if (const auto s = findColorSource(name)) return *s;
  inputError(where, ": unknown colour source '", excerpt(name), "' (accepted: ", colorSourceNames(),
             ")");
}

void validateFurParams(FurParams& p, const std::string& source) {
  checkRange(source, "hairs", p.hairs, 0.0, std::numeric_limits<double>::max());
  checkRange(source, "density", p.densityPerM2, 0.0, 1e10);
  checkRange(source, "coverage", p.coverage, 0.0, kMaxCoverage);
  checkRange(source, "undercoatShare", p.undercoatShare, 0.0, 1.0);
  checkRange(source, "lengthScale", p.lengthScale, 0.0, 10.0);
  checkCoat(source, "overcoat", p.coats[kOvercoat]);
  checkCoat(source, "undercoat", p.coats[kUndercoat]);
  const LengthRegion& r = p.lengthRegion;
  checkRange(source, "lengthRegion.scale", r.scale, 0.0, 10.0);
  for (int k = 0; k < 3; ++k) {
    checkRange(source, str("lengthRegion.center[", k, "]"), r.center[k], -1e4, 1e4);
    checkRange(source, str("lengthRegion.min[", k, "]"), r.boxMin[k], -1e4, 1e4);
    checkRange(source, str("lengthRegion.max[", k, "]"), r.boxMax[k], -1e4, 1e4);
  }
  if (r.shape == RegionShape::Sphere)
    checkRange(source, "lengthRegion.radius", r.radius, 1e-6, 1e4);
  if (r.shape == RegionShape::Box)
    for (int k = 0; k < 3; ++k)
      if (r.boxMin[k] > r.boxMax[k])
        inputError(source, ": lengthRegion.min[", k, "] = ", r.boxMin[k],
                   " exceeds lengthRegion.max[", k, "] = ", r.boxMax[k],
                   " (a box needs min <= max)");
  if (p.regions.size() > kMaxFurRegions)
    inputError(source, ": regions has ", p.regions.size(), " entries; accepted: at most ",
               kMaxFurRegions);
  for (std::size_t i = 0; i < p.regions.size(); ++i) {
    const FurRegion& g = p.regions[i];
    const std::string at = str("regions[", i, "].");
    if (g.match.empty())
      inputError(source, ": ", at,
                 "match is empty (a region, material or joint name; '*' "
                 "wildcards)");
    checkRange(source, at + "lengthScale", g.lengthScale, 0.0, 10.0);
    checkRange(source, at + "lengthMm", g.lengthMm, 0.0, 10000.0);
    checkRange(source, at + "densityScale", g.densityScale, 0.0, 100.0);
    for (int k = 0; k < 3; ++k) checkRange(source, str(at, "tint[", k, "]"), g.tint[k], 0.0, 10.0);
    const auto checkPair = [&](const std::optional<Eigen::Vector2f>& v, const char* field,
                               double hi) {
      if (v)
        for (int k = 0; k < 2; ++k)
          checkRange(source, str(at, field, "[", k, "]"), (*v)[k], 0.0, hi);
    };
    checkPair(g.stiffness, "stiffness", 1.0);
    checkPair(g.segmentDirectionWeight, "segmentDirectionWeight", 1.0);
    checkPair(g.curlRadius, "curl.radius", kMaxCurlRadius);
    checkPair(g.curlTurns, "curl.turns", kMaxCurlTurns);
    checkPair(g.widthScale, "widthScale", kMaxWidthScale);
  }
  for (int k = 0; k < 3; ++k) checkRange(source, str("up[", k, "]"), p.up[k], -1e6, 1e6);
  const float upLength = p.up.norm();
  if (!(upLength > 1e-6f))
    inputError(source,
               ": up = (0, 0, 0) has no direction (give a non-zero vector, e.g. [0, 0, 1])");
  p.up /= upLength;
  checkRange(source, "culling.referenceDistance", p.culling.referenceDistance, 0.0, 1e4);
  checkRange(source, "culling.fovDegrees", p.culling.fovYDegrees, 1.0, 179.0);
  checkRange(source, "culling.referenceHeight", p.culling.referenceHeight, 16, 16384);
  // A total above kMaxHairs is refused with the memory it would need (a density is checked when
  // the roots are grown, against the skin's area).
  if (p.densityPerM2 == 0.0 && p.coverage == 0.0) checkHairBudget(p, 0.0);
  for (int c = 0; c < kCoatCount; ++c) {
    const float s = p.coats[static_cast<std::size_t>(c)].stiffness;
    if (1.0f - s < 0.02f)
      warn(str(source, ": ", c == 0 ? "overcoat" : "undercoat", ".stiffness ", s,
               " would make floppiness ", 1.0f - s,
               " < 0.02; using floppiness 0.02 (the paper, sec. 3.7: "
               "\"floppiness is required to be at least .02\")"));
  }
}

}  // namespace pelage::fur
