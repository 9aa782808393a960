#include "options.h"

#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <utility>

#include <nlohmann/json.hpp>

#include "pelage/anatomy/pose_file.h"
#include "pelage/animation/clip.h"
#include "pelage/fur/preset.h"
#include "pelage/scene/clock.h"
#include "pelage/skin/skin_mesh.h"
#include "pelage/util/color.h"
#include "pelage/util/log.h"
#include "pelage/util/parallel.h"

namespace pelage::app {
namespace {

// "%g" of a default value, for help texts (the defaults shown are the libraries' own).
std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

// An on/off switch: `what` (the help text before the accepted values), its default shown.
void addSwitch(CLI::App& cmd, const std::string& name, std::string& value,
               const std::string& what) {
  cmd.add_option(name, value, what + ": on or off (default " + value + ")")
      ->check(CLI::IsMember({"on", "off"}));
}

// The --threads value every command shares (the top-level option and each command's).
int& sharedThreads() {
  static int threads = 0;
  return threads;
}

}  // namespace

std::string_view optionForField(std::string_view field) {
  static constexpr std::array<std::pair<std::string_view, std::string_view>, 33> kOptions{{
      {"ambient", "--ambient"},
      {"benchmark frames", "--benchmark-frames"},
      {"benchmark hairs", "--benchmark-hairs"},
      {"camera", "--camera"},
      {"clip", "--clip"},
      {"dynamics", "--dynamics"},
      {"encoders", "--encoders"},
      {"format", "--format"},
      {"fov", "--fov"},
      {"fps", "--fps"},
      {"frames", "--frames"},
      {"hair source", "--hair-source"},
      {"light", "--light"},
      {"light color", "--light-color"},
      {"hold", "--hold"},
      {"no fur", "--no-fur"},
      {"out", "--out"},
      {"pass", "--pass"},
      {"plot", "--plot"},
      {"preroll", "--preroll"},
      {"resume", "--resume"},
      {"samples", "--samples"},
      {"scene files", "--scene-files"},
      {"screenshot", "--screenshot"},
      {"shading", "--shading"},
      {"size", "--size"},
      {"skin color", "--skin-color"},
      {"subdivide", "--subdivide"},
      {"sweep", "--sweep"},
      {"time", "--time"},
      {"triangles", "--triangles"},
      {"unit scale", "--unit-scale"},
      {"video", "--video"},
  }};
  for (const auto& [name, option] : kOptions)
    if (name == field) return option;
  return {};
}

std::string describe(const InputError& error) {
  const std::string_view option = optionForField(error.field());
  if (option.empty()) return error.what();
  return InputError::join(std::string(option), error.detail());
}

// ---- CommonOptions -------------------------------------------------------------------------

void CommonOptions::add(CLI::App& cmd, bool quietOption) {
  cmd.add_option("--threads", sharedThreads(), "Worker threads [0, 1024] (default 0: all cores)");
  if (quietOption)
    cmd.add_flag("--quiet", quiet,
                 "Print nothing but warnings and errors (no progress, no summary)");
}

void CommonOptions::apply() const {
  const int t = sharedThreads();
  if (t < 0 || t > 1024) inputError("--threads ", t, " is out of range [0, 1024]");
  setThreadCount(t);
}

// ---- ModelOptions --------------------------------------------------------------------------

void ModelOptions::add(CLI::App& cmd) {
  cmd.add_option("model", model,
                 "Creature: 'monkey' (built-in, default), a creature .json, a .gltf/.glb, or a "
                 "static .obj/.ply/.off/.stl mesh; anywhere on the line");
  cmd.add_option("--triangles", triangles,
                 "Skin triangles for creatures built from shapes [2000, 2000000] (default: the "
                 "creature's, 130000 for the monkey)");
  cmd.add_option("--unit-scale", unitScale,
                 "glTF and static meshes: metres per file unit (0, 1000000] (default: glTF "
                 "detected from the bounding box, meshes 1)");
  cmd.add_option("--no-fur", noFur,
                 "glTF: regions (material or node names, '*' wildcards) that grow no fur, "
                 "replacing the default list (Eye*, Hooves, Nose, *Horn*, ...); each must match a "
                 "region (see `pelage info`)");
  cmd.add_option("--directions", directions,
                 "glTF: JSON side file of per-joint segment directions (default: "
                 "<model>.directions.json if it exists)");
  cmd.add_option("--subdivide", subdivide,
                 "glTF and static meshes: subdivision levels of the skin under the roots, "
                 "'auto' or [0, 3] (default auto: a skin under 4000 triangles is subdivided until "
                 "it has 4000; 0 keeps the file's)");
}

scene::Model ModelOptions::load() const {
  scene::LoadOptions opt;
  opt.triangles = triangles;
  if (unitScale != 0.0 && !(unitScale > 0.0 && unitScale <= 1e6))
    inputError("--unit-scale ", unitScale, " is out of range (0, 1000000] metres per file unit");
  opt.unitScale = static_cast<float>(unitScale);
  if (!noFur.empty()) opt.noFurRegions = noFur;
  opt.segmentDirections = directions;
  if (subdivide != "auto") {
    if (subdivide.size() != 1 || subdivide[0] < '0' || subdivide[0] > '3')
      inputError("--subdivide '", excerpt(subdivide), "' is not auto or a level in [0, 3]");
    opt.subdivide = subdivide[0] - '0';
  }
  scene::Model m = scene::loadModel(model, opt);
  const float size = scene::modelSizeMeters(m);
  if (size > scene::kPlausibleSizeMeters[1] || size < scene::kPlausibleSizeMeters[0])
    warn(str(m.source, ": the creature is ", size,
             " m long, implausible for an animal; if the "
             "file is not in metres, give --unit-scale (metres per file unit, e.g. 0.01 for "
             "centimetres, 0.3 to make it 0.3 times as large)"));
  return m;
}

// ---- PoseOptions ---------------------------------------------------------------------------

void PoseOptions::add(CLI::App& cmd) {
  cmd.add_option("--pose", posePath, "Pose file (JSON) bending segments from the rest pose");
  cmd.add_option("--clip", clip,
                 "Clip: one of the model's (see `pelage info`) or a clip .json file (default: "
                 "the model's first, for commands that play one)");
  timeOption = cmd.add_option("--time", time,
                              "Clip time in seconds [0, 1000000] of the pose, or of frame 0 of a "
                              "sequence (default 0; loops wrap)");
}

anatomy::Pose PoseOptions::stillPose(scene::Model& model) const {
  scene::validateStartSeconds(time);
  if (clip.empty()) {
    if (timeOption && timeOption->count() > 0) inputError("--time needs --clip");
    return posePath.empty() ? anatomy::restPose(model.body)
                            : anatomy::loadPose(model.body, posePath);
  }
  if (!posePath.empty()) inputError("--pose and --clip cannot be used together");
  anatomy::Pose pose;
  const int c = scene::resolveClip(model, clip);
  animation::sampleClip(model.clips[static_cast<std::size_t>(c)], model.body, time, pose);
  return pose;
}

void PoseOptions::sequence(scene::Model& model, scene::PlaybackOptions& playback) const {
  scene::validateStartSeconds(time);
  if (!posePath.empty()) {
    if (!clip.empty()) inputError("--pose and --clip cannot be used together");
    if (timeOption && timeOption->count() > 0) inputError("--time needs --clip");
    playback.clip = -1;
    playback.stillPose = anatomy::loadPose(model.body, posePath);
    return;
  }
  playback.clip = scene::resolveClip(model, clip);
  if (playback.clip < 0 && timeOption && timeOption->count() > 0)
    inputError("--time needs a clip, and model '", model.name, "' has none");
  playback.clock.startSeconds = time;
}

// ---- FurOptions ----------------------------------------------------------------------------

void FurOptions::add(CLI::App& cmd) {
  const fur::FurParams d;
  cmd.add_option("--fur", preset,
                 std::string("Fur preset: built-in name (default, fig8, fig9) or a .json file "
                             "(default: ") +
                     fur::kDefaultPreset + ")");
  hairsOption = cmd.add_option(
      "--hairs", hairs, "Total hairs over the skin, both coats [0, 2e7] (default: the preset's)");
  cmd.add_option("--style", style,
                 "Hair style of both coats: " + fur::styleNames() + " (default: the preset's)");
  seedOption = cmd.add_option("--seed", seed, "Random seed [0, 2^53] (default: the preset's)");
  shareOption = cmd.add_option("--undercoat-share", undercoatShare,
                               "Share of the hairs in the undercoat [0, 1] (default: the "
                               "preset's)");
  lengthOption = cmd.add_option("--length-scale", lengthScale,
                                "Scale of every hair length [0, 10] (default: the preset's)");
  stiffnessOption = cmd.add_option("--stiffness", stiffness,
                                   "Stiffness of both coats [0, 1], floppiness = 1 - stiffness "
                                   "(default: the preset's)");
  widthOption = cmd.add_option("--hair-width", hairWidth,
                               "Hair width at the root of both coats, mm [0.001, 20]; the tips "
                               "keep their share of it (default: the preset's, 0.4 to 0.02)");
  cmd.add_option(
      "--groom", groom,
      "Groom file of per-vertex values (length, density, tint, comb, clump) for this model's mesh, "
      "from Python's Model.write_groom or `pelage info --groom-out` (default: the "
      "preset's 'groom', else none)");
  cmd.add_option("--fur-set", settings,
                 "Any preset field, FIELD=VALUE (repeatable), e.g. overcoat.stiffness=0.6, "
                 "undercoat.diffuse=[0.3,0.2,0.1], overcoat.curl.turns=3, culling.enabled=false "
                 "(fields: models/presets/README.md); a field also set by a named option is "
                 "refused");
}

fur::FurParams FurOptions::resolve() const {
  fur::FurParams p = fur::loadFurPreset(preset.empty() ? fur::kDefaultPreset : preset);
  // The named options, and the preset fields each sets (a --fur-set of one of them is refused).
  struct Named {
    const char* option;
    bool given;
    std::vector<std::string> fields;
  };
  const std::vector<Named> named = {
      {"--hairs", hairsOption && hairsOption->count() > 0, {"hairs", "density", "coverage"}},
      {"--style", !style.empty(), {"overcoat.style", "undercoat.style"}},
      {"--seed", seedOption && seedOption->count() > 0, {"seed"}},
      {"--undercoat-share", shareOption && shareOption->count() > 0, {"undercoatShare"}},
      {"--length-scale", lengthOption && lengthOption->count() > 0, {"lengthScale"}},
      {"--stiffness",
       stiffnessOption && stiffnessOption->count() > 0,
       {"overcoat.stiffness", "undercoat.stiffness"}},
      {"--groom", !groom.empty(), {"groom"}},
      {"--hair-width",
       widthOption && widthOption->count() > 0,
       {"overcoat.width", "undercoat.width", "overcoat.width.root", "undercoat.width.root",
        "overcoat.width.tip", "undercoat.width.tip"}},
  };
  if (!settings.empty()) {
    // The settings as a preset's fields (FIELD a dotted path into its groups), applied over it.
    nlohmann::json fields = nlohmann::json::object();
    for (const std::string& s : settings) {
      const std::size_t eq = s.find('=');
      if (eq == std::string::npos || eq == 0 || eq + 1 == s.size())
        inputError("--fur-set '", excerpt(s), "' is not FIELD=VALUE (e.g. overcoat.stiffness=0.6)");
      const std::string field = s.substr(0, eq), text = s.substr(eq + 1);
      for (const Named& n : named)
        for (const std::string& f : n.fields)
          if (n.given && f == field)
            inputError(n.option, " and --fur-set ", excerpt(s), " both set ", field,
                       ": give one (a named option and --fur-set never silently override each "
                       "other)");
      nlohmann::json value = nlohmann::json::parse(text, nullptr, false);
      if (value.is_discarded()) value = text;  // a bare word: a string (e.g. a style name)
      nlohmann::json* node = &fields;
      std::size_t start = 0;
      for (;;) {
        const std::size_t dot = field.find('.', start);
        const std::string part =
            field.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
        if (part.empty())
          inputError("--fur-set '", excerpt(s), "': empty field name in '", excerpt(field), "'");
        if (dot == std::string::npos) {
          // "hairs", "density" and "coverage" exclude each other: setting one drops the others.
          if (node == &fields && (part == "hairs" || part == "density" || part == "coverage"))
            for (const char* other : {"hairs", "density", "coverage"})
              if (part != other) fields.erase(other);
          (*node)[part] = value;
          break;
        }
        nlohmann::json& next = (*node)[part];
        if (!next.is_object()) next = nlohmann::json::object();
        node = &next;
        start = dot + 1;
      }
    }
    p = fur::applyFurPresetFields(p, fields.dump(), "--fur-set options");
  }
  if (hairsOption && hairsOption->count() > 0) p.setHairCount(hairs);
  if (!groom.empty()) p.groom = groom;
  if (!style.empty()) {
    const fur::HairStyle s = fur::parseStyle(style, "--style");
    for (auto& c : p.coats) c.style = s;
  }
  if (seedOption && seedOption->count() > 0) {
    if (seed < 0 || seed > (std::int64_t(1) << 53))
      inputError("--seed ", seed, " is out of range [0, 2^53]");
    p.seed = static_cast<std::uint64_t>(seed);
  }
  if (shareOption && shareOption->count() > 0)
    p.undercoatShare = static_cast<float>(undercoatShare);
  if (lengthOption && lengthOption->count() > 0) p.lengthScale = static_cast<float>(lengthScale);
  if (stiffnessOption && stiffnessOption->count() > 0)
    for (auto& c : p.coats) c.stiffness = static_cast<float>(stiffness);
  if (widthOption && widthOption->count() > 0) {
    if (!(hairWidth >= 0.001 && hairWidth <= 20.0))
      inputError("--hair-width ", hairWidth, " mm is out of range [0.001, 20]");
    for (auto& c : p.coats) {
      const float root = static_cast<float>(hairWidth);
      c.width.tipMm = std::min(20.0f, c.width.tipMm * root / c.width.rootMm);
      c.width.rootMm = root;
    }
  }
  fur::validateFurParams(p, "fur '" + p.name + "' with the command-line options");
  return p;
}

// ---- DynamicsOptions -----------------------------------------------------------------------

void DynamicsOptions::add(CLI::App& cmd, bool withPreRoll) {
  const fur::CoatDynamics d;
  addSwitch(cmd, "--dynamics", mode,
            "Fur dynamics: 'on' makes each hair's end follow the paper's (quasi-static) end "
            "through a damped spring; 'off' is the paper's model");
  cmd.add_option("--frequency", frequency,
                 "With --dynamics on: natural frequency of a 1 cm hair, Hz (0, 100]: one value "
                 "for both coats or two (overcoat undercoat) (default " +
                     number(static_cast<double>(d.frequencyHz)) + ")")
      ->expected(1, 2);
  cmd.add_option("--damping", damping,
                 "With --dynamics on: damping ratio [0, 10] (1 = critical): one value or two "
                 "(overcoat undercoat) (default " +
                     number(static_cast<double>(d.dampingRatio)) + ")")
      ->expected(1, 2);
  if (withPreRoll)
    preRollOption = cmd.add_option(
        "--preroll", preRoll,
        "With --dynamics on: frames simulated before the first one shown [0, 10000000] "
        "(default: from the clip's start, so any frame range matches a whole run exactly)");
}

fur::DynamicsParams DynamicsOptions::resolve() const {
  fur::DynamicsParams p;
  for (int c = 0; c < fur::kCoatCount; ++c) {
    const auto ci = static_cast<std::size_t>(c);
    if (!frequency.empty())
      p.coats[ci].frequencyHz = static_cast<float>(frequency[std::min(ci, frequency.size() - 1)]);
    if (!damping.empty())
      p.coats[ci].dampingRatio = static_cast<float>(damping[std::min(ci, damping.size() - 1)]);
  }
  fur::validateDynamicsParams(p, "--frequency/--damping");
  const bool preRollGiven = preRollOption && preRollOption->count() > 0;
  if (preRollGiven) scene::validatePreRoll(preRoll, "preroll", false);
  // Options that cannot take effect are refused, never silently ignored.
  if (!enabled()) {
    const char* given = !frequency.empty() ? "--frequency"
                        : !damping.empty() ? "--damping"
                        : preRollGiven     ? "--preroll"
                                           : nullptr;
    if (given) inputError(given, " needs --dynamics on (without it the fur is quasi-static)");
  }
  return p;
}

// ---- FrameOptions --------------------------------------------------------------------------

void FrameOptions::add(CLI::App& cmd) {
  cmd.add_option("--frames", frames,
                 "Frames FIRST:LAST (inclusive) or one frame F; frame f shows clip time --time + "
                 "f / fps (default: the whole clip, 0 to duration x fps; the still pose: 0)");
  addFps(cmd);
}

void FrameOptions::addFps(CLI::App& cmd) {
  cmd.add_option("--fps", fps, "Frames per second [1, 1000] (default " + number(fps) + ")");
}

void FrameOptions::validateFps() const {
  scene::validateFramesPerSecond(fps);
}

scene::FrameRange FrameOptions::range(const scene::Model& model, int clip, double startSeconds,
                                      bool quiet) const {
  validateFps();
  if (frames.empty()) return scene::wholeClip(model, clip, fps);
  const scene::FrameRange r = scene::parseFrameRange(frames);
  if (!quiet && clip >= 0) {
    const animation::Clip& c = model.clips[static_cast<std::size_t>(clip)];
    const double end = static_cast<double>(c.duration);
    const double lastSeconds = startSeconds + r.last / fps;
    if (lastSeconds > end + 1e-9) {
      // The first frame whose time is past the end.
      const int firstPast = static_cast<int>(std::floor((end - startSeconds) * fps + 1e-9)) + 1;
      std::fprintf(stderr,
                   "pelage: note: frames %d..%d lie past the end of clip '%s' (%g s at %g fps): "
                   "%s\n",
                   std::max(r.first, firstPast), r.last, c.name.c_str(), end, fps,
                   c.loop ? "they show it looped" : "they hold its last pose");
    }
  }
  return r;
}

// ---- ViewOptions ---------------------------------------------------------------------------

void parseSize(const std::string& text, const char* option, int& width, int& height) {
  char x = 0;
  std::istringstream in(text);
  if (!(in >> width >> x >> height) || x != 'x' || !in.eof())
    inputError(option, " '", excerpt(text), "' is not WIDTHxHEIGHT (e.g. 1920x1080)");
  scene::validateImageSize(width, height, option);
}

void ViewOptions::add(CLI::App& cmd) {
  cmd.add_option("--size", size,
                 "Image or window size WIDTHxHEIGHT, [16, 16384] per side "
                 "(default " +
                     size + ")");
  cmd.add_option("--samples", samples,
                 "MSAA samples [0, 64]; -1 = 4 on a GPU, 0 on a software rasteriser (default -1)");
  cmd.add_option("--camera", camera,
                 "Camera preset: " + scene::cameraPresetNames() + " (default " + camera + ")");
  cmd.add_flag("--follow,--track", follow,
               "Move the camera with the creature (its root's horizontal motion)");
  cmd.add_option("--fov", fov,
                 "Vertical field of view, degrees (1, 179) (default " + number(fov) + ")");
  cmd.add_option("--hair-source", hairSource,
                 "Where hairs are computed each frame: gpu or cpu (default " + hairSource +
                     "; dynamic fur is always the CPU's)");
  cmd.add_option(
      "--shading", shading,
      "Hair shading: paper, kajiya-kay, marschner or physical (default " + shading + ")");
  cmd.add_flag("--lines", lines,
               "Draw hairs as the paper's 1-pixel lines instead of strands of their width "
               "(sec. 3.3)");
  addSwitch(cmd, "--transparency", transparency,
            "Strands blended with their pixel coverage as alpha, in any order (weighted blended "
            "OIT; off: opaque, at least 1 pixel wide)");
  cmd.add_flag("--shadows", shadows,
               "Shadow map: the skin shadows itself and the fur (without self-shadowing the "
               "hairs' shadows are hard)");
  addSwitch(cmd, "--self-shadowing", selfShadowing,
            "The fur's own soft shadow (deep opacity maps): the coat darkens inside and the skin "
            "under it");
  cmd.add_flag("--no-culling", noCulling, "Draw every hair at any distance (no sec. 3.3 culling)");
  cmd.add_option("--skin-color", skinColor,
                 "Skin colour R G B, each in [0, 1] (default: the model's)")
      ->expected(3);
  cmd.add_option("--background", background,
                 "The frames' background: R G B (sRGB, each in [0, 1]; default 0.80 0.82 0.86), or "
                 "'transparent' (PNGs with straight alpha, 0 where nothing is drawn; over the "
                 "default colour they equal the opaque frames). Frames are opaque otherwise")
      ->expected(1, 3);
  cmd.add_option("--light", light,
                 "The key light's place: azimuth (degrees about +Z from +X, [-360, 360]) and "
                 "elevation (degrees above the ground, [-90, 90]) (default " +
                     number(static_cast<double>(scene::kKeyLightAzimuthDegrees)) + " " +
                     number(static_cast<double>(scene::kKeyLightElevationDegrees)) + ")")
      ->expected(2);
  const scene::Light defaults;
  cmd.add_option("--light-color", lightColor,
                 "The key light's colour and strength: I, or R G B (linear, each in [0, " +
                     number(static_cast<double>(scene::kMaxLightIntensity)) + "]; default " +
                     number(static_cast<double>(defaults.color.x())) +
                     "; 0 leaves the ambient light alone)")
      ->expected(1, 3);
  cmd.add_option("--ambient", ambient,
                 "The ambient light: I, or R G B (linear, each in [0, " +
                     number(static_cast<double>(scene::kMaxLightIntensity)) + "]; default " +
                     number(static_cast<double>(defaults.ambient.x())) +
                     "; 0 leaves the key light alone)")
      ->expected(1, 3);
}

namespace {
// I (grey) or R G B from an option's values; `fallback` when not given.
Eigen::Vector3f intensity(const std::vector<float>& v, const char* option,
                          const Eigen::Vector3f& fallback) {
  if (v.empty()) return fallback;
  if (v.size() == 1) return Eigen::Vector3f::Constant(v[0]);
  if (v.size() != 3) inputError(option, " takes I or R G B, got ", v.size(), " values");
  return {v[0], v[1], v[2]};
}
}  // namespace

Eigen::Vector3f ViewOptions::keyLightColor() const {
  return intensity(lightColor, "--light-color", scene::Light{}.color);
}

Eigen::Vector3f ViewOptions::ambientLight() const {
  return intensity(ambient, "--ambient", scene::Light{}.ambient);
}

float ViewOptions::lightAzimuth() const {
  return light.size() == 2 ? light[0] : scene::kKeyLightAzimuthDegrees;
}

float ViewOptions::lightElevation() const {
  return light.size() == 2 ? light[1] : scene::kKeyLightElevationDegrees;
}

int ViewOptions::width() const {
  int w = 0, h = 0;
  parseSize(size, "--size", w, h);
  return w;
}

int ViewOptions::height() const {
  int w = 0, h = 0;
  parseSize(size, "--size", w, h);
  return h;
}

scene::CameraPreset ViewOptions::cameraPreset() const {
  return scene::parseCameraPreset(camera);
}

scene::HairSource ViewOptions::source() const {
  return scene::parseHairSource(hairSource);
}

scene::HairShading ViewOptions::hairShading() const {
  return scene::parseHairShading(shading);
}

scene::HairWidth ViewOptions::hairWidth() const {
  return lines ? scene::HairWidth::Lines : scene::HairWidth::Strands;
}

Eigen::Vector3f ViewOptions::backgroundColor() const {
  if (background.size() != 3) return scene::kDefaultBackground;
  Eigen::Vector3f srgb;
  for (int c = 0; c < 3; ++c) {
    const std::string& text = background[static_cast<std::size_t>(c)];
    float v = 0.0f;
    const auto r = std::from_chars(text.data(), text.data() + text.size(), v);
    if (r.ec != std::errc() || r.ptr != text.data() + text.size() || !(v >= 0.0f && v <= 1.0f))
      inputError("--background ", "RGB"[c], " = '", excerpt(text),
                 "' is not a number in [0, 1] (give R G B in [0, 1], or transparent)");
    srgb[c] = v;
  }
  return srgbToLinear(srgb);
}

bool ViewOptions::transparentBackground() const {
  return background.size() == 1 && background[0] == "transparent";
}

std::optional<Eigen::Vector3f> ViewOptions::skin() const {
  if (skinColor.empty()) return std::nullopt;
  return Eigen::Vector3f(skinColor[0], skinColor[1], skinColor[2]);
}

void ViewOptions::validate() const {
  int w = 0, h = 0;
  parseSize(size, "--size", w, h);
  scene::validateSamples(samples);
  scene::validateFov(fov);
  cameraPreset();
  source();
  hairShading();
  if (background.size() == 1 && background[0] != "transparent")
    inputError("--background '", excerpt(background[0]),
               "': give R G B (sRGB, each in [0, 1]) or transparent");
  if (background.size() == 2)
    inputError("--background takes R G B (3 values) or transparent, got 2 values");
  backgroundColor();
  if (!skinColor.empty()) {
    if (skinColor.size() != 3)
      inputError("--skin-color takes 3 values (R G B in [0, 1]), got ", skinColor.size());
    scene::validateColor(Eigen::Vector3f(skinColor[0], skinColor[1], skinColor[2]), "skin color");
  }
  scene::validateLightAngles(lightAzimuth(), lightElevation());
  scene::validateLightIntensity(keyLightColor(), "light color");
  scene::validateLightIntensity(ambientLight(), "ambient");
}

// ---- Output folders --------------------------------------------------------------------------

NewFolders::NewFolders(const std::string& dir) : exceptions_(std::uncaught_exceptions()) {
  std::error_code ec;
  for (std::filesystem::path p = std::filesystem::absolute(dir, ec).lexically_normal();
       !p.empty() && !std::filesystem::exists(p, ec) && p != p.parent_path(); p = p.parent_path())
    created_.push_back(p.string());
}

NewFolders::~NewFolders() {
  if (std::uncaught_exceptions() <= exceptions_) return;
  for (const std::string& d : created_) {
    std::error_code ec;
    if (!std::filesystem::is_directory(d, ec) || !std::filesystem::is_empty(d, ec)) return;
    std::filesystem::remove(d, ec);
  }
}

// ---- Argument normalisation ------------------------------------------------------------------

namespace {

bool isModelSpec(const std::string& token) {
  if (token == scene::kDefaultModel) return true;
  std::error_code ec;
  return scene::modelFileKind(token) != scene::ModelFileKind::None &&
         std::filesystem::is_regular_file(token, ec);
}

bool takesSeveralValues(const std::string& token) {
  for (const char* o : {"--no-fur", "--fur-set", "--frequency", "--damping", "--skin-color",
                        "--background", "--benchmark-hairs"})
    if (token == o) return true;
  return false;
}

}  // namespace

std::vector<std::string> normalizeArguments(const std::vector<std::string>& args) {
  static const char* kCommands[] = {"info", "skin",   "hair",   "bench",
                                    "view", "render", "export", "analyze"};
  std::size_t command = args.size();
  for (std::size_t i = 0; i < args.size() && command == args.size(); ++i)
    for (const char* c : kCommands)
      if (args[i] == c) command = i;
  if (command == args.size()) return args;
  std::vector<std::string> out(args.begin(),
                               args.begin() + static_cast<std::ptrdiff_t>(command) + 1);
  std::vector<std::string> rest;
  std::string model;
  bool afterSeveral = false;
  for (std::size_t i = command + 1; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a.rfind("-", 0) == 0 && a.size() > 1 && !std::isdigit(static_cast<unsigned char>(a[1]))) {
      afterSeveral = takesSeveralValues(a);
      rest.push_back(a);
      continue;
    }
    if (afterSeveral && model.empty() && isModelSpec(a)) {
      model = a;  // ends the list; the model goes first
      afterSeveral = false;
      continue;
    }
    rest.push_back(a);
  }
  if (!model.empty()) out.push_back(model);
  out.insert(out.end(), rest.begin(), rest.end());
  return out;
}

}  // namespace pelage::app
