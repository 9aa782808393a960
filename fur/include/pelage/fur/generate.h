// Per-frame fur: from the deformed skin and the constant roots to GPU-ready hair buffers
// (Van Gelder & Wilhelms 1997, sec. 4: "We do not normally explicitly store information about
// individual hairs ... recalculating the fur from scratch"). The per-hair maths is in hair_math.h;
// this runs it for every drawn hair, in parallel, into preallocated memory.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <new>
#include <string>
#include <vector>

#include "pelage/fur/culling.h"
#include "pelage/fur/fur_params.h"
#include "pelage/fur/hair_layout.h"
#include "pelage/fur/hair_math.h"
#include "pelage/fur/roots.h"
#include "pelage/skin/deform.h"
#include "pelage/skin/skin_mesh.h"

namespace pelage::fur {

// A float array aligned to 64 bytes (streaming SIMD stores), not zeroed on resize.
class FloatBuffer {
 public:
  FloatBuffer() = default;
  FloatBuffer(FloatBuffer&&) noexcept = default;
  FloatBuffer& operator=(FloatBuffer&&) noexcept = default;
  // Makes room for n floats, keeping nothing; allocates only when n exceeds the capacity.
  void resize(std::size_t n);
  float* data() { return data_.get(); }
  const float* data() const { return data_.get(); }
  std::size_t size() const { return size_; }

