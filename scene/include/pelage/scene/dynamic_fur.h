// Dynamic fur (fur/dynamics.h) over a clip's frames: frame f shows clip time f / fps. The state of
// frame f depends on every frame before it, so a frame range shown on its own first pre-rolls the
// simulation from the clip's start (frame 0; bit-identical to a whole run) or, when asked, from a
// given number of frames before the range (faster, approximately equal).
#pragma once

#include "pelage/fur/dynamics.h"
#include "pelage/scene/clock.h"
#include "pelage/scene/frame.h"
#include "pelage/scene/model.h"

namespace pelage::scene {

// Resets `state` and advances it through the frames [preRollStart, firstFrame) of clip `clip`
// (evaluated into `scratch`; no hairs drawn), each 1 / fps after the one before and from
// preRollStart(firstFrame, clock). Then step frame firstFrame, firstFrame + 1, ... with
// stepClipDynamics.
void preRollDynamics(const Model& model, const Fur& fur, const fur::DynamicsParams& dynamics,
                     int clip, int firstFrame, const Clock& clock, fur::FurDynamicsState& state,
                     FrameState& scratch);

// Advances `state` to the skin already evaluated in `frame` (evaluateFrame / evaluateClipFrame),
// `stepSeconds` after the previous step; with a view, also the frame's hairs (culled for the view,
// as evaluateFur) built from the dynamic ends; null: only the springs' step, no hairs.
void stepClipDynamics(const Model& model, const Fur& fur, const fur::DynamicsParams& dynamics,
                      double stepSeconds, const fur::FurView* view, fur::FurDynamicsState& state,
                      FrameState& frame);

}  // namespace pelage::scene
