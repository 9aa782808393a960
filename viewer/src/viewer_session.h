// The state of one viewer run, shared by the window loop (with its ImGui panel) and the headless
// loop: the model, the fur (with roots regrown on a worker thread when the hair count changes),
// playback, camera, light and render settings, and the renderer. Private to pelage::viewer.
#pragma once

#include <chrono>
#include <cstdint>
#include <future>
#include <memory>
#include <optional>
#include <string>

#include "pelage/fur/dynamics.h"
#include "pelage/render/renderer.h"
#include "pelage/scene/draw_list.h"
#include "pelage/scene/dynamic_fur.h"
#include "pelage/scene/frame.h"
#include "pelage/scene/groom_editor.h"
#include "pelage/scene/playback.h"
#include "pelage/viewer/viewer_app.h"

namespace pelage::viewer::detail {

class ViewerSession {
 public:
  // Takes the model, loads the fur preset, grows the roots (on the calling thread) and creates the
  // renderer; needs a current OpenGL context.
  ViewerSession(const ViewerOptions& options, scene::Model model);
  ~ViewerSession();

  // Evaluates the frame at the current time for a width x height viewport, renders it into the
  // renderer's framebuffer, then advances playback by `dtSeconds` of wall time.
  void frame(double dtSeconds, int width, int height);

  // ---- What the UI edits (applied on the next frame) -----------------------------------------
  fur::FurParams edit;    // the parameters being edited; roots follow when count/share/seed change
  std::string editError;  // why `edit` was not applied (validation message), or empty
  std::string message;    // last preset save/load result
  scene::Orbit orbit;
  bool follow = false;
  scene::HairSource hairSource = scene::HairSource::Gpu;  // the CPU's hairs with dynamics on
  scene::HairShading shading = scene::kDefaultHairShading;
  scene::HairWidth hairWidth = scene::HairWidth::Strands;
  bool transparency = true;
  Eigen::Vector3f skinColor;  // the skin's diffuse colour (the model's, or --skin-color)
  // The skin drawn in skinColor alone (set, or edited in the panel); else in the model's own
  // colours (materials, textures, vertex colours), as `pelage render` draws it.
  bool ownSkinColor = false;
  Eigen::Vector3f background = scene::kDefaultBackground;  // linear RGB
  bool drawSkin = true;
  bool drawFur = true;
  float lightAzimuth = scene::kKeyLightAzimuthDegrees;
  float lightElevation = scene::kKeyLightElevationDegrees;
  Eigen::Vector3f lightColor = scene::Light{}.color;
  Eigen::Vector3f ambient = scene::Light{}.ambient;
  bool shadows = false;
  bool selfShadowing = true;
  bool playing = true;
  float turntableDegPerSecond = 0.0f;  // without a clip: turn the creature about +Z (0 = still)
  bool loop = true;
  float speed = 1.0f;
  // Dynamic fur (fur/dynamics.h): each hair's end follows the paper's through a damped spring,
  // stepped by the played time; its hairs are computed on the CPU. Restarts from the quasi-static
  // hairs when switched on, when the roots are regrown, on a clip change and when scrubbing.
  bool dynamics = false;
  fur::DynamicsParams dynamicsParams;

  // Playback of the model's clips (none: the still pose).
  int clip() const { return clip_; }
  // Switches to clip `index` (-1: the still pose), cross-fading over kCrossFadeSeconds in step
  // (the new clip starts at the same phase).
  void selectClip(int index);
  double time() const { return time_; }
  void setTime(double seconds);  // scrubbing
  double clipDuration() const;   // 0 without a clip
  static constexpr double kCrossFadeSeconds = 0.3;

  // Camera presets and orbit controls.
  void applyPreset(scene::CameraPreset preset);
  void orbitBy(float dAzimuthDeg, float dElevationDeg);
  void panBy(float dxFraction, float dyFraction);  // fractions of the view height
  void zoomBy(float factor);                       // distance *= factor

  // Presets (the fur module's JSON format). Saving writes the panel's parameters (`edit`) when they
  // are valid, so a hair count still being regrown is saved too; otherwise it reports why not.
  void loadPreset(const std::string& nameOrPath);
  void savePreset(const std::string& path);

