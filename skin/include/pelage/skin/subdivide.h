// Subdivision of a skin under the roots: a low-poly skin's flat facets would show through a dense
// coat, since the paper grows each hair from its triangle's plane (Van Gelder & Wilhelms 1997,
// sec. 3.2: barycentric roots, interpolated normals). Subdividing before the roots grow gives the
// roots, their normals and directions a curved surface; sec. 3.2's allocation and barycentric
// roots then run on the finer mesh as on any. The scheme interpolates (the file's vertices stay
// where they are): Loop's approximating masks, tried first, pulled the Fox's ears 5.7 cm down and
// its body 11 % thinner (its limit surface lies inside the coarse mesh).
#pragma once

#include "pelage/skin/skin_mesh.h"

namespace pelage::skin {

// Below this many triangles a glTF creature or mesh is subdivided by default (scene::LoadOptions).
inline constexpr int kSmoothSkinTriangles = 4000;
// The most levels `subdivideSkin` takes (each multiplies the triangles by 4).
inline constexpr int kMaxSubdivisionLevels = 3;

// The levels that bring `triangles` to at least kSmoothSkinTriangles, at most kMaxSubdivisionLevels
// (0 for a skin already that fine).
int autoSubdivisionLevels(int triangles);

// `skin` subdivided `levels` times (0 to kMaxSubdivisionLevels; 0 returns a copy). Each triangle
// becomes four (its corners and its edges' new vertices, orientation kept). The file's vertices
// stay; an edge's new vertex lies at the middle of the cubic edge curve of PN triangles (Vlachos,
// Peters, Boyd and Mitchell 2001, "Curved PN Triangles") through the edge's ends with their
// area-weighted vertex normals, so the edges bend with the surface and neighbouring triangles share
// the curve. Per-vertex values: an edge vertex takes the mean of its ends' skin weights (summed
// per segment, the 4 largest kept and renormalised, the largest first: ends bound alike stay
// bound alike), segment directions (normalised, 0 where they cancel), vertex and fur colours and
// fur lengths, except that fur stays bare where it was (an edge with a bare end gets length 0, so
// bare regions do not grow a fringe of fur) and the edge takes its barer end's region (its first
// end's when neither is bare). Corner texture coordinates and materials are split linearly with
// their triangle (UV seams kept). Deterministic.
SkinMesh subdivideSkin(const SkinMesh& skin, int levels);

}  // namespace pelage::skin
