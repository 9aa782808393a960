// OpenGL contexts for the renderer. Two backends, chosen once at start (as polyscope chooses its
// backend in initialize_backend.cpp): an EGL headless context (this file; export, tests,
// benchmarks) and a GLFW window (viewer/window.h). The renderer draws into its own framebuffer in
// both cases.
#pragma once

#include <memory>
#include <string>

namespace pelage::render {

// What a created context turned out to be.
struct ContextInfo {
  std::string backend;   // "egl-device", "egl-surfaceless" or "glfw"
  std::string device;    // EGL device name/extensions summary, or the X display
  std::string renderer;  // GL_RENDERER
  std::string version;   // GL_VERSION
  int major = 0;
  int minor = 0;
  bool debug = false;     // a KHR_debug context
  bool software = false;  // a software rasteriser (llvmpipe, softpipe, swrast)
};

// A current OpenGL context. Destroying it releases the context.
class GlContext {
 public:
  virtual ~GlContext() = default;
  virtual void makeCurrent() = 0;
  virtual const ContextInfo& info() const = 0;
};

struct ContextOptions {
  // Ask for a debug context so that KHR_debug messages are reported (tests turn them into
  // failures).
  bool debug = false;
};

// An EGL headless context: the device platform (preferring a device without
// EGL_MESA_device_software, e.g. an NVIDIA GPU), then the surfaceless platform; OpenGL core 4.6,
// then 4.5, then 4.3. Made current on the calling thread. Throws InputError with what was tried and
// why it failed (no EGL library, no device, no GL 4.3 core) so callers can print it and exit
// non-zero.
std::unique_ptr<GlContext> createHeadlessContext(const ContextOptions& options = {});

// Fills the GL_* fields of `info` from the current context.
void queryContextInfo(ContextInfo& info);

}  // namespace pelage::render
