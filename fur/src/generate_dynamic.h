// The per-frame fur entry point with fur dynamics (dynamics.h): generateFur (generate.h) where
// each coat may carry its dynamic state (dynamics_kernel.h). Private to pelage::fur.
#pragma once

#include <array>

#include "kernel.h"
#include "pelage/fur/generate.h"

namespace pelage::fur::detail {

// As generateFur, with dynamics[c] (or null) advancing/reading coat c's damped ends. With `emit`
// false nothing is drawn: the kernel runs over every root of each coat with dynamics (no culling)
// and only advances its state; `view` and `frame` are not used.
void generateFurWithDynamics(const skin::SkinMesh& skin, const FurRoots& roots,
                             const FurParams& params, const skin::DeformedSkin& deformed,
                             const FurView& view, FurWorkspace& workspace, FurFrame& frame,
                             const std::array<const CoatDynamicsArgs*, kCoatCount>& dynamics,
                             bool emit);

}  // namespace pelage::fur::detail
