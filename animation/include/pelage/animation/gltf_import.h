// glTF 2.0 creatures (.gltf with embedded or external buffers, .glb): the node hierarchy becomes
// the Body, the skinned (and rigid) meshes one SkinMesh, and every animation a Clip.
//
// Conventions (pelage: metres, Z up, the creature facing +X with its left at +Y; glTF: Y up, the
// asset's front at +Z and its left at +X): the change of basis C (x, y, z) -> (z, x, y) times the
// unit scale s is applied to the root nodes (rotation C q, translation s C t, scale s S), to the
// animation channels that drive them, to the inverse bind matrices (IBM C^-1 / s) and to the bind
// positions (s C p). Nothing below the roots changes, so every other channel plays as stored.
//
// Unit scale (metres per file unit), unless LoadOptions gives one: glTF units are metres, so the
// scale is 1 unless the longest side L of the bind-pose bounding box is implausible for an animal:
// L > 30 is read as centimetres (0.01; the Khronos Fox, L = 155, becomes 1.55 m) and L > 3000 as
// millimetres (0.001). The Quaternius animals (L = 4-6) and CesiumMan (L = 1.5) stay in metres.
//
// Body: every node on a path from the scene roots to a joint of a used skin, or to a rigid mesh
// node, becomes a segment (named after the node; unnamed nodes "node<i>"). Bind transforms: a
// joint's is the inverse of its inverse bind matrix; any other node's is its parent's bind
// transform times its rest transform (for roots, the rest transform). Body::inverseBind is the
// inverse of the bind transform, so a joint's equals its IBM and a rigid mesh bound to its own node
// follows that node.
//
// Skin: skinned primitives (JOINTS_0/WEIGHTS_0, and JOINTS_1/WEIGHTS_1 when present) keep their
// positions as stored (the bind space); rigid mesh nodes (unskinned, e.g. the Stag's antlers under
// the Head joint) are placed by their node's bind transform and bound 100% to their node's segment.
// The 4 largest influences are kept and renormalised; Binding::segment[0] has the largest weight.
// Vertices at the same position with the same binding are welded (within and across primitives),
// so the skin's normals are smooth and fur flows over seams; a welded vertex between two regions
// takes the barer one (a no-fur region wins), so fur thins to nothing at eyes and hooves. Triangle
// strips and fans become triangles; points and lines are skipped; degenerate triangles are dropped
// with a warning; a triangle that would make an edge non-manifold gets its own copies of vertices.
// Regions: a skinned primitive's region is its material name ("body" without one); a rigid mesh's
// region is its node name ("Stag_Horns").
//
// Fur length: 2% of the bind-pose bounding-box diagonal (in metres) everywhere, 0 in the no-fur
// regions: LoadOptions' list or, by default, any region matching (case-insensitive, * wildcards)
// Eye*, *Eyes*, Eye_*, Hooves, *Hoof*, Nose, *Horn*, *Antler*, *Teeth*, *Tongue*, *Claw*.
//
// Segment directions (paper sec. 3.4: "Animal hairs typically are oriented from head to tail"):
// see headToTailDirections below; overridable per segment by a JSON side file
//   { "directions": { "b_Tail01_012": [-1, 0, -0.2], "b_Head_05": [0, 0, 0] } }
// (bind-pose world coordinates after the conversion above; [0, 0, 0] = no segment direction). The
// side file is LoadOptions' `segmentDirections`, else `<model path without
// extension>.directions.json` when it exists.
//
// Appearance (skin/skin_mesh.h): TEXCOORD_0 becomes per-corner UVs (so welding keeps UV seams),
// COLOR_0 (VEC3 or VEC4, float or normalised integers) a per-vertex linear colour (a welded vertex
// takes its first copy's), and every material a SkinMaterial: pbrMetallicRoughness.baseColorFactor
// and baseColorTexture (TEXCOORD_0 only; its sampler's wrap modes, NEAREST or LINEAR
// magnification). Images are decoded by util/image.h (PNG, JPEG, ...; sRGB), from a bufferView
// (.glb), a data URI, or a file beside the .gltf (relative paths inside its folder only). An image
// over 16384 pixels per side or 256 MiB decoded, the creature's images over 1 GiB together, or a
// missing, truncated or corrupt image: a warning naming the image and the problem, and the material
// keeps its base colour (the model still loads). Triangles without a material get one of the skin's
// colour.
//
// Clips: each animation becomes a looping clip named after it ("clip<i>" when unnamed), duration =
// its last key time. Channels that drive nodes outside the body have no effect on the skin and are
// dropped; morph-target ("weights") channels are skipped with a warning.
//
// Bad files never crash or read out of bounds: the GLB container, buffers, buffer views, accessors
// (type, component type, count, stride, range), indices, joint indices, weights, node tree (cycles,
// several parents), matrices, animation samplers and required extensions are all checked, and
// NaN/infinite values rejected, with an InputError naming the file and the element at fault.
#pragma once

