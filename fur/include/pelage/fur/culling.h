// Distance-based culling (Van Gelder & Wilhelms 1997, sec. 3.3): "we draw the full number of hairs
// at the distance such that approximately the area of the animal's face, or less, is visible on the
// screen. We decrease the number of hairs drawn by the zoom factor 1/c for greater viewing
// distances." One factor c for the whole creature, from the camera's distance to the centre of the
// creature's bounding sphere: the paper scales "the animal's projected area" as a whole, and one c
// keeps the hair density uniform over the body (a per-triangle c would thin the far side of the
// creature and change the density between neighbouring triangles as the camera turns).
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <vector>

#include "pelage/fur/fur_params.h"
#include "pelage/fur/roots.h"
#include "pelage/skin/deform.h"
#include "pelage/skin/skin_mesh.h"

namespace pelage::fur {

// What the camera sees, for culling.
struct FurView {
  bool culling = false;            // off: every hair is drawn
  float viewDistance = 0.0f;       // camera to the creature's bounding-sphere centre (m)
  float referenceDistance = 1.0f;  // distance with full density (m), > 0
};

// c = max(1, viewDistance / referenceDistance); 1 when culling is off.
float cullingFactor(const FurView& view);

// The size (m) of the creature's face: the largest extent of the bind-pose vertices of the skin
// region named "face"; without such a region, a quarter of the skin's bounding-box diagonal (the
// size of a head relative to a small quadruped's body).
float faceSize(const skin::SkinMesh& skin);

// The default reference distance: where the face fills the screen height for a camera with vertical
// field of view fovY, D = faceSize / (2 tan(fovY / 2)). For the monkey (face ~0.07 m) at 45 degrees
// this is ~0.09 m: a close-up of the face draws every hair, the whole monkey in view (~1 m) ~1/11.
float defaultReferenceDistance(const skin::SkinMesh& skin, float fovYDegrees);

// The reference distance in use: params.culling.referenceDistance, or the default when that is 0.
float referenceDistance(const skin::SkinMesh& skin, const CullingParams& params);

// Centre of the bounding box of the deformed skin (the bounding-sphere centre used for distance).
Eigen::Vector3f creatureCenter(const skin::DeformedSkin& deformed);

// The view for a camera at `camera`.
FurView makeFurView(const skin::SkinMesh& skin, const FurParams& params,
                    const skin::DeformedSkin& deformed, const Eigen::Vector3f& camera);

// Sec. 3.3: triangle t with k roots draws k' = min(k, floor(k / c + u_t)) of them (random rounding,
// u_t = uniform01(coatSeed, kStreamCulling, t), fixed from frame to frame so nothing flickers),
// the first k' in creation order. Writes drawnStart (nT + 1, CSR over drawn hairs) and returns the
// total. Parallel, no allocation when drawnStart already has nT + 1 entries.
std::int64_t computeDrawnStart(const CoatRoots& roots, std::uint64_t coatSeedValue, float factor,
                               std::vector<std::int32_t>& drawnStart);

}  // namespace pelage::fur
