#include "pelage/fur/generate.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>

#include "dynamics_kernel.h"
#include "generate_dynamic.h"
#include "kernel.h"
#include "pelage/util/error.h"
#include "pelage/util/parallel.h"
#include "pelage/util/random.h"

namespace pelage::fur {
namespace {

constexpr double kPi = 3.14159265358979323846;
// Drawn hairs per parallel task (a multiple of the SIMD block, so blocks and their stores stay
// aligned).
constexpr std::int64_t kHairsPerTask = 4096;
static_assert(kHairsPerTask % 16 == 0);
// Outputs above this many bytes per coat use non-temporal stores (they would not stay in cache).
constexpr double kStreamStoreBytes = 8.0 * 1024.0 * 1024.0;

}  // namespace

void FloatBuffer::resize(std::size_t n) {
  if (n > capacity_) {
    data_.reset(static_cast<float*>(
        ::operator new[](std::max<std::size_t>(n, 1) * sizeof(float), std::align_val_t(64))));
    capacity_ = n;
  }
  size_ = n;
}

void makeTwistTable(std::uint64_t seed, float normalRandomize, std::vector<float>& table) {
  table.resize(static_cast<std::size_t>(kBarycentricTableSize) * kPolylinePoints * 2);
  // Van Gelder & Wilhelms 1997, sec. 3.7: "each shading normal is rotated through a random angle,
  // with the line segment as axis": angle r pi (2u - 1).
  for (std::int64_t j = 0; j < kBarycentricTableSize; ++j)
    for (int i = 0; i < kPolylinePoints; ++i) {
      const auto u = static_cast<double>(
          uniform01(seed, kStreamNormal, static_cast<std::uint64_t>(j * kPolylinePoints + i)));
      const double angle = static_cast<double>(normalRandomize) * kPi * (2.0 * u - 1.0);
      table[static_cast<std::size_t>((j * kPolylinePoints + i) * 2)] =
          static_cast<float>(std::cos(angle));
      table[static_cast<std::size_t>((j * kPolylinePoints + i) * 2 + 1)] =
          static_cast<float>(std::sin(angle));
    }
}

void prepareFurFrame(const FurRoots& roots, const FurParams& params, FurFrame& frame) {
  std::array<std::size_t, kCoatCount> floats{};
  for (int c = 0; c < kCoatCount; ++c) {
    const auto ci = static_cast<std::size_t>(c);
    frame.coats[ci].layout = coatLayout(params, roots, c);
    floats[ci] = static_cast<std::size_t>(roots.coats[ci].size()) *
                 static_cast<std::size_t>(frame.coats[ci].layout.pointsPerHair()) * 3;
  }
  frame.positions.resize(floats[0] + floats[1]);
  frame.normals.resize(floats[0] + floats[1]);
  std::size_t offset = 0;
  for (int c = 0; c < kCoatCount; ++c) {
    const auto ci = static_cast<std::size_t>(c);
    HairBuffers& hb = frame.coats[ci];
    hb.positions = {frame.positions.data() + offset, floats[ci]};
    hb.normals = {frame.normals.data() + offset, floats[ci]};
    offset += floats[ci];
    const auto n = static_cast<std::size_t>(roots.coats[ci].size());
    if (hb.hairIds.size() != n) hb.hairIds.resize(n);
    hb.drawn = 0;
  }
}

namespace {

// Packs position, fur length, normal and segment direction of every vertex into 48-byte records,
// so a hair's three vertices are three contiguous reads.
void packVertices(const skin::SkinMesh& skin, const float* len, const skin::DeformedSkin& d,
                  std::vector<float>& out) {
  const std::int64_t nV = skin.numVertices();
  if (out.size() != static_cast<std::size_t>(nV * kVertexRecordFloats))
    out.resize(static_cast<std::size_t>(nV * kVertexRecordFloats));
  float* o = out.data();
  parallelForChunks(nV, 8192, [&](std::int64_t b, std::int64_t e) {
    for (std::int64_t v = b; v < e; ++v) {
      float* r = o + v * kVertexRecordFloats;
      const auto sv = static_cast<std::size_t>(v);
      r[0] = d.positions[sv].x();
      r[1] = d.positions[sv].y();
      r[2] = d.positions[sv].z();
      r[3] = len[v];
      r[4] = d.normals[sv].x();
      r[5] = d.normals[sv].y();
      r[6] = d.normals[sv].z();
      r[7] = 0.0f;
      r[8] = d.directions[sv].x();
      r[9] = d.directions[sv].y();
      r[10] = d.directions[sv].z();
      r[11] = 0.0f;
    }
  });
}

void ensureTwist(const FurParams& params, int coat, std::uint64_t seed, FurWorkspace& ws) {
  const auto c = static_cast<std::size_t>(coat);
  const float r = params.coats[c].normalRandomize;
  if (ws.twistAmount[c] == r && ws.twistSeed[c] == seed && !ws.twist[c].empty()) return;
  makeTwistTable(seed, r, ws.twist[c]);
  ws.twistAmount[c] = r;
  ws.twistSeed[c] = seed;
}

// Writes a hair's points (P x 3) to a flat array; the normals are not needed.
struct PointSink {
  float* positions;
  void operator()(int i, const Vec3<float>& p, const Vec3<float>&) {
    positions[3 * i] = p.x;
    positions[3 * i + 1] = p.y;
    positions[3 * i + 2] = p.z;
  }
};

// The polyline twist of the hair using table entry `entry` (sec. 3.7), from a coat's twist table.
HairTwist<float> twistOf(const std::vector<float>& table, int entry) {
  HairTwist<float> twist{};
  for (int i = 0; i < kPolylinePoints; ++i) {
    twist.cosAngle[i] = table[static_cast<std::size_t>(16 * entry + 2 * i)];
    twist.sinAngle[i] = table[static_cast<std::size_t>(16 * entry + 2 * i + 1)];
  }
  return twist;
}

// A hair's strand points (K x 3) from its points (K x M x 3): the points themselves (M = 1), or
// each ring's centre, the mean of its M points in order.
void strandPointsOf(const float* points, int K, int M, float* out) {
  for (int k = 0; k < K; ++k)
    for (int a = 0; a < 3; ++a) {
      float sum = 0.0f;
      for (int m = 0; m < M; ++m) sum += points[3 * (k * M + m) + a];
      out[3 * k + a] = M == 1 ? sum : sum / static_cast<float>(M);
    }
}

// Moves a hair's points (K x M x 3) toward its clump centre's strand points `centre` (K x 3):
// every point of ring k by scale s_k (C_k - S_k), S_k the hair's own strand point (strandPointsOf),
// scale the groom's clump scale at the root (1 without).
void addClump(const std::array<float, kMaxCurvePoints>& w, float scale, int K, int M,
              const float* centre, float* points) {
  float own[3 * kMaxCurvePoints];
  strandPointsOf(points, K, M, own);
  for (int k = 1; k < K; ++k) {  // s_0 = 0: the root stays
    const float wk = w[static_cast<std::size_t>(k)] * scale;
    const float o[3] = {wk * (centre[3 * k] - own[3 * k]),
                        wk * (centre[3 * k + 1] - own[3 * k + 1]),
                        wk * (centre[3 * k + 2] - own[3 * k + 2])};
    for (int m = 0; m < M; ++m)
      for (int a = 0; a < 3; ++a) points[3 * (k * M + m) + a] += o[a];
  }
}

// This frame's strand points of every clump centre of coat `coat` (unclumped, no frizz) into
// ws.clumpCentres: each centre hair as referenceHair computes it (rootInput, buildHair).
void computeClumpCentres(const skin::SkinMesh& skin, const FurRoots& roots,
                         const skin::DeformedSkin& deformed, int coat, const CoatShape& shape,
                         const HairLayout& layout, const detail::CoatDynamicsArgs* dynamics,
                         FurWorkspace& ws) {
  // With dynamics the centres take their dynamic ends from the state, already stepped.
  PELAGE_CHECK(!dynamics || !dynamics->update, "clump centres from an unstepped dynamics state");
  const auto ci = static_cast<std::size_t>(coat);
  const CoatRoots& cr = roots.coats[ci];
  const int K = layout.strandPoints, M = layout.ringSides;
  std::vector<float>& out = ws.clumpCentres[ci];
  out.resize(cr.clumpCentres.size() * static_cast<std::size_t>(3 * K));
  parallelForChunks(
      static_cast<std::int64_t>(cr.clumpCentres.size()), 256, [&](std::int64_t b, std::int64_t e) {
        std::vector<float> points(static_cast<std::size_t>(3 * shape.points));
        for (std::int64_t s = b; s < e; ++s) {
          const std::int32_t root = cr.clumpCentres[static_cast<std::size_t>(s)];
          const HairTwist<float> twist =
              shape.twist ? twistOf(ws.twist[ci], cr.tableIndex[static_cast<std::size_t>(root)])
                          : HairTwist<float>{};
          PointSink sink{points.data()};
          HairFrame<float> f;
          hairFrame(shape, rootInput(skin, roots, deformed, coat, root), f);
          if (dynamics) detail::dynamicEnds(shape, *dynamics, &root, 1, f);
          emitHair(shape, f, twist, sink);
          strandPointsOf(points.data(), K, M, out.data() + s * 3 * K);
        }
      });
}

}  // namespace

std::array<float, kMaxCurvePoints> clumpWeights(const Clump& clump, int K) {
  std::array<float, kMaxCurvePoints> w{};
  for (int k = 0; k < K; ++k)
    w[static_cast<std::size_t>(k)] =
        static_cast<float>(static_cast<double>(clump.strength) *
                           std::pow(k / double(K - 1), static_cast<double>(clump.shape)));
  return w;
}

bool coatClumps(const FurParams& params, const FurRoots& roots, int coat) {
  const auto ci = static_cast<std::size_t>(coat);
  return params.coats[ci].clump.on() && !roots.coats[ci].clumpSlot.empty();
}

void generateClumpCentres(const skin::SkinMesh& skin, const FurRoots& roots,
                          const FurParams& params, const skin::DeformedSkin& deformed,
                          FurWorkspace& ws) {
  PELAGE_CHECK(roots.triangleCount == skin.numTriangles(), "roots grown on ", roots.triangleCount,
               " triangles, skin has ", skin.numTriangles());
  for (int c = 0; c < kCoatCount; ++c) {
    const auto ci = static_cast<std::size_t>(c);
    if (!coatClumps(params, roots, c)) {
      ws.clumpCentres[ci].clear();
      continue;
    }
    const CoatShape shape = makeCoatShape(params, roots, c);
    if (shape.twist) ensureTwist(params, c, coatSeed(roots.seed, c), ws);
    computeClumpCentres(skin, roots, deformed, c, shape, coatLayout(params, roots, c), nullptr, ws);
  }
}

void generateFur(const skin::SkinMesh& skin, const FurRoots& roots, const FurParams& params,
                 const skin::DeformedSkin& deformed, const FurView& view, FurWorkspace& ws,
                 FurFrame& frame) {
  detail::generateFurWithDynamics(skin, roots, params, deformed, view, ws, frame,
                                  {nullptr, nullptr}, true);
}

void detail::generateFurWithDynamics(
    const skin::SkinMesh& skin, const FurRoots& roots, const FurParams& params,
    const skin::DeformedSkin& deformed, const FurView& view, FurWorkspace& ws, FurFrame& frame,
    const std::array<const CoatDynamicsArgs*, kCoatCount>& dynamics, bool emit) {
  PELAGE_CHECK(roots.triangleCount == skin.numTriangles(), "roots grown on ", roots.triangleCount,
               " triangles, skin has ", skin.numTriangles());
  PELAGE_CHECK(deformed.positions.size() == static_cast<std::size_t>(skin.numVertices()) &&
                   deformed.normals.size() == deformed.positions.size() &&
                   deformed.directions.size() == deformed.positions.size(),
               "deformed skin does not match the skin");
  bool sized = true;
  for (int c = 0; c < kCoatCount; ++c) {
    const HairBuffers& hb = frame.coats[static_cast<std::size_t>(c)];
    sized = sized && hb.layout == coatLayout(params, roots, c) &&
            hb.hairIds.size() ==
                static_cast<std::size_t>(roots.coats[static_cast<std::size_t>(c)].size());
  }
  if (!sized && emit) prepareFurFrame(roots, params, frame);
  packVertices(skin, roots.lengths(skin), deformed, ws.vertexRecords);
  const float factor = emit ? cullingFactor(view) : 1.0f;
  if (emit) frame.cullingFactor = factor;
  for (int c = 0; c < kCoatCount; ++c) {
    const auto ci = static_cast<std::size_t>(c);
    const CoatRoots& cr = roots.coats[ci];
    if (!emit && !dynamics[ci]) continue;
    HairBuffers& hb = frame.coats[ci];
    const std::uint64_t seed = coatSeed(roots.seed, c);
    const CoatShape shape = makeCoatShape(params, roots, c);
    if (shape.twist) ensureTwist(params, c, seed, ws);
    std::int64_t drawn = cr.size();
    const std::int32_t* drawnStart = cr.triangleStart.data();
    if (factor > 1.0f) {
      drawn = computeDrawnStart(cr, seed, factor, ws.drawnStart[ci]);
      drawnStart = ws.drawnStart[ci].data();
    }
    if (emit) {
      hb.drawn = drawn;
      if (cr.widthScale.empty())
        hb.widthScales.clear();
      else
        hb.widthScales.resize(static_cast<std::size_t>(drawn));
    }
    if (drawn == 0) continue;
    detail::CoatKernelArgs a;
    a.shape = &shape;
    a.vertices = ws.vertexRecords.data();
    a.triangles = skin.triangles.data();
    a.triangleStart = cr.triangleStart.data();
    a.drawnStart = drawnStart;
    a.triangleCount = roots.triangleCount;
    a.allDrawn = drawnStart == cr.triangleStart.data();
    a.rootTriangle = cr.triangle.data();
    a.tableIndex = cr.tableIndex.data();
    a.jitter = cr.jitter.data();
    a.lengthScale = cr.lengthScale.empty() ? nullptr : cr.lengthScale.data();
    a.comb = cr.comb.empty() ? nullptr : cr.comb.data();
    a.floppiness = cr.floppiness.empty() ? nullptr : cr.floppiness.data();
    a.segmentWeight = cr.segmentWeight.empty() ? nullptr : cr.segmentWeight.data();
    a.curlRadius = cr.curlRadius.empty() ? nullptr : cr.curlRadius.data();
    a.curlTurns = cr.curlTurns.empty() ? nullptr : cr.curlTurns.data();
    a.widthScale = shape.perHairWidth ? cr.widthScale.data() : nullptr;
    a.barycentric = roots.barycentric.data();
    a.twist = shape.twist ? ws.twist[ci].data() : nullptr;
    a.positions = emit ? hb.positions.data() : nullptr;
    a.normals = emit ? hb.normals.data() : nullptr;
    a.hairIds = emit ? hb.hairIds.data() : nullptr;
    a.dynamics = dynamics[ci];
    a.emit = emit;
    const double bytes = static_cast<double>(drawn) * shape.points * 24.0;
    // Streaming needs 16-byte aligned rows of 4 floats: P a multiple of 4 (a hair's 3 P floats are
    // whole rows) or lines (4 lines' 24 floats are six rows), and coat 1's arrays start where coat
    // 0's end: only at a 64-byte boundary.
    const auto aligned = [](const float* p) {
      return reinterpret_cast<std::uintptr_t>(p) % 64 == 0;
    };
    const Clump& clump = params.coats[ci].clump;
    // With dynamics, generateDynamicFur steps the state before drawing a fur that clumps.
    const bool clumps = emit && coatClumps(params, roots, c);
    std::array<float, kMaxCurvePoints> clumpW{};
    if (clumps) {
      computeClumpCentres(skin, roots, deformed, c, shape, hb.layout, dynamics[ci], ws);
      clumpW = clumpWeights(clump, hb.layout.strandPoints);
    }
    // Not with frizz or clumps: they read the points back at once.
    a.streamStores = emit && !shape.frizz && !clumps &&
                     (shape.points % 4 == 0 || shape.style == HairStyle::Line) &&
                     bytes > kStreamStoreBytes && aligned(a.positions) && aligned(a.normals);
    parallelForChunks(drawn, kHairsPerTask, [&](std::int64_t b, std::int64_t e) {
      detail::runCoatRange(a, b, e);
      if (emit && !cr.widthScale.empty())
        for (std::int64_t h = b; h < e; ++h)
          hb.widthScales[static_cast<std::size_t>(h)] =
              cr.widthScale[static_cast<std::size_t>(a.hairIds[h])];
      if (clumps)
        for (std::int64_t h = b; h < e; ++h) {
          const auto r = static_cast<std::size_t>(a.hairIds[h]);
          const std::int32_t slot = cr.clumpSlot[r];
          if (slot < 0 || cr.clumpCentres[static_cast<std::size_t>(slot)] == a.hairIds[h]) continue;
          const int K = hb.layout.strandPoints;
          addClump(clumpW, cr.clumpScale.empty() ? 1.0f : cr.clumpScale[r], K, hb.layout.ringSides,
                   ws.clumpCentres[ci].data() + static_cast<std::size_t>(slot) * 3 * K,
                   a.positions + h * shape.points * 3);
        }
      if (emit && shape.frizz)
        for (std::int64_t h = b; h < e; ++h)
          addFrizz(shape, static_cast<std::uint32_t>(a.hairIds[h]),
                   a.positions + h * shape.points * 3);
    });
  }
}

namespace {
struct VectorSink {
  std::vector<float>& positions;
  std::vector<float>& normals;
  void operator()(int i, const Vec3<float>& p, const Vec3<float>& n) {
    const auto o = static_cast<std::size_t>(3 * i);
    positions[o] = p.x;
    positions[o + 1] = p.y;
    positions[o + 2] = p.z;
    normals[o] = n.x;
    normals[o + 1] = n.y;
    normals[o + 2] = n.z;
  }
};
}  // namespace

HairInput<float> rootInput(const skin::SkinMesh& skin, const FurRoots& roots,
                           const skin::DeformedSkin& deformed, int coat, std::int64_t rootIndex) {
  const CoatRoots& cr = roots.coats[static_cast<std::size_t>(coat)];
  PELAGE_CHECK(rootIndex >= 0 && rootIndex < cr.size(), "root ", rootIndex, " of ", cr.size());
  const auto r = static_cast<std::size_t>(rootIndex);
  const std::int32_t* tv = skin.triangles.data() + 3 * static_cast<std::int64_t>(cr.triangle[r]);
  const float* len = roots.lengths(skin);
  float records[3][kVertexRecordFloats];
  for (int k = 0; k < 3; ++k) {
    const auto v = static_cast<std::size_t>(tv[k]);
    const Eigen::Vector3f& p = deformed.positions[v];
    const Eigen::Vector3f& n = deformed.normals[v];
    const Eigen::Vector3f& s = deformed.directions[v];
    float* rec = records[k];
    rec[0] = p.x(), rec[1] = p.y(), rec[2] = p.z(), rec[3] = len[v];
    rec[4] = n.x(), rec[5] = n.y(), rec[6] = n.z(), rec[7] = 0.0f;
    rec[8] = s.x(), rec[9] = s.y(), rec[10] = s.z(), rec[11] = 0.0f;
  }
  const float curlValues[2] = {cr.curlRadius.empty() ? 0.0f : cr.curlRadius[r],
                               cr.curlTurns.empty() ? 0.0f : cr.curlTurns[r]};
  const float* curl = cr.curlRadius.empty() ? nullptr : curlValues;
  return interpolateRoot(
      roots.barycentric.data() + 4 * cr.tableIndex[r], records[0], records[1], records[2],
      cr.jitter.data() + 4 * r, cr.lengthScale.empty() ? 1.0f : cr.lengthScale[r],
      cr.comb.empty() ? 0u : cr.comb[r], cr.floppiness.empty() ? 0.0f : cr.floppiness[r],
      cr.segmentWeight.empty() ? 0.0f : cr.segmentWeight[r], curl,
      cr.widthScale.empty() ? 1.0f : cr.widthScale[r]);
}

void referenceHair(const skin::SkinMesh& skin, const FurRoots& roots, const FurParams& params,
                   const skin::DeformedSkin& deformed, int coat, std::int64_t rootIndex,
                   std::vector<float>& positions, std::vector<float>& normals) {
  const auto ci = static_cast<std::size_t>(coat);
  const CoatRoots& cr = roots.coats[ci];
  const CoatShape shape = makeCoatShape(params, roots, coat);
  std::vector<float> table;
  if (shape.twist)
    makeTwistTable(coatSeed(roots.seed, coat), params.coats[ci].normalRandomize, table);
  const auto paperHair = [&](std::int64_t root, std::vector<float>& p, std::vector<float>& n) {
    const HairInput<float> in = rootInput(skin, roots, deformed, coat, root);
    const HairTwist<float> twist =
        shape.twist ? twistOf(table, cr.tableIndex[static_cast<std::size_t>(root)])
                    : HairTwist<float>{};
    p.assign(static_cast<std::size_t>(3 * shape.points), 0.0f);
    n.assign(static_cast<std::size_t>(3 * shape.points), 0.0f);
    VectorSink sink{p, n};
    buildHair(shape, in, twist, sink);
  };
  paperHair(rootIndex, positions, normals);
  // Clumping: toward the centre hair's strand points, computed the same way.
  const Clump& clump = params.coats[ci].clump;
  const std::int32_t slot =
      cr.clumpSlot.empty() ? -1 : cr.clumpSlot[static_cast<std::size_t>(rootIndex)];
  if (coatClumps(params, roots, coat) && slot >= 0 &&
      cr.clumpCentres[static_cast<std::size_t>(slot)] != rootIndex) {
    const HairLayout layout = coatLayout(params, roots, coat);
    const int K = layout.strandPoints;
    std::vector<float> p, n, centre(static_cast<std::size_t>(3 * K));
    paperHair(cr.clumpCentres[static_cast<std::size_t>(slot)], p, n);
    strandPointsOf(p.data(), K, layout.ringSides, centre.data());
    const float scale =
        cr.clumpScale.empty() ? 1.0f : cr.clumpScale[static_cast<std::size_t>(rootIndex)];
    addClump(clumpWeights(clump, K), scale, K, layout.ringSides, centre.data(), positions.data());
  }
  if (shape.frizz) addFrizz(shape, static_cast<std::uint32_t>(rootIndex), positions.data());
}

}  // namespace pelage::fur
