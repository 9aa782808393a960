// Hair roots (Van Gelder & Wilhelms 1997, sec. 3.2): how many hairs each skin triangle gets and
// where on the triangle they grow. Constant model: grown once for a skin and a FurParams' count,
// share and seed; read-only during playback.
#pragma once

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "pelage/fur/fur_params.h"
#include "pelage/fur/groom.h"
#include "pelage/skin/skin_mesh.h"

namespace pelage::fur {

// Sec. 3.2: "a table of 2048 random triplets of barycentric coordinates (b1, b2, b3)".
inline constexpr int kBarycentricTableSize = 2048;

// The shared barycentric table: entry j = (b1, b2, b3, 0) with b1 = 1 - sqrt(u1),
// b2 = (1 - b1) u2, b3 = 1 - b1 - b2, u1 = uniform01(seed, kStreamBarycentricTable, 2 j),
// u2 = uniform01(seed, kStreamBarycentricTable, 2 j + 1). Row-major kBarycentricTableSize x 4.
std::vector<float> makeBarycentricTable(std::uint64_t seed);

// The roots of one coat in creation order, grouped by triangle (roots of triangle t are
// [triangleStart[t], triangleStart[t + 1])), so culling can draw a per-triangle prefix.
struct CoatRoots {
  std::vector<std::int32_t> triangleStart;  // nT + 1 (CSR offsets)
  std::vector<std::int32_t> triangle;       // nRoots: the root's triangle
  std::vector<std::uint16_t> tableIndex;    // nRoots: index into the barycentric table
  // nRoots x 4: (xi.x, xi.y, xi.z, phase). xi is uniform in the unit ball (hair end randomize,
  // sec. 3.5) from uniform01(coatSeed, kStreamHairEnd, 3 k + {0, 1, 2}); phase in [0, 1) (helix
  // start angle, in turns) from uniform01(coatSeed, kStreamHairEnd + kPhaseStreamOffset, k).
  std::vector<float> jitter;
  // nRoots: the length map's value at the root (multiplies its interpolated length, sec. 3.2);
  // empty without a length map.
  std::vector<float> lengthScale;
  // nRoots: the groom's comb at the root (groom.h), interpolated from its triangle's vertices at
  // rest and packed in the root's tangent frame (hair_math.h packComb); empty without a comb.
  std::vector<std::uint32_t> comb;
  // Clumping (fur_params.h Clump; assignClumps): the clump centres as root indices, ascending, and
  // per root the index into clumpCentres of its clump's centre (-1: in no clump; a centre is in
  // its own). Both empty when the coat does not clump.
  std::vector<std::int32_t> clumpCentres;
  std::vector<std::int32_t> clumpSlot;
  // nRoots: the groom's clump scale at the root (groom.h; sum b_i clump_i of its triangle's
  // vertices), multiplying the coat's clump strength; empty without one or without clumping.
  std::vector<float> clumpScale;
  // nRoots: the hair's floppiness (sec. 3.5) from the groom's per-vertex stiffness of this coat
  // interpolated at the root at rest (groom.h VertexGroom::stiffness); empty without one (the
  // coat's floppiness for every hair).
  std::vector<float> floppiness;
  // nRoots: the hair's segment direction weight w (sec. 3.4) from the groom's per-vertex weights
  // of this coat interpolated at the root at rest (VertexGroom::segmentDirectionWeight); empty
  // without them (the coat's w for every hair).
  std::vector<float> segmentWeight;
  // nRoots each: the hair's helix radius (a fraction of its length) and turns (sec. 3.8) from the
  // groom's per-vertex curl of this coat interpolated at the root at rest (VertexGroom::curlRadius,
  // ::curlTurns; the coat's value where the groom has only the other); empty without either (the
  // coat's helix for every hair).
  std::vector<float> curlRadius, curlTurns;
  // nRoots: the multiple of the coat's hair width (StrandWidth) the hair is drawn, exported and
  // (tubes) grown at, the groom's per-vertex width scale of this coat interpolated at the root at
  // rest (VertexGroom::widthScale); empty without one (the coat's width for every hair).
  std::vector<float> widthScale;
  double expectedHairs = 0.0;  // N_coat, before random rounding
  std::int64_t size() const { return static_cast<std::int64_t>(triangle.size()); }
};

struct FurRoots {
  std::array<CoatRoots, kCoatCount> coats;
  std::vector<float> barycentric;  // kBarycentricTableSize x 4, shared by both coats
  std::int32_t triangleCount = 0;  // of the skin they were grown on
  double furredArea = 0.0;         // m^2: rest area of triangles with some fur
  std::uint64_t seed = 0;
  // nV: the fur length at each skin vertex (metres) when a groom set them (fur/groom.h), which the
  // hairs interpolate in place of the skin's (sec. 3.2); empty: the skin's.
  std::vector<float> vertexLength;
  // The fur lengths the hairs interpolate: vertexLength, or the skin's.
  const float* lengths(const skin::SkinMesh& skin) const {
    return vertexLength.empty() ? skin.furLengths() : vertexLength.data();
  }
  std::int64_t total() const { return coats[0].size() + coats[1].size(); }
};

// The seed of one coat's random streams: the base seed for the overcoat, a mix of it for the
// undercoat, so the coats never share random numbers.
std::uint64_t coatSeed(std::uint64_t seed, int coat);

// Offset added to kStreamHairEnd for the helix phase stream.
inline constexpr std::uint64_t kPhaseStreamOffset = 64;

// Total N from the params: `hairs`, or density * furredArea.
double requestedHairs(const FurParams& params, double furredArea);

// Bytes the roots and the hair buffers of both coats take for `hairs` hairs (for the up-front
// refusal of absurd counts).
double estimateFurBytes(const FurParams& params, double hairs);

// Throws InputError if the requested count is outside [0, kMaxHairs] or needs more than
// kMaxFurBytes, with the memory estimate in the message (e.g. "2e+10 hairs need 4.4 TB").
void checkHairBudget(const FurParams& params, double furredArea);

// Grows the roots of both coats on `skin` (rest-pose areas):
// Van Gelder & Wilhelms 1997, sec. 3.2: triangle t gets floor(alpha_t N_c + u_t) hairs, alpha_t the
// triangle's fraction of the furred skin area, u_t = uniform01(coatSeed, kStreamAllocation, t)
// ("random rounding"). Triangles whose three vertex fur lengths are 0 get none and do not count
// in the area. Coat c's roots cycle through the table: root k uses entry k mod 2048.
// With a density map (maps.density), alpha_t is the triangle's share of the furred area weighted
// by the map's mean over it (sampled at the centroids of its 4^L sub-triangles, L from its size in
// texels), so the total stays N and random rounding still holds; inside the triangle, candidate
// table entries (k mod 2048 onwards) are accepted with probability density / the triangle's
// sampled maximum (u = uniform01(coatSeed, kStreamDensity, t 2^20 + attempt)), so no root grows
// where the map is zero. With a length map, each root keeps the map's value at its point.
// The groom's vertex values (fur/groom.h): its lengths replace the skin's (which triangles carry
// fur, and each hair's interpolated length), and alpha_t is further weighted by the mean of the
// triangle's three vertex densities. Calls checkHairBudget first.
FurRoots growRoots(const skin::SkinMesh& skin, const FurParams& params, const Groom& groom = {});

// Clumping (fur_params.h Clump), at rest: space is cut into cubes of side a = 1 cm /
// sqrt(density); in each cube holding roots, the root of least priority u_k = uniform01(coatSeed,
// kStreamClump, k) (ties: the lower index) is a clump centre, so there are about `density` clumps
// per cm^2 of skin; each root joins the nearest centre (ties: the lower index) among those of its
// own cube and the 26 around it, if within the radius. Fills cr.clumpCentres and cr.clumpSlot
// (cleared when the coat does not clump). Called by growRoots; deterministic, thread-independent.
void assignClumps(const skin::SkinMesh& skin, const std::vector<float>& barycentric,
                  std::uint64_t coatSeed, const Clump& clump, CoatRoots& cr);
// A root's rest position: its table entry's barycentric point on its triangle in the rest pose.
Eigen::Vector3f restRootPosition(const skin::SkinMesh& skin, const std::vector<float>& barycentric,
                                 const CoatRoots& cr, std::int64_t k);
// Rest-pose area of each triangle (m^2), nT.
std::vector<double> triangleAreas(const skin::SkinMesh& skin);

// Whether triangle t carries fur (some vertex fur length > 0), with the vertex lengths `lengths`
// (nV; the skin's or a groom's).
bool triangleHasFur(const skin::SkinMesh& skin, const float* lengths, std::int32_t t);

// A groom's density weight of the triangle with vertices v[0..2]: the mean of their densities
// (`density`, nV), by which growRoots multiplies the triangle's share of the hairs.
inline float triangleDensity(const std::vector<float>& density, const std::int32_t* v) {
  return (density[static_cast<std::size_t>(v[0])] + density[static_cast<std::size_t>(v[1])] +
          density[static_cast<std::size_t>(v[2])]) /
         3.0f;
}

}  // namespace pelage::fur
