#include "viewer_session.h"

#include <algorithm>
#include <cmath>

#include "pelage/anatomy/pose_file.h"
#include "pelage/animation/clip.h"
#include "pelage/fur/preset.h"
#include "pelage/util/error.h"
#include "pelage/viewer/gl_context.h"

namespace pelage::viewer::detail {
namespace {

fur::FurParams initialParams(const ViewerOptions& o) {
  fur::FurParams p = o.fur;
  if (o.noCulling) p.culling.enabled = false;
  fur::validateFurParams(p, "fur '" + p.name + "'");
  return p;
}

}  // namespace

ViewerSession::ViewerSession(const ViewerOptions& options, scene::Model model)
    : edit(initialParams(options)), model_(std::move(model)) {
  stillPose_ = options.posePath.empty() ? anatomy::restPose(model_.body)
                                        : anatomy::loadPose(model_.body, options.posePath);
  if (!options.clip.empty() && !options.posePath.empty())
    inputError("--pose and --clip cannot be used together");
  if (!(options.time >= 0.0 && options.time <= 1e6))
    inputError("--time ", options.time, " is out of range [0, 1000000] s");
  if (!options.clip.empty()) {
    clip_ = model_.findClip(options.clip);
    if (clip_ < 0) {
      std::string names;
      for (const animation::Clip& c : model_.clips) names += (names.empty() ? "" : ", ") + c.name;
      inputError("--clip: model '", model_.name, "' has no clip '", options.clip, "' (",
                 names.empty() ? std::string("it has no clips") : "its clips: " + names, ")");
    }
  } else if (options.posePath.empty() && !model_.clips.empty()) {
    clip_ = 0;
  }
  time_ = options.time;
  fur_ = scene::growFur(model_, edit, "fur '" + edit.name + "'");
  follow = options.follow;
  hairSource = options.hairSource == "cpu" ? scene::HairSource::Cpu : scene::HairSource::Gpu;
  if (options.hairSource != "cpu" && options.hairSource != "gpu")
    inputError("--hair-source '", options.hairSource, "' (accepted: gpu, cpu)");
  shading = scene::parseHairShading(options.shading);
  hairWidth = options.ribbons ? scene::HairWidth::Ribbons : scene::HairWidth::Lines;
  shadows = options.shadows;
  dynamics = options.dynamics;
  dynamicsParams = options.dynamicsParams;
  fur::validateDynamicsParams(dynamicsParams, "--frequency/--damping");
  skinColor = model_.skin.color;
  if (!options.skinColor.empty()) {
    if (options.skinColor.size() != 3)
      inputError("--skin-color takes 3 values (R G B in [0, 1]), got ", options.skinColor.size());
    for (int c = 0; c < 3; ++c) {
      const float v = options.skinColor[static_cast<std::size_t>(c)];
      if (!(v >= 0.0f && v <= 1.0f))
        inputError("--skin-color ", "RGB"[c], " = ", v, " is out of range [0, 1]");
      skinColor[c] = v;
    }
  }
  RendererOptions ro;
  ro.samples = options.samples;
  if (ro.samples < 0) {
    // MSAA costs ~2.3x on llvmpipe (../shared/docs/headless-gl.md): keep software rasterisers fast.
    ContextInfo info;
    queryContextInfo(info);
    ro.samples = info.software ? 0 : 4;
  }
  renderer_ = std::make_unique<Renderer>(ro);
  // The first camera: the preset on the first frame.
  posedFrame();
  framing_ = scene::framingOf(model_, frame_, scene::maxHairLength(model_, fur_.params));
  lastRoot_ = framing_.rootPosition;
  pivot_ = Eigen::Vector3f(framing_.center.x(), framing_.center.y(), 0.0f);
  pendingPreset_ = scene::parseCameraPreset(options.camera);
  orbit =
      scene::orbitOf(scene::presetCamera(framing_, *pendingPreset_, options.width, options.height));
}

ViewerSession::~ViewerSession() {
  if (pending_.valid()) pending_.wait();  // the worker reads model_
}

float ViewerSession::referenceDistance() const {
  return fur::referenceDistance(model_.skin, fur_.params.culling);
}

void ViewerSession::applyPreset(scene::CameraPreset preset) {
  pendingPreset_ = preset;
  if (preset == scene::CameraPreset::Follow) follow = true;
}

void ViewerSession::orbitBy(float dAzimuthDeg, float dElevationDeg) {
  orbit.azimuthDegrees = std::fmod(orbit.azimuthDegrees + dAzimuthDeg, 360.0f);
  orbit.elevationDegrees = std::clamp(orbit.elevationDegrees + dElevationDeg, -89.0f, 89.0f);
}

void ViewerSession::panBy(float dx, float dy) {
  const scene::Camera cam = scene::orbitCamera(orbit, 16, 16);
  const Eigen::Vector3f f = (cam.target - cam.eye).normalized();
  const Eigen::Vector3f right = f.cross(Eigen::Vector3f::UnitZ()).normalized();
  const Eigen::Vector3f up = right.cross(f);
  const float h = 2.0f * orbit.distanceMeters * std::tan(cam.fovYDegrees * 3.14159265f / 360.0f);
  orbit.target += (-dx * right + dy * up) * h;
}

void ViewerSession::zoomBy(float factor) {
  orbit.distanceMeters = std::clamp(orbit.distanceMeters * factor, 1e-3f, 1e4f);
}

void ViewerSession::loadPreset(const std::string& nameOrPath) {
  try {
    fur::FurParams p = fur::loadFurPreset(nameOrPath);
    edit = p;
    message = "loaded " + nameOrPath;
  } catch (const InputError& e) {
    message = e.what();
  }
}

void ViewerSession::savePreset(const std::string& path) {
  try {
    fur::FurParams p = edit;
    fur::validateFurParams(p, "fur panel");
    fur::saveFurPreset(path, p);
    message = "saved " + path;
  } catch (const InputError& e) {
    message = e.what();
  }
}

// Parameters take effect on the next frame; a new hair count, undercoat share or seed regrows the
// roots on a worker thread while the old fur keeps drawing, and swaps them in when ready.
void ViewerSession::applyEdits() {
  fur::FurParams candidate = edit;
  try {
    fur::validateFurParams(candidate, "fur panel");
    editError.clear();
  } catch (const InputError& e) {
    editError = e.what();
    return;
  }
  if (pending_.valid() && pending_.wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
    try {
      fur_ = pending_.get();
    } catch (const InputError& e) {
      editError = e.what();  // e.g. a hair count over the memory budget
      edit.hairs = fur_.params.hairs;
      edit.densityPerM2 = fur_.params.densityPerM2;
    }
  }
  if (scene::rootsDiffer(fur_.params, candidate)) {
    if (!pending_.valid()) {
      pending_ = std::async(std::launch::async, [this, candidate] {
        return scene::growFur(model_, candidate, "fur panel");
      });
    }
    // Until the new roots arrive, everything but the root parameters applies to the old ones.
    const fur::FurParams& grown = fur_.params;
    candidate.hairs = grown.hairs;
    candidate.densityPerM2 = grown.densityPerM2;
    candidate.undercoatShare = grown.undercoatShare;
    candidate.seed = grown.seed;
  }
  fur_.params = candidate;
}

void ViewerSession::selectClip(int index) {
  if (index == clip_ || index < -1 || index >= static_cast<int>(model_.clips.size())) return;
  if (clip_ >= 0 && index >= 0) {
    fromClip_ = clip_;
    fromTime_ = time_;
    fadeSeconds_ = 0.0;
    time_ = animation::syncedTime(model_.clips[static_cast<std::size_t>(clip_)], time_,
                                  model_.clips[static_cast<std::size_t>(index)]);
  } else {
    fromClip_ = -1;
    time_ = 0.0;
  }
  clip_ = index;
  dynamicsRunning_ = false;
}

void ViewerSession::setTime(double seconds) {
  time_ = std::max(seconds, 0.0);
  fromClip_ = -1;  // scrubbing ends a cross-fade
  dynamicsRunning_ = false;
}

double ViewerSession::clipDuration() const {
  return clip_ >= 0 ? static_cast<double>(model_.clips[static_cast<std::size_t>(clip_)].duration)
                    : 0.0;
}

void ViewerSession::advance(double dtSeconds) {
  // The dynamic springs step by the played clip time; with the clip still (paused, speed 0), by
  // the wall time, so hairs keep settling.
  lastStep_ = dtSeconds;
  if (!playing) return;
  const double step = dtSeconds * static_cast<double>(speed);
  if (step > 0.0) lastStep_ = step;
  time_ += step;
  fromTime_ += step;
  fadeSeconds_ += dtSeconds;
  if (fromClip_ >= 0 && fadeSeconds_ >= kCrossFadeSeconds) fromClip_ = -1;
  // Without looping a clip plays once and stops on its last frame.
  if (!loop && clip_ >= 0 && time_ >= clipDuration()) {
    time_ = clipDuration();
    playing = false;
  }
}

void ViewerSession::posedFrame() {
  if (clip_ >= 0) {
    const animation::Clip& c = model_.clips[static_cast<std::size_t>(clip_)];
    if (fromClip_ >= 0) {
      const float w = animation::crossFadeWeight(fadeSeconds_, kCrossFadeSeconds);
      animation::sampleBlend(model_.clips[static_cast<std::size_t>(fromClip_)], fromTime_, c, time_,
                             w, model_.body, blendScratch_, pose_);
    } else {
      animation::sampleClip(c, model_.body, time_, pose_);
    }
  } else {
    pose_ = stillPose_;  // same size every frame: no allocation after the first
  }
  if (turntableDegPerSecond != 0.0f) {
    // The root segment turned about the world +Z axis through the creature's first centre.
    const double deg = std::fmod(time_ * static_cast<double>(turntableDegPerSecond), 360.0);
    const Eigen::Quaternionf q(Eigen::AngleAxisf(static_cast<float>(deg * 3.14159265358979 / 180.0),
                                                 Eigen::Vector3f::UnitZ()));
    anatomy::Transform& root = pose_.local[0];
    root.rotation = q * root.rotation;
    root.translation = q * (root.translation - pivot_) + pivot_;
  }
  scene::evaluateFrame(model_, pose_, frame_);
}

void ViewerSession::frame(double dtSeconds, int width, int height) {
  applyEdits();
  posedFrame();
  framing_ = scene::framingOf(model_, frame_, scene::maxHairLength(model_, fur_.params));
  if (follow) orbit.target += framing_.rootPosition - lastRoot_;
  lastRoot_ = framing_.rootPosition;
  if (pendingPreset_) {
    orbit = scene::orbitOf(
        scene::presetCamera(framing_, *pendingPreset_, std::max(width, 1), std::max(height, 1)));
    pendingPreset_.reset();
  }
  scene::Camera cam = scene::orbitCamera(orbit, std::max(width, 1), std::max(height, 1));
  // Clip planes around the creature, so zooming far out or close in keeps it visible.
  const float d = (cam.eye - framing_.center).norm();
  cam.nearMeters = std::max((d - framing_.radius) * 0.5f, framing_.radius * 0.002f);
  cam.farMeters = d + framing_.radius * 2.0f;
  const bool cpu = hairSource == scene::HairSource::Cpu || dynamics;
  if (drawFur && dynamics) {
    dynamicFur(cam.eye, lastStep_);
  } else {
    dynamicsRunning_ = false;
    if (drawFur) scene::evaluateFur(model_, fur_, cam.eye, cpu, frame_);
  }
  scene::Light light;
  light.direction = scene::lightDirection(lightAzimuth, lightElevation);
  light.shadows = shadows;
  scene::DrawOptions opt;
  opt.hairSource = cpu ? scene::HairSource::Cpu : hairSource;
  opt.hairShading = shading;
  opt.hairWidth = hairWidth;
  opt.drawSkin = drawSkin;
  opt.drawFur = drawFur;
  scene::buildDrawList(model_, frame_, drawFur ? &fur_ : nullptr, cam, light, opt, list_);
  list_.ribbonRootWidthPixels = ribbonWidth;
  if (list_.skin.positions) list_.skin.material = scene::skinMaterial(skinColor);
  const RenderStats stats = renderer_->render(list_);
  hairsDrawn_ = stats.hairsDrawn;
  advance(dtSeconds);  // the first frame shows the start time exactly
}

void ViewerSession::dynamicFur(const Eigen::Vector3f& cameraEye, double stepSeconds) {
  // The spring parameters come from the panel: invalid ones (mid-edit) keep the last valid set.
  try {
    fur::validateDynamicsParams(dynamicsParams, "dynamics panel");
    appliedDynamics_ = dynamicsParams;
  } catch (const InputError& e) {
    editError = e.what();
  }
  if (!dynamicsRunning_ || dynamicsGeneration_ != fur_.generation) {
    fur::resetFurDynamics(fur_.roots, dynamicsState_);
    dynamicsGeneration_ = fur_.generation;
    dynamicsRunning_ = true;
  }
  // The spring step is exact for any dt; dt is kept in [1 ms, 1 s] (fps [1, 1000]); the first
  // frame's (0) is ignored after a reset.
  scene::DynamicsClock clock;
  clock.fps = 1.0 / std::clamp(stepSeconds, 1e-3, 1.0);
  scene::stepClipDynamics(model_, fur_, appliedDynamics_, clock, cameraEye, true, dynamicsState_,
                          frame_);
}

}  // namespace pelage::viewer::detail