#include <Eigen/Core>

#include <optional>
#include <string>
#include <vector>

#include "pelage/anatomy/body.h"
#include "pelage/animation/clip.h"
#include "pelage/skin/skin_mesh.h"

namespace pelage::animation {

struct GltfImportOptions {
  float unitScale = 0.0f;  // metres per file unit; 0 = detect (range when given: [1e-6, 1e6])
  // Region names or patterns (case-insensitive, '*' wildcards) that grow no fur; nullopt =
  // defaults.
  std::optional<std::vector<std::string>> noFurRegions;
  float furLengthMeters = 0.0f;   // 0 = 2% of the bounding-box diagonal
  std::string segmentDirections;  // side file; "" = <model>.directions.json if present
};

struct GltfCreature {
  std::string name;  // the file's stem
  anatomy::Body body;
  skin::SkinMesh skin;
  std::vector<Clip> clips;
  float unitScale = 1.0f;  // metres per file unit that was applied
  std::string unitScaleReason;
};

// Imports a glTF 2.0 file. Throws InputError naming the file for anything missing or malformed.
GltfCreature importGltf(const std::string& path, const GltfImportOptions& options = {});

// The default no-fur region patterns.
const std::vector<std::string>& defaultNoFurRegions();

// The unit scale heuristic above for a longest bind-pose extent `longest` (file units); `reason`
// receives a one-line explanation.
float detectUnitScale(float longest, std::string* reason = nullptr);

// Default segment directions (bind-pose world, unit or zero), head to tail along the skeleton:
//  1. the head is the shallowest segment whose name contains "head" (case-insensitive); failing
//     that, the extreme joint of the skeleton's longest axis (front, +X, for long low skeletons;
//     top, +Z, for tall ones such as bipeds);
//  2. every bone (segment to child) is oriented away from the head: with d(s) the number of tree
//     edges from the head to s, from the end nearer the head to the farther one;
//  3. the spine is the tree path from the head to the joint farthest from it along the bones (an
//     animal's tail tip); a spine segment's direction is the normalised mean of its (at most two)
//     oriented spine bones, so the back and neck point to the tail and the tail to its tip;
//  4. any other segment takes the normalised mean of its oriented bones to its parent and
//     children (legs and arms point to the paws, ears to their tips); a leaf, its parent bone.
// Only segments that skin vertices are bound to (`bound`) get a direction and count as bone ends;
// others, and zero-length bones, get zero. `bindJoints` are the segments' bind-pose positions.
std::vector<Eigen::Vector3f> headToTailDirections(const anatomy::Body& body,
                                                  const std::vector<Eigen::Vector3f>& bindJoints,
                                                  const std::vector<bool>& bound);

// Applies a direction side file to `body` (segment names; see above). InputError naming the file
// and field for unknown segments or malformed values.
void applyDirectionFile(anatomy::Body& body, const std::string& path);

}  // namespace pelage::animation
