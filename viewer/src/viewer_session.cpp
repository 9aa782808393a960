#include "viewer_session.h"

#include <algorithm>
#include <cmath>

#include "pelage/anatomy/pose_file.h"
#include "pelage/animation/clip.h"
#include "pelage/fur/groom.h"
#include "pelage/fur/groom_strokes.h"
#include "pelage/fur/preset.h"
#include "pelage/render/gl_context.h"
#include "pelage/util/atomic_file.h"
#include "pelage/util/error.h"

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
    : edit(initialParams(options)),
      model_(std::move(model)),
      groomEditor_(model_, scene::startingGroom(model_, edit, "fur '" + edit.name + "'")) {
  if (!(options.time >= 0.0 && options.time <= 1e6))
    fieldError("time", options.time, " is out of range [0, 1000000] s");
  stillPose_ = options.stillPose.local.empty() ? anatomy::restPose(model_.body) : options.stillPose;
  PELAGE_CHECK(static_cast<int>(stillPose_.local.size()) == model_.body.size(), "still pose of ",
               stillPose_.local.size(), " segments");
  const int clips = static_cast<int>(model_.clips.size());
  PELAGE_CHECK(options.clip >= -1 && (options.clip < clips || clips == 0), "clip ", options.clip,
               " of ", clips);
  clip_ = clips > 0 ? options.clip : -1;
  time_ = options.time;
  for (std::size_t i = 0; i < options.strokes.size(); ++i)
    groomEditor_.applyStroke(options.strokes[i], "strokes[" + std::to_string(i) + "]");
  if (!options.strokes.empty()) {
    groomEdited_ = true;
    brushMode = true;
    fur_ = scene::growFur(model_, edit, groomEditor_.groom(), "fur '" + edit.name + "'");
  } else {
    fur_ = scene::growFur(model_, edit, "fur '" + edit.name + "'");
  }
  grownRevision_ = groomEditor_.revision();
  follow = options.follow;
  hairSource = options.hairSource;
  shading = options.shading;
  hairWidth = options.hairWidth;
  transparency = options.transparency;
  shadows = options.shadows;
  selfShadowing = options.selfShadowing;
  lightAzimuth = options.lightAzimuth;
  lightElevation = options.lightElevation;
  lightColor = options.lightColor;
  ambient = options.ambient;
  dynamics = options.dynamics;
  dynamicsParams = options.dynamicsParams;
  fur::validateDynamicsParams(dynamicsParams, "dynamics");
  appliedDynamics_ = dynamicsParams;
  skinColor = model_.skin.color;
  if (options.skinColor) {
    scene::validateColor(*options.skinColor, "skin color");
    skinColor = *options.skinColor;
    ownSkinColor = true;
  }
  background = options.background;
  render::RendererOptions ro;
  ro.samples = options.samples;
  renderer_ = std::make_unique<render::Renderer>(ro);
  scene::PlaybackOptions po;
  po.stillPose = stillPose_;
  po.hairSource = hairSource;
  playback_ = std::make_unique<scene::Playback>(model_, fur_, po);
  // The first camera: the preset on the first frame.
  playback_->posePlayed(played(), 0.0);
  framing_ = playback_->framing();
  lastRoot_ = framing_.rootPosition;
  pendingPreset_ = options.camera;
  orbit =
      scene::orbitOf(scene::presetCamera(framing_, *pendingPreset_, options.width, options.height));
}

ViewerSession::~ViewerSession() {
  if (pending_.valid()) pending_.wait();  // the worker reads model_
}

