// Culling (Van Gelder & Wilhelms 1997, sec. 3.3): "we draw the full number of hairs at the distance
// such that approximately the area of the animal's face, or less, is visible on the screen. We
// decrease the number of hairs drawn by the zoom factor 1/c for greater viewing distances." The
// zoom factor is the creature's scale on screen: pixels per metre at the centre of its bounding
// sphere, s = H / (2 d tan(fovY / 2)) for an image H pixels high, a camera at distance d with
// vertical field of view fovY; c = s_ref / s against the reference camera's s_ref. The paper's
// distance rule is the case of equal fields of view and image sizes (c = d / d_ref); a narrower
// field of view or a larger image draws more hairs, as the creature covers more pixels. One c for
// the whole creature: the paper scales "the animal's projected area" as a whole, and one c keeps
// the hair density uniform over the body (a per-triangle c would thin the far side of the creature
// and change the density between neighbouring triangles as the camera turns).
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
  // The camera's and the reference's vertical fields of view (degrees) and image heights (pixels):
  // equal by default, so c is the distance ratio.
  float fovYDegrees = 45.0f;
  float referenceFovYDegrees = 45.0f;
  int imageHeight = 1080;
  int referenceHeight = 1080;
};

// The creature's scale on screen for camera `view`, in pixels per metre at distance d:
// H / (2 d tan(fovY / 2)).
float pixelsPerMeter(float distance, float fovYDegrees, int imageHeight);

// c = max(1, s_ref / s) = max(1, (d / d_ref) (tan(fovY / 2) / tan(fovY_ref / 2)) (H_ref / H));
// 1 when culling is off.
float cullingFactor(const FurView& view);

// How wide (pixels) the overcoat's hair root is at the default reference scale.
inline constexpr float kReferenceRootPixels = 0.25f;

// The default reference distance: where the overcoat's root width (fur::StrandWidth) spans
// kReferenceRootPixels of the reference image (referenceHeight pixels, vertical field of view
// fovYDegrees): D = w_root H_ref / (2 tan(fovY / 2) kReferenceRootPixels). The paper chose the
// distance at which the face fills the screen, for 1-pixel lines; with hairs of a physical width
// drawn with their coverage (the renderer's strands), the coat covers the skin correctly at any
// count, so culling starts where a hair becomes narrower than a quarter pixel, and the hairs left
// are widened by c back to a quarter pixel (drawn one pixel wide at that coverage): fewer strands,
// never wider than a pixel. The value is measured: at half a pixel the monkey's 320 vs 1280
// box-filtered renders differed by 7.8/255, at a quarter by 4.7 (tests/render/strand_look_test).
// For the default fur (0.4 mm) at 45 degrees and 1080 pixels: 2.09 m.
float defaultReferenceDistance(const FurParams& params);

// The reference distance in use: params.culling.referenceDistance, or the default when that is 0.
float referenceDistance(const FurParams& params);

// Centre of the bounding box of the deformed skin (the bounding-sphere centre used for distance).
Eigen::Vector3f creatureCenter(const skin::DeformedSkin& deformed);

// The camera culling needs: where it is, its vertical field of view and its image height.
struct ViewCamera {
  Eigen::Vector3f eye = Eigen::Vector3f::Zero();
  float fovYDegrees = 45.0f;
  int imageHeight = 1080;
};

// The view for `camera`.
FurView makeFurView(const FurParams& params, const skin::DeformedSkin& deformed,
                    const ViewCamera& camera);

// Sec. 3.3: triangle t with k roots draws k' = min(k, floor(k / c + u_t)) of them (random rounding,
// u_t = uniform01(coatSeed, kStreamCulling, t), fixed from frame to frame so nothing flickers),
// the first k' in creation order. Writes drawnStart (nT + 1, CSR over drawn hairs) and returns the
// total. Parallel, no allocation when drawnStart already has nT + 1 entries.
std::int64_t computeDrawnStart(const CoatRoots& roots, std::uint64_t coatSeedValue, float factor,
                               std::vector<std::int32_t>& drawnStart);

}  // namespace pelage::fur
