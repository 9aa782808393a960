// The small enums shared by the fur parameters and the per-hair maths (no Eigen, so the SIMD
// kernels can include hair_math.h without it). 32-bit, so the per-coat constants that hold them
// (CoatShape) are the GPU's std430 block as they are.
#pragma once

#include <cstdint>

namespace pelage::fur {

// Hair styles, Van Gelder & Wilhelms 1997, sec. 3.6 to 3.8. Each style's layout (points, topology,
// memory) is in hair_layout.h.
enum class HairStyle : std::int32_t {
  Line,      // sec. 3.6: root to end, 2 points, skin-normal shading
  Polyline,  // sec. 3.7: 8 control points in the hair plane, a shading normal per point
  Curve,     // sec. 3.8 nurbs curve: cubic Bezier tessellated to K points, one normal (skin normal)
  Tube,      // sec. 3.8 nurbs surface: a thin tube of M-point rings around the curve
};

// Shape of the user's length-scaling region (sec. 3.2: "all hairs in a selected 3D region").
enum class RegionShape : std::int32_t { None, Sphere, Box };

}  // namespace pelage::fur
