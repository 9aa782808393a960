#include "pelage/scene/dynamic_fur.h"

#include <algorithm>

#include "pelage/util/error.h"
#include "pelage/util/interrupt.h"

namespace pelage::scene {

int preRollStart(int firstFrame, const DynamicsClock& clock) {
  if (clock.preRollFrames < 0) return 0;
  return std::max(0, firstFrame - clock.preRollFrames);
}

void preRollDynamics(const Model& model, const Fur& fur, const fur::DynamicsParams& dynamics,
                     int clip, int firstFrame, const DynamicsClock& clock,
                     fur::FurDynamicsState& state, FrameState& scratch) {
  PELAGE_CHECK(clock.fps >= 1.0 && clock.fps <= 1000.0, "fps ", clock.fps);
  fur::resetFurDynamics(fur.roots, state);
  for (int f = preRollStart(firstFrame, clock); f < firstFrame; ++f) {
    checkInterrupt();
    evaluateClipFrame(model, clip, clock.startSeconds + f / clock.fps, scratch);
    stepClipDynamics(model, fur, dynamics, clock, nullptr, state, scratch);
  }
}

void stepClipDynamics(const Model& model, const Fur& fur, const fur::DynamicsParams& dynamics,
                      const DynamicsClock& clock, const fur::FurView* view,
                      fur::FurDynamicsState& state, FrameState& frame) {
  const double dt = 1.0 / clock.fps;
  if (!view) {
    fur::stepFurDynamics(model.skin, fur.roots, fur.params, dynamics, frame.skin, dt, state,
                         frame.furWorkspace);
    return;
  }
  frame.furView = *view;
  frame.cullFactor = fur::cullingFactor(frame.furView);
  fur::generateDynamicFur(model.skin, fur.roots, fur.params, dynamics, frame.skin, dt,
                          frame.furView, state, frame.furWorkspace, frame.fur);
  fur::fillHairColors(fur.colors, frame.fur);
  for (int c = 0; c < fur::kCoatCount; ++c)
    frame.drawnHairs[static_cast<std::size_t>(c)] =
        frame.fur.coats[static_cast<std::size_t>(c)].drawn;
  frame.cpuFur = true;
}

}  // namespace pelage::scene
