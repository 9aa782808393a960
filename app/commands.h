// The pelage command line: one file per subcommand, each adding itself to the CLI11 app.
#pragma once

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

#include "pelage/anatomy/pose.h"
#include "pelage/fur/dynamics.h"
#include "pelage/fur/fur_params.h"
#include "pelage/fur/roots.h"
#include "pelage/scene/dynamic_fur.h"
#include "pelage/scene/model.h"
#include "pelage/skin/deform.h"

namespace pelage::app {

// Options shared by the subcommands that load a model.
struct ModelArgs {
  std::string model;  // empty = built-in monkey
  int triangles = 0;
  // glTF only: metres per file unit (0 = detect), no-fur region patterns, direction side file.
  double unitScale = 0.0;
  std::vector<std::string> noFur;
  std::string directions;
  void add(CLI::App& cmd);
  scene::Model load() const;
};

// Options that choose the creature's pose: a pose file, or a clip (the model's, by name, or a clip
// .json file) sampled at a time. Neither: the rest pose.
struct PoseArgs {
  std::string posePath;
  std::string clip;
  double time = 0.0;
  CLI::Option* timeOpt = nullptr;
  void add(CLI::App& cmd);
  anatomy::Pose resolve(scene::Model& model) const;
};

// Options choosing the fur: a preset (built-in name or file) and overrides (cmd_hair.cpp).
struct FurArgs {
  std::string preset;  // empty = the default preset
  double hairs = 0.0;
  std::string style;
  std::int64_t seed = 0;
  double undercoatShare = 0.0;
  double lengthScale = 0.0;
  double stiffness = 0.0;
  // The override options, to tell "given" from "absent".
  CLI::Option* hairsOpt = nullptr;
  CLI::Option* seedOpt = nullptr;
  CLI::Option* shareOpt = nullptr;
  CLI::Option* lengthOpt = nullptr;
  CLI::Option* stiffnessOpt = nullptr;
  void add(CLI::App& cmd);
  fur::FurParams resolve() const;  // validated; InputError naming the option on bad values
};

void addInfoCommand(CLI::App& app);
void addSkinCommand(CLI::App& app);
void addHairCommand(CLI::App& app);
void addBenchCommand(CLI::App& app);
// `pelage view` (only when built with PELAGE_BUILD_VIEWER).
void addViewCommand(CLI::App& app);

// Fur dynamics options (issue 7; cmd_analyze.cpp): --dynamics on|off, --frequency, --damping
// (one value for both coats or two) and, where the command has no frame clock of its own, --fps;
// --preroll where frame ranges are rendered.
struct DynamicsArgs {
  std::string mode = "off";
  std::vector<double> frequency;
  std::vector<double> damping;
  double fps = 30.0;
  int preRoll = -1;  // -1: from the clip's start
  void add(CLI::App& cmd, bool fpsOption = true, bool preRollOption = true);
  bool enabled() const;
  fur::DynamicsParams resolve() const;  // validated; InputError naming the option
  scene::DynamicsClock clock() const;
};
// `pelage analyze` (cmd_analyze.cpp).
void addAnalyzeCommand(CLI::App& app);

// Any fur parameter by its preset-file path, e.g. `--fur-set overcoat.stiffness=0.6` (repeatable;
// cmd_export.cpp). Used by `pelage render` and `pelage export`.
struct FurSettings {
  std::vector<std::string> settings;  // "path.to.field=JSON value"
  void add(CLI::App& cmd);
  // `params` with the settings applied, validated (InputError naming the setting's field).
  fur::FurParams apply(const fur::FurParams& params) const;
};

// The clip and frame range of `pelage render` and `pelage export`: --clip, --frames FIRST:LAST,
// --fps (cmd_export.cpp).
struct ClipFramesArgs {
  std::string clip;
  std::string frames = "0:0";
  double fps = 30.0;
  void add(CLI::App& cmd);
};

// `pelage render` (only with PELAGE_BUILD_VIEWER) and `pelage export` (cmd_render.cpp,
// cmd_export.cpp).
void addRenderCommand(CLI::App& app);
void addExportCommand(CLI::App& app);

}  // namespace pelage::app