 private:
  struct Free {
    void operator()(float* p) const { ::operator delete[](p, std::align_val_t(64)); }
  };
  std::unique_ptr<float[], Free> data_;
  std::size_t size_ = 0;
  std::size_t capacity_ = 0;
};

// A view of floats in a FloatBuffer (non-owning).
struct FloatSpan {
  float* begin = nullptr;
  std::size_t count = 0;
  float* data() { return begin; }
  const float* data() const { return begin; }
  std::size_t size() const { return count; }
};

// One coat's hairs for one frame, laid out as `layout` says (hair_layout.h): hair i (i < drawn)
// has P = layout.pointsPerHair() points, at [i * P, (i + 1) * P) in `positions` and `normals`, each
// point 3 floats (x, y, z), world metres; `hairIds[i]` is the hair's index into the coat's roots
// (CoatRoots). Point 0 is the root. Shading normals: line and curve repeat the skin normal;
// polyline has one per point (sec. 3.7); tube points are ring points with radial normals (point
// k * M + j: ring k, direction j). The arrays are views into the FurFrame's.
struct HairBuffers {
  HairLayout layout;
  std::int64_t drawn = 0;
  FloatSpan positions;                // (capacity * P) x 3
  FloatSpan normals;                  // (capacity * P) x 3
  std::vector<std::int32_t> hairIds;  // capacity
  // Per drawn hair, its root and tip colour (fur/colors.h packing: 2 per hair), filled by
  // fillHairColors when the coat's hairs have colours of their own; empty otherwise.
  std::vector<std::uint32_t> colors;
  // Per drawn hair, its width scale (CoatRoots::widthScale through hairIds: a groom's), filled by
  // generateFur where the coat's roots carry one; empty otherwise (every hair the coat's width).
  std::vector<float> widthScales;
  // Drawn hair i's width scale: widthScales[i], or 1.
  float widthScaleOf(std::int64_t i) const {
    return widthScales.empty() ? 1.0f : widthScales[static_cast<std::size_t>(i)];
  }
};

// One frame's hairs, both coats in one allocation: coat 0's roots, then coat 1's (each coat's slots
// for all its roots). Without culling every root is drawn, so the two coats' hairs are one
// contiguous array (what the Python package hands out as a single numpy view).
struct FurFrame {
  std::array<HairBuffers, kCoatCount> coats;
  FloatBuffer positions;  // sum over coats of (roots * P) x 3
  FloatBuffer normals;
  float cullingFactor = 1.0f;
  std::int64_t drawn() const { return coats[0].drawn + coats[1].drawn; }
};

// Per-frame scratch kept between frames: packed vertex records, drawn-hair offsets, the twist
// tables. Sized on first use.
struct FurWorkspace {
  std::vector<float> vertexRecords;  // nV x 12: position, fur length, normal, 0, direction, 0
  std::array<std::vector<std::int32_t>, kCoatCount> drawnStart;  // nT + 1 each, when culling
  // Polyline normal twist (sec. 3.7), per coat kBarycentricTableSize x 8 x (cos, sin):
  // entry (j, i) rotates point i of hairs using table entry j by r pi (2u - 1),
  // u = uniform01(coatSeed, kStreamNormal, 8 j + i).
  std::array<std::vector<float>, kCoatCount> twist;
  std::array<float, kCoatCount> twistAmount{-1.0f, -1.0f};
  std::array<std::uint64_t, kCoatCount> twistSeed{0, 0};
  // Clumping: per coat, this frame's strand points (K x 3) of each clump centre hair
  // (CoatRoots::clumpCentres order), unclumped and without frizz.
  std::array<std::vector<float>, kCoatCount> clumpCentres;
};

// Fills `table` (2048 x 8 x 2) with the polyline twist (cos, sin) of coat seed `seed` and normal
// randomize r.
void makeTwistTable(std::uint64_t seed, float normalRandomize, std::vector<float>& table);

// Sizes `frame` for every root of `roots` being drawn (the most a frame can draw). Allocates.
void prepareFurFrame(const FurRoots& roots, const FurParams& params, FurFrame& frame);

// Computes one frame of fur: for each coat, the drawn hairs (culling, sec. 3.3) and their points
// and normals (sec. 3.2 to 3.8). `roots` must have been grown on `skin` with `params`' count, share
// and seed; `params` validated. Parallel over hairs (util/parallel.h threads); the output is
// bit-identical whatever the thread count and whichever SIMD path runs. Allocates only on the first
// call (or when the roots or styles change size); never throws for valid inputs.
void generateFur(const skin::SkinMesh& skin, const FurRoots& roots, const FurParams& params,
                 const skin::DeformedSkin& deformed, const FurView& view, FurWorkspace& workspace,
                 FurFrame& frame);

// Clumping (fur_params.h Clump): the weight s_k = strength t_k^shape of strand point k of K, the
// share of the way toward its clump centre's strand point that point k of a clumped hair moves.
std::array<float, kMaxCurvePoints> clumpWeights(const Clump& clump, int K);

// Whether coat `coat` clumps: its Clump is on and its roots were assigned to clumps (growRoots
// with that clump density and radius). The one test of the CPU kernel path, referenceHair,
// generateClumpCentres and the GPU.
bool coatClumps(const FurParams& params, const FurRoots& roots, int coat);

// Clumping where the hairs are built elsewhere (render::GpuFur): this frame's strand points (K x
// 3) of every clump centre hair of each coat that clumps, into workspace.clumpCentres, exactly as
// generateFur computes them (unclumped, no frizz); the vectors of coats that do not clump are
// cleared. The hairs of a clump then move toward them by clumpWeights (generateFur's rule).
void generateClumpCentres(const skin::SkinMesh& skin, const FurRoots& roots,
                          const FurParams& params, const skin::DeformedSkin& deformed,
                          FurWorkspace& workspace);

// The kernel's SIMD targets (Google Highway, e.g. "AVX3", "AVX2", "SSE4", "SSSE3", "NEON",
// "SCALAR") that this CPU runs, best first; generateFur uses the first unless one is forced. All
// give bit-identical output.
std::vector<std::string> kernelTargets();
// Forces one of kernelTargets() for the whole process (tests and benchmarks compare them); "auto"
// or "" returns to the best. False (and nothing changes) for a name not in kernelTargets().
bool setKernelTarget(const std::string& name);
// The target generateFur uses now.
std::string activeKernelTarget();

// Sec. 3.2: the inputs of root `rootIndex` of coat `coat` interpolated on the deformed skin
// (interpolateRoot of hair_math.h on its triangle's vertex records).
HairInput<float> rootInput(const skin::SkinMesh& skin, const FurRoots& roots,
                           const skin::DeformedSkin& deformed, int coat, std::int64_t rootIndex);

// One hair computed with the scalar reference (hair_math.h with T = float), for tests and GPU
// parity: root `rootIndex` of `coat`, P points into positions/normals (P x 3 each).
void referenceHair(const skin::SkinMesh& skin, const FurRoots& roots, const FurParams& params,
                   const skin::DeformedSkin& deformed, int coat, std::int64_t rootIndex,
                   std::vector<float>& positions, std::vector<float>& normals);

}  // namespace pelage::fur
