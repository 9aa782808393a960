#include "viewer_panel.h"

#include <imgui.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

#include "pelage/fur/groom_strokes.h"
#include "pelage/fur/preset.h"

namespace pelage::viewer::detail {
namespace {

bool color(const char* label, Eigen::Vector3f& c) {
  return ImGui::ColorEdit3(label, c.data(), ImGuiColorEditFlags_Float);
}

// A file path field, applied when Enter is pressed (an empty path: no map).
void pathField(const char* label, std::string& path) {
  char buffer[1024];
  std::snprintf(buffer, sizeof buffer, "%s", path.c_str());
  if (ImGui::InputText(label, buffer, sizeof buffer, ImGuiInputTextFlags_EnterReturnsTrue))
    path = buffer;
}

// The colour model of a coat (fur_params.h: CoatColor).
void coatColorPanel(fur::CoatColor& k) {
  if (!ImGui::TreeNode("colour")) return;
  constexpr fur::ColorSource kSources[] = {fur::ColorSource::Material, fur::ColorSource::Creature,
                                           fur::ColorSource::Texture, fur::ColorSource::Vertex,
                                           fur::ColorSource::Map};
  const char* names[std::size(kSources)];
  int current = 0;
  for (std::size_t i = 0; i < std::size(kSources); ++i) {
    names[i] = fur::colorSourceName(kSources[i]).data();
    if (kSources[i] == k.source) current = static_cast<int>(i);
  }
  if (ImGui::Combo("source", &current, names, static_cast<int>(std::size(kSources))))
    k.source = kSources[current];
  ImGui::DragFloat3("tint", k.tint.data(), 0.01f, 0.0f, 10.0f, "%.2f");
  ImGui::SliderFloat("tip lightness", &k.tipLightness, 0.0f, 10.0f, "%.2f",
                     ImGuiSliderFlags_Logarithmic);
  ImGui::Checkbox("tip colour", &k.hasTipColor);
  if (k.hasTipColor) {
    ImGui::SameLine();
    color("##tip", k.tipColor);
  }
  ImGui::SliderFloat("hue variation (deg)", &k.hueVariation, 0.0f, 180.0f);
  ImGui::SliderFloat("value variation", &k.valueVariation, 0.0f, 1.0f);
  ImGui::TreePop();
}

void coatPanel(const char* title, fur::CoatParams& c, bool undercoat) {
  if (!ImGui::TreeNodeEx(title, ImGuiTreeNodeFlags_DefaultOpen)) return;
  ImGui::PushID(title);
  // The styles of fur/hair_layout.h, in enum order.
  const char* styles[fur::kHairStyleCount];
  for (int i = 0; i < fur::kHairStyleCount; ++i) styles[i] = fur::styleName(fur::kHairStyles[i]);
  int style = static_cast<int>(c.style);
  if (ImGui::Combo("style", &style, styles, fur::kHairStyleCount))
    c.style = fur::kHairStyles[style];
  ImGui::SliderFloat("stiffness", &c.stiffness, 0.0f, 1.0f);
  ImGui::SliderFloat("normal randomize", &c.normalRandomize, 0.0f, 1.0f);
  ImGui::SliderFloat("hair end randomize", &c.hairEndRandomize, 0.0f, 2.0f);
  ImGui::SliderFloat("segment direction wt", &c.segmentDirectionWeight, 0.0f, 1.0f);
  ImGui::SliderFloat(undercoat ? "relative length" : "length factor", &c.lengthFactor, 0.0f, 10.0f,
                     "%.3f", ImGuiSliderFlags_Logarithmic);
  if (fur::usesCurveParams(c.style)) {
    ImGui::SliderInt("curve points (K)", &c.curvePoints, 2, 64);
    ImGui::SliderFloat("curl radius", &c.curlRadius, 0.0f, 0.5f);
    ImGui::SliderFloat("curl turns", &c.curlTurns, 0.0f, 20.0f);
  }
  if (fur::usesTubeParams(c.style)) ImGui::SliderInt("tube sides (M)", &c.tubeSides, 3, 32);
  ImGui::SliderFloat("frizz (mm)", &c.frizz.amplitudeMm, 0.0f, 100.0f, "%.2f",
                     ImGuiSliderFlags_Logarithmic);
  if (c.frizz.amplitudeMm > 0.0f) {
    ImGui::SliderFloat("frizz frequency", &c.frizz.frequency, 0.1f, 64.0f, "%.1f",
                       ImGuiSliderFlags_Logarithmic);
    ImGui::SliderFloat("frizz tip weight", &c.frizz.tipWeight, 1.0f, 8.0f);
  }
  ImGui::SliderFloat("clumps per cm^2", &c.clump.density, 0.0f, 100.0f, "%.2f",
                     ImGuiSliderFlags_Logarithmic);
  if (c.clump.density > 0.0f) {
    ImGui::SliderFloat("clump strength", &c.clump.strength, 0.0f, 1.0f);
    ImGui::SliderFloat("clump shape", &c.clump.shape, 0.1f, 10.0f, "%.2f",
                       ImGuiSliderFlags_Logarithmic);
    ImGui::SliderFloat("clump radius (mm)", &c.clump.radiusMm, 0.1f, 1000.0f, "%.1f",
                       ImGuiSliderFlags_Logarithmic);
  }
  ImGui::SliderFloat("root width (mm)", &c.width.rootMm, 0.001f, 20.0f, "%.3f",
                     ImGuiSliderFlags_Logarithmic);
  ImGui::SliderFloat("tip width (mm)", &c.width.tipMm, 0.0f, 20.0f, "%.3f",
                     ImGuiSliderFlags_Logarithmic);
  color("ambient", c.material.ambient);
  color("diffuse", c.material.diffuse);
  color("specular", c.material.specular);
  ImGui::SliderFloat("shininess", &c.material.shininess, 1.0f, 1000.0f, "%.0f",
                     ImGuiSliderFlags_Logarithmic);
  coatColorPanel(c.color);
  ImGui::PopID();
  ImGui::TreePop();
}

void furPanel(ViewerSession& s) {
  fur::FurParams& p = s.edit;
  if (!ImGui::CollapsingHeader("Fur", ImGuiTreeNodeFlags_DefaultOpen)) return;
  float hairs = static_cast<float>(p.hairs);
  if (ImGui::SliderFloat("hairs", &hairs, 0.0f, static_cast<float>(fur::kMaxHairs), "%.0f",
                         ImGuiSliderFlags_Logarithmic))
    p.setHairCount(std::round(static_cast<double>(hairs)));
  float density = static_cast<float>(p.densityPerM2);
  if (ImGui::SliderFloat("density (/m^2)", &density, 0.0f, 1e8f, "%.0f",
                         ImGuiSliderFlags_Logarithmic))
    p.densityPerM2 = static_cast<double>(density);
  ImGui::SameLine();
  ImGui::TextDisabled("(0: use hairs)");
  float coverage = static_cast<float>(p.coverage);
  if (ImGui::SliderFloat("coverage", &coverage, 0.0f, static_cast<float>(fur::kMaxCoverage),
                         "%.3f"))
    p.coverage = static_cast<double>(coverage);
  ImGui::SameLine();
  ImGui::TextDisabled("(share of skin hidden; 0: use density or hairs)");
  ImGui::SliderFloat("undercoat share", &p.undercoatShare, 0.0f, 1.0f);
  // Any seed the presets accept ([0, 2^53]); validation reports one out of range.
  const std::uint64_t step = 1;
  ImGui::InputScalar("seed", ImGuiDataType_U64, &p.seed, &step);
  if (s.regrowing()) ImGui::TextColored(ImVec4(1, 0.8f, 0.3f, 1), "growing new roots...");
  ImGui::SliderFloat("length scale (all)", &p.lengthScale, 0.0f, 10.0f, "%.3f",
                     ImGuiSliderFlags_Logarithmic);

  if (ImGui::TreeNode("groom maps (images on the skin's UVs; Enter applies)")) {
    pathField("density map", p.maps.density);
    pathField("length map", p.maps.length);
    pathField("colour map", p.maps.color);
    ImGui::TreePop();
  }

  if (ImGui::TreeNode("length scale in a 3D region")) {
    const char* shapes[] = {"none", "sphere", "box"};
    int shape = static_cast<int>(p.lengthRegion.shape);
    if (ImGui::Combo("region", &shape, shapes, 3)) {
      p.lengthRegion.shape = static_cast<fur::LengthRegion::Shape>(shape);
      const scene::Framing f = scene::framingOf(s.model(), s.state(), 0.0f);
      if (p.lengthRegion.radius <= 0.0f) {  // start around the face
        p.lengthRegion.center = f.faceCenter;
        p.lengthRegion.radius = f.faceRadius;
        p.lengthRegion.boxMin = f.faceCenter - Eigen::Vector3f::Constant(f.faceRadius);
        p.lengthRegion.boxMax = f.faceCenter + Eigen::Vector3f::Constant(f.faceRadius);
      }
    }
    if (p.lengthRegion.shape == fur::LengthRegion::Shape::Sphere) {
      ImGui::DragFloat3("centre (m)", p.lengthRegion.center.data(), 0.002f);
      ImGui::DragFloat("radius (m)", &p.lengthRegion.radius, 0.001f, 1e-6f, 10.0f);
    } else if (p.lengthRegion.shape == fur::LengthRegion::Shape::Box) {
      ImGui::DragFloat3("min (m)", p.lengthRegion.boxMin.data(), 0.002f);
      ImGui::DragFloat3("max (m)", p.lengthRegion.boxMax.data(), 0.002f);
    }
    ImGui::SliderFloat("scale inside", &p.lengthRegion.scale, 0.0f, 10.0f);
    ImGui::TreePop();
  }
  if (ImGui::TreeNode("gravity")) {
    // Sec. 3.5: hairs droop along gravity = -U (the paper's -Z).
    Eigen::Vector3f g = -p.up;
    if (ImGui::DragFloat3("direction", g.data(), 0.01f, -1.0f, 1.0f) && g.norm() > 1e-3f)
      p.up = -g.normalized();
    ImGui::TreePop();
  }
  if (ImGui::TreeNode("culling by screen scale (sec. 3.3)")) {
    ImGui::Checkbox("enabled", &p.culling.enabled);
    ImGui::TextWrapped("every hair while the creature looks as large as from the reference camera");
    ImGui::SliderFloat("reference distance (m)", &p.culling.referenceDistance, 0.0f, 10.0f, "%.3f",
                       ImGuiSliderFlags_Logarithmic);
    ImGui::Text("0 = where a root is a quarter pixel wide: %.3f m",
                static_cast<double>(s.referenceDistance()));
    ImGui::SliderFloat("reference fov (degrees)", &p.culling.fovYDegrees, 5.0f, 120.0f);
    ImGui::SliderInt("reference height (pixels)", &p.culling.referenceHeight, 16, 4320);
    ImGui::TreePop();
  }
  coatPanel("overcoat", p.coats[fur::kOvercoat], false);
  coatPanel("undercoat", p.coats[fur::kUndercoat], true);
  if (!s.editError.empty()) ImGui::TextColored(ImVec4(1, 0.4f, 0.4f, 1), "%s", s.editError.c_str());
}

// Dynamic fur (fur/dynamics.h; not in the paper): off by default, the paper's quasi-static model.
void dynamicsPanel(ViewerSession& s) {
  if (!ImGui::CollapsingHeader("Dynamics")) return;
  ImGui::Checkbox("dynamic fur (hair ends lag through damped springs)", &s.dynamics);
  ImGui::TextDisabled("off: the paper's quasi-static droop; on: hairs are computed on the CPU");
  for (int c = 0; c < fur::kCoatCount; ++c) {
    fur::CoatDynamics& d = s.dynamicsParams.coats[static_cast<std::size_t>(c)];
    ImGui::PushID(c);
    ImGui::Text("%s", c == fur::kOvercoat ? "overcoat" : "undercoat");
    ImGui::SliderFloat("frequency (Hz at 1 cm)", &d.frequencyHz, 0.1f, 100.0f, "%.2f",
                       ImGuiSliderFlags_Logarithmic);
    ImGui::SliderFloat("damping ratio", &d.dampingRatio, 0.0f, 10.0f, "%.3f",
                       ImGuiSliderFlags_Logarithmic);
    ImGui::PopID();
  }
}

void presetPanel(ViewerSession& s, PanelState& st) {
  if (!ImGui::CollapsingHeader("Presets")) return;
  static const std::vector<std::string> names = fur::builtinPresetNames();
  std::vector<const char*> items;
  for (const std::string& n : names) items.push_back(n.c_str());
  ImGui::Combo("built-in", &st.builtinPreset, items.data(), static_cast<int>(items.size()));
  ImGui::SameLine();
  if (ImGui::Button("use") && st.builtinPreset < static_cast<int>(names.size()))
    s.loadPreset(names[static_cast<std::size_t>(st.builtinPreset)]);
  ImGui::InputText("file", st.presetPath.data(), st.presetPath.size());
  if (ImGui::Button("load file")) s.loadPreset(st.presetPath.data());
  ImGui::SameLine();
  if (ImGui::Button("save file")) s.savePreset(st.presetPath.data());
  if (!s.message.empty()) ImGui::TextWrapped("%s", s.message.c_str());
}

// A file name from the creature's name: letters, digits, '-' and '_' kept, others '_'.
std::string fileStem(const std::string& name) {
  std::string stem;
  for (const char ch : name)
    stem += std::isalnum(static_cast<unsigned char>(ch)) || ch == '-' || ch == '_' ? ch : '_';
  return stem.empty() ? std::string("creature") : stem;
}

// The groom files in the working directory (to load without typing a path), newest first.
std::vector<std::string> groomFilesHere() {
  std::vector<std::pair<std::filesystem::file_time_type, std::string>> found;
  std::error_code ec;
  // Unreadable entries (or directory) are skipped, never thrown.
  for (std::filesystem::directory_iterator it(".", ec), end; !ec && it != end && found.size() < 64;
       it.increment(ec)) {
    const std::string name = it->path().filename().string();
    std::error_code timeError;
    const auto time = it->last_write_time(timeError);
    if (!timeError && name.size() > 11 && name.compare(name.size() - 11, 11, ".groom.json") == 0)
      found.emplace_back(time, name);
  }
  std::sort(found.begin(), found.end(), std::greater<>());
  std::vector<std::string> names;
  for (auto& f : found) names.push_back(std::move(f.second));
  return names;
}

// Brushes (issue 28): tool, radius, strength, mirror; undo/redo; groom and strokes files.
void groomPanel(ViewerSession& s, PanelState& st) {
  ImGui::SetNextItemOpen(s.brushMode, ImGuiCond_Once);  // open when started with strokes
  if (!ImGui::CollapsingHeader("Groom (brushes)")) return;
  if (st.groomPath[0] == '\0')
    std::snprintf(st.groomPath.data(), st.groomPath.size(), "%s.groom.json",
                  fileStem(s.model().name).c_str());
  if (st.strokesPath[0] == '\0')
    std::snprintf(st.strokesPath.data(), st.strokesPath.size(), "%s.strokes.json",
                  fileStem(s.model().name).c_str());
  ImGui::Checkbox("brush with the left button (Alt: orbit)", &s.brushMode);
  ViewerSession::Brush& b = s.brush;
  const char* tools[] = {"length", "density", "color", "comb", "cut", "clump"};
  int tool = static_cast<int>(b.stroke.tool);
  if (ImGui::Combo("tool", &tool, tools, 6)) {
    b.stroke.tool = static_cast<fur::BrushTool>(tool);
    const fur::StrengthRange r = fur::brushStrengthRange(b.stroke.tool);
    b.stroke.strength =
        std::clamp(b.stroke.tool == fur::BrushTool::Length ? 1.5f : 1.0f, r.lo, r.hi);
  }
  int unit = b.screenRadius ? 1 : 0;
  const char* units[] = {"cm on the skin", "pixels on the screen"};
  if (ImGui::Combo("radius in", &unit, units, 2)) {
    b.screenRadius = unit == 1;
    b.radius = b.screenRadius ? 40.0f : 0.03f;
  }
  if (b.screenRadius) {
    ImGui::SliderFloat("radius (px)", &b.radius, 2.0f, 400.0f, "%.0f",
                       ImGuiSliderFlags_Logarithmic);
  } else {
    float cm = 100.0f * b.radius;
    if (ImGui::SliderFloat("radius (cm)", &cm, 0.1f, 100.0f, "%.1f", ImGuiSliderFlags_Logarithmic))
      b.radius = 0.01f * cm;
  }
  const fur::StrengthRange r = fur::brushStrengthRange(b.stroke.tool);
  const char* strengthLabel = b.stroke.tool == fur::BrushTool::Length    ? "length factor"
                              : b.stroke.tool == fur::BrushTool::Density ? "density"
                              : b.stroke.tool == fur::BrushTool::Clump   ? "clump strength"
                                                                         : "strength";
  ImGui::SliderFloat(strengthLabel, &b.stroke.strength, std::max(r.lo, 0.01f), r.hi, "%.2f",
                     r.hi > 1.0f ? ImGuiSliderFlags_Logarithmic : 0);
  if (b.stroke.tool == fur::BrushTool::Color) color("tint", b.stroke.color);
  if (b.stroke.tool == fur::BrushTool::Cut) {
    float mm = 1000.0f * b.stroke.cutLength;
    if (ImGui::SliderFloat("cut to (mm)", &mm, 0.0f, 200.0f, "%.1f"))
      b.stroke.cutLength = 0.001f * mm;
  }
  int mirror = b.stroke.mirrorAxis + 1;
  const char* axes[] = {"none", "x", "y", "z"};
  if (ImGui::Combo("mirror across", &mirror, axes, 4)) b.stroke.mirrorAxis = mirror - 1;
  const scene::GroomEditor& g = s.groomEditor();
  ImGui::BeginDisabled(!g.canUndo());
  if (ImGui::Button("undo (Ctrl+Z)")) s.undoStroke();
  ImGui::EndDisabled();
  ImGui::SameLine();
  ImGui::BeginDisabled(!g.canRedo());
  if (ImGui::Button("redo (Ctrl+Y)")) s.redoStroke();
  ImGui::EndDisabled();
  ImGui::SameLine();
  ImGui::Text("%zu strokes%s", g.strokes().size(), s.groomShown() ? "" : ", growing...");
  ImGui::InputText("groom file", st.groomPath.data(), st.groomPath.size());
  if (ImGui::Button("save groom")) s.saveGroom(st.groomPath.data());
  ImGui::SameLine();
  if (ImGui::Button("load groom")) s.loadGroom(st.groomPath.data());
  ImGui::SameLine();
  if (ImGui::BeginCombo("##here", "groom files here", ImGuiComboFlags_NoPreview)) {
    for (const std::string& name : groomFilesHere())
      if (ImGui::Selectable(name.c_str())) {
        std::snprintf(st.groomPath.data(), st.groomPath.size(), "%s", name.c_str());
        s.loadGroom(name);
      }
    ImGui::EndCombo();
  }
  ImGui::InputText("strokes file", st.strokesPath.data(), st.strokesPath.size());
  if (ImGui::Button("save strokes")) s.saveStrokes(st.strokesPath.data());
  if (!s.message.empty()) ImGui::TextWrapped("%s", s.message.c_str());
}

void viewPanel(ViewerSession& s) {
  if (!ImGui::CollapsingHeader("View", ImGuiTreeNodeFlags_DefaultOpen)) return;
  // Playback: clip selector (cross-fades), play/pause, scrub, speed, loop.
  const auto& clips = s.model().clips;
  std::string current =
      s.clip() >= 0 ? clips[static_cast<std::size_t>(s.clip())].name : std::string("(still pose)");
  if (ImGui::BeginCombo("clip", current.c_str())) {
    if (ImGui::Selectable("(still pose)", s.clip() < 0)) s.selectClip(-1);
    for (int i = 0; i < static_cast<int>(clips.size()); ++i)
      if (ImGui::Selectable(clips[static_cast<std::size_t>(i)].name.c_str(), s.clip() == i))
        s.selectClip(i);
    ImGui::EndCombo();
  }
  ImGui::Checkbox("play", &s.playing);
  ImGui::SameLine();
  ImGui::Checkbox("loop", &s.loop);
  if (s.clip() >= 0) {
    const double duration = s.clipDuration();
    float t = duration > 0.0 ? static_cast<float>(std::fmod(s.time(), duration)) : 0.0f;
    if (ImGui::SliderFloat("time (s)", &t, 0.0f, static_cast<float>(duration), "%.2f")) {
      // Scrub within the current cycle (root motion of earlier cycles is kept).
      const double cycles = duration > 0.0 ? std::floor(s.time() / duration) : 0.0;
      s.setTime(cycles * duration + static_cast<double>(t));
    }
  }
  ImGui::SliderFloat("speed", &s.speed, 0.0f, 4.0f);
  ImGui::SliderFloat("turntable (deg/s)", &s.turntableDegPerSecond, -90.0f, 90.0f);
  const char* presets[] = {"front", "side", "3/4", "face", "follow"};
  for (int i = 0; i < 5; ++i) {
    if (i) ImGui::SameLine();
    if (ImGui::Button(presets[i])) s.applyPreset(static_cast<scene::CameraPreset>(i));
  }
  ImGui::Checkbox("follow the creature", &s.follow);
  ImGui::SliderFloat("light azimuth", &s.lightAzimuth, -180.0f, 180.0f);
  ImGui::SliderFloat("light elevation", &s.lightElevation, -89.0f, 89.0f);
  ImGui::Checkbox("shadows", &s.shadows);
  ImGui::SameLine();
  ImGui::Checkbox("self-shadowing", &s.selfShadowing);
  ImGui::SameLine();
  ImGui::Checkbox("skin", &s.drawSkin);
  ImGui::SameLine();
  if (ImGui::ColorEdit3("##skin colour", s.skinColor.data(),
                        ImGuiColorEditFlags_NoInputs | ImGuiColorEditFlags_Float))
    s.ownSkinColor = true;  // from now on the skin is drawn in this colour
  if (s.ownSkinColor) {
    ImGui::SameLine();
    if (ImGui::SmallButton("model's")) s.ownSkinColor = false;  // back to the model's colours
  }
  ImGui::SameLine();
  ImGui::Checkbox("fur", &s.drawFur);
  int shading = static_cast<int>(s.shading);
  const char* shadings[] = {"paper (Phong, style normals)", "Kajiya-Kay (tangents)",
                            "Marschner (R, TT, TRT lobes)",
                            "physical (calibrated against a path tracer)"};
  if (ImGui::Combo("hair shading", &shading, shadings, 4))
    s.shading = static_cast<scene::HairShading>(shading);
  int width = static_cast<int>(s.hairWidth);
  const char* widths[] = {"1-pixel lines (the paper's)", "strands of their width (coat panel)"};
  if (ImGui::Combo("hairs drawn as", &width, widths, 2))
    s.hairWidth = static_cast<scene::HairWidth>(width);
  if (s.hairWidth == scene::HairWidth::Strands)
    ImGui::Checkbox("transparency (coverage, any order)", &s.transparency);
  int source = static_cast<int>(s.hairSource);
  const char* sources[] = {"CPU fur model", "GPU compute"};
  if (ImGui::Combo("hairs computed on", &source, sources, 2))
    s.hairSource = static_cast<scene::HairSource>(source);
}

void statusLine(ViewerSession& s) {
  const ImGuiViewport* vp = ImGui::GetMainViewport();
  ImGui::SetNextWindowPos(ImVec2(vp->WorkPos.x, vp->WorkPos.y + vp->WorkSize.y), ImGuiCond_Always,
                          ImVec2(0, 1));
  ImGui::SetNextWindowBgAlpha(0.6f);
  ImGui::Begin("status", nullptr,
               ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize |
                   ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoSavedSettings |
                   ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoNav);
  const scene::FrameState& f = s.state();
  ImGui::Text("hairs drawn %lld of %lld (c = %.2f) | frame %.1f ms | skin %d triangles | %s | %s",
              static_cast<long long>(s.hairsDrawn()), static_cast<long long>(s.fur().roots.total()),
              static_cast<double>(f.cullFactor), s.frameMs(), s.model().skin.numTriangles(),
              s.dynamics                               ? "CPU dynamic fur"
              : s.hairSource == scene::HairSource::Gpu ? "GPU fur"
                                                       : "CPU fur",
              s.model().name.c_str());
  ImGui::End();
}

}  // namespace

float drawPanel(ViewerSession& s, PanelState& st) {
  const ImGuiViewport* vp = ImGui::GetMainViewport();
  ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(400, vp->WorkSize.y - 50), ImGuiCond_FirstUseEver);
  float right = 0.0f;
  if (ImGui::Begin("pelage")) {
    ImGui::PushItemWidth(ImGui::GetWindowWidth() * 0.55f);
    groomPanel(s, st);  // first: open when the viewer starts with strokes
    viewPanel(s);
    furPanel(s);
    dynamicsPanel(s);
    presetPanel(s, st);
    ImGui::PopItemWidth();
    right = ImGui::GetWindowPos().x + ImGui::GetWindowWidth();
  }
  ImGui::End();
  statusLine(s);
  return right;
}

}  // namespace pelage::viewer::detail
