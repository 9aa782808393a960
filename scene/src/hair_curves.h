// Hairs as the curves the geometry exporters write (private to pelage::scene): the centre line of a
// hair (its points, or the centres of a tube's rings) and its cubic Bezier control points.
#pragma once

#include <cstdint>
#include <vector>

#include "pelage/fur/fur_params.h"
#include "pelage/fur/generate.h"

namespace pelage::scene::detail {

// Centre line of hair h of `b`: b.layout.strandPoints x 3 floats into `out` (the strand points, or
// the centres of a tube's rings).
void hairCenterLine(const fur::HairBuffers& b, std::int64_t h, float* out);

// Van Gelder & Wilhelms 1997, sec. 3.8: the hair curve is the cubic Bezier P0 = R,
// P1 = R + (L/3) n_p, P2 = R + (2/3)(E - R), P3 = E, tessellated at t_k = k / (K - 1) as
// C_k = R + c1_k (L n_p) + c2_k (E - R). Recovers the control points from the K tessellated points:
// L n_p by least squares over k (exact up to rounding for a curve without curl). 4 x 3 floats.
void bezierFromTessellation(const fur::CoatShape& shape, const float* points, float* control);

// A piecewise cubic Bezier through K points (Catmull-Rom tangents, end tangents one-sided):
// 3 (K - 1) + 1 control points x 3 floats; it passes through every point. Used for curled hairs,
// which a single cubic cannot follow.
void bezierThroughPoints(const float* points, int K, float* control);

// Control points of hair h as the exporters write it (b.layout's basis): b.layout.curveVertices()
// x 3 floats.
void hairCurve(const fur::HairBuffers& b, const fur::CoatShape& shape, std::int64_t h,
               std::vector<float>& centerScratch, float* out);

}  // namespace pelage::scene::detail
