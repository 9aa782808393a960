// The viewer's Dear ImGui panel: playback, camera, every fur parameter of both coats, length
// region, gravity, culling, shading, presets, and the status line. Private to pelage::viewer.
#pragma once

#include <array>
#include <string>

#include "viewer_session.h"

namespace pelage::viewer::detail {

// UI-only state kept between frames.
struct PanelState {
  std::array<char, 512> presetPath{};  // the preset file to save or load
  int builtinPreset = 0;
  std::array<char, 512> groomPath{};  // the groom file to save or load (default: MODEL.groom.json)
  std::array<char, 512> strokesPath{};  // the strokes file to save (default: MODEL.strokes.json)
};

// Draws the panel and the status line (between ImGui::NewFrame and ImGui::Render); edits `session`.
// Returns the panel's right edge in pixels (0 when collapsed), so the view can be centred beside
// it.
float drawPanel(ViewerSession& session, PanelState& state);

}  // namespace pelage::viewer::detail
