// The frame owner: everything a client needs for frame f and a camera, decided in one place. The
// viewer, `pelage render`, `pelage export`, `pelage analyze`, the benchmarks and the Python package
// all play a model through a Playback, the way every MuJoCo program advances its simulation with
// mj_step.
//
// Per frame, in order:
//  1. the pose: sequence frame f (clip time f / fps, or the still pose), or any pose the client
//     computed (the viewer's cross-fades and turntable), then forward kinematics and the skin;
//  2. the fur for a camera: distance culling (Van Gelder & Wilhelms 1997, sec. 3.3) and either the
//     hairs themselves (the CPU fur model) or the counts the GPU will draw; with dynamic fur, the
//     springs are stepped to this frame (a frame reached out of order is pre-rolled from the clip's
//     start, so any frame range equals a whole run bit for bit);
//  3. the draw list for the camera and light.
// The Model and the Fur are the constant part (not owned; they must outlive the Playback); the
// Playback owns the per-frame state, the dynamic springs and the pre-roll.
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <optional>
#include <utility>

#include "pelage/anatomy/pose.h"
#include "pelage/fur/dynamics.h"
#include "pelage/scene/camera.h"
#include "pelage/scene/clock.h"
#include "pelage/scene/draw_list.h"
#include "pelage/scene/dynamic_fur.h"
#include "pelage/scene/frame.h"
#include "pelage/scene/frame_range.h"
#include "pelage/scene/light.h"
#include "pelage/scene/model.h"

namespace pelage::scene {

struct PlaybackOptions {
  int clip = -1;            // index into model.clips; -1: the still pose in every frame
  anatomy::Pose stillPose;  // the pose without a clip; empty: the rest pose
  Clock clock;              // frame f shows clip time clock.secondsAt(f); the dynamics' pre-roll
  // Where hairs are computed. Dynamic fur is computed on the CPU (its state lives there), so with
  // dynamics on the CPU's hairs are drawn whatever this says (see hairSource()).
  HairSource hairSource = HairSource::Gpu;
  // Dynamic fur (fur/dynamics.h): each hair's end follows the paper's through a damped spring.
  // Needs a clip for sequence frames.
  bool dynamics = false;
  fur::DynamicsParams dynamicsParams;
};

// The pose an interactive player shows (Playback::posePlayed): any clip at any time, cross-faded
// from another, turned on a turntable. The player keeps the clock; the playback makes the pose.
struct PlayedPose {
  int clip = -1;         // index into model.clips; -1: the playback's still pose
  double seconds = 0.0;  // clip time (a looping clip wraps with its root motion: sampleClip)
  int fromClip = -1;     // the clip faded out (-1: none)
  double fromSeconds = 0.0;
  float fadeWeight = 1.0f;   // weight of `clip` against `fromClip`, [0, 1] (crossFadeWeight)
  double turnDegrees = 0.0;  // the root segment turned about the world +Z axis through the
                             // centre of the first pose played (unturned), in degrees
};

// Checks the options against `model` (clip index, fps, pre-roll, dynamics parameters, dynamics
// without a clip); InputError naming the field ("fps", "preroll", "dynamics", ...) otherwise.
void validatePlaybackOptions(const Model& model, const PlaybackOptions& options);

// The frames of clip `clip` played whole at `fps`: 0 to round(duration x fps) (the last frame shows
// the clip's end); the still pose (clip -1): frame 0. The default frame range of every client.
FrameRange wholeClip(const Model& model, int clip, double fps);

// The one frame at clip time `seconds` (`pelage hair`, Python's Fur.hairs): without dynamics the
// clip posed at `seconds` (frame 0 with startSeconds = seconds); with dynamics the clip played from
// its start (startSeconds 0) to the frame nearest `seconds`. Sets `options` and returns the frame
// to pose; InputError naming "time" when `seconds` is out of [0, 1000000].
int oneFrameAt(PlaybackOptions& options, double seconds);

class Playback {
 public:
  // Validates the options and poses the first frame (sequence frame 0, whose framing places
  // preset cameras).
  Playback(const Model& model, const Fur& fur, PlaybackOptions options);

  const Model& model() const { return *model_; }
  const Fur& fur() const { return *fur_; }
  const PlaybackOptions& options() const { return options_; }
  // The source the draw list uses: the CPU when asked for or when dynamics is on, else the GPU.
  HairSource hairSource() const;
  bool cpuHairs() const { return hairSource() == HairSource::Cpu; }

