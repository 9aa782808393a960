// `pelage view [MODEL]`: the interactive viewer (GLFW + Dear ImGui), or offscreen with --headless.
#include <cstdio>
#include <memory>
#include <sstream>

#include "commands.h"
#include "pelage/anatomy/pose_file.h"
#include "pelage/util/error.h"
#include "pelage/viewer/viewer_app.h"

namespace pelage::app {
namespace {

// "WxH" -> width, height.
void parseSize(const std::string& text, int& width, int& height) {
  char x = 0;
  std::istringstream in(text);
  if (!(in >> width >> x >> height) || x != 'x' || !in.eof())
    inputError("--size '", text, "' is not WIDTHxHEIGHT (e.g. 1280x800)");
}

}  // namespace

void addViewCommand(CLI::App& app) {
  auto* cmd =
      app.add_subcommand("view",
                         "Interactive viewer: play the creature's clips with fur, edit every fur "
                         "parameter live (needs a display, or --headless)");
  auto args = std::make_shared<ModelArgs>();
  auto furArgs = std::make_shared<FurArgs>();
  auto o = std::make_shared<viewer::ViewerOptions>();
  struct Words {
    std::string size = "1280x720", posePath, clip, camera = "three-quarter", hairSource = "gpu",
                shading = "paper";
    std::vector<float> skinColor;
  };
  auto w = std::make_shared<Words>();
  auto benchHairs = std::make_shared<std::vector<double>>();
  auto dyn = std::make_shared<DynamicsArgs>();
  args->add(*cmd);
  cmd->add_option("--pose", w->posePath, "Pose file (JSON) for the still pose");
  cmd->add_option("--clip", w->clip,
                  "Clip to play (default: the model's first; see `pelage info`)");
  cmd->add_option("--time", o->time, "Start time in the clip, seconds")->capture_default_str();
  furArgs->add(*cmd);
  cmd->add_option("--size", w->size, "Window or image size WIDTHxHEIGHT (--benchmark: 1920x1080)")
      ->capture_default_str();
  cmd->add_option("--samples", o->samples,
                  "MSAA samples of the renderer [0, 64]; -1 = 4 on a GPU, 0 on a software "
                  "rasteriser")
      ->capture_default_str();
  cmd->add_option("--camera", w->camera, "Camera preset: front, side, three-quarter, face, follow")
      ->capture_default_str();
  cmd->add_flag("--follow", o->follow, "Camera follows the creature");
  cmd->add_option("--hair-source", w->hairSource, "Where hairs are computed each frame: gpu or cpu")
      ->capture_default_str();
  cmd->add_option("--shading", w->shading, "Hair shading: paper or kajiya-kay")
      ->capture_default_str();
  cmd->add_flag("--ribbons", o->ribbons, "Draw hairs as tapered ribbons instead of 1-pixel lines");
  cmd->add_flag("--shadows", o->shadows, "Shadow map: fur and skin shadow each other");
  cmd->add_option("--skin-color", w->skinColor,
                  "Skin colour R G B in [0, 1] (default: the model's)")
      ->expected(3);
  cmd->add_flag("--no-culling", o->noCulling,
                "Draw every hair at any distance (no sec. 3.3 culling)");
  dyn->add(*cmd, false, false);
  cmd->add_option("--screenshot", o->screenshot,
                  "Write the last frame to this PNG and exit (a window: its back buffer, UI "
                  "included; --headless: the scene)");
  cmd->add_option("--frames", o->frames,
                  "Frames to run before exiting (0 = until closed; with --screenshot 3 in a "
                  "window, 1 headless)");
  cmd->add_flag("--headless", o->headless, "No window: render offscreen through EGL (no UI)");
  cmd->add_flag("--benchmark", o->benchmark,
                "Print ms/frame for several hair counts (offscreen, through EGL)");
  cmd->add_option("--benchmark-hairs", *benchHairs,
                  "Hair counts for --benchmark (default 500000 1000000 5000000)");
  cmd->add_option("--benchmark-frames", o->benchmarkFrames, "Timed frames per count")
      ->capture_default_str();
  cmd->add_flag("--debug-gl", o->debugGl, "OpenGL debug output to stderr; GL errors fail the run");
  cmd->callback([cmd, args, furArgs, o, w, benchHairs, dyn] {
    // The benchmark's reference resolution is 1080p (issue 5) unless a size is given.
    parseSize(o->benchmark && cmd->count("--size") == 0 ? std::string("1920x1080") : w->size,
              o->width, o->height);
    o->fur = furArgs->resolve();
    o->dynamics = dyn->enabled();
    o->dynamicsParams = dyn->resolve();
    o->camera = scene::parseCameraPreset(w->camera);
    o->hairSource = scene::parseHairSource(w->hairSource);
    o->shading = scene::parseHairShading(w->shading);
    if (!w->skinColor.empty())
      o->skinColor = Eigen::Vector3f(w->skinColor[0], w->skinColor[1], w->skinColor[2]);
    if (!benchHairs->empty()) o->benchmarkHairs = *benchHairs;
    viewer::validateViewerOptions(*o);
    scene::Model model = args->load();
    if (!w->clip.empty() && !w->posePath.empty())
      inputError("--pose and --clip cannot be used together");
    if (!w->posePath.empty()) {
      o->clip = -1;
      o->stillPose = anatomy::loadPose(model.body, w->posePath);
    } else {
      o->clip = scene::resolveClip(model, w->clip);
    }
    int status = 0;
    try {
      status = viewer::runViewer(*o, std::move(model));
    } catch (const InputError& e) {
      if (e.field() != "window") throw;
      inputError(
          "cannot open a window: ", e.detail().substr(e.detail().find(": ") + 2),
          ". Run on a desktop, under a virtual display (xvfb-run -a pelage view ...), or add "
          "--headless to render offscreen through EGL");
    }
    if (status != 0) throw CLI::RuntimeError(status);
  });
}

}  // namespace pelage::app
