// EGL headless context, following ../shared/docs/headless-gl.md: device platform (a non-software
// device first), then the surfaceless platform; core 4.6 -> 4.5 -> 4.3; surfaceless make-current.
#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstring>
#include <string>
#include <vector>

#include "pelage/render/gl.h"
#include "pelage/render/gl_context.h"
#include "pelage/util/error.h"

namespace pelage::render {
namespace {

const char* eglErrorName(EGLint e) {
  switch (e) {
    case EGL_SUCCESS:
      return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED:
      return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS:
      return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC:
      return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE:
      return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG:
      return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT:
      return "EGL_BAD_CONTEXT";
    case EGL_BAD_DISPLAY:
      return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH:
      return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER:
      return "EGL_BAD_PARAMETER";
    case EGL_BAD_SURFACE:
      return "EGL_BAD_SURFACE";
    default:
      return "EGL error";
  }
}

bool hasExtension(const char* list, const char* name) {
  if (!list) return false;
  const std::size_t n = std::strlen(name);
  for (const char* p = list; (p = std::strstr(p, name)) != nullptr; p += n)
    if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
  return false;
}

class EglContext final : public GlContext {
 public:
  EglContext(EGLDisplay display, EGLContext context, ContextInfo info)
      : display_(display), context_(context), info_(std::move(info)) {}
  ~EglContext() override {
    eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(display_, context_);
    // No eglTerminate: the display is process-wide (another context may share it), and
    // terminating unloads Mesa's driver, whose few unfreed bytes LeakSanitizer then reports from an
    // unknown module.
  }
  void makeCurrent() override {
    PELAGE_CHECK(eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_) == EGL_TRUE,
                 "eglMakeCurrent: ", eglErrorName(eglGetError()));
  }
  const ContextInfo& info() const override { return info_; }

 private:
  EGLDisplay display_;
  EGLContext context_;
  ContextInfo info_;
};

struct Candidate {
  EGLDisplay display = EGL_NO_DISPLAY;
  std::string backend;
  std::string device;
};

// Tries to create a core context on an initialised display; returns EGL_NO_CONTEXT on failure and
// appends the reason to `log`.
EGLContext createCoreContext(EGLDisplay display, bool debug, int& major, int& minor,
                             std::string& log) {
  if (eglBindAPI(EGL_OPENGL_API) != EGL_TRUE) {
    log += str("  eglBindAPI(EGL_OPENGL_API): ", eglErrorName(eglGetError()), "\n");
    return EGL_NO_CONTEXT;
  }
  // The default EGL_SURFACE_TYPE is EGL_WINDOW_BIT, which headless platforms do not offer.
  const EGLint configAttribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE,
                                  EGL_PBUFFER_BIT, EGL_NONE};
  EGLConfig config = nullptr;
  EGLint count = 0;
  if (eglChooseConfig(display, configAttribs, &config, 1, &count) != EGL_TRUE || count < 1) {
    // No config at all: a context without one (EGL_KHR_no_config_context) still renders into FBOs.
    if (!hasExtension(eglQueryString(display, EGL_EXTENSIONS), "EGL_KHR_no_config_context")) {
      log += str("  eglChooseConfig(EGL_OPENGL_BIT, EGL_PBUFFER_BIT): no config (",
                 eglErrorName(eglGetError()), ")\n");
      return EGL_NO_CONTEXT;
    }
    config = EGL_NO_CONFIG_KHR;
  }
  const int versions[][2] = {{4, 6}, {4, 5}, {4, 3}};
  for (const auto& v : versions) {
    const EGLint attribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                              v[0],
                              EGL_CONTEXT_MINOR_VERSION,
                              v[1],
                              EGL_CONTEXT_OPENGL_PROFILE_MASK,
                              EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                              EGL_CONTEXT_OPENGL_DEBUG,
                              debug ? EGL_TRUE : EGL_FALSE,
                              EGL_NONE};
    EGLContext ctx = eglCreateContext(display, config, EGL_NO_CONTEXT, attribs);
    if (ctx != EGL_NO_CONTEXT) {
      major = v[0];
      minor = v[1];
      return ctx;
    }
    log += str("  core ", v[0], ".", v[1], ": ", eglErrorName(eglGetError()), "\n");
  }
  return EGL_NO_CONTEXT;
}

}  // namespace