  // Changes that take effect on the next frame. A Fur with other roots (a new generation)
  // restarts the springs.
  void setFur(const Fur& fur);
  void setHairSource(HairSource source) { options_.hairSource = source; }
  // Dynamics on or off with `params` (validated by the caller); switching on restarts the springs.
  void setDynamics(bool on, const fur::DynamicsParams& params);
  // The next fur step restarts the springs from the quasi-static hairs (the viewer's clip change
  // or seek).
  void restartDynamics() { running_ = false; }

  // ---- 1. The pose ------------------------------------------------------------------------------
  // Sequence frame `frame` (>= 0): its pose, skin and bounds. With dynamics, the springs are made
  // ready to step to it (pre-rolled unless it follows the last frame stepped).
  void poseFrame(int frame);
  // The posed frame held still one frame time longer: the same skin, the springs step once more
  // (analysis of a body that stops).
  void holdFrame();
  // Any pose, `stepSeconds` after the previous one: the springs step by it, kept in [1 ms, 1 s].
  void posePose(const anatomy::Pose& pose, double stepSeconds);
  // The pose an interactive player asks for (the viewer's), `stepSeconds` after the previous one,
  // as posePose: see PlayedPose.
  void posePlayed(const PlayedPose& played, double stepSeconds);

  // The posed frame's framing (skin plus the longest hair) and that of sequence frame 0.
  Framing framing() const;
  const Framing& firstFraming() const { return firstFraming_; }

  // ---- 2. The fur -------------------------------------------------------------------------------
  // Seen by `camera`: culling, and the CPU hairs or the GPU's counts; with dynamics, the springs'
  // step to the posed frame (once per pose) and the hairs from their ends.
  void evaluateFur(const Camera& camera);
  // The same for an explicit view (a viewing distance rather than a camera; `pelage hair`).
  void evaluateFur(const fur::FurView& view);
  // Only the springs' step to the posed frame, no hairs (dynamics on; analysis).
  void stepDynamics();

  // ---- 3. The draw list -------------------------------------------------------------------------
  // The posed frame (after evaluateFur) for `camera` and `light`, hairs from hairSource();
  // `skin` overrides the model's skin material.
  const DrawList& drawList(const Camera& camera, const Light& light, const DrawOptions& options,
                           const Material* skin = nullptr);
  // Sequence frame `frame` posed (poseFrame) and the camera `rig` gives it in a width x height
  // image (rigCamera): the one camera of a sequence's frame.
  Camera sequenceCamera(int frame, const CameraRig& rig, int width, int height);
  // All three for sequence frame `frame` seen by `rig` in a width x height image.
  const DrawList& sequenceFrame(int frame, const CameraRig& rig, int width, int height,
                                const Light& light, const DrawOptions& options,
                                const Material* skin = nullptr);

  const FrameState& state() const { return state_; }
  // Moves the frame's CPU hairs out into `out` (swapping buffers): a client that keeps each frame's
  // hairs (the Python package's frame iterator) takes them without a copy; the next frame sizes
  // new buffers.
  void takeHairs(fur::FurFrame& out) { std::swap(out, state_.fur); }
  const fur::FurDynamicsState& dynamicsState() const { return dynamics_; }

 private:
  void evaluatePose(int frame, FrameState& into) const;
  // Advances the springs to the posed frame; with a view, also the frame's hairs.
  void step(const fur::FurView* view);

  const Model* model_;
  const Fur* fur_;
  PlaybackOptions options_;
  anatomy::Pose stillPose_;
  anatomy::Pose played_, blendScratch_;       // posePlayed's pose and cross-fade scratch
  std::optional<Eigen::Vector3f> turnPivot_;  // posePlayed's turntable pivot, from its first pose
  FrameState state_;
  FrameState scratch_;  // the pre-roll's frames
  Framing firstFraming_;
  DrawList list_;
  // Dynamic fur: the springs, whether they run (false: the next step restarts them), the roots
  // they were sized to, whether the posed frame still needs its step and how long it is (the
  // sequence's 1 / fps, or the time between the viewer's poses).
  fur::FurDynamicsState dynamics_;
  bool running_ = false;
  std::uint64_t generation_ = 0;
  bool stepPending_ = false;
  double stepSeconds_ = 0.0;
  int nextFrame_ = -1;  // the sequence frame the springs are ready to step to (-1: none)
};

}  // namespace pelage::scene
