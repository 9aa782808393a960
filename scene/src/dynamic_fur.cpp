#include "pelage/scene/dynamic_fur.h"

#include "pelage/util/error.h"
#include "pelage/util/interrupt.h"

namespace pelage::scene {

void preRollDynamics(const Model& model, const Fur& fur, const fur::DynamicsParams& dynamics,
                     int clip, int firstFrame, const Clock& clock, fur::FurDynamicsState& state,
                     FrameState& scratch) {
  PELAGE_CHECK(clock.fps >= kMinFramesPerSecond && clock.fps <= kMaxFramesPerSecond, "fps ",
               clock.fps);
  fur::resetFurDynamics(fur.roots, state);
  for (int f = preRollStart(firstFrame, clock); f < firstFrame; ++f) {
    checkInterrupt();
    evaluateClipFrame(model, clip, clock.secondsAt(f), scratch);
    stepClipDynamics(model, fur, dynamics, 1.0 / clock.fps, nullptr, state, scratch);
  }
}

void stepClipDynamics(const Model& model, const Fur& fur, const fur::DynamicsParams& dynamics,
                      double stepSeconds, const fur::FurView* view, fur::FurDynamicsState& state,
                      FrameState& frame) {
  const double dt = stepSeconds;
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