void queryContextInfo(ContextInfo& info) {
  const auto* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  const auto* version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  info.renderer = renderer ? renderer : "?";
  info.version = version ? version : "?";
  glGetIntegerv(GL_MAJOR_VERSION, &info.major);
  glGetIntegerv(GL_MINOR_VERSION, &info.minor);
  GLint flags = 0;
  glGetIntegerv(GL_CONTEXT_FLAGS, &flags);
  info.debug = (flags & GL_CONTEXT_FLAG_DEBUG_BIT) != 0;
  info.software = info.renderer.find("llvmpipe") != std::string::npos ||
                  info.renderer.find("softpipe") != std::string::npos ||
                  info.renderer.find("swrast") != std::string::npos;
}

std::unique_ptr<GlContext> createHeadlessContext(const ContextOptions& options) {
  std::string log;
  const char* clientExts = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  auto getPlatformDisplay = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
      eglGetProcAddress("eglGetPlatformDisplayEXT"));
  auto queryDevices =
      reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
  auto queryDeviceString = reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(
      eglGetProcAddress("eglQueryDeviceStringEXT"));

  std::vector<Candidate> candidates;
  if (getPlatformDisplay && queryDevices && hasExtension(clientExts, "EGL_EXT_platform_device")) {
    EGLDeviceEXT devices[16];
    EGLint n = 0;
    if (queryDevices(16, devices, &n) == EGL_TRUE && n > 0) {
      // Hardware devices first: on a machine with a GPU and Mesa, both appear.
      std::vector<Candidate> hardware, software;
      for (EGLint i = 0; i < n; ++i) {
        const char* exts = queryDeviceString ? queryDeviceString(devices[i], EGL_EXTENSIONS) : "";
        const bool isSoftware = hasExtension(exts, "EGL_MESA_device_software");
        Candidate c;
        c.display = getPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
        c.backend = "egl-device";
        c.device = str("device ", i, isSoftware ? " (software)" : "", exts ? str(": ", exts) : "");
        if (c.display == EGL_NO_DISPLAY) {
          log += str("  EGL device ", i, ": no display (", eglErrorName(eglGetError()), ")\n");
          continue;
        }
        (isSoftware ? software : hardware).push_back(c);
      }
      candidates.insert(candidates.end(), hardware.begin(), hardware.end());
      candidates.insert(candidates.end(), software.begin(), software.end());
    } else {
      log += "  EGL device platform: no devices\n";
    }
  } else {
    log += "  EGL device platform: not supported by this EGL\n";
  }
  if (getPlatformDisplay && hasExtension(clientExts, "EGL_MESA_platform_surfaceless")) {
    Candidate c;
    c.display = getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    c.backend = "egl-surfaceless";
    c.device = "surfaceless platform";
    if (c.display != EGL_NO_DISPLAY)
      candidates.push_back(c);
    else
      log += str("  surfaceless platform: no display (", eglErrorName(eglGetError()), ")\n");
  } else {
    log += "  EGL surfaceless platform: not supported by this EGL\n";
  }

  for (const Candidate& c : candidates) {
    EGLint eglMajor = 0, eglMinor = 0;
    if (eglInitialize(c.display, &eglMajor, &eglMinor) != EGL_TRUE) {
      log += str("  ", c.backend, " (", c.device, "): eglInitialize: ", eglErrorName(eglGetError()),
                 "\n");
      continue;
    }
    int major = 0, minor = 0;
    EGLContext ctx = createCoreContext(c.display, options.debug, major, minor, log);
    if (ctx == EGL_NO_CONTEXT) {
      eglTerminate(c.display);
      continue;
    }
    if (eglMakeCurrent(c.display, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx) != EGL_TRUE) {
      log += str("  ", c.backend,
                 ": eglMakeCurrent without a surface: ", eglErrorName(eglGetError()), "\n");
      eglDestroyContext(c.display, ctx);
      eglTerminate(c.display);
      continue;
    }
    ContextInfo info;
    info.backend = c.backend;
    info.device = c.device;
    queryContextInfo(info);
    return std::make_unique<EglContext>(c.display, ctx, std::move(info));
  }
  inputError("no OpenGL 4.3+ core context through EGL (headless). Tried:\n", log,
             "Install Mesa's EGL and llvmpipe (Debian: libegl1 libegl-mesa0 libgl1-mesa-dri) or a "
             "GPU driver with EGL.");
}

}  // namespace pelage::render
