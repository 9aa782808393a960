#include "pelage/fur/roots.h"

#include "pelage/fur/coverage.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <unordered_map>

#include "pelage/fur/hair_layout.h"
#include "pelage/fur/hair_math.h"
#include "pelage/skin/deform.h"
#include "pelage/util/error.h"
#include "pelage/util/parallel.h"
#include "pelage/util/random.h"
#include "vertex_value.h"

namespace pelage::fur {
namespace {

constexpr double kPi = 3.14159265358979323846;

// "4.4 TB", "512.0 MB": decimal units, one decimal.
std::string humanBytes(double bytes) {
  const char* units[] = {"B", "KB", "MB", "GB", "TB", "PB", "EB"};
  int u = 0;
  while (bytes >= 1000.0 && u < 6) {
    bytes /= 1000.0;
    ++u;
  }
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.1f %s", bytes, units[u]);
  return buf;
}

// Bytes one root of a coat keeps: triangle, table index, jitter; plus its drawn slot in the frame
// buffers (the style's layout).
double bytesPerHair(const CoatParams& coat) {
  // + a length-map scale and a root and tip colour (when the preset asks for them).
  const double rootBytes =
      sizeof(std::int32_t) + sizeof(std::uint16_t) + 4 * sizeof(float) + sizeof(float) + 8;
  return rootBytes + hairLayout(coat).frameBytesPerHair();
}

// The density map's mean and maximum over triangle t: at the centroids of its 4^L congruent
// sub-triangles (n = 2^L per edge), L from the triangle's area in texels (at least 4 samples per
// texel, 4 <= 4^L <= 4096), nearest texels.
void triangleDensity(const skin::SkinMesh& skin, const skin::Texture& map, std::int32_t t,
                     float& mean, float& max) {
  const Eigen::Vector2f* uv = skin.cornerUv.data() + 3 * static_cast<std::size_t>(t);
  const Eigen::Vector2f e1 = uv[1] - uv[0], e2 = uv[2] - uv[0];
  const double texels = 0.5 * std::abs(static_cast<double>(e1.x() * e2.y() - e1.y() * e2.x())) *
                        map.width * map.height;
  int n = 2;
  while (n < 64 && static_cast<double>(n) * n < 4.0 * texels) n *= 2;
  double sum = 0.0;
  float hi = 0.0f;
  int samples = 0;
  const auto at = [&](double b2, double b3) {
    const float b[3] = {static_cast<float>(1.0 - b2 - b3), static_cast<float>(b2),
                        static_cast<float>(b3)};
    const float d = map.sample(skin.uvAt(t, b)).x();
    sum += static_cast<double>(d);
    hi = std::max(hi, d);
    ++samples;
  };
  const double third = 1.0 / (3.0 * n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; i + j < n; ++j) {
      at((3 * i + 1) * third, (3 * j + 1) * third);                      // upward sub-triangle
      if (i + j + 2 <= n) at((3 * i + 2) * third, (3 * j + 2) * third);  // downward
    }
  mean = static_cast<float>(sum / samples);
  max = hi;
}

// The table entry of the next root of triangle t under a density map: candidates (first +
// attempt) mod 2048 in turn, each accepted with probability density / max; after 4096 rejected
// candidates the best one seen is taken.
std::uint16_t acceptedEntry(const skin::SkinMesh& skin, const skin::Texture& map,
                            const std::vector<float>& table, std::int32_t t, std::int64_t first,
                            std::uint64_t seed, float max, std::int64_t& attempt) {
  constexpr int kMaxTries = 4096;
  std::uint16_t best = 0;
  float bestDensity = -1.0f;
  for (int tries = 0; tries < kMaxTries; ++tries, ++attempt) {
    const auto entry = static_cast<std::uint16_t>((first + attempt) % kBarycentricTableSize);
    const float d = map.sample(skin.uvAt(t, table.data() + 4 * entry)).x();
    const float u = uniform01(seed, kStreamDensity,
                              (static_cast<std::uint64_t>(t) << 20) +
                                  static_cast<std::uint64_t>(attempt & ((1 << 20) - 1)));
    if (u * max < d) {
      ++attempt;
      return entry;
    }
    if (d > bestDensity) {
      bestDensity = d;
      best = entry;
    }
  }
  return best;
}

}  // namespace

std::vector<float> makeBarycentricTable(std::uint64_t seed) {
  std::vector<float> table(static_cast<std::size_t>(kBarycentricTableSize) * 4);
  // Van Gelder & Wilhelms 1997, sec. 3.2: b1 = 1 - sqrt(u1) (triangular on [0, 1], peak at 0),
  // b2 = (1 - b1) u2 (uniform on [0, 1 - b1]), b3 = 1 - b1 - b2.
  for (std::uint64_t j = 0; j < kBarycentricTableSize; ++j) {
    const double u1 = uniform01(seed, kStreamBarycentricTable, 2 * j);
    const double u2 = uniform01(seed, kStreamBarycentricTable, 2 * j + 1);
    const double b1 = 1.0 - std::sqrt(u1);
    const double b2 = (1.0 - b1) * u2;
    const double b3 = 1.0 - b1 - b2;
    float* e = table.data() + 4 * j;
    e[0] = static_cast<float>(b1);
    e[1] = static_cast<float>(b2);
    e[2] = static_cast<float>(b3);
    e[3] = 0.0f;
  }
  return table;
}

std::uint64_t coatSeed(std::uint64_t seed, int coat) {
  return coat == 0 ? seed
                   : mix64(seed ^ (0x9e3779b97f4a7c15ull * static_cast<std::uint64_t>(coat)));
}

double requestedHairs(const FurParams& params, double furredArea) {
  return params.densityPerM2 > 0.0 ? params.densityPerM2 * furredArea : params.hairs;
}

double estimateFurBytes(const FurParams& params, double hairs) {
  const double share = static_cast<double>(params.undercoatShare);
  return hairs * (1.0 - share) * bytesPerHair(params.coats[0]) +
         hairs * share * bytesPerHair(params.coats[1]);
}

void checkHairBudget(const FurParams& params, double furredArea) {
  const double n = requestedHairs(params, furredArea);
  const double bytes = estimateFurBytes(params, n);
  if (std::isfinite(n) && n >= 0.0 && n <= kMaxHairs && bytes <= kMaxFurBytes) return;
  std::string origin;
  if (params.densityPerM2 > 0.0)
    origin = str(" (density ", params.densityPerM2, " hairs/m^2 over ", furredArea,
                 " m^2 of furred skin)");
  inputError("fur '", params.name, "': ", n, " hairs", origin, " need ", humanBytes(bytes), " (",
             styleName(params.coats[0].style), " overcoat, ", styleName(params.coats[1].style),
             " undercoat); accepted: 0 to ", kMaxHairs, " hairs using at most ",
             humanBytes(kMaxFurBytes));
}

std::vector<double> triangleAreas(const skin::SkinMesh& skin) {
  const std::int64_t nT = skin.numTriangles();
  std::vector<double> area(static_cast<std::size_t>(nT));
  const float* p = skin.restPositions();
  const std::int32_t* tri = skin.triangles.data();
  parallelFor(nT, 8192, [&](std::int64_t t) {
    const Eigen::Vector3d a = Eigen::Map<const Eigen::Vector3f>(p + 3 * tri[3 * t]).cast<double>();
    const Eigen::Vector3d b =
        Eigen::Map<const Eigen::Vector3f>(p + 3 * tri[3 * t + 1]).cast<double>();
    const Eigen::Vector3d c =
        Eigen::Map<const Eigen::Vector3f>(p + 3 * tri[3 * t + 2]).cast<double>();
    area[static_cast<std::size_t>(t)] = 0.5 * (b - a).cross(c - a).norm();
  });
  return area;
}

bool triangleHasFur(const skin::SkinMesh& skin, const float* len, std::int32_t t) {
  const std::int32_t* v = skin.triangles.data() + 3 * static_cast<std::int64_t>(t);
  return len[v[0]] > 0.0f || len[v[1]] > 0.0f || len[v[2]] > 0.0f;
}

namespace {
// The comb of a root at barycentric b of triangle t: sum b_i comb_i of its vertices, in the root's
// rest tangent frame (hair_math.h combFrame, packComb).
std::uint32_t restComb(const skin::SkinMesh& skin, const skin::DeformedSkin& rest,
                       const std::vector<Eigen::Vector3f>& comb, std::int32_t t, const float* b) {
  const std::int32_t* v = skin.triangles.data() + 3 * static_cast<std::int64_t>(t);
  Eigen::Vector3f c = Eigen::Vector3f::Zero(), n = Eigen::Vector3f::Zero();
  for (int k = 0; k < 3; ++k) {
    const auto vk = static_cast<std::size_t>(v[k]);
    c += b[k] * comb[vk];
    n += b[k] * rest.normals[vk];
  }
  if (c.squaredNorm() == 0.0f || n.squaredNorm() <= 1e-20f) return 0;
  n.normalize();
  const Eigen::Vector3f e = rest.positions[static_cast<std::size_t>(v[1])] -
                            rest.positions[static_cast<std::size_t>(v[0])];
  const auto vec = [](const Eigen::Vector3f& a) { return Vec3<float>{a.x(), a.y(), a.z()}; };
  const CombFrame<float> frame = combFrame(vec(n), vec(e), Vec3<float>{0.0f, 0.0f, 0.0f});
  if (dot(frame.u, frame.u) == 0.0f) return 0;  // no tangent plane direction: no comb
  return packComb(dot(vec(c), frame.u), dot(vec(c), frame.v));
}
}  // namespace

Eigen::Vector3f restRootPosition(const skin::SkinMesh& skin, const std::vector<float>& barycentric,
                                 const CoatRoots& cr, std::int64_t k) {
  const auto ks = static_cast<std::size_t>(k);
  const std::int32_t* v = skin.triangles.data() + 3 * static_cast<std::int64_t>(cr.triangle[ks]);
  const float* b = barycentric.data() + 4 * cr.tableIndex[ks];
  const float* rest = skin.restPositions();
  Eigen::Vector3f p = Eigen::Vector3f::Zero();
  for (int i = 0; i < 3; ++i) p += b[i] * Eigen::Map<const Eigen::Vector3f>(rest + 3 * v[i]);
  return p;
}

void assignClumps(const skin::SkinMesh& skin, const std::vector<float>& barycentric,
                  std::uint64_t coatSeed, const Clump& clump, CoatRoots& cr) {
  cr.clumpCentres.clear();
  cr.clumpSlot.clear();
  const std::int64_t n = cr.size();
  if (!clump.on() || n == 0) return;
  const double side = 0.01 / std::sqrt(static_cast<double>(clump.density));
  std::vector<Eigen::Vector3f> at(static_cast<std::size_t>(n));
  std::vector<std::uint64_t> cell(static_cast<std::size_t>(n));
  // Cube (i, j, k) packed as 21 bits each (wrapping only 2^20 cubes away, kilometres off).
  const auto key = [](std::int64_t i, std::int64_t j, std::int64_t k) {
    constexpr std::uint64_t m = (1u << 21) - 1;
    return (static_cast<std::uint64_t>(i) & m) << 42 | (static_cast<std::uint64_t>(j) & m) << 21 |
           (static_cast<std::uint64_t>(k) & m);
  };
  const auto cube = [&](const Eigen::Vector3f& p) {
    const auto index = [&](float x) {
      return static_cast<std::int64_t>(std::floor(static_cast<double>(x) / side));
    };
    return Eigen::Vector3<std::int64_t>(index(p.x()), index(p.y()), index(p.z()));
  };
  parallelFor(n, 4096, [&](std::int64_t k) {
    const auto ks = static_cast<std::size_t>(k);
    at[ks] = restRootPosition(skin, barycentric, cr, k);
    const Eigen::Vector3<std::int64_t> c = cube(at[ks]);
    cell[ks] = key(c.x(), c.y(), c.z());
  });
  // The centre of each cube: the least (priority, index).
  std::unordered_map<std::uint64_t, std::int32_t> centreOf;
  centreOf.reserve(static_cast<std::size_t>(n / 8 + 16));
  for (std::int64_t k = 0; k < n; ++k) {
    const auto [it, added] =
        centreOf.try_emplace(cell[static_cast<std::size_t>(k)], static_cast<std::int32_t>(k));
    if (!added && uniform01(coatSeed, kStreamClump, static_cast<std::uint64_t>(k)) <
                      uniform01(coatSeed, kStreamClump, static_cast<std::uint64_t>(it->second)))
      it->second = static_cast<std::int32_t>(k);
  }
  std::vector<std::int32_t> slotOf(static_cast<std::size_t>(n), -1);
  for (const auto& [c, root] : centreOf) cr.clumpCentres.push_back(root);
  std::sort(cr.clumpCentres.begin(), cr.clumpCentres.end());
  for (std::size_t s = 0; s < cr.clumpCentres.size(); ++s)
    slotOf[static_cast<std::size_t>(cr.clumpCentres[s])] = static_cast<std::int32_t>(s);
  const float radius2 = 1e-6f * clump.radiusMm * clump.radiusMm;
  cr.clumpSlot.assign(static_cast<std::size_t>(n), -1);
  parallelFor(n, 4096, [&](std::int64_t k) {
    const auto ks = static_cast<std::size_t>(k);
    const Eigen::Vector3<std::int64_t> c = cube(at[ks]);
    float best = std::numeric_limits<float>::infinity();
    std::int32_t bestRoot = -1;
    for (std::int64_t dx = -1; dx <= 1; ++dx)
      for (std::int64_t dy = -1; dy <= 1; ++dy)
        for (std::int64_t dz = -1; dz <= 1; ++dz) {
          const auto it = centreOf.find(key(c.x() + dx, c.y() + dy, c.z() + dz));
          if (it == centreOf.end()) continue;
          const float d2 = (at[static_cast<std::size_t>(it->second)] - at[ks]).squaredNorm();
          if (d2 < best || (d2 == best && it->second < bestRoot)) {
            best = d2;
            bestRoot = it->second;
          }
        }
    if (bestRoot >= 0 && best <= radius2)
      cr.clumpSlot[ks] = slotOf[static_cast<std::size_t>(bestRoot)];
  });
}

FurRoots growRoots(const skin::SkinMesh& skin, const FurParams& params, const Groom& groom) {
  const std::int32_t nT = skin.numTriangles();
  PELAGE_CHECK(groom.vertex.comb.empty() ||
                   groom.vertex.comb.size() == static_cast<std::size_t>(skin.numVertices()),
               "groom comb has ", groom.vertex.comb.size(), " values for ", skin.numVertices(),
               " vertices");
  PELAGE_CHECK(groom.vertex.clump.empty() ||
                   groom.vertex.clump.size() == static_cast<std::size_t>(skin.numVertices()),
               "groom clump has ", groom.vertex.clump.size(), " values for ", skin.numVertices(),
               " vertices");
  PELAGE_CHECK(groom.vertex.stiffness.empty() ||
                   groom.vertex.stiffness.size() == static_cast<std::size_t>(skin.numVertices()),
               "groom stiffness has ", groom.vertex.stiffness.size(), " values for ",
               skin.numVertices(), " vertices");
  skin::DeformedSkin rest;  // rest normals, for the comb's tangent frames
  if (!groom.vertex.comb.empty()) skin::restSkin(skin, rest);
  const std::vector<double> area = triangleAreas(skin);
  PELAGE_CHECK(groom.vertex.length.empty() ||
                   groom.vertex.length.size() == static_cast<std::size_t>(skin.numVertices()),
               "groom length has ", groom.vertex.length.size(), " values for ", skin.numVertices(),
               " vertices");
  const float* lengths = groomedLengths(skin, groom.vertex);
  std::vector<char> furred(static_cast<std::size_t>(nT));
  double furredArea = 0.0;
  for (std::int32_t t = 0; t < nT; ++t) {
    furred[static_cast<std::size_t>(t)] = triangleHasFur(skin, lengths, t) ? 1 : 0;
    if (furred[static_cast<std::size_t>(t)]) furredArea += area[static_cast<std::size_t>(t)];
  }
  // A coverage asks for the count that hides that share of the skin (fur/coverage.h).
  FurParams counted = params;
  if (params.coverage > 0.0)
    counted.setHairCount(hairsForCoverage(skin, params, params.coverage, lengths));
  checkHairBudget(counted, furredArea);
  const double total = requestedHairs(counted, furredArea);
  // The density map's mean and maximum over each furred triangle, times the mean of the groom's
  // vertex densities; weightedArea = sum area x mean.
  const bool densityMap = !groom.density.empty();
  const std::vector<float>& vertexDensity = groom.vertex.density;
  const bool weighted = densityMap || !vertexDensity.empty();
  std::vector<float> densityMean, densityMax;
  double weightedArea = furredArea;
  if (weighted) {
    densityMean.assign(static_cast<std::size_t>(nT), 1.0f);
    densityMax.assign(static_cast<std::size_t>(nT), 1.0f);
  }
  if (densityMap) {
    PELAGE_CHECK(skin.hasUv(), "a density map on a skin without texture coordinates");
    parallelFor(nT, 1024, [&](std::int64_t t) {
      const auto ts = static_cast<std::size_t>(t);
      densityMean[ts] = densityMax[ts] = 0.0f;
      if (!furred[ts]) return;
      triangleDensity(skin, groom.density, static_cast<std::int32_t>(t), densityMean[ts],
                      densityMax[ts]);
    });
  }
  if (!vertexDensity.empty()) {
    PELAGE_CHECK(vertexDensity.size() == static_cast<std::size_t>(skin.numVertices()),
                 "groom density has ", vertexDensity.size(), " values for ", skin.numVertices(),
                 " vertices");
    const std::int32_t* tri = skin.triangles.data();
    for (std::int32_t t = 0; t < nT; ++t) {
      const std::int32_t* v = tri + 3 * static_cast<std::int64_t>(t);
      densityMean[static_cast<std::size_t>(t)] *= triangleDensity(vertexDensity, v);
    }
  }
  if (weighted) {
    weightedArea = 0.0;
    for (std::int32_t t = 0; t < nT; ++t)
      if (furred[static_cast<std::size_t>(t)])
        weightedArea += area[static_cast<std::size_t>(t)] *
                        static_cast<double>(densityMean[static_cast<std::size_t>(t)]);
  }

  FurRoots roots;
  roots.triangleCount = nT;
  roots.furredArea = furredArea;
  roots.seed = params.seed;
  roots.vertexLength = groom.vertex.length;
  roots.barycentric = makeBarycentricTable(params.seed);
  for (int c = 0; c < kCoatCount; ++c) {
    CoatRoots& cr = roots.coats[static_cast<std::size_t>(c)];
    const std::uint64_t seed = coatSeed(params.seed, c);
    // The lead's design: the coats are separate root sets, N_over = N (1 - share), N_under = N
    // share.
    const double share = static_cast<double>(params.undercoatShare);
    const double nc = c == kOvercoat ? total * (1.0 - share) : total * share;
    cr.expectedHairs = nc;
    // Van Gelder & Wilhelms 1997, sec. 3.2: floor(alpha N + u) hairs per triangle ("random
    // rounding"), alpha = area / furred area; no-fur triangles get none.
    std::vector<std::int32_t> count(static_cast<std::size_t>(nT), 0);
    if (!weighted && furredArea > 0.0 && nc > 0.0) {
      parallelFor(nT, 8192, [&](std::int64_t t) {
        const auto ts = static_cast<std::size_t>(t);
        if (!furred[ts]) return;
        const double u = uniform01(seed, kStreamAllocation, static_cast<std::uint64_t>(t));
        count[ts] = static_cast<std::int32_t>(std::floor(area[ts] / furredArea * nc + u));
      });
    }
    if (weighted && weightedArea > 0.0 && nc > 0.0) {
      parallelFor(nT, 8192, [&](std::int64_t t) {
        const auto ts = static_cast<std::size_t>(t);
        if (!furred[ts] || !(densityMean[ts] > 0.0f)) return;
        const double u = uniform01(seed, kStreamAllocation, static_cast<std::uint64_t>(t));
        const double alpha = area[ts] * static_cast<double>(densityMean[ts]) / weightedArea;
        count[ts] = static_cast<std::int32_t>(std::floor(alpha * nc + u));
      });
    }
    cr.triangleStart.assign(static_cast<std::size_t>(nT) + 1, 0);
    std::int64_t sum = 0;
    for (std::int32_t t = 0; t < nT; ++t) {
      sum += count[static_cast<std::size_t>(t)];
      PELAGE_CHECK(sum <= std::numeric_limits<std::int32_t>::max(), "root count overflow");
      cr.triangleStart[static_cast<std::size_t>(t) + 1] = static_cast<std::int32_t>(sum);
    }
    const auto n = static_cast<std::size_t>(sum);
    cr.triangle.resize(n);
    cr.tableIndex.resize(n);
    cr.jitter.resize(4 * n);
    if (!groom.length.empty()) {
      PELAGE_CHECK(skin.hasUv(), "a length map on a skin without texture coordinates");
      cr.lengthScale.resize(n);
    }
    if (!groom.vertex.comb.empty()) cr.comb.resize(n);
    const bool clumpScaled =
        !groom.vertex.clump.empty() && params.coats[static_cast<std::size_t>(c)].clump.on();
    if (clumpScaled) cr.clumpScale.resize(n);
    if (!groom.vertex.stiffness.empty()) cr.floppiness.resize(n);
    if (!groom.vertex.segmentDirectionWeight.empty()) cr.segmentWeight.resize(n);
    if (!groom.vertex.widthScale.empty()) cr.widthScale.resize(n);
    const CoatParams& coat = params.coats[static_cast<std::size_t>(c)];
    const bool curled = !groom.vertex.curlRadius.empty() || !groom.vertex.curlTurns.empty();
    if (curled) {
      cr.curlRadius.assign(n, coat.curlRadius);
      cr.curlTurns.assign(n, coat.curlTurns);
    }
    parallelForChunks(nT, 4096, [&](std::int64_t tb, std::int64_t te) {
      for (std::int64_t t = tb; t < te; ++t) {
        const std::int64_t first = cr.triangleStart[static_cast<std::size_t>(t)];
        std::int64_t attempt = 0;  // density map: candidates tried in this triangle
        for (std::int64_t k = first; k < cr.triangleStart[static_cast<std::size_t>(t) + 1]; ++k) {
          const auto ks = static_cast<std::size_t>(k);
          cr.triangle[ks] = static_cast<std::int32_t>(t);
          // Sec. 3.2: "generated by cycling through the values in this table".
          if (!densityMap) {
            cr.tableIndex[ks] = static_cast<std::uint16_t>(k % kBarycentricTableSize);
          } else {
            cr.tableIndex[ks] =
                acceptedEntry(skin, groom.density, roots.barycentric, static_cast<std::int32_t>(t),
                              first, seed, densityMax[static_cast<std::size_t>(t)], attempt);
          }
          if (!cr.lengthScale.empty()) {
            const float* b = roots.barycentric.data() + 4 * cr.tableIndex[ks];
            cr.lengthScale[ks] =
                groom.length.sample(skin.uvAt(static_cast<std::int32_t>(t), b)).x();
          }
          if (clumpScaled) {
            const float* b = roots.barycentric.data() + 4 * cr.tableIndex[ks];
            const std::int32_t* v = skin.triangles.data() + 3 * t;
            const auto at = [&](int i) {
              return groom.vertex.clump[static_cast<std::size_t>(v[i])];
            };
            cr.clumpScale[ks] = b[0] * at(0) + b[1] * at(1) + b[2] * at(2);
          }
          const auto atRoot = [&](const std::vector<Eigen::Vector2f>& values) {
            return detail::coatValueAtRoot(values, skin.triangles.data() + 3 * t,
                                           roots.barycentric.data() + 4 * cr.tableIndex[ks], c);
          };
          if (!cr.floppiness.empty())
            cr.floppiness[ks] = floppiness(atRoot(groom.vertex.stiffness));
          if (!cr.segmentWeight.empty())
            cr.segmentWeight[ks] = atRoot(groom.vertex.segmentDirectionWeight);
          if (curled && !groom.vertex.curlRadius.empty())
            cr.curlRadius[ks] = atRoot(groom.vertex.curlRadius);
          if (curled && !groom.vertex.curlTurns.empty())
            cr.curlTurns[ks] = atRoot(groom.vertex.curlTurns);
          if (!cr.widthScale.empty()) cr.widthScale[ks] = atRoot(groom.vertex.widthScale);
          if (!cr.comb.empty())
            cr.comb[ks] = restComb(skin, rest, groom.vertex.comb, static_cast<std::int32_t>(t),
                                   roots.barycentric.data() + 4 * cr.tableIndex[ks]);
          // Sec. 3.5 hair end randomize: xi uniform in the unit ball (direction uniform on the
          // sphere, radius cbrt(u3)).
          const auto uk = static_cast<std::uint64_t>(k);
          const auto u = [&](std::uint64_t i) {
            return static_cast<double>(uniform01(seed, kStreamHairEnd, i));
          };
          const double z = 2.0 * u(3 * uk) - 1.0;
          const double phi = 2.0 * kPi * u(3 * uk + 1);
          const double rad = std::cbrt(u(3 * uk + 2));
          const double s = std::sqrt(std::max(0.0, 1.0 - z * z));
          float* j = cr.jitter.data() + 4 * ks;
          j[0] = static_cast<float>(rad * s * std::cos(phi));
          j[1] = static_cast<float>(rad * s * std::sin(phi));
          j[2] = static_cast<float>(rad * z);
          j[3] = uniform01(seed, kStreamHairEnd + kPhaseStreamOffset, uk);
        }
      }
    });
    assignClumps(skin, roots.barycentric, seed, params.coats[static_cast<std::size_t>(c)].clump,
                 cr);
  }
  return roots;
}

}  // namespace pelage::fur
