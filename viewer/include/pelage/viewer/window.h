// The GLFW window backend: an OpenGL 4.5 (else 4.3) core context in a window. The renderer still
// draws into its own framebuffer, which is blitted to the window before the UI is drawn on top.
#pragma once

#include <memory>
#include <string>

#include "pelage/render/gl_context.h"

struct GLFWwindow;

namespace pelage::viewer {

class GlfwWindow final : public render::GlContext {
 public:
  // Opens a window of width x height pixels titled `title` and makes its context current. Throws
  // InputError with GLFW's reason when there is no display (e.g. "X11: The DISPLAY environment
  // variable is missing") or no OpenGL 4.3 core context.
  GlfwWindow(int width, int height, const std::string& title, bool debug);
  ~GlfwWindow() override;
  GlfwWindow(const GlfwWindow&) = delete;
  GlfwWindow& operator=(const GlfwWindow&) = delete;

  void makeCurrent() override;
  const render::ContextInfo& info() const override { return info_; }

  GLFWwindow* handle() const { return window_; }
  bool shouldClose() const;
  void requestClose();
  // Framebuffer size in pixels (may differ from the window size on high-DPI screens).
  void framebufferSize(int& width, int& height) const;
  void swapBuffers();
  void pollEvents();

 private:
  GLFWwindow* window_ = nullptr;
  render::ContextInfo info_;
};

}  // namespace pelage::viewer
