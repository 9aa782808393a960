// Grooming strokes as data (issue 28): what a brush does to a fur's per-vertex groom (groom.h),
// recorded as JSON so that a stroke can be replayed without a display (`pelage groom`, Python) and
// tested:
//   {"strokes": [{"tool": "length", "points": [[x, y, z], ...], "radius": 0.06, "strength": 1.5,
//                 "mirror": "y"}, ...]}
// Points are in the model's rest pose, metres. Each stroke covers the skin vertices near the
// polyline through its points (one point: a dab) with a falloff of the distance d from it: full
// strength where d <= radius / 2, smoothstep down to 0 at the radius, nothing beyond (vertices
// farther than the radius keep their values bit for bit). Tools (w: the falloff weight):
//  length:  the fur length times 1 + w (strength - 1), at most 10 m; strength (0, 10] (1.5: half
//           as long again);
//  density: the density scale painted toward `strength`, [0, 100]: d + w (strength - d);
//  color:   the tint painted toward `color` (linear RGB multipliers, [0, 10] each) with opacity
//           `strength` [0, 1]: t + w strength (color - t);
//  comb:    the comb (groom.h) moved toward the stroke's direction u (its nearest segment's,
//           projected on the skin's tangent plane at the vertex, unit) by `strength` [0, 1]:
//           c + w strength (u - c); strength 1 under the brush's core lays the hairs along the
//           stroke (gravity still applies). Needs two distinct points;
//  cut:     the fur length trimmed toward `length` (metres, [0, 10]) with opacity `strength`
//           [0, 1]: l + w strength (min(l, length) - l); it only shortens (the clippers). Length 0
//           shaves: a triangle whose three vertices reach 0 grows no hair;
//  clump:   the clump scale (groom.h) painted toward `strength` [0, 1]: c + w (strength - c);
//           it multiplies each coat's clump strength (only where a coat clumps: fur_params.h).
// "mirror": "x", "y" or "z" applies the stroke a second time with that coordinate negated (the
// creature's symmetry plane through the origin; the mirrored comb runs along the mirrored stroke).
// Strokes apply in list order.
#pragma once

#include <Eigen/Core>

#include <cstddef>
#include <string>
#include <vector>

#include "pelage/fur/groom.h"
#include "pelage/skin/skin_mesh.h"

namespace pelage::fur {

enum class BrushTool { Length, Density, Color, Comb, Cut, Clump };

struct GroomStroke {
  BrushTool tool = BrushTool::Length;
  std::vector<Eigen::Vector3f> points;      // rest pose, metres; at least one
  float radius = 0.05f;                     // metres, (0, 10]
  float strength = 1.0f;                    // the tool's range (above)
  Eigen::Vector3f color{1.0f, 1.0f, 1.0f};  // the colour tool's target tint
  float cutLength = 0.0f;                   // the cut tool's length (metres)
  int mirrorAxis = -1;                      // 0, 1, 2 (x, y, z) or -1: none
};

inline constexpr std::size_t kMaxGroomStrokes = 100000;
inline constexpr std::size_t kMaxStrokePoints = 100000;
inline constexpr float kMaxBrushRadiusMeters = 10.0f;

// "length", "density", "color", "comb", "cut", "clump".
const char* brushToolName(BrushTool tool);

// The strengths a tool accepts, [lo, hi] (length: (0, 10], lo the smallest accepted).
struct StrengthRange {
  float lo = 0.0f, hi = 1.0f;
};
StrengthRange brushStrengthRange(BrushTool tool);

// Checks a stroke built in code (the viewer's brushes) as parseGroomStrokes checks a file's:
// InputError naming `source`, the field and the accepted range. A stroke being drawn may lack its
// points (`needPoints` false); a finished one needs them (a comb: two distinct).
void validateGroomStroke(const GroomStroke& stroke, const std::string& source,
                         bool needPoints = true);

// Parses a strokes file's text from `source`; InputError naming the source, the field
// (strokes[2].radius) and the accepted range.
std::vector<GroomStroke> parseGroomStrokes(const std::string& text, const std::string& source);
// The same for a file.
std::vector<GroomStroke> readGroomStrokes(const std::string& path);
// The strokes as a strokes file's JSON text (parseGroomStrokes reads it back to the same strokes).
std::string groomStrokesJson(const std::vector<GroomStroke>& strokes);

// The falloff weight of a vertex at distance d from a stroke of radius r: 1 for d <= r / 2,
// smoothstep to 0 at d = r, 0 beyond.
float brushFalloff(float distance, float radius);

// Applies `strokes` in order to `groom` on `skin` (rest positions). Arrays the strokes need and
// `groom` lacks start from the skin's fur lengths, density 1, tint 1, comb 0, clump 1.
void applyGroomStrokes(const skin::SkinMesh& skin, const std::vector<GroomStroke>& strokes,
                       VertexGroom& groom);

}  // namespace pelage::fur
