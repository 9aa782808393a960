// `pelage view`: the window loop (GLFW + Dear ImGui), the headless loop (EGL) and the benchmark.
#include "pelage/viewer/viewer_app.h"

#include "pelage/render/gl.h"  // before GLFW, which must not include the legacy GL header
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <thread>

#include "pelage/fur/preset.h"
#include "pelage/render/gl.h"
#include "pelage/render/gl_context.h"
#include "pelage/render/gl_debug.h"
#include "pelage/render/image.h"
#include "pelage/scene/clock.h"
#include "pelage/util/error.h"
#include "pelage/util/path.h"
#include "pelage/viewer/window.h"
#include "viewer_panel.h"
#include "viewer_session.h"

namespace pelage::viewer {
namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

// Throws (a failure, exit 3) when the debug log recorded GL errors.
void failOnGlErrors(const render::GlDebugLog* log) {
  if (!log) return;
  const std::string errors = log->errors();
  PELAGE_CHECK(errors.empty(), "OpenGL reported errors:\n", errors);
}

// The window's back buffer as an image (after the UI is drawn, before the swap).
render::Image readBackBuffer(int width, int height) {
  render::Image img;
  img.width = width;
  img.height = height;
  const std::size_t row = static_cast<std::size_t>(width) * 4;
  img.rgba.resize(row * static_cast<std::size_t>(height));
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  glReadBuffer(GL_BACK);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, img.rgba.data());
  for (int y = 0; y < height / 2; ++y)
    std::swap_ranges(
        img.rgba.begin() + static_cast<std::ptrdiff_t>(row * static_cast<std::size_t>(y)),
        img.rgba.begin() + static_cast<std::ptrdiff_t>(row * static_cast<std::size_t>(y + 1)),
        img.rgba.begin() +
            static_cast<std::ptrdiff_t>(row * static_cast<std::size_t>(height - 1 - y)));
  return img;
}

// Mouse and keyboard camera controls (when the UI does not want the input):
// left drag orbits, right or middle drag pans, the wheel zooms; arrows orbit, +/- (or PgUp/PgDn)
// zoom, W/A/S/D pan, space plays/pauses, F toggles follow, 1-5 pick the camera presets, Esc quits.
// In brush mode the left button brushes the skin under the cursor (with Alt it orbits; a circle
// shows the brush), Ctrl+Z undoes a stroke, Ctrl+Y or Ctrl+Shift+Z redoes it.
class Controls {
 public:
  // `viewX`: where the 3D view starts in the framebuffer (right of the panel).
  void update(GLFWwindow* w, detail::ViewerSession& s, int viewX, int height, double dt) {
    const ImGuiIO& io = ImGui::GetIO();
    // The cursor in the view's pixels (the framebuffer's, which a HiDPI screen scales).
    const float px = io.MousePos.x * io.DisplayFramebufferScale.x - static_cast<float>(viewX);
    const float py = io.MousePos.y * io.DisplayFramebufferScale.y;
    const bool brushing = s.brushMode && !io.KeyAlt;
    if (!io.MouseDown[0] || !brushing) {
      if (s.brushing()) s.endBrush();
      brushArmed_ = false;
    }
    if (!io.WantCaptureMouse) {
      const float dx = io.MouseDelta.x, dy = io.MouseDelta.y;
      // A press in the view arms the brush; the stroke starts where the drag first meets the skin.
      if (brushing && io.MouseClicked[0]) brushArmed_ = true;
      if (brushArmed_) s.brushAt(px, py);
      if (brushing && !io.MouseDown[0]) {
        // The brush's circle on the skin under the cursor.
        if (const std::optional<scene::SkinHit> hit = s.skinAt(px, py))
          ImGui::GetForegroundDrawList()->AddCircle(
              io.MousePos,
              s.metersToPixels(*hit, s.brushRadiusAt(*hit)) / io.DisplayFramebufferScale.y,
              IM_COL32(255, 220, 80, 220), 48, 1.5f);
      }
      if (io.MouseDown[0] && !brushing) s.orbitBy(-dx * 0.4f, dy * 0.4f);
      if (io.MouseDown[1] || io.MouseDown[2])
        s.panBy(dx / static_cast<float>(height), dy / static_cast<float>(height));
      if (io.MouseWheel != 0.0f) s.zoomBy(std::pow(0.9f, io.MouseWheel));
    }
    if (io.WantCaptureKeyboard) return;
    if (io.KeyCtrl && pressed(w, GLFW_KEY_Z)) io.KeyShift ? s.redoStroke() : s.undoStroke();
    if (io.KeyCtrl && pressed(w, GLFW_KEY_Y)) s.redoStroke();
    if (io.KeyCtrl) return;  // Ctrl+key is a shortcut, not a camera move
    const auto step = static_cast<float>(dt);
    auto down = [&](int key) { return glfwGetKey(w, key) == GLFW_PRESS; };
    if (down(GLFW_KEY_LEFT)) s.orbitBy(-90.0f * step, 0.0f);
    if (down(GLFW_KEY_RIGHT)) s.orbitBy(90.0f * step, 0.0f);
    if (down(GLFW_KEY_UP)) s.orbitBy(0.0f, 60.0f * step);
    if (down(GLFW_KEY_DOWN)) s.orbitBy(0.0f, -60.0f * step);
    if (down(GLFW_KEY_EQUAL) || down(GLFW_KEY_KP_ADD) || down(GLFW_KEY_PAGE_UP))
      s.zoomBy(std::pow(0.3f, step));
    if (down(GLFW_KEY_MINUS) || down(GLFW_KEY_KP_SUBTRACT) || down(GLFW_KEY_PAGE_DOWN))
      s.zoomBy(std::pow(3.0f, step));
    if (down(GLFW_KEY_A)) s.panBy(-0.8f * step, 0.0f);
    if (down(GLFW_KEY_D)) s.panBy(0.8f * step, 0.0f);
    if (down(GLFW_KEY_W)) s.panBy(0.0f, -0.8f * step);
    if (down(GLFW_KEY_S)) s.panBy(0.0f, 0.8f * step);
    if (pressed(w, GLFW_KEY_SPACE)) s.playing = !s.playing;
    if (pressed(w, GLFW_KEY_F)) s.follow = !s.follow;
    const scene::CameraPreset presets[] = {scene::CameraPreset::Front, scene::CameraPreset::Side,
                                           scene::CameraPreset::ThreeQuarter,
                                           scene::CameraPreset::Face, scene::CameraPreset::Follow};
    for (int i = 0; i < 5; ++i)
      if (pressed(w, GLFW_KEY_1 + i)) s.applyPreset(presets[i]);
    if (pressed(w, GLFW_KEY_ESCAPE)) glfwSetWindowShouldClose(w, GLFW_TRUE);
  }

