// The small enums shared by the fur parameters and the per-hair maths (no Eigen, so the SIMD
// kernels can include hair_math.h without it).
#pragma once

#include <cstdint>

namespace pelage::fur {

// Hair styles, Van Gelder & Wilhelms 1997, sec. 3.6 to 3.8.
enum class HairStyle : std::uint8_t {
  Line,      // sec. 3.6: root to end, 2 points, skin-normal shading
  Polyline,  // sec. 3.7: 8 control points in the hair plane, a shading normal per point
  Curve,     // sec. 3.8 nurbs curve: cubic Bezier tessellated to K points, one normal (skin normal)
  Tube,      // sec. 3.8 nurbs surface: a thin tube of M-point rings around the curve
};

// Shape of the user's length-scaling region (sec. 3.2: "all hairs in a selected 3D region").
enum class RegionShape : std::uint8_t { None, Sphere, Box };

}  // namespace pelage::fur
