// The layout of each hair style: how many points a hair has, how they are connected, how much
// memory a hair takes, and how exporters describe it. The one place these are decided: the hair
// budget, the CPU kernels' buffers, the draw list, the renderer's index buffers, the PLY, USD and
// glb exporters and the viewer's panel all ask hairLayout(). Adding a style means an enum value
// (hair_style.h), its maths (hair_math.h and its GLSL mirror) and its entry here; every switch over
// HairStyle has no `default:`, so the compiler lists the places that must learn it.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "pelage/fur/hair_style.h"

namespace pelage::fur {

struct CoatParams;

// Every style, in enum order (menus, loops in tests and benchmarks).
inline constexpr HairStyle kHairStyles[] = {HairStyle::Line, HairStyle::Polyline, HairStyle::Curve,
                                            HairStyle::Tube};
inline constexpr int kHairStyleCount = 4;

// "line", "polyline", "curve", "tube".
const char* styleName(HairStyle style);
// Parses a style name; throws InputError naming `where` and the accepted names.
HairStyle parseStyle(std::string_view name, const std::string& where);
// "line, polyline, curve, tube" (for messages and help texts).
std::string styleNames();

// How a hair's points are joined when drawn or exported.
enum class HairTopology : std::uint8_t {
  Strand,  // one line strip through the strand points (1-D hairs: line, polyline, curve)
  Rings,   // rings of ringSides points around each strand point, joined by triangles (tube)
};

// How an exporter describes a hair's centre line.
enum class CurveBasis : std::uint8_t {
  Linear,  // straight segments between the strand points (line, polyline)
  Bezier,  // a sampled cubic Bezier (sec. 3.8): the exporters write its control points
};

// One style's layout for one coat's parameters. Point k * ringSides + j of a hair is ring point j
// around strand point k (ringSides = 1: the strand points themselves).
struct HairLayout {
  HairStyle style = HairStyle::Polyline;
  HairTopology topology = HairTopology::Strand;
  CurveBasis basis = CurveBasis::Linear;
  int strandPoints = 2;  // points along the hair (line 2, polyline 8, curve and tube K)
  int ringSides = 1;     // points around each strand point (tube M), else 1
  bool curl = false;     // a Bezier strand with a helix: exported piecewise through its points

  // P: points per hair.
  int pointsPerHair() const { return strandPoints * ringSides; }
  // Segments between consecutive points (Strand: P - 1; Rings: 0).
  int segmentsPerHair() const;
  // Triangles of the surface (Rings: (K - 1) M 2; Strand: 0).
  int trianglesPerHair() const;
  // Indices a hair takes in an index buffer: Strand, its P points and a primitive-restart index;
  // Rings, three per triangle.
  int indicesPerHair() const;
  // Bytes of one drawn hair in the per-frame buffers (fur::HairBuffers): P points of position and
  // shading vector (3 floats each) and the hair id.
  double frameBytesPerHair() const;
  // Control points an exporter writes for the centre line: Linear, the strand points; Bezier, 4
  // (one cubic), or 3 (K - 1) + 1 when curled.
  int curveVertices() const;
  // Where point k (0 <= k < P) lies along its hair: 0 at the root, 1 at the tip (its strand point
  // over K - 1; every point of a ring shares its strand point's value).
  float along(int k) const {
    return strandPoints > 1
               ? static_cast<float>(k / ringSides) / static_cast<float>(strandPoints - 1)
               : 0.0f;
  }

  bool operator==(const HairLayout&) const = default;
};

// The layout of `coat`'s style with its curve points and tube sides.
HairLayout hairLayout(const CoatParams& coat);

// Points per hair of a coat: hairLayout(coat).pointsPerHair().
int pointsPerHair(const CoatParams& coat);

// Whether the style reads a coat parameter (the panel shows only those, presets keep them all).
bool usesCurveParams(HairStyle style);  // curve points K, curl radius and turns
bool usesTubeParams(HairStyle style);   // tube sides M and radius

// The triangles of a Rings hair: (K - 1) * M * 2 triangles as point indices within one hair (add
// i * P for hair i), counter-clockwise seen from outside. Empty for Strand layouts.
std::vector<std::int32_t> hairTriangles(const HairLayout& layout);
// The same for K curve points and M tube sides.
std::vector<std::int32_t> tubeTriangles(int curvePoints, int tubeSides);

// One hair's index pattern (indicesPerHair() entries), to be offset by i * P for hair i: Strand,
// 0..P-1 followed by `restart`; Rings, hairTriangles().
std::vector<std::uint32_t> hairIndexPattern(const HairLayout& layout, std::uint32_t restart);

}  // namespace pelage::fur