 private:
  // True on the frame a key goes down.
  bool pressed(GLFWwindow* w, int key) {
    const bool now = glfwGetKey(w, key) == GLFW_PRESS;
    bool& was = wasDown_[static_cast<std::size_t>(key) % wasDown_.size()];
    const bool edge = now && !was;
    was = now;
    return edge;
  }
  std::array<bool, 512> wasDown_{};
  bool brushArmed_ = false;  // the left button went down in the view in brush mode
};

int runWindow(const ViewerOptions& o, scene::Model model) {
  GlfwWindow window(o.width, o.height, "pelage view", o.debugGl);
  std::unique_ptr<render::GlDebugLog> log;
  if (o.debugGl) {
    log = std::make_unique<render::GlDebugLog>();
    log->setEcho(true);
  }
  std::printf("pelage view: %s, %s (%s)\n", window.info().renderer.c_str(),
              window.info().version.c_str(), window.info().backend.c_str());
  detail::ViewerSession session(o, std::move(model));

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini next to the user's files
  ImGui::StyleColorsDark();
  if (!ImGui_ImplGlfw_InitForOpenGL(window.handle(), true) ||
      !ImGui_ImplOpenGL3_Init("#version 410 core"))
    inputError("cannot initialise the Dear ImGui OpenGL backend");
  detail::PanelState panel;
  Controls controls;

  const int frames = o.frames > 0 ? o.frames : (o.screenshot.empty() ? 0 : 3);
  int rendered = 0;
  Clock::time_point last = Clock::now();
  while (!window.shouldClose()) {
    const Clock::time_point t0 = Clock::now();
    const double dt = std::min(std::chrono::duration<double>(t0 - last).count(), 0.1);
    last = t0;
    window.pollEvents();
    int fbw = 0, fbh = 0;
    window.framebufferSize(fbw, fbh);
    if (fbw <= 0 || fbh <= 0) {  // minimised: nothing to draw; do not spin
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
      continue;
    }

    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    // The 3D view takes the part of the window right of the panel (all of it when that is narrow).
    const int panelRight = static_cast<int>(detail::drawPanel(session, panel));
    const int viewX = fbw - panelRight >= std::max(160, fbw / 3) ? panelRight : 0;
    const int viewW = fbw - viewX;
    controls.update(window.handle(), session, viewX, fbh, dt);

    session.frame(dt, viewW, fbh);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, fbw, fbh);
    glClearColor(0.06f, 0.06f, 0.07f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    session.renderer().blitTo(0, viewX, 0, viewW, fbh);
    ImGui::Render();
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    ++rendered;
    const bool last_frame = frames > 0 && rendered >= frames;
    if (last_frame && !o.screenshot.empty()) {
      render::Image shot = readBackBuffer(fbw, fbh);
      render::makeOpaque(shot);
      render::writeImage(o.screenshot, shot);
      std::printf("wrote %s (%dx%d, %lld hairs drawn, %d skin triangles)\n", o.screenshot.c_str(),
                  fbw, fbh, static_cast<long long>(session.hairsDrawn()),
                  session.model().skin.numTriangles());
    }
    window.swapBuffers();
    session.recordFrameTime(msSince(t0));
    failOnGlErrors(log.get());
    if (last_frame) window.requestClose();
  }
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  return 0;
}