  // ---- Grooming (issue 28): brushes on the skin under the cursor ------------------------------
  // The brush the panel sets: the stroke's tool, strength, colour, cut length and mirror (its
  // points come from the cursor), and its radius in metres on the skin or in pixels on the screen.
  struct Brush {
    fur::GroomStroke stroke = [] {
      fur::GroomStroke s;
      s.strength = 1.5f;  // the length brush's: half as long again
      return s;
    }();
    float radius = 0.03f;
    bool screenRadius = false;
  };
  Brush brush;
  bool brushMode = false;  // the left mouse button brushes instead of orbiting
  // While a stroke is drawn or its fur grows, the frame is drawn at half the size with at most
  // this many hairs (sec. 3.3's culling, each drawn hair widened to cover for those left out), so
  // a software rasteriser keeps up with the cursor; 0: no preview.
  double brushPreviewHairs = 60000;
  bool previewing() const { return previewing_; }
  // Starts or continues a stroke at pixel (x, y) of the last frame's viewport (from its top-left):
  // the skin under it, recorded at rest, points kept a quarter of the radius apart. The fur regrows
  // with the new groom on a worker thread while the old one draws. Returns whether the cursor is on
  // the skin; an invalid brush is reported in `editError`.
  bool brushAt(float x, float y);
  void endBrush();
  bool brushing() const { return groomEditor_.drawing(); }
  // The skin under pixel (x, y) of the last frame, and the brush's radius there in metres.
  std::optional<scene::SkinHit> skinAt(float x, float y) const;
  float brushRadiusAt(const scene::SkinHit& hit) const;
  // The pixels that `meters` span at `hit` (the cursor's circle).
  float metersToPixels(const scene::SkinHit& hit, float meters) const;
  void undoStroke();
  void redoStroke();
  const scene::GroomEditor& groomEditor() const { return groomEditor_; }
  // The groom the fur shows has grown (no regrowth pending).
  bool groomShown() const { return grownRevision_ == groomEditor_.revision() && !pending_.valid(); }
  // Groom files (fur/groom.h) and strokes files (fur/groom_strokes.h); the result in `message`.
  // Loading a groom starts the strokes and the history over from it.
  void saveGroom(const std::string& path);
  void loadGroom(const std::string& path);
  void saveStrokes(const std::string& path);

  // ---- What the UI shows ---------------------------------------------------------------------
  const scene::Model& model() const { return model_; }
  const scene::Fur& fur() const { return fur_; }
  const scene::FrameState& state() const { return playback_->state(); }
  const scene::DrawList& drawList() const { return *list_; }
  render::Renderer& renderer() { return *renderer_; }
  bool regrowing() const { return pending_.valid(); }
  double frameMs() const { return frameMs_; }
  // Records one frame's wall time (the status line shows a running average).
  void recordFrameTime(double ms) { frameMs_ = frameMs_ == 0.0 ? ms : 0.9 * frameMs_ + 0.1 * ms; }
  std::int64_t hairsDrawn() const { return hairsDrawn_; }
  float referenceDistance() const;

 private:
  void applyEdits();
  void advance(double dtSeconds);
  // The frame's pose as the playback makes it (clip or still, cross-fade, turntable).
  scene::PlayedPose played() const;

  scene::Model model_;
  anatomy::Pose stillPose_;
  int clip_ = -1;
  int fromClip_ = -1;  // the clip being faded out, or -1
  double fromTime_ = 0.0;
  double fadeSeconds_ = 0.0;
  scene::Fur fur_;
  std::future<scene::Fur> pending_;
  scene::GroomEditor groomEditor_;
  bool groomEdited_ = false;                   // the editor's groom replaces the preset's
  std::uint64_t grownRevision_ = 0;            // the editor revision fur_ was grown with
  std::uint64_t pendingRevision_ = 0;          // the one pending_ grows
  scene::Camera lastCamera_;                   // the last frame's camera (picking)
  float strokeRadius_ = 0.0f;                  // metres, of the stroke being drawn
  bool previewing_ = false;                    // the last frame drew the brush preview
  std::unique_ptr<scene::Playback> playback_;  // the frame owner, playing model_ and fur_
  const scene::DrawList* list_ = nullptr;
  std::unique_ptr<render::Renderer> renderer_;
  scene::Framing framing_;
  std::optional<scene::CameraPreset>
      pendingPreset_;  // applied on the next frame, at its viewport size
  Eigen::Vector3f lastRoot_ = Eigen::Vector3f::Zero();
  double time_ = 0.0;
  double frameMs_ = 0.0;
  std::int64_t hairsDrawn_ = 0;
  double lastStep_ = 0.0;                // clip seconds played since the previous frame
  fur::DynamicsParams appliedDynamics_;  // the last valid dynamicsParams
};

// `pelage view --headless --benchmark`: ms/frame for each of options.benchmarkHairs.
int runBenchmark(const ViewerOptions& options, const scene::Model& model);

}  // namespace pelage::viewer::detail
