// Tutorial 103: render one frame offscreen (EGL, no window or display) and write it as a PNG.
//
//   103_render_png [MODEL [OUT.png [WIDTH HEIGHT]]]
//
// The frame is frame 10 of the model's first clip, seen by the three-quarter camera preset, the fur
// computed and drawn on the GPU (Mesa's llvmpipe where there is no GPU).
#include <cstdio>
#include <exception>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>

#include "pelage/fur/preset.h"
#include "pelage/render/gl_context.h"
#include "pelage/render/image.h"
#include "pelage/render/render_sequence.h"
#include "pelage/scene/frame.h"
#include "pelage/scene/model.h"

int main(int argc, char** argv) {
  using namespace pelage;
  const std::string modelSpec = argc > 1 ? argv[1] : "monkey";
  const std::string out = argc > 2 ? argv[2] : "frame.png";
  try {
    scene::Model model = scene::loadModel(modelSpec);
    const scene::Fur fur = scene::growFur(model, fur::loadFurPreset("default"));

    // An OpenGL 4.5 core context with no window; the renderer needs it current for its life.
    const std::unique_ptr<render::GlContext> context = render::createHeadlessContext();

    render::SequenceOptions options;
    options.playback.clip = scene::resolveClip(model, "");
    options.width = argc > 4 ? std::stoi(argv[3]) : 640;
    options.height = argc > 4 ? std::stoi(argv[4]) : 360;
    options.camera.preset = scene::CameraPreset::ThreeQuarter;
    options.outDir = std::filesystem::path(out).parent_path().string();  // where the frame goes
    if (options.outDir.empty()) options.outDir = ".";
    render::validateSequenceOptions(options);
    render::SequenceRenderer renderer(model, fur, options);
    render::Image image;
    const render::RenderStats stats = renderer.render(10, image);
    render::writePng(out, image);  // opaque RGBA, written to a temporary file and renamed
    std::printf("%s: %dx%d, %lld hairs drawn on %s\n", out.c_str(), image.width, image.height,
                static_cast<long long>(stats.hairsDrawn), context->info().renderer.c_str());
  } catch (const std::invalid_argument&) {  // std::stoi on an argument that is not a number
    std::fprintf(
        stderr,
        "usage: 103_render_png [MODEL [OUT.png [WIDTH HEIGHT]]]: WIDTH and HEIGHT are numbers\n");
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "103_render_png: %s\n", e.what());
    return 1;
  }
  return 0;
}