int runHeadless(const ViewerOptions& o, scene::Model model) {
  render::ContextOptions co;
  co.debug = o.debugGl;
  auto context = render::createHeadlessContext(co);
  std::unique_ptr<render::GlDebugLog> log;
  if (o.debugGl) {
    log = std::make_unique<render::GlDebugLog>();
    log->setEcho(true);
  }
  std::printf("headless view: %s, %s (%s)\n", context->info().renderer.c_str(),
              context->info().version.c_str(), context->info().backend.c_str());
  detail::ViewerSession session(o, std::move(model));
  const int frames = o.frames > 0 ? o.frames : 1;
  double totalMs = 0.0;
  for (int i = 0; i < frames; ++i) {
    const Clock::time_point t0 = Clock::now();
    session.frame(1.0 / 30.0, o.width, o.height);  // a fixed step: the same frames on every run
    session.renderer().finish();
    totalMs += msSince(t0);
  }
  failOnGlErrors(log.get());
  std::printf("rendered %d frame(s) at %dx%d: %lld hairs drawn, %d skin triangles, %.1f ms/frame\n",
              frames, o.width, o.height, static_cast<long long>(session.hairsDrawn()),
              session.model().skin.numTriangles(), totalMs / frames);
  if (!o.screenshot.empty()) {
    render::writeImage(o.screenshot, session.renderer().readPixels(
                                         o.transparentBackground ? render::FrameAlpha::Straight
                                                                 : render::FrameAlpha::Opaque));
    std::printf("wrote %s\n", o.screenshot.c_str());
  }
  return 0;
}

}  // namespace

void validateViewerOptions(const ViewerOptions& o) {
  scene::validateImageSize(o.width, o.height);
  if (o.frames < 0 || o.frames > kMaxViewerFrames)
    fieldError("frames", o.frames, " is out of range [0, ", kMaxViewerFrames, "]");
  scene::validateSamples(o.samples);
  scene::validateLightAngles(o.lightAzimuth, o.lightElevation);
  scene::validateLightIntensity(o.lightColor, "light color");
  scene::validateLightIntensity(o.ambient, "ambient");
  scene::validateStartSeconds(o.time);
  if (o.skinColor) scene::validateColor(*o.skinColor, "skin color");
  if (o.benchmarkFrames < 1 || o.benchmarkFrames > 100000)
    fieldError("benchmark frames", o.benchmarkFrames, " is out of range [1, 100000]");
  if (!o.screenshot.empty()) {
    const std::string ext = lowerExtension(o.screenshot);
    if (ext != ".png" && ext != ".jpg" && ext != ".jpeg")
      fieldError("screenshot", o.screenshot, ": the file must end in .png or .jpg");
    const std::filesystem::path parent = std::filesystem::path(o.screenshot).parent_path();
    if (std::error_code ec; !parent.empty() && !std::filesystem::is_directory(parent, ec))
      fieldError("screenshot", o.screenshot, ": the directory ", parent.string(),
                 " does not exist");
  }
  if (o.transparentBackground && !o.headless)
    fieldError("background",
               "transparent needs the headless screenshot (a window's screenshot "
               "holds the panel beside the view)");
  for (double h : o.benchmarkHairs)
    if (!(h >= 0.0 && h <= fur::kMaxHairs))
      fieldError("benchmark hairs", h, " is out of range [0, ", fur::kMaxHairs, "]");
}

int runViewer(const ViewerOptions& options, scene::Model model) {
  validateViewerOptions(options);
  if (options.benchmark) return detail::runBenchmark(options, model);
  if (options.headless) return runHeadless(options, std::move(model));
  return runWindow(options, std::move(model));
}

}  // namespace pelage::viewer
