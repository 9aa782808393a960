// `pelage view`: the interactive viewer (GLFW window + Dear ImGui panel) and its offscreen modes
// (--headless through EGL: screenshots and the speed benchmark).
#pragma once

#include <Eigen/Core>

#include <optional>
#include <string>
#include <vector>

#include "pelage/anatomy/pose.h"
#include "pelage/fur/dynamics.h"
#include "pelage/fur/fur_params.h"
#include "pelage/fur/groom_strokes.h"
#include "pelage/scene/camera.h"
#include "pelage/scene/draw_list.h"
#include "pelage/scene/model.h"

namespace pelage::viewer {

// The most frames a run may be asked to show (ViewerOptions::frames).
inline constexpr int kMaxViewerFrames = 10000000;

struct ViewerOptions {
  // The clip to play: an index into the model's clips (0, the first, by default; none when the
  // model has no clips); -1: the still pose.
  int clip = 0;
  anatomy::Pose stillPose;  // the still pose (empty: the rest pose)
  double time = 0.0;        // start time in the clip, seconds [0, 1000000]
  fur::FurParams fur;       // the fur to start with (e.g. a preset; validated by the viewer)
  // Strokes (fur/groom_strokes.h) replayed into the brushing session at the start, undoable as
  // drawn ones; the panel's brushes then continue from them.
  std::vector<fur::GroomStroke> strokes;
  std::optional<Eigen::Vector3f> skinColor;  // skin diffuse colour in [0, 1]; none: the model's
  int width = 1280;                          // window or image size, [16, 16384] per side
  int height = 720;
  int samples = -1;  // MSAA samples [0, 64]; -1 = 4 on a GPU, 0 on a software rasteriser
  scene::CameraPreset camera = scene::CameraPreset::ThreeQuarter;
  bool follow = false;  // camera follows the creature
  scene::HairSource hairSource = scene::HairSource::Gpu;
  scene::HairShading shading = scene::kDefaultHairShading;
  scene::HairWidth hairWidth = scene::HairWidth::Strands;
  bool transparency = true;  // strands blended by coverage (order-independent)
  bool shadows = false;
  bool selfShadowing = true;                            // the fur's deep opacity shadow
  float lightAzimuth = scene::kKeyLightAzimuthDegrees;  // the key light's place, degrees
  float lightElevation = scene::kKeyLightElevationDegrees;
  Eigen::Vector3f lightColor = scene::Light{}.color;  // the key light's colour (linear)
  Eigen::Vector3f ambient = scene::Light{}.ambient;   // the ambient light (linear)
  bool noCulling = false;
  bool dynamics = false;  // dynamic fur (fur/dynamics.h): hair ends lag through damped springs
  fur::DynamicsParams dynamicsParams;
  Eigen::Vector3f background = scene::kDefaultBackground;  // linear RGB
  std::string screenshot;  // write the last frame here (PNG) and exit
  // The headless screenshot with straight alpha, 0 where nothing is drawn (FrameAlpha::Straight);
  // a window's screenshot (the panel with the view) is opaque.
  bool transparentBackground = false;
  int frames = 0;  // frames to run, [0, kMaxViewerFrames] (0: until the window closes; with a
                   // screenshot, 3 in a window (the panel needs two to lay itself out), 1 headless)
  bool headless = false;   // EGL, no window, no UI
  bool benchmark = false;  // print ms/frame for benchmarkHairs (headless)
  std::vector<double> benchmarkHairs{500000, 1000000, 5000000};
  int benchmarkFrames = 20;
  bool debugGl = false;  // KHR_debug messages to stderr (errors make the run fail)
};

// Checks the options; InputError naming the field ("size", "frames", "samples", "time",
// "skin color", ...).
void validateViewerOptions(const ViewerOptions& options);

// Runs the viewer on `model`; returns the process exit status. Throws InputError for bad options
// or inputs (unknown preset or clip, no display without --headless, no OpenGL).
int runViewer(const ViewerOptions& options, scene::Model model);

}  // namespace pelage::viewer
