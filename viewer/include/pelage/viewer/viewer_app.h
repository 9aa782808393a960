// `pelage view`: the interactive viewer (GLFW window + Dear ImGui panel) and its offscreen modes
// (--headless through EGL: screenshots and the speed benchmark).
#pragma once

#include <string>
#include <vector>

#include "pelage/fur/dynamics.h"
#include "pelage/fur/fur_params.h"
#include "pelage/scene/model.h"

namespace pelage::viewer {

struct ViewerOptions {
  std::string posePath;          // a pose file: a still pose instead of a clip
  std::string clip;              // clip to play ("" = the model's first clip, if any)
  double time = 0.0;             // start time in the clip (s)
  fur::FurParams fur;            // the fur to start with (e.g. a preset; validated by the viewer)
  std::vector<float> skinColor;  // skin diffuse colour (3 values in [0, 1]); empty = the model's
  int width = 1280;
  int height = 800;
  int samples = -1;  // MSAA samples (0 = none; -1 = 4 on a GPU, 0 on a software rasteriser)
  std::string camera = "three-quarter";
  bool follow = false;             // camera follows the creature
  std::string hairSource = "gpu";  // "gpu" or "cpu"
  std::string shading = "paper";   // "paper" or "kajiya-kay"
  bool ribbons = false;
  bool shadows = false;
  bool noCulling = false;
  bool dynamics = false;  // dynamic fur (fur/dynamics.h): hair ends lag through damped springs
  fur::DynamicsParams dynamicsParams;
  std::string screenshot;  // write the last frame here (PNG) and exit
  int frames = 0;          // frames to run (0 = until the window closes; 3 with --screenshot)
  bool headless = false;   // EGL, no window, no UI
  bool benchmark = false;  // print ms/frame for benchmarkHairs (headless)
  std::vector<double> benchmarkHairs{500000, 1000000, 5000000};
  int benchmarkFrames = 20;
  bool debugGl = false;  // KHR_debug messages to stderr (errors make the run fail)
};

// Runs the viewer on `model`; returns the process exit status. Throws InputError for bad options
// or inputs (unknown preset or clip, no display without --headless, no OpenGL).
int runViewer(const ViewerOptions& options, scene::Model model);

}  // namespace pelage::viewer
