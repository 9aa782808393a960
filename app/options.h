// The command line's option set, defined once: every option that more than one command takes is
// declared here, with one name, one default and one help text, and each command adds the groups
// that make sense for it. The libraries speak in fields and values ("fps 0 is out of range"); this
// is the one place that knows the options that set them ("--fps 0 is out of range").
#pragma once

#include <CLI/CLI.hpp>

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "pelage/anatomy/pose.h"
#include "pelage/fur/dynamics.h"
#include "pelage/fur/fur_params.h"
#include "pelage/scene/camera.h"
#include "pelage/scene/draw_list.h"
#include "pelage/scene/frame_range.h"
#include "pelage/scene/model.h"
#include "pelage/scene/playback.h"
#include "pelage/util/error.h"

namespace pelage::app {

// ---- Messages -------------------------------------------------------------------------------

// The option that sets library field `field` ("fps" -> "--fps"), or "" when none does.
std::string_view optionForField(std::string_view field);

// An error's message in the command line's words: a field error names the option instead.
std::string describe(const InputError& error);

// ---- Output folders --------------------------------------------------------------------------

// The output folder rule of every command that writes files: a missing folder is created (with
// its parents), and the folders a failed command created are removed again while still empty, so
// a bad model or value leaves nothing behind. Construct before the folder is created.
class NewFolders {
 public:
  explicit NewFolders(const std::string& dir);
  ~NewFolders();  // on an exception: removes the empty folders this run created, deepest first
  NewFolders(const NewFolders&) = delete;
  NewFolders& operator=(const NewFolders&) = delete;

