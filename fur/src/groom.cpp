#include "pelage/fur/groom.h"

#include <algorithm>
#include <optional>

#include "pelage/util/error.h"
#include "pelage/util/image.h"
#include "pelage/util/path.h"

namespace pelage::fur {
namespace {

skin::Texture loadMap(const std::string& path, const char* field, bool srgb, skin::Filter filter) {
  if (path.empty()) return {};
  try {
    skin::Texture t = skin::makeTexture(readImageFile(path), path, srgb);
    t.filter = filter;
    return t;
  } catch (const MissingFileError& e) {
    throw MissingFileError(field, std::string(": ") + e.what());
  } catch (const InputError& e) {
    fieldError(field, ": ", e.what());
  }
}

// "a, b, c" of at most `most` names, then "... (n in all)".
std::string nameList(const std::vector<std::string>& names, std::size_t most) {
  std::string s;
  for (std::size_t i = 0; i < names.size() && i < most; ++i) s += (i ? ", " : "") + names[i];
  if (names.size() > most) s += str(", ... (", names.size(), " in all)");
  return s.empty() ? "none" : s;
}

}  // namespace

Groom loadGroomMaps(const GroomMapPaths& paths, const skin::SkinMesh& skin,
                    const std::string& modelName) {
  Groom m;
  if (!paths.any()) return m;
  if (!skin.hasUv()) {
    const char* field = !paths.density.empty()  ? "maps.density"
                        : !paths.length.empty() ? "maps.length"
                                                : "maps.color";
    fieldError(
        field, ": model '", modelName,
        "' has no texture coordinates, so groom maps cannot be placed on it (they need a "
        "glTF model with TEXCOORD_0); groom it by regions instead (a preset's \"regions\": "
        "lengthScale, lengthMm, densityScale, tint, stiffness, segmentDirectionWeight, curl, "
        "widthScale, colorSource per region or joint)");
  }
  m.density = loadMap(paths.density, "maps.density", false, skin::Filter::Nearest);
  m.length = loadMap(paths.length, "maps.length", false, skin::Filter::Linear);
  m.color = loadMap(paths.color, "maps.color", true, skin::Filter::Linear);
  return m;
}

std::vector<float> regionWeights(const skin::SkinMesh& skin, const anatomy::Body& body,
                                 const std::string& pattern, RegionMatch* match) {
  const int nV = skin.numVertices();
  std::vector<char> region(skin.regionNames.size(), 0);
  std::vector<char> joint(static_cast<std::size_t>(body.size()), 0);
  RegionMatch m;
  m.pattern = pattern;
  for (std::size_t r = 0; r < skin.regionNames.size(); ++r)
    if (globMatches(pattern, skin.regionNames[r])) {
      region[r] = 1;
      m.regions.push_back(skin.regionNames[r]);
    }
  for (int s = 0; s < body.size(); ++s)
    if (globMatches(pattern, body.segments[static_cast<std::size_t>(s)].name)) {
      joint[static_cast<std::size_t>(s)] = 1;
      m.joints.push_back(body.segments[static_cast<std::size_t>(s)].name);
    }
  std::vector<float> w(static_cast<std::size_t>(nV), 0.0f);
  const std::int32_t* regionOf = skin.regions();
  const skin::Binding* bind = skin.bindings();
  for (int v = 0; v < nV; ++v) {
    const auto r = static_cast<std::size_t>(regionOf[v]);
    float jointWeight = 0.0f;
    for (std::size_t k = 0; k < 4; ++k) {
      const auto s = static_cast<std::size_t>(bind[v].segment[k]);
      if (bind[v].weight[k] > 0.0f && s < joint.size() && joint[s])
        jointWeight += bind[v].weight[k];
    }
    const float fromRegion = r < region.size() && region[r] ? 1.0f : 0.0f;
    w[static_cast<std::size_t>(v)] = std::max(fromRegion, std::min(jointWeight, 1.0f));
    if (w[static_cast<std::size_t>(v)] > 0.0f) ++m.vertices;
  }
  if (match) *match = std::move(m);
  return w;
}

VertexGroom groomFromRegions(const skin::SkinMesh& skin, const anatomy::Body& body,
                             const FurParams& params, const std::string& source,
                             std::vector<RegionMatch>* matches, VertexGroom start) {
  VertexGroom g = std::move(start);
  if (matches) matches->clear();
  if (params.regions.empty()) return g;
  const auto nV = static_cast<std::size_t>(skin.numVertices());
  const float* skinLength = skin.furLengths();
  for (std::size_t i = 0; i < params.regions.size(); ++i) {
    const FurRegion& reg = params.regions[i];
    RegionMatch m;
    const std::vector<float> w = regionWeights(skin, body, reg.match, &m);
    if (m.regions.empty() && m.joints.empty()) {
      std::vector<std::string> joints;
      for (const anatomy::Segment& s : body.segments) joints.push_back(s.name);
      inputError(source, params.file.empty() ? "" : " (" + excerpt(params.file) + ")", ": regions[",
                 i, "].match '", excerpt(reg.match),
                 "' matches no region or joint of the model (regions: ",
                 nameList(skin.regionNames, 40), "; joints: ", nameList(joints, 40), ")");
    }
    // Moves value toward `target` by the weight: value + w (target - value). Where w is 1 this is
    // the target exactly.
    const auto blend = [](float value, float target, float wv) {
      return wv == 1.0f ? target : value + wv * (target - value);
    };
    if (reg.lengthScale != 1.0f || reg.lengthMm > 0.0f) {
      if (g.length.empty()) g.length.assign(skinLength, skinLength + nV);
      for (std::size_t v = 0; v < nV; ++v) {
        if (w[v] <= 0.0f || !(skinLength[v] > 0.0f)) continue;
        const float base = reg.lengthMm > 0.0f ? 1e-3f * reg.lengthMm : g.length[v];
        g.length[v] = blend(g.length[v], base * reg.lengthScale, w[v]);
      }
    }
    if (reg.densityScale != 1.0f) {
      if (g.density.empty()) g.density.assign(nV, 1.0f);
      for (std::size_t v = 0; v < nV; ++v)
        if (w[v] > 0.0f) g.density[v] = blend(g.density[v], g.density[v] * reg.densityScale, w[v]);
    }
    if (reg.tint != Eigen::Vector3f::Ones()) {
      if (g.tint.empty()) g.tint.assign(nV, Eigen::Vector3f::Ones());
      for (std::size_t v = 0; v < nV; ++v)
        if (w[v] > 0.0f)
          for (int k = 0; k < 3; ++k)
            g.tint[v][k] = blend(g.tint[v][k], g.tint[v][k] * reg.tint[k], w[v]);
    }
    // A per-coat value (stiffness, segment direction weight, curl radius and turns, width scale)
    // moves from the coats' own.
    const auto blendCoats = [&](std::vector<Eigen::Vector2f>& values,
                                const std::optional<Eigen::Vector2f>& target, float overcoat,
                                float undercoat) {
      if (!target) return;
      if (values.empty()) values.assign(nV, Eigen::Vector2f(overcoat, undercoat));
      for (std::size_t v = 0; v < nV; ++v)
        if (w[v] > 0.0f)
          for (int k = 0; k < 2; ++k) values[v][k] = blend(values[v][k], (*target)[k], w[v]);
    };
    const CoatParams& over = params.coats[kOvercoat];
    const CoatParams& under = params.coats[kUndercoat];
    blendCoats(g.stiffness, reg.stiffness, over.stiffness, under.stiffness);
    blendCoats(g.segmentDirectionWeight, reg.segmentDirectionWeight, over.segmentDirectionWeight,
               under.segmentDirectionWeight);
    blendCoats(g.curlRadius, reg.curlRadius, over.curlRadius, under.curlRadius);
    blendCoats(g.curlTurns, reg.curlTurns, over.curlTurns, under.curlTurns);
    blendCoats(g.widthScale, reg.widthScale, 1.0f, 1.0f);  // the coats' own width: scale 1
    // A colour source: every source's weight moves toward 1 for the region's, 0 for the others,
    // from the coats' own sources (weight 1 each), so a coat's weights keep summing to 1.
    if (reg.colorSource) {
      for (int s = 0; s < kColorSourceCount; ++s) {
        const auto named = static_cast<ColorSource>(s);
        const auto own = [&](const CoatParams& c) { return c.color.source == named ? 1.0f : 0.0f; };
        const auto target = [&](int c) { return (*reg.colorSource)[c] == named ? 1.0f : 0.0f; };
        blendCoats(g.colorSourceWeight[static_cast<std::size_t>(s)],
                   Eigen::Vector2f(target(0), target(1)), own(over), own(under));
      }
    }
    if (matches) matches->push_back(std::move(m));
  }
  return g;
}

VertexGroom resolveVertexGroom(const skin::SkinMesh& skin, const anatomy::Body& body,
                               const std::string& modelName, const FurParams& params,
                               const std::string& source, std::vector<RegionMatch>* matches) {
  VertexGroom fromFile;
  if (!params.groom.empty()) fromFile = readGroomFile(params.groom, skin, modelName);
  return groomFromRegions(skin, body, params, source, matches, std::move(fromFile));
}

}  // namespace pelage::fur