float ViewerSession::referenceDistance() const {
  return fur::referenceDistance(fur_.params);
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
      grownRevision_ = pendingRevision_;
    } catch (const InputError& e) {
      grownRevision_ = pendingRevision_;  // that groom cannot grow: not retried every frame
      editError = e.what();               // e.g. a hair count over the memory budget
      edit.hairs = fur_.params.hairs;
      edit.densityPerM2 = fur_.params.densityPerM2;
      edit.coverage = fur_.params.coverage;
    }
  }
  const bool newRoots = scene::rootsDiffer(fur_.params, candidate);
  if ((newRoots || grownRevision_ != groomEditor_.revision()) && !pending_.valid()) {
    // The latest brushed groom grows with the panel's parameters; strokes drawn meanwhile wait
    // for the next regrowth (the fur catches up as soon as this one lands).
    pendingRevision_ = groomEditor_.revision();
    if (groomEdited_) {
      pending_ = std::async(std::launch::async, [this, candidate, g = groomEditor_.groom()] {
        return scene::growFur(model_, candidate, g, "fur panel");
      });
    } else {
      pending_ = std::async(std::launch::async, [this, candidate] {
        return scene::growFur(model_, candidate, "fur panel");
      });
    }
  }
  if (newRoots) {
    // Until the new roots arrive, everything but the root parameters applies to the old ones.
    const fur::FurParams& grown = fur_.params;
    candidate.hairs = grown.hairs;
    candidate.densityPerM2 = grown.densityPerM2;
    candidate.coverage = grown.coverage;
    candidate.undercoatShare = grown.undercoatShare;
    candidate.seed = grown.seed;
    candidate.maps.density = grown.maps.density;
    candidate.maps.length = grown.maps.length;
    for (std::size_t c = 0; c < candidate.coats.size(); ++c) {  // the clumps the roots carry
      candidate.coats[c].clump.density = grown.coats[c].clump.density;
      candidate.coats[c].clump.radiusMm = grown.coats[c].clump.radiusMm;
      if (!grown.coats[c].clump.on()) candidate.coats[c].clump.strength = 0.0f;
    }
  }
  // Colour edits recolour the roots in place (no new roots); a source the creature lacks or an
  // unreadable colour map is reported and the colours stay as they were.
  if (scene::colorsDiffer(fur_.params, candidate)) {
    try {
      scene::recolorFur(model_, fur_, candidate, "fur panel");
    } catch (const InputError& e) {
      editError = e.what();
      const fur::FurParams& kept = fur_.params;
      candidate.maps.color = edit.maps.color = kept.maps.color;
      for (std::size_t c = 0; c < candidate.coats.size(); ++c) {
        for (fur::CoatParams* p : {&candidate.coats[c], &edit.coats[c]}) {
          p->color = kept.coats[c].color;
          p->material.diffuse = kept.coats[c].material.diffuse;
          p->material.ambient = kept.coats[c].material.ambient;
        }
      }
    }
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
  playback_->restartDynamics();
}

