// How much of its skin a coat hides: the coat's density and optical depth, the numbers a groomer
// reads and sets. A layer of hairs of density n (hairs per unit area), mean length L and mean width
// w covers n L w of each unit of skin with hair (its optical depth tau: the hairs' own area per
// area of skin, were they laid flat). Hairs fall independently (sec. 3.2's random roots), so a
// point of skin stays visible with probability exp(-k tau), k the share of a hair's area that
// faces the viewer (hairs stand off the skin at an angle and overlap in depth).
#pragma once

#include <array>

#include "pelage/fur/fur_params.h"
#include "pelage/fur/groom.h"
#include "pelage/skin/skin_mesh.h"

namespace pelage::fur {

// k: the share of the coat's hair area that hides skin, calibrated on side views of the default
// fur (the monkey 0.54, the Fox 0.41: README, "How much skin the fur hides").
inline constexpr double kProjectedShare = 0.5;

struct CoatCoverage {
  double hairs = 0.0;          // N_c, expected
  double densityPerCm2 = 0.0;  // N_c / furred area, hairs per square centimetre
  double meanLengthMm = 0.0;   // the coat's mean hair length over the furred skin (rest pose)
  double meanWidthMm = 0.0;    // (root + tip) / 2: the mean of the linear taper
  double opticalDepth = 0.0;   // tau_c = n_c L_c w_c
};

struct FurCoverage {
  double furredAreaM2 = 0.0;
  std::array<CoatCoverage, kCoatCount> coats{};
  double opticalDepth = 0.0;  // both coats: sum of tau_c
  double hiddenShare = 0.0;   // 1 - exp(-kProjectedShare tau): the expected share of skin hidden
};

// The hairs a coverage may ask for before its hairs widen instead: 2 million (a creature in
// centimetres read as metres needs 100 times the hairs of the same creature in metres).
inline constexpr double kCoverageHairBudget = 2e6;

// `params`, with a coverage that would need more than kCoverageHairBudget hairs met by wider
// hairs instead: both coats' root and tip widths times N / kCoverageHairBudget (at most 20 mm),
// so the coverage's count is the budget. Unchanged otherwise. scene::growFur applies it.
FurParams fitCoverageToBudget(const skin::SkinMesh& skin, FurParams params,
                              const float* lengths = nullptr);

// The coats' expected density and optical depth on `skin` (its rest pose and per-vertex fur
// lengths, or `lengths` (nV, a groom's: fur/groom.h) when given; the preset's lengthScale and
// relative lengths). The hair count is params' (hairs, density or coverage). With `groom`, its
// per-vertex density and width scale count as the roots get them (roots.h growRoots, CoatRoots::
// widthScale): a triangle's hairs are its share of the furred area weighted by the mean of its
// vertices' densities, and each hair's length and width scale are interpolated at its root, so a
// coat's mean length, mean width and optical depth n E[L w] are means over its hairs, E[L s] over a
// triangle being the exact mean of the product of two linear interpolants. A density or length map
// and lengthRegion are not counted; the expected share hidden takes the coat's mean optical depth
// as if spread evenly (where the depth varies, the skin hides somewhat less).
FurCoverage estimateCoverage(const skin::SkinMesh& skin, const FurParams& params,
                             const float* lengths = nullptr, const VertexGroom* groom = nullptr);

// The total hair count N for which the expected share of skin hidden is `hiddenShare` (in
// (0, kMaxCoverage]) with params' widths, lengths and undercoat share; 0 on a skin without fur.
// It counts the lengths, not a density or width groom: with those, estimateCoverage(..., groom)
// reports the share the groomed hairs hide.
double hairsForCoverage(const skin::SkinMesh& skin, const FurParams& params, double hiddenShare,
                        const float* lengths = nullptr);

}  // namespace pelage::fur
