// Tutorial 104: pelage's fur in your own OpenGL program. The window, the context and the loop are
// yours (GLFW here); each frame pelage poses the creature, computes its hairs on the GPU and
// renders them into its own framebuffer, which you copy into yours and draw over.
//
//   104_gl_loop [MODEL [FRAMES]]
//
// FRAMES (default: until the window closes) bounds the loop. Needs a display (X11 or Wayland).
#include "pelage/render/gl.h"  // OpenGL 4.5 core prototypes (libglvnd), before GLFW's header

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <cstdio>
#include <exception>
#include <stdexcept>
#include <string>

#include "pelage/fur/preset.h"
#include "pelage/render/renderer.h"
#include "pelage/scene/frame.h"
#include "pelage/scene/model.h"
#include "pelage/scene/playback.h"

int main(int argc, char** argv) {
  using namespace pelage;
  const std::string modelSpec = argc > 1 ? argv[1] : "monkey";
  if (!glfwInit()) {
    std::fprintf(stderr, "104_gl_loop: GLFW could not start (no display?)\n");
    return 1;
  }
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  GLFWwindow* window = glfwCreateWindow(960, 540, "pelage: your GL loop", nullptr, nullptr);
  if (!window) {
    std::fprintf(stderr, "104_gl_loop: no OpenGL 4.5 core window\n");
    glfwTerminate();
    return 1;
  }
  glfwMakeContextCurrent(window);
  glfwSwapInterval(1);
  int status = 0;
  try {
    const int frames = argc > 2 ? std::stoi(argv[2]) : -1;
    scene::Model model = scene::loadModel(modelSpec);
    const scene::Fur fur = scene::growFur(model, fur::loadFurPreset("default"));
    scene::PlaybackOptions options;
    options.clip = scene::resolveClip(model, "");
    options.hairSource = scene::HairSource::Gpu;  // hairs computed by compute shaders
    scene::Playback playback(model, fur, options);
    render::Renderer renderer;  // needs the current context for its whole life
    scene::CameraRig rig;       // the three-quarter preset, framed on the first pose
    const scene::Light light;
    scene::DrawOptions look;
    look.hairSource = playback.hairSource();
    for (int frame = 0; !glfwWindowShouldClose(window) && frame != frames; ++frame) {
      int width = 0, height = 0;
      glfwGetFramebufferSize(window, &width, &height);
      if (width > 0 && height > 0) {
        renderer.render(playback.sequenceFrame(frame, rig, width, height, light, look));
        renderer.blitTo(0, 0, 0, width, height);  // into the window's framebuffer
        // ... your own drawing goes here, over pelage's frame ...
      }
      glfwSwapBuffers(window);
      glfwPollEvents();
    }
    std::printf("104_gl_loop: %s, %lld hairs\n", model.name.c_str(),
                static_cast<long long>(fur.roots.total()));
  } catch (const std::invalid_argument&) {  // std::stoi on an argument that is not a number
    std::fprintf(stderr, "usage: 104_gl_loop [MODEL [FRAMES]]: FRAMES is a number\n");
    status = 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "104_gl_loop: %s\n", e.what());
    status = 1;
  }
  glfwDestroyWindow(window);
  glfwTerminate();
  return status;
}
