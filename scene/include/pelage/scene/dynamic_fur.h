// Dynamic fur (fur/dynamics.h) over a clip's frames: frame f shows clip time f / fps. The state of
// frame f depends on every frame before it, so a frame range shown on its own first pre-rolls the
// simulation from the clip's start (frame 0; bit-identical to a whole run) or, when asked, from a
// given number of frames before the range (faster, approximately equal).
#pragma once

#include <Eigen/Core>

#include "pelage/fur/dynamics.h"
#include "pelage/scene/frame.h"
#include "pelage/scene/model.h"

namespace pelage::scene {

// How a frame range is reached.
struct DynamicsClock {
  double fps = 30.0;          // frames per second, [1, 1000]
  double startSeconds = 0.0;  // clip time of frame 0
  int preRollFrames = -1;     // -1: from the clip's start (frame 0); else this many frames before
};

// The first frame simulated to show frames from `firstFrame` on: 0, or max(0, first - preRoll).
int preRollStart(int firstFrame, const DynamicsClock& clock);

// Resets `state` and advances it through the frames [preRollStart, firstFrame) of clip `clip`
// (evaluated into `scratch`; no hairs drawn). Then step frame firstFrame, firstFrame + 1, ... with
// stepClipDynamics.
void preRollDynamics(const Model& model, const Fur& fur, const fur::DynamicsParams& dynamics,
                     int clip, int firstFrame, const DynamicsClock& clock,
                     fur::FurDynamicsState& state, FrameState& scratch);

// Advances `state` to the skin already evaluated in `frame` (evaluateFrame / evaluateClipFrame),
// 1 / fps after the previous step; with a view, also the frame's hairs (culled for the view, as
// evaluateFur) built from the dynamic ends; null: only the springs' step, no hairs.
void stepClipDynamics(const Model& model, const Fur& fur, const fur::DynamicsParams& dynamics,
                      const DynamicsClock& clock, const fur::FurView* view,
                      fur::FurDynamicsState& state, FrameState& frame);

}  // namespace pelage::scene
