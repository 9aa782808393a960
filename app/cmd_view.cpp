// `pelage view [MODEL]`: the interactive viewer (GLFW + Dear ImGui), or offscreen with --headless.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "commands.h"
#include "options.h"
#include "pelage/fur/groom_strokes.h"
#include "pelage/util/error.h"
#include "pelage/viewer/viewer_app.h"

namespace pelage::app {

void addViewCommand(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "view",
      "Interactive viewer: play the creature's clips with fur, edit every fur parameter live "
      "(needs a display, or --headless)");
  auto model = std::make_shared<ModelOptions>();
  auto pose = std::make_shared<PoseOptions>();
  auto furArgs = std::make_shared<FurOptions>();
  auto dyn = std::make_shared<DynamicsOptions>();
  auto view = std::make_shared<ViewOptions>();
  auto common = std::make_shared<CommonOptions>();
  auto o = std::make_shared<viewer::ViewerOptions>();
  auto benchHairs = std::make_shared<std::vector<double>>();
  model->add(*cmd);
  pose->add(*cmd);
  furArgs->add(*cmd);
  view->add(*cmd);
  dyn->add(*cmd, false);
  auto strokes = std::make_shared<std::string>();
  cmd->add_option("--strokes", *strokes,
                  "Strokes file (as `pelage groom` reads) replayed into the panel's brushing "
                  "session at the start, undoable; the brushes continue from it");
  cmd->add_option("--screenshot", o->screenshot,
                  "Write the last frame to this .png or .jpg and exit (a window: its back buffer, "
                  "UI included; --headless: the scene)");
  cmd->add_option(
      "--frames", o->frames,
      "Frames to run before exiting [0, " + std::to_string(viewer::kMaxViewerFrames) +
          "] (default 0: until closed; with --screenshot: 3 in a window, whose panel needs two "
          "frames to lay itself out, 1 headless)");
  cmd->add_flag("--headless", o->headless, "No window: render offscreen through EGL (no UI)");
  cmd->add_flag("--benchmark", o->benchmark,
                "Print ms/frame for several hair counts (offscreen, through EGL; --size defaults "
                "to 1920x1080)");
  cmd->add_option("--benchmark-hairs", *benchHairs,
                  "Hair counts for --benchmark (default 500000 1000000 5000000)");
  cmd->add_option("--benchmark-frames", o->benchmarkFrames,
                  "Timed frames per count [1, 100000] (default 20)");
  cmd->add_flag("--debug-gl", o->debugGl, "OpenGL debug output to stderr; GL errors fail the run");
  common->add(*cmd, false);
  cmd->callback([cmd, model, pose, furArgs, dyn, view, o, benchHairs, strokes] {
    view->validate();
    if (!strokes->empty()) o->strokes = fur::readGroomStrokes(*strokes);
    // The benchmark's reference resolution is 1080p (issue 5) unless a size is given.
    if (o->benchmark && cmd->count("--size") == 0) {
      o->width = 1920;
      o->height = 1080;
    } else {
      o->width = view->width();
      o->height = view->height();
    }
    o->samples = view->samples;
    o->camera = view->cameraPreset();
    o->follow = view->follow;
    o->hairSource = view->source();
    o->shading = view->hairShading();
    o->hairWidth = view->hairWidth();
    o->transparency = view->transparent();
    o->shadows = view->shadows;
    o->selfShadowing = view->selfShadowed();
    o->lightAzimuth = view->lightAzimuth();
    o->lightElevation = view->lightElevation();
    o->lightColor = view->keyLightColor();
    o->ambient = view->ambientLight();
    o->noCulling = view->noCulling;
    o->skinColor = view->skin();
    o->background = view->backgroundColor();
    o->transparentBackground = view->transparentBackground();
    o->fur = furArgs->resolve();
    o->dynamics = dyn->enabled();
    o->dynamicsParams = dyn->resolve();
    if (!benchHairs->empty()) o->benchmarkHairs = *benchHairs;
    viewer::validateViewerOptions(*o);
    scene::Model m = model->load();
    scene::PlaybackOptions po;
    pose->sequence(m, po);
    o->clip = po.clip;
    o->stillPose = po.stillPose;
    o->time = po.clock.startSeconds;
    int status = 0;
    try {
      status = viewer::runViewer(*o, std::move(m));
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
