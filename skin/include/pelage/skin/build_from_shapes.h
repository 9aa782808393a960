// Building a creature's skin from its body shapes: the smooth union of the shapes' signed distance
// fields is polygonised into one closed, manifold triangle mesh, cleaned with OpenMesh's tools,
// bound to the segments (each vertex to its closest segment, sec. 3.4, blended smoothly near
// joints), and given fur lengths and regions from the creature's fur-length regions (sec. 3.2).
#pragma once

#include <Eigen/Core>

#include "pelage/anatomy/creature.h"
#include "pelage/skin/skin_mesh.h"

namespace pelage::skin {

struct SkinBuildOptions {
  // Target triangle count; the result is within a few percent. Accepted range [2000, 2000000].
  int triangles = 130000;
};

// Signed distance (metres, negative inside) of the creature's smooth union of shapes at `p`.
float creatureDistance(const anatomy::Creature& creature, const Eigen::Vector3f& p);

// Builds the bind-pose skin of a creature. Throws InputError for an out-of-range triangle count.
SkinMesh buildSkin(const anatomy::Creature& creature, const SkinBuildOptions& options);

// Binds every vertex: segment[0] = the closest segment (by shape distance), weights blended
// smoothly with the neighbouring segments near joints; sets segmentDirection from segment[0].
void bindToSegments(const anatomy::Creature& creature, SkinMesh& skin);

// Sets furLength and region of every vertex from the creature's fur-length regions.
void assignFurRegions(const anatomy::Creature& creature, SkinMesh& skin);

// Sets furColor (linear) of every vertex from the creature's fur colours: back or belly by the rest
// normal's up (Z) component, then each region with a colour blended in by its membership, as
// lengths are. Leaves furColor empty when the creature has none. After finalizeSkin.
void assignFurColors(const anatomy::Creature& creature, SkinMesh& skin);

}  // namespace pelage::skin
