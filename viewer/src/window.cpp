#include "pelage/viewer/window.h"

#include "pelage/render/gl.h"  // before GLFW, which must not include the legacy GL header
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <mutex>

#include "pelage/render/gl.h"
#include "pelage/util/error.h"

namespace pelage::viewer {
namespace {

// GLFW reports errors through a callback; the last one explains a failed call.
std::mutex gErrorMutex;
std::string gLastError;

void onGlfwError(int code, const char* description) {
  std::lock_guard<std::mutex> lock(gErrorMutex);
  gLastError =
      str(description ? description : "unknown error", " (GLFW error 0x", std::hex, code, ")");
}

std::string lastGlfwError() {
  std::lock_guard<std::mutex> lock(gErrorMutex);
  return gLastError.empty() ? std::string("no reason given") : gLastError;
}

}  // namespace

GlfwWindow::GlfwWindow(int width, int height, const std::string& title, bool debug) {
  glfwSetErrorCallback(onGlfwError);
  if (glfwInit() != GLFW_TRUE) fieldError("window", "cannot be opened: ", lastGlfwError());
  const int versions[][2] = {{4, 6}, {4, 5}, {4, 3}};
  std::string tried;
  for (const auto& v : versions) {
    glfwDefaultWindowHints();
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, v[0]);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, v[1]);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, debug ? GLFW_TRUE : GLFW_FALSE);
    glfwWindowHint(GLFW_SAMPLES, 0);  // the renderer has its own multisampled framebuffer
    window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
    if (window_) break;
    tried += str(" core ", v[0], ".", v[1], ": ", lastGlfwError(), ";");
  }
  if (!window_) inputError("cannot create an OpenGL 4.3+ core window:", tried);
  glfwMakeContextCurrent(window_);
  glfwSwapInterval(1);
  info_.backend = "glfw";
  const char* platform = glfwGetVersionString();
  info_.device = platform ? platform : "";
  render::queryContextInfo(info_);
}

GlfwWindow::~GlfwWindow() {
  if (window_) glfwDestroyWindow(window_);
  // No glfwTerminate: it unloads libGL and, through libglvnd, Mesa's driver, whose few unfreed
  // bytes LeakSanitizer then reports from an unknown module (unsuppressible). GLFW stays
  // initialised until the process exits; a later window in the same process reuses it.
}

void GlfwWindow::makeCurrent() {
  glfwMakeContextCurrent(window_);
}
bool GlfwWindow::shouldClose() const {
  return glfwWindowShouldClose(window_) == GLFW_TRUE;
}
void GlfwWindow::requestClose() {
  glfwSetWindowShouldClose(window_, GLFW_TRUE);
}
void GlfwWindow::framebufferSize(int& width, int& height) const {
  glfwGetFramebufferSize(window_, &width, &height);
}
void GlfwWindow::swapBuffers() {
  glfwSwapBuffers(window_);
}
void GlfwWindow::pollEvents() {
  glfwPollEvents();
}

}  // namespace pelage::viewer