void ViewerSession::setTime(double seconds) {
  time_ = std::max(seconds, 0.0);
  fromClip_ = -1;  // scrubbing ends a cross-fade
  playback_->restartDynamics();
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

scene::PlayedPose ViewerSession::played() const {
  scene::PlayedPose p;
  p.clip = clip_;
  p.seconds = time_;
  if (clip_ >= 0 && fromClip_ >= 0) {
    p.fromClip = fromClip_;
    p.fromSeconds = fromTime_;
    p.fadeWeight = animation::crossFadeWeight(fadeSeconds_, kCrossFadeSeconds);
  }
  if (turntableDegPerSecond != 0.0f)
    p.turnDegrees = std::fmod(time_ * static_cast<double>(turntableDegPerSecond), 360.0);
  return p;
}

void ViewerSession::frame(double dtSeconds, int width, int height) {
  applyEdits();
  // Dynamic fur (its springs step by the played time): parameters from the panel; invalid ones
  // (mid-edit) keep the last valid set. Without fur drawn the springs stop, and restart with it.
  if (dynamics && drawFur) {
    try {
      fur::validateDynamicsParams(dynamicsParams, "dynamics panel");
      appliedDynamics_ = dynamicsParams;
    } catch (const InputError& e) {
      editError = e.what();
    }
  }
  playback_->setDynamics(dynamics && drawFur, appliedDynamics_);
  playback_->setHairSource(hairSource);
  playback_->posePlayed(played(), lastStep_);
  framing_ = playback_->framing();
  if (follow) orbit.target += framing_.rootPosition - lastRoot_;
  lastRoot_ = framing_.rootPosition;
  if (pendingPreset_) {
    orbit = scene::orbitOf(
        scene::presetCamera(framing_, *pendingPreset_, std::max(width, 1), std::max(height, 1)));
    pendingPreset_.reset();
  }
  scene::Camera cam = scene::orbitCamera(orbit, std::max(width, 1), std::max(height, 1));
  scene::fitClipPlanes(cam, framing_);
  lastCamera_ = cam;  // picking: the viewport's pixels
  // The brush preview, while a stroke is drawn or its fur grows: the frame at half the size
  // (the window scales it up) and culling (sec. 3.3) with the reference distance shortened so that
  // c is at least the total over the preview's hairs (the next frame's applyEdits restores it). A
  // software rasteriser's frame time is bound by the coat's fragments, which culling keeps (each
  // drawn hair widens), so the smaller image is what makes it keep up.
  previewing_ = brushPreviewHairs > 0.0 && (groomEditor_.drawing() || !groomShown());
  if (previewing_) {
    cam.width = std::max(cam.width / 2, 1);
    cam.height = std::max(cam.height / 2, 1);
    const double total = static_cast<double>(fur_.roots.total());
    const fur::FurView view =
        fur::makeFurView(fur_.params, playback_->state().skin, scene::viewCamera(cam));
    const float ratio = fur::pixelsPerMeter(view.referenceDistance, view.referenceFovYDegrees,
                                            view.referenceHeight) /
                        fur::pixelsPerMeter(view.viewDistance, view.fovYDegrees, view.imageHeight);
    const auto target = static_cast<float>(total / brushPreviewHairs);
    if (total > brushPreviewHairs && (!fur_.params.culling.enabled || ratio < target)) {
      fur_.params.culling.enabled = true;
      fur_.params.culling.referenceDistance = view.referenceDistance * ratio / target;
    }
  }
  if (drawFur) playback_->evaluateFur(cam);
  scene::Light light;
  light.direction = scene::lightDirection(lightAzimuth, lightElevation);
  light.color = lightColor;
  light.ambient = ambient;
  light.shadows = shadows;
  light.selfShadowing = selfShadowing;
  scene::DrawOptions opt;
  opt.hairShading = shading;
  opt.hairWidth = hairWidth;
  opt.transparency = transparency;
  opt.drawSkin = drawSkin;
  opt.drawFur = drawFur;
  opt.background = background;
  const Material skin = scene::skinMaterial(skinColor);
  list_ = &playback_->drawList(cam, light, opt, ownSkinColor ? &skin : nullptr);
  const render::RenderStats stats = renderer_->render(*list_);
  hairsDrawn_ = stats.hairsDrawn;
  advance(dtSeconds);  // the first frame shows the start time exactly
}

std::optional<scene::SkinHit> ViewerSession::skinAt(float x, float y) const {
  if (playback_->state().skin.positions.empty()) return std::nullopt;  // before the first frame
  return scene::pickSkin(model_, playback_->state(), lastCamera_, x, y);
}

float ViewerSession::brushRadiusAt(const scene::SkinHit& hit) const {
  return brush.screenRadius ? scene::pixelsToMeters(lastCamera_, brush.radius, hit.distance)
                            : brush.radius;
}

float ViewerSession::metersToPixels(const scene::SkinHit& hit, float meters) const {
  return meters * fur::pixelsPerMeter(hit.distance, lastCamera_.fovYDegrees, lastCamera_.height);
}

bool ViewerSession::brushAt(float x, float y) {
  const std::optional<scene::SkinHit> hit = skinAt(x, y);
  if (!hit) return false;
  if (!groomEditor_.drawing()) {
    // The radius is fixed at the stroke's first point (a screen radius: at its depth).
    fur::GroomStroke s = brush.stroke;
    s.radius = std::min(brushRadiusAt(*hit), fur::kMaxBrushRadiusMeters);
    try {
      groomEditor_.beginStroke(s, "brush");
    } catch (const InputError& e) {
      editError = e.what();
      return true;
    }
    strokeRadius_ = s.radius;
  }
  if (groomEditor_.addPoint(hit->rest, 0.25f * strokeRadius_)) groomEdited_ = true;
  return true;
}

void ViewerSession::endBrush() {
  groomEditor_.endStroke();
}

void ViewerSession::undoStroke() {
  groomEditor_.undo();
}

void ViewerSession::redoStroke() {
  groomEditor_.redo();
}

void ViewerSession::saveGroom(const std::string& path) {
  try {
    fur::writeGroomFile(path, model_.skin, groomEditor_.groom());
    message = "saved " + path + " (" + std::to_string(groomEditor_.strokes().size()) + " strokes)";
  } catch (const InputError& e) {
    message = e.what();
  }
}

void ViewerSession::saveStrokes(const std::string& path) {
  try {
    writeFileAtomically(path, fur::groomStrokesJson(groomEditor_.strokes()));
    message = "saved " + path + " (" + std::to_string(groomEditor_.strokes().size()) + " strokes)";
  } catch (const InputError& e) {
    message = e.what();
  }
}

void ViewerSession::loadGroom(const std::string& path) {
  try {
    groomEditor_.reset(fur::readGroomFile(path, model_.skin, model_.name));
    groomEdited_ = true;
    message = "loaded " + path;
  } catch (const InputError& e) {
    message = e.what();
  }
}

}  // namespace pelage::viewer::detail
