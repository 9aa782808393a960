#include "pelage/scene/playback.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

#include "pelage/animation/clip.h"
#include "pelage/util/error.h"
#include "pelage/util/interrupt.h"

namespace pelage::scene {

FrameRange wholeClip(const Model& model, int clip, double fps) {
  if (clip < 0) return {0, 0};
  const double duration =
      static_cast<double>(model.clips.at(static_cast<std::size_t>(clip)).duration);
  return {0, static_cast<int>(std::lround(duration * fps))};
}

int oneFrameAt(PlaybackOptions& options, double seconds) {
  validateStartSeconds(seconds);
  if (!options.dynamics) {
    options.clock.startSeconds = seconds;
    return 0;
  }
  options.clock.startSeconds = 0.0;
  return static_cast<int>(std::lround(seconds * options.clock.fps));
}

void validatePlaybackOptions(const Model& model, const PlaybackOptions& o) {
  PELAGE_CHECK(o.clip >= -1 && o.clip < static_cast<int>(model.clips.size()), "clip ", o.clip,
               " of ", model.clips.size());
  validateClock(o.clock);
  if (o.dynamics) {
    if (o.clip < 0) fieldError("dynamics", "on needs a clip: the rest pose does not move");
    fur::validateDynamicsParams(o.dynamicsParams, "dynamics");
  }
  if (o.clip < 0 && !o.stillPose.local.empty())
    PELAGE_CHECK(static_cast<int>(o.stillPose.local.size()) == model.body.size(), "still pose of ",
                 o.stillPose.local.size(), " segments, body ", model.body.size());
}

Playback::Playback(const Model& model, const Fur& fur, PlaybackOptions options)
    : model_(&model), fur_(&fur), options_(std::move(options)) {
  validatePlaybackOptions(model, options_);
  stillPose_ =
      options_.stillPose.local.empty() ? anatomy::restPose(model.body) : options_.stillPose;
  stepSeconds_ = 1.0 / options_.clock.fps;
  generation_ = fur.generation;
  evaluatePose(0, state_);
  firstFraming_ = framing();
}

HairSource Playback::hairSource() const {
  // Fur dynamics run on the CPU only (the GPU shader has no state to step).
  return options_.hairSource == HairSource::Cpu || options_.dynamics ? HairSource::Cpu
                                                                     : HairSource::Gpu;
}

void Playback::setFur(const Fur& fur) {
  fur_ = &fur;
}

void Playback::setDynamics(bool on, const fur::DynamicsParams& params) {
  if (on && !options_.dynamics) running_ = false;
  options_.dynamics = on;
  options_.dynamicsParams = params;
  if (!on) running_ = false;
}

void Playback::evaluatePose(int frame, FrameState& into) const {
  if (options_.clip >= 0)
    evaluateClipFrame(*model_, options_.clip, options_.clock.secondsAt(frame), into);
  else
    evaluateFrame(*model_, stillPose_, into);
}

void Playback::poseFrame(int frame) {
  PELAGE_CHECK(frame >= 0, "frame ", frame);
  checkInterrupt();  // every frame any command or binding plays: a stop asked for ends it here
  if (options_.dynamics && frame != nextFrame_) {
    // Reached out of order (the first frame, or one after skipped frames): pre-roll the springs
    // through the frames before it, exactly as a whole run from frame 0 reaches it.
    preRollDynamics(*model_, *fur_, options_.dynamicsParams, options_.clip, frame, options_.clock,
                    dynamics_, scratch_);
    running_ = true;
    generation_ = fur_->generation;
    nextFrame_ = frame;
  }
  evaluatePose(frame, state_);
  stepSeconds_ = 1.0 / options_.clock.fps;
  stepPending_ = true;
}

void Playback::holdFrame() {
  checkInterrupt();
  stepSeconds_ = 1.0 / options_.clock.fps;
  stepPending_ = true;
  nextFrame_ = -1;
}

void Playback::posePose(const anatomy::Pose& pose, double stepSeconds) {
  evaluateFrame(*model_, pose, state_);
  // The spring step is exact for any dt; dt is kept in [1 ms, 1 s] (fps [1, 1000]).
  stepSeconds_ = std::clamp(stepSeconds, 1e-3, 1.0);
  stepPending_ = true;
  nextFrame_ = -1;
}

void Playback::posePlayed(const PlayedPose& p, double stepSeconds) {
  const auto clips = static_cast<int>(model_->clips.size());
  PELAGE_CHECK(p.clip >= -1 && p.clip < clips && p.fromClip >= -1 && p.fromClip < clips, "clips ",
               p.clip, " and ", p.fromClip, " of ", clips);
  if (p.clip < 0) {
    played_ = stillPose_;  // same size every frame: no allocation after the first
  } else if (p.fromClip >= 0) {
    animation::sampleBlend(model_->clips[static_cast<std::size_t>(p.fromClip)], p.fromSeconds,
                           model_->clips[static_cast<std::size_t>(p.clip)], p.seconds, p.fadeWeight,
                           model_->body, blendScratch_, played_);
  } else {
    animation::sampleClip(model_->clips[static_cast<std::size_t>(p.clip)], model_->body, p.seconds,
                          played_);
  }
  if (!turnPivot_) {
    // The turntable's pivot: the centre of the first pose played, on the ground plane.
    posePose(played_, stepSeconds);
    const Framing f = framing();
    turnPivot_ = Eigen::Vector3f(f.center.x(), f.center.y(), 0.0f);
  }
  if (p.turnDegrees != 0.0) {
    const double deg = std::fmod(p.turnDegrees, 360.0);
    const Eigen::Quaternionf q(Eigen::AngleAxisf(static_cast<float>(deg * 3.14159265358979 / 180.0),
                                                 Eigen::Vector3f::UnitZ()));
    anatomy::Transform& root = played_.local[0];
    root.rotation = q * root.rotation;
    root.translation = q * (root.translation - *turnPivot_) + *turnPivot_;
  }
  posePose(played_, stepSeconds);
}

Framing Playback::framing() const {
  return framingOf(*model_, state_, maxHairLength(*model_, fur_->params));
}

void Playback::step(const fur::FurView* view) {
  PELAGE_CHECK(stepPending_, "the springs were stepped to this pose already");
  if (!running_ || generation_ != fur_->generation) {
    // Restart from the quasi-static hairs: the first step after a reset starts on them, at rest.
    fur::resetFurDynamics(fur_->roots, dynamics_);
    generation_ = fur_->generation;
    running_ = true;
  }
  stepClipDynamics(*model_, *fur_, options_.dynamicsParams, stepSeconds_, view, dynamics_, state_);
  stepPending_ = false;
  if (nextFrame_ >= 0) ++nextFrame_;
}

void Playback::evaluateFur(const Camera& camera) {
  evaluateFur(fur::makeFurView(fur_->params, state_.skin, viewCamera(camera)));
}

void Playback::evaluateFur(const fur::FurView& view) {
  if (options_.dynamics) {
    step(&view);
    return;
  }
  scene::evaluateFur(*model_, *fur_, view, cpuHairs(), state_);
}

void Playback::stepDynamics() {
  PELAGE_CHECK(options_.dynamics, "stepDynamics without dynamics");
  step(nullptr);
}

const DrawList& Playback::drawList(const Camera& camera, const Light& light,
                                   const DrawOptions& options, const Material* skin) {
  DrawOptions o = options;
  o.hairSource = hairSource();
  if (skin)
    buildDrawList(*model_, state_, fur_, camera, light, o, *skin, list_);
  else
    buildDrawList(*model_, state_, fur_, camera, light, o, list_);
  return list_;
}

Camera Playback::sequenceCamera(int frame, const CameraRig& rig, int width, int height) {
  poseFrame(frame);
  return rigCamera(rig, firstFraming_, framing(), frame, width, height);
}

const DrawList& Playback::sequenceFrame(int frame, const CameraRig& rig, int width, int height,
                                        const Light& light, const DrawOptions& options,
                                        const Material* skin) {
  const Camera camera = sequenceCamera(frame, rig, width, height);
  evaluateFur(camera);
  return drawList(camera, light, options, skin);
}

}  // namespace pelage::scene