 private:
  std::vector<std::string> created_;  // the folders that did not exist, deepest first
  int exceptions_ = 0;
};

// ---- Shared option groups -------------------------------------------------------------------

// --threads (every command) and --quiet (every command that writes files).
struct CommonOptions {
  int threads = 0;
  bool quiet = false;
  void add(CLI::App& cmd, bool quietOption);
  // Validates --threads and sets the worker thread count.
  void apply() const;
};

// The model: a positional argument (anywhere on the line) and how it is loaded.
struct ModelOptions {
  std::string model;  // empty = the built-in monkey
  int triangles = 0;
  double unitScale = 0.0;
  std::vector<std::string> noFur;
  std::string directions;
  std::string subdivide = "auto";  // "auto" or levels 0 to 3
  void add(CLI::App& cmd);
  // Loads the model; warns (a warning: --quiet keeps it) when its size is implausible for an
  // animal.
  scene::Model load() const;
};

// The pose: --pose FILE, or --clip NAME|FILE at --time T (a still frame); for sequences --clip is
// the clip played and --time the clip time of frame 0.
struct PoseOptions {
  std::string posePath;
  std::string clip;
  double time = 0.0;
  CLI::Option* timeOption = nullptr;
  void add(CLI::App& cmd);
  // The still pose of a single-frame command: the pose file, the clip at --time, or the rest pose.
  anatomy::Pose stillPose(scene::Model& model) const;
  // What a sequence plays (clip, still pose, start time) into `playback`.
  void sequence(scene::Model& model, scene::PlaybackOptions& playback) const;
};

// The fur: a preset and overrides, by named option or by any preset field (--fur-set).
struct FurOptions {
  std::string preset;  // empty = the default preset
  double hairs = 0.0;
  std::string style;
  std::int64_t seed = 0;
  double undercoatShare = 0.0;
  double lengthScale = 0.0;
  double stiffness = 0.0;
  double hairWidth = 0.0;
  std::vector<std::string> settings;  // "path.to.field=JSON value"
  std::string groom;                  // a groom file; empty = the preset's
  CLI::Option* hairsOption = nullptr;
  CLI::Option* seedOption = nullptr;
  CLI::Option* shareOption = nullptr;
  CLI::Option* lengthOption = nullptr;
  CLI::Option* stiffnessOption = nullptr;
  CLI::Option* widthOption = nullptr;
  void add(CLI::App& cmd);
  // The preset with the overrides, validated; InputError naming the option. A named option and a
  // --fur-set that set the same field are refused.
  fur::FurParams resolve() const;
};

// Dynamic fur: --dynamics on|off, --frequency, --damping (one value or one per coat), --preroll.
struct DynamicsOptions {
  std::string mode = "off";
  std::vector<double> frequency;
  std::vector<double> damping;
  int preRoll = -1;
  CLI::Option* preRollOption = nullptr;
  void add(CLI::App& cmd, bool preRollOption);
  bool enabled() const { return mode == "on"; }
  // The spring parameters, validated; the spring options without --dynamics on are refused.
  fur::DynamicsParams resolve() const;
};

// Frames of a sequence: --frames A:B (default: the clip's whole duration) and --fps.
struct FrameOptions {
  std::string frames;
  double fps = 30.0;
  void add(CLI::App& cmd);
  void addFps(CLI::App& cmd);  // --fps alone (`pelage hair`: the frames simulated for dynamics)
  // The range for `clip` of `model` (-1: the still pose, frame 0).
  // With `quiet` false, a note on stderr (once) when frames lie past the clip's end, where it
  // loops (or holds its last pose); `startSeconds` is the clip time of frame 0 (--time).
  scene::FrameRange range(const scene::Model& model, int clip, double startSeconds = 0.0,
                          bool quiet = true) const;
  void validateFps() const;
};

// How frames are seen and drawn: size, samples, camera, hair source, shading, culling, skin.
struct ViewOptions {
  std::string size = "1280x720";
  int samples = -1;
  std::string camera = "three-quarter";
  bool follow = false;
  double fov = static_cast<double>(scene::kDefaultFovYDegrees);
  std::string hairSource = "gpu";
  std::string shading{scene::hairShadingName(scene::kDefaultHairShading)};
  bool lines = false;
  std::string transparency = "on";
  bool shadows = false;
  std::string selfShadowing = "on";
  bool noCulling = false;
  std::vector<float> skinColor;
  std::vector<std::string> background;  // "transparent", or R G B (sRGB, [0, 1])
  std::vector<float> light;             // the key light's azimuth and elevation (degrees)
  std::vector<float> lightColor;        // the key light's colour: I or R G B (linear)
  std::vector<float> ambient;           // the ambient light: I or R G B (linear)
  void add(CLI::App& cmd);
  int width() const;
  int height() const;
  scene::CameraPreset cameraPreset() const;
  scene::HairSource source() const;
  scene::HairShading hairShading() const;
  scene::HairWidth hairWidth() const;  // strands, or the paper's lines with --lines
  bool transparent() const { return transparency == "on"; }
  // --background: the colour (linear RGB; the default's when not given or transparent), and
  // whether frames get straight alpha with a transparent background.
  Eigen::Vector3f backgroundColor() const;
  bool transparentBackground() const;
  bool selfShadowed() const { return selfShadowing == "on"; }
  std::optional<Eigen::Vector3f> skin() const;
  // --light AZ EL, or the default place (scene/light.h).
  float lightAzimuth() const;
  float lightElevation() const;
  // --light-color and --ambient (one value: grey), or scene::Light's defaults (linear RGB).
  Eigen::Vector3f keyLightColor() const;
  Eigen::Vector3f ambientLight() const;
  // Parses and checks every value (size, samples, fov, names, colour).
  void validate() const;
};

// "WIDTHxHEIGHT" -> width, height; InputError naming `option` otherwise.
void parseSize(const std::string& text, const char* option, int& width, int& height);

// ---- Argument normalisation ------------------------------------------------------------------

// Makes the model argument position-independent: an option that takes several values (--no-fur,
// --fur-set, --frequency, --damping, --skin-color, --benchmark-hairs) stops at a value that names a
// model (the built-in monkey, or an existing file with a model extension), which is moved to just
// after the command's name. `args` excludes the program name.
std::vector<std::string> normalizeArguments(const std::vector<std::string>& args);

}  // namespace pelage::app
