// The groom: what shapes the fur over the skin beyond the preset's per-coat values. Two kinds:
//  - maps: images on the skin's UV layout (as Maya XGen's density and length maps, Blender's
//  density
//    masks), sampled at each root's texture coordinates (the root's barycentric point, sec. 3.2);
//  - vertex values: per skin vertex, so they need no UVs (most glTF creatures have none), from the
//    preset's regions (fur_params.h FurRegion) resolved on the creature.
// Read once per fur; constant during playback.
#pragma once

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "pelage/anatomy/body.h"
#include "pelage/fur/fur_params.h"
#include "pelage/skin/skin_mesh.h"
#include "pelage/skin/texture.h"

namespace pelage::fur {

// The ranges of the per-vertex values (groom files, strokes): length in metres, density scale,
// tint per channel.
inline constexpr float kMaxGroomLengthMeters = 10.0f;
inline constexpr float kMaxGroomDensity = 100.0f;
inline constexpr float kMaxGroomTint = 10.0f;
// |comb|^2 at most 1, with room for a float's rounding of a unit vector.
inline constexpr float kMaxCombLength2 = 1.0f + 1e-5f;

// Per-vertex groom values; each array has one entry per skin vertex, or is empty (neutral).
//  length: the fur length at the vertex (metres), replacing the skin's (Van Gelder & Wilhelms 1997,
//    sec. 3.2: a hair's length is interpolated from its triangle's vertex lengths); 0 grows none.
//  density: multiplies the hairs a triangle gets by the mean of its three vertices' values (>= 0).
//  tint: multiplies each hair's colour (linear RGB, interpolated at the root).
//  comb: the combed direction times the comb amount a in [0, 1] (|comb| <= 1), rest pose, in the
//    skin's tangent plane; a hair's weightless direction d (sec. 3.4) turns toward it:
//    d' = normalize((1 - a) d + a t), t the comb's direction carried with the skin (roots.h).
//    Gravity (sec. 3.5) still applies. 0: not combed (d exactly).
//  clump: multiplies each coat's clump strength (fur_params.h Clump) at the vertex, [0, 1]
//    (interpolated at the root at rest); 0: that hair stays out of its clump. Only where the coat
//    clumps.
//  stiffness: each coat's stiffness at the vertex (overcoat, undercoat), [0, 1], replacing the
//    coat's: a hair's floppiness (sec. 3.5) is floppiness() of the stiffness interpolated at its
//    root at rest (roots.h CoatRoots::floppiness), so gravity bends it as a coat of that stiffness.
//  segmentDirectionWeight: each coat's segment direction weight w at the vertex (overcoat,
//    undercoat), [0, 1], replacing the coat's: a hair's weightless direction (sec. 3.4)
//    d = normalize((1 - w) n + w s) takes the w interpolated at its root at rest
//    (CoatRoots::segmentWeight).
//  curlRadius, curlTurns: each coat's helix at the vertex (overcoat, undercoat), radius [0, 0.5]
//    (a fraction of the length) and turns [0, 20], replacing the coat's (sec. 3.8's curve and
//    tube styles): a hair winds with the values interpolated at its root at rest
//    (CoatRoots::curlRadius, ::curlTurns); either alone keeps the coat's other.
//  widthScale: multiplies each coat's hair width (fur_params.h StrandWidth, root and tip) at the
//    vertex (overcoat, undercoat), [0, kMaxWidthScale]: a hair takes the scale interpolated at its
//    root at rest (CoatRoots::widthScale), drawn, exported and (tubes) grown that wide.
//  colorSourceWeight: per colour source (indexed by ColorSource), each coat's weight of that
//    source at the vertex (overcoat, undercoat), [0, 1], the weights of a coat summing to 1:
//    a hair's root colour is the sum of the sources' colours at its root times their weights
//    interpolated there (colors.h colorRoots). All five empty: each coat's own source.
struct VertexGroom {
  std::vector<float> length;
  std::vector<float> density;
  std::vector<Eigen::Vector3f> tint;
  std::vector<Eigen::Vector3f> comb;
  std::vector<float> clump;
  std::vector<Eigen::Vector2f> stiffness;
  std::vector<Eigen::Vector2f> segmentDirectionWeight;
  std::vector<Eigen::Vector2f> curlRadius;
  std::vector<Eigen::Vector2f> curlTurns;
  std::vector<Eigen::Vector2f> widthScale;
  std::array<std::vector<Eigen::Vector2f>, kColorSourceCount> colorSourceWeight;
  bool hasColorSourceWeights() const { return !colorSourceWeight[0].empty(); }
  bool empty() const {
    return length.empty() && density.empty() && tint.empty() && comb.empty() && clump.empty() &&
           stiffness.empty() && segmentDirectionWeight.empty() && curlRadius.empty() &&
           curlTurns.empty() && widthScale.empty() && !hasColorSourceWeights();
  }
};

// The groom of one fur: its maps, loaded (empty textures where the preset names none), and its
// per-vertex values.
//  density: linear data, nearest texel (each texel a cell of constant density, so a zero texel
//    grows no hair); a triangle's hairs are proportional to its area times the map's mean over it.
//  length: linear data, bilinear; multiplies each hair's interpolated length (grey 0.5: half).
//  color: sRGB colour, bilinear; the Map colour source.
struct Groom {
  skin::Texture density, length, color;
  VertexGroom vertex;
  bool anyMap() const { return !density.empty() || !length.empty() || !color.empty(); }
};

// Reads the maps `paths` names (util/image.h limits) into a Groom with no vertex values. InputError
// naming the field ("maps.density") and the file for a missing or unreadable image, and for maps on
// a skin without texture coordinates (naming `modelName`).
Groom loadGroomMaps(const GroomMapPaths& paths, const skin::SkinMesh& skin,
                    const std::string& modelName);

// What one region pattern matched on a creature (for `pelage info` and messages).
struct RegionMatch {
  std::string pattern;
  std::vector<std::string> regions;  // skin region names (glTF: material or rigid node names)
  std::vector<std::string> joints;   // body segment (joint) names
  int vertices = 0;                  // skin vertices with some weight in the region
};

// The skin's weight in region `pattern` per vertex, in [0, 1]: 1 where the vertex's skin region
// matches; for matching joints, the sum of the vertex's skin weights on them (a joint region's
// border blends as the skinning does); the larger of the two. `match` receives what matched.
std::vector<float> regionWeights(const skin::SkinMesh& skin, const anatomy::Body& body,
                                 const std::string& pattern, RegionMatch* match = nullptr);

// The per-vertex values of params.regions on the creature, in list order: starting from `start`'s
// values (a groom file's; where it has none, the skin's fur lengths, density 1 and tint 1), each
// region moves a vertex's values toward its own by the
// vertex's weight w in it (value + w (region value - value)): length -> lengthMm (if set, where the
// skin has fur) times lengthScale; density -> density x densityScale; tint -> tint x region tint.
// Where w is 1 a region's lengthScale s gives exactly s times the length; between, the blend is
// monotone in w. Arrays a region list never touches stay empty. A pattern that matches nothing is
// an InputError naming `source`, the region (regions[i].match) and the creature's names. `matches`
// receives one entry per region.
VertexGroom groomFromRegions(const skin::SkinMesh& skin, const anatomy::Body& body,
                             const FurParams& params, const std::string& source,
                             std::vector<RegionMatch>* matches = nullptr, VertexGroom start = {});

// Groom files: a VertexGroom saved for one mesh, JSON:
//   {"format": "pelage groom", "version": 1,
//    "mesh": {"vertices": nV, "triangles": nT, "hash": "16 hex digits"},
//    "length": [nV metres], "density": [nV], "tint": [nV x [r, g, b]], "comb": [nV x [x, y, z]],
//    "clump": [nV], "stiffness": [nV x [overcoat, undercoat]],
//    "segmentDirectionWeight": [nV x [overcoat, undercoat]], "curlRadius": [nV x [o, u]],
//    "curlTurns": [nV x [o, u]], "widthScale": [nV x [o, u]],
//    "colorSourceWeight": {"material": [nV x [o, u]], "creature": ..., "texture": ...,
//    "vertex": ..., "map": ...}}
// (each array optional; floats written with round-trip precision, so a file reads back
// bit-identically). The hash (meshHash) keys the file to the skin's vertex and triangle order and
// rest positions; loading it on another mesh is an error naming both meshes. Values: length
// [0, 10] m, density [0, 100], tint [0, 10] each, comb of length <= 1, clump, stiffness and
// segment direction weight [0, 1], curl radius [0, 0.5], curl turns [0, 20], width scale [0, 10],
// colour source weights [0, 1] (all five sources or none), all finite.
inline constexpr int kGroomFileVersion = 1;

// FNV-1a 64 over the vertex and triangle counts, the triangles' vertex indices and the rest
// positions' bytes.
std::uint64_t meshHash(const skin::SkinMesh& skin);

// The groom file's text for `groom` on `skin` (PELAGE_CHECK: array sizes match the skin).
std::string groomFileJson(const skin::SkinMesh& skin, const VertexGroom& groom);
// Writes it atomically (util/atomic_file.h: no half-written file).
void writeGroomFile(const std::string& path, const skin::SkinMesh& skin, const VertexGroom& groom);
// Parses a groom file's text for `skin`; InputError naming `source`, the field (e.g. "length[12]")
// and the accepted range, or both meshes when it belongs to another one (`modelName` names the
// skin's).
VertexGroom parseGroomFile(const std::string& text, const std::string& source,
                           const skin::SkinMesh& skin, const std::string& modelName);
VertexGroom readGroomFile(const std::string& path, const skin::SkinMesh& skin,
                          const std::string& modelName);

// The per-vertex groom a fur grows from: params.groom's file read on `skin` (none: empty), then
// params.regions applied on top (groomFromRegions; `source` and `matches` as there).
VertexGroom resolveVertexGroom(const skin::SkinMesh& skin, const anatomy::Body& body,
                               const std::string& modelName, const FurParams& params,
                               const std::string& source,
                               std::vector<RegionMatch>* matches = nullptr);

// The fur length at each vertex: the groom's when it has lengths, else the skin's.
inline const float* groomedLengths(const skin::SkinMesh& skin, const VertexGroom& vertex) {
  return vertex.length.empty() ? skin.furLengths() : vertex.length.data();
}

}  // namespace pelage::fur
