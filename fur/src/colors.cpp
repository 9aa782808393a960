#include "pelage/fur/colors.h"

#include <algorithm>
#include <cmath>

#include "pelage/fur/generate.h"
#include "pelage/util/color.h"
#include "pelage/util/error.h"
#include "pelage/util/parallel.h"
#include "pelage/util/random.h"
#include "vertex_value.h"

namespace pelage::fur {
namespace {

float luminance(const Eigen::Vector3f& c) {
  return 0.2126f * c.x() + 0.7152f * c.y() + 0.0722f * c.z();
}

Eigen::Vector3f clamp01(const Eigen::Vector3f& c) {
  return c.cwiseMax(0.0f).cwiseMin(1.0f);
}

// The source colour of root k (triangle t, barycentric b) for a resolved source.
Eigen::Vector3f sourceColor(const skin::SkinMesh& skin, const Groom& maps, const Material& linear,
                            ColorSource source, std::int32_t t, const float* b) {
  switch (source) {
    case ColorSource::Material:
    case ColorSource::Creature:  // (resolved before: never reaches here)
      return linear.diffuse;
    case ColorSource::Texture:
      return skin.surfaceColorAt(t, b).head<3>();
    case ColorSource::Vertex: {
      const std::int32_t* v = skin.triangles.data() + 3 * static_cast<std::size_t>(t);
      const auto at = [&](int k) -> Eigen::Vector3f {
        const auto vi = static_cast<std::size_t>(v[k]);
        return skin.furColor.empty() ? Eigen::Vector3f(skin.vertexColor[vi].head<3>())
                                     : skin.furColor[vi];
      };
      return (at(0) * b[0] + at(1) * b[1]) + at(2) * b[2];
    }
    case ColorSource::Map:
      return maps.color.sample(skin.uvAt(t, b)).head<3>();
  }
  return linear.diffuse;
}

}  // namespace

ColorSource resolveColorSource(const skin::SkinMesh& skin, ColorSource asked, const Groom& maps,
                               const std::string& field) {
  switch (asked) {
    case ColorSource::Material:
      return asked;
    case ColorSource::Creature:
      if (!skin.furColor.empty()) return ColorSource::Vertex;
      return skin.hasSurfaceColor() ? ColorSource::Texture : ColorSource::Material;
    case ColorSource::Texture:
      if (!skin.hasSurfaceColor())
        fieldError(field,
                   "texture: the model has no materials, textures or vertex colours (use "
                   "material, creature or map)");
      return asked;
    case ColorSource::Vertex:
      if (skin.furColor.empty() && skin.vertexColor.empty())
        fieldError(field, "vertex: the model has no vertex colours (COLOR_0) and no fur colours");
      return asked;
    case ColorSource::Map:
      if (maps.color.empty()) fieldError(field, "map: the preset names no maps.color image");
      return asked;
  }
  return ColorSource::Material;
}

std::uint32_t packSrgb8(const Eigen::Vector3f& linear) {
  return static_cast<std::uint32_t>(linearToSrgb8(linear.x())) |
         static_cast<std::uint32_t>(linearToSrgb8(linear.y())) << 8 |
         static_cast<std::uint32_t>(linearToSrgb8(linear.z())) << 16 | 0xFF000000u;
}

Eigen::Vector3f unpackSrgb8(std::uint32_t p) {
  const float* lut = srgb8ToLinearTable();
  return {lut[p & 0xFFu], lut[(p >> 8) & 0xFFu], lut[(p >> 16) & 0xFFu]};
}

Eigen::Vector3f gradeHairColor(const std::uint32_t* pair, float t) {
  const Eigen::Vector3f a = unpackSrgb8(pair[0]);
  const Eigen::Vector3f b = unpackSrgb8(pair[1]);
  return a + (b - a) * t;
}

Eigen::Vector3f hairColorAt(const CoatColors& c, std::int64_t root, float t) {
  return c.perHair ? gradeHairColor(c.packed.data() + 2 * root, t) : c.diffuse;
}

Eigen::Vector3f drawnHairColorAt(const CoatColors& c, const HairBuffers& hb, std::int64_t i,
                                 float t) {
  return c.perHair ? gradeHairColor(hb.colors.data() + 2 * i, t) : c.diffuse;
}

Eigen::Vector3f shiftHue(const Eigen::Vector3f& rgb, float degrees) {
  const float mx = rgb.maxCoeff(), mn = rgb.minCoeff(), delta = mx - mn;
  if (!(delta > 0.0f)) return rgb;  // grey: no hue
  float h;                          // degrees in [0, 360)
  if (mx == rgb.x())
    h = 60.0f * std::fmod((rgb.y() - rgb.z()) / delta + 6.0f, 6.0f);
  else if (mx == rgb.y())
    h = 60.0f * ((rgb.z() - rgb.x()) / delta + 2.0f);
  else
    h = 60.0f * ((rgb.x() - rgb.y()) / delta + 4.0f);
  h = std::fmod(h + degrees + 720.0f, 360.0f);
  // Back from (h, s = delta / mx, v = mx).
  const float hp = h / 60.0f;
  const float x = delta * (1.0f - std::abs(std::fmod(hp, 2.0f) - 1.0f));
  Eigen::Vector3f c;
  if (hp < 1.0f)
    c = {delta, x, 0.0f};
  else if (hp < 2.0f)
    c = {x, delta, 0.0f};
  else if (hp < 3.0f)
    c = {0.0f, delta, x};
  else if (hp < 4.0f)
    c = {0.0f, x, delta};
  else if (hp < 5.0f)
    c = {x, 0.0f, delta};
  else
    c = {delta, 0.0f, x};
  return c + Eigen::Vector3f::Constant(mn);
}

FurColors colorRoots(const skin::SkinMesh& skin, const FurRoots& roots, const FurParams& params,
                     const Groom& maps) {
  FurColors out;
  for (int c = 0; c < kCoatCount; ++c) {
    const auto ci = static_cast<std::size_t>(c);
    const CoatParams& coat = params.coats[ci];
    const CoatColor& model = coat.color;
    CoatColors& cc = out.coats[ci];
    cc.source = resolveColorSource(
        skin, model.source, maps,
        std::string(c == kOvercoat ? "overcoat" : "undercoat") + ".color.source");
    const Material linear = linearMaterial(coat.material);  // lighting is linear (util/color.h)
    const float lumD = luminance(linear.diffuse);
    cc.ambientRatio =
        lumD > 1e-6f ? std::clamp(luminance(linear.ambient) / lumD, 0.0f, 4.0f) : 0.0f;
    const std::vector<Eigen::Vector3f>& vertexTint = maps.vertex.tint;
    const CoatRoots& cr = roots.coats[ci];
    cc.perHairWidth = !cr.widthScale.empty();
    // A groom's colour source weights (regions' colour sources): the sources this coat's hairs
    // blend, each resolved on this skin.
    const auto& sourceWeight = maps.vertex.colorSourceWeight;
    const bool blended = maps.vertex.hasColorSourceWeights();
    std::array<ColorSource, kColorSourceCount> resolved{};
    std::array<bool, kColorSourceCount> used{};
    for (int s = 0; s < kColorSourceCount && blended; ++s) {
      const auto& w = sourceWeight[static_cast<std::size_t>(s)];
      used[static_cast<std::size_t>(s)] =
          std::any_of(w.begin(), w.end(), [&](const Eigen::Vector2f& x) { return x[c] > 0.0f; });
      if (used[static_cast<std::size_t>(s)])
        resolved[static_cast<std::size_t>(s)] =
            resolveColorSource(skin, static_cast<ColorSource>(s), maps,
                               str(c == kOvercoat ? "overcoat" : "undercoat",
                                   " colour source (a region's or groom's)"));
    }
    if (model.uniformOver(cc.source) && vertexTint.empty() && !cc.perHairWidth && !blended) {
      cc.perHair = false;
      cc.diffuse = clamp01(linear.diffuse.cwiseProduct(model.tint));
      cc.ambient = clamp01(linear.ambient.cwiseProduct(model.tint));
      continue;
    }
    cc.perHair = true;
    const std::int64_t n = cr.size();
    cc.packed.assign(static_cast<std::size_t>(2 * n), 0u);
    const std::uint64_t seed = coatSeed(roots.seed, c);
    const Eigen::Vector3f tipLinear = srgbToLinear(model.tipColor);
    parallelFor(n, 4096, [&](std::int64_t k) {
      const auto ks = static_cast<std::size_t>(k);
      const float* b = roots.barycentric.data() + 4 * cr.tableIndex[ks];
      // The groom's vertex tint at the root (fur/groom.h), interpolated as sec. 3.2 interpolates.
      Eigen::Vector3f groomTint = Eigen::Vector3f::Ones();
      if (!vertexTint.empty()) {
        const std::int32_t* v =
            skin.triangles.data() + 3 * static_cast<std::size_t>(cr.triangle[ks]);
        groomTint = (vertexTint[static_cast<std::size_t>(v[0])] * b[0] +
                     vertexTint[static_cast<std::size_t>(v[1])] * b[1]) +
                    vertexTint[static_cast<std::size_t>(v[2])] * b[2];
      }
      Eigen::Vector3f source = Eigen::Vector3f::Zero();
      if (!blended) {
        source = sourceColor(skin, maps, linear, cc.source, cr.triangle[ks], b);
      } else {
        // Each source's weight at the root: exactly 1 where the three vertices take one source,
        // so such a hair has that source's colour.
        const std::int32_t* v =
            skin.triangles.data() + 3 * static_cast<std::size_t>(cr.triangle[ks]);
        for (int s = 0; s < kColorSourceCount; ++s) {
          if (!used[static_cast<std::size_t>(s)]) continue;
          const float weight =
              detail::coatValueAtRoot(sourceWeight[static_cast<std::size_t>(s)], v, b, c);
          if (weight > 0.0f)
            source +=
                weight * sourceColor(skin, maps, linear, resolved[static_cast<std::size_t>(s)],
                                     cr.triangle[ks], b);
        }
      }
      Eigen::Vector3f root = clamp01(source.cwiseProduct(model.tint).cwiseProduct(groomTint));
      Eigen::Vector3f tip = model.hasTipColor ? clamp01(tipLinear.cwiseProduct(groomTint))
                                              : clamp01(root * model.tipLightness);
      // Per-hair variation (one hue shift and one brightness factor for the whole hair).
      if (model.hueVariation > 0.0f) {
        const float u = uniform01(seed, kStreamColor, 2 * static_cast<std::uint64_t>(k));
        const float degrees = model.hueVariation * (2.0f * u - 1.0f);
        root = shiftHue(root, degrees);
        tip = shiftHue(tip, degrees);
      }
      if (model.valueVariation > 0.0f) {
        const float u = uniform01(seed, kStreamColor, 2 * static_cast<std::uint64_t>(k) + 1);
        const float f = 1.0f + model.valueVariation * (2.0f * u - 1.0f);
        root = clamp01(root * f);
        tip = clamp01(tip * f);
      }
      cc.packed[2 * ks] = packSrgb8(root);
      cc.packed[2 * ks + 1] = packSrgb8(tip);
      if (cc.perHairWidth) packHairWidth(cc.packed.data() + 2 * ks, cr.widthScale[ks]);
    });
  }
  return out;
}

void packHairWidth(std::uint32_t* pair, float widthScale) {
  const auto code = static_cast<std::uint32_t>(
      std::lround(std::clamp(widthScale, 0.0f, kMaxWidthScale) * kWidthScaleCodes));
  pair[0] = (pair[0] & 0x00FFFFFFu) | (code & 0xFFu) << 24;
  pair[1] = (pair[1] & 0x00FFFFFFu) | (code >> 8) << 24;
}

float hairWidthScale(const std::uint32_t* pair) {
  return static_cast<float>((pair[0] >> 24) | (pair[1] >> 24) << 8) / kWidthScaleCodes;
}

void pointColorsSrgb8(const CoatColors& cc, const HairBuffers& hb, std::vector<std::uint8_t>& rgb) {
  const int P = hb.layout.pointsPerHair();
  rgb.resize(static_cast<std::size_t>(3 * hb.drawn * P));
  if (!cc.perHair) {
    const std::uint8_t u[3] = {linearToSrgb8(cc.diffuse.x()), linearToSrgb8(cc.diffuse.y()),
                               linearToSrgb8(cc.diffuse.z())};
    for (std::size_t i = 0; i < rgb.size(); i += 3) std::copy(u, u + 3, rgb.data() + i);
    return;
  }
  PELAGE_CHECK(hb.colors.size() == static_cast<std::size_t>(2 * hb.drawn),
               "pointColorsSrgb8 before fillHairColors");
  parallelForChunks(hb.drawn, 16384, [&](std::int64_t b, std::int64_t e) {
    for (std::int64_t i = b; i < e; ++i) {
      std::uint8_t* out = rgb.data() + 3 * i * P;
      for (int k = 0; k < P; ++k) {
        const Eigen::Vector3f c = gradeHairColor(hb.colors.data() + 2 * i, hb.layout.along(k));
        for (int j = 0; j < 3; ++j) out[3 * k + j] = linearToSrgb8(c[j]);
      }
    }
  });
}

void fillHairColors(const FurColors& colors, FurFrame& frame) {
  for (int c = 0; c < kCoatCount; ++c) {
    const auto ci = static_cast<std::size_t>(c);
    const CoatColors& cc = colors.coats[ci];
    HairBuffers& hb = frame.coats[ci];
    if (!cc.perHair) {
      hb.colors.clear();
      continue;
    }
    hb.colors.resize(static_cast<std::size_t>(2 * hb.drawn));
    const std::uint32_t* src = cc.packed.data();
    std::uint32_t* dst = hb.colors.data();
    const std::int32_t* ids = hb.hairIds.data();
    parallelForChunks(hb.drawn, 65536, [&](std::int64_t b, std::int64_t e) {
      for (std::int64_t i = b; i < e; ++i) {
        const auto r = static_cast<std::size_t>(ids[i]);
        dst[2 * i] = src[2 * r];
        dst[2 * i + 1] = src[2 * r + 1];
      }
    });
  }
}

}  // namespace pelage::fur
