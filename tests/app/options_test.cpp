// One command line that behaves the same everywhere (app/options.h): every shared option is present
// in every command where it makes sense, with one help text (so one default and one range), the
// same message for the same bad value, defaults in the help equal to the libraries' own; options
// that take several values stop at the model; every usage error exits 2 with "pelage: error:".
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "pelage/fur/dynamics.h"
#include "pelage/render/render_sequence.h"
#include "pelage/scene/camera.h"
#include "pelage/scene/playback.h"
#include "pelage/viewer/viewer_app.h"
#include "support/files.h"

namespace pelage {
namespace {

using test::runPelage;
using test::TempDir;

const std::vector<std::string> kAll = {"info", "skin",   "hair",   "bench",
                                       "view", "render", "export", "analyze"};
const std::vector<std::string> kPosed = {"skin",   "hair",   "bench",  "view",
                                         "render", "export", "analyze"};
const std::vector<std::string> kFurred = {"hair", "bench", "view", "render", "export", "analyze"};
const std::vector<std::string> kDynamic = {"hair", "view", "render", "export", "analyze"};
const std::vector<std::string> kPreRolled = {"hair", "render", "export", "analyze"};
const std::vector<std::string> kSequences = {"render", "export", "analyze"};
const std::vector<std::string> kFps = {"hair", "render", "export", "analyze"};
const std::vector<std::string> kViewed = {"view", "render"};
const std::vector<std::string> kWriting = {"skin", "hair", "render", "export", "analyze"};

// Which commands take each shared option.
const std::map<std::string, std::vector<std::string>>& sharedOptions() {
  static const std::map<std::string, std::vector<std::string>> m = {{"--threads", kAll},
                                                                    {"--triangles", kAll},
                                                                    {"--unit-scale", kAll},
                                                                    {"--no-fur", kAll},
                                                                    {"--directions", kAll},
                                                                    {"--pose", kPosed},
                                                                    {"--clip", kPosed},
                                                                    {"--time", kPosed},
                                                                    {"--fur", kFurred},
                                                                    {"--hairs", kFurred},
                                                                    {"--style", kFurred},
                                                                    {"--seed", kFurred},
                                                                    {"--undercoat-share", kFurred},
                                                                    {"--length-scale", kFurred},
                                                                    {"--stiffness", kFurred},
                                                                    {"--hair-width", kFurred},
                                                                    {"--fur-set", kFurred},
                                                                    {"--dynamics", kDynamic},
                                                                    {"--frequency", kDynamic},
                                                                    {"--damping", kDynamic},
                                                                    {"--preroll", kPreRolled},
                                                                    {"--frames", kSequences},
                                                                    {"--fps", kFps},
                                                                    {"--size", kViewed},
                                                                    {"--samples", kViewed},
                                                                    {"--camera", kViewed},
                                                                    {"--follow", kViewed},
                                                                    {"--fov", kViewed},
                                                                    {"--hair-source", kViewed},
                                                                    {"--shading", kViewed},
                                                                    {"--lines", kViewed},
                                                                    {"--transparency", kViewed},
                                                                    {"--shadows", kViewed},
                                                                    {"--no-culling", kViewed},
                                                                    {"--skin-color", kViewed},
                                                                    {"--quiet", kWriting}};
  return m;
}

// The option's help line of `pelage CMD --help`, from the option name on ("" if absent).
std::string helpLine(const std::string& help, const std::string& option) {
  std::istringstream in(help);
  for (std::string line; std::getline(in, line);) {
    std::size_t at = line.find_first_not_of(' ');
    if (at == std::string::npos || line.compare(at, 2, "--") != 0) continue;
    const std::size_t end = line.find_first_of(" ,", at);
    if (line.substr(at, end - at) == option) return line.substr(at);
  }
  return "";
}

std::string helpOf(const std::string& command) {
  const test::RunResult r = runPelage(command + " --help");
  EXPECT_EQ(r.exitCode, 0) << r.output;
  return r.output;
}

TEST(SharedOptions, EveryCommandHasItsSharedOptionsWithOneHelpText) {
  std::map<std::string, std::string> help;
  for (const std::string& c : kAll) help[c] = helpOf(c);
  for (const auto& [option, commands] : sharedOptions()) {
    const std::string first = helpLine(help[commands.front()], option);
    ASSERT_FALSE(first.empty()) << option << " missing from " << commands.front();
    for (const std::string& c : commands) {
      SCOPED_TRACE(option + " in " + c);
      // The same line: the same value type, help text, default and range.
      EXPECT_EQ(helpLine(help[c], option), first);
    }
  }
}

// The help's "(default X)" for an option.
std::string helpDefault(const std::string& command, const std::string& option) {
  const std::string line = helpLine(helpOf(command), option);
  const std::size_t at = line.find("(default ");
  if (at == std::string::npos) return "";
  const std::size_t end = line.find_first_of(";)", at);
  return line.substr(at + 9, end - at - 9);
}

std::string g(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

TEST(SharedOptions, HelpDefaultsAreTheLibrariesDefaults) {
  const fur::CoatDynamics d;
  EXPECT_EQ(helpDefault("render", "--frequency"), g(static_cast<double>(d.frequencyHz)));
  EXPECT_EQ(helpDefault("render", "--damping"), g(static_cast<double>(d.dampingRatio)));
  const scene::PlaybackOptions playback;
  EXPECT_EQ(helpDefault("export", "--fps"), g(playback.clock.fps));
  EXPECT_EQ(helpDefault("render", "--fov"), g(static_cast<double>(scene::kDefaultFovYDegrees)));
  const render::SequenceOptions sequence;
  const viewer::ViewerOptions viewer;
  EXPECT_EQ(helpDefault("render", "--size"),
            std::to_string(sequence.width) + "x" + std::to_string(sequence.height));
  EXPECT_EQ(helpDefault("view", "--size"),
            std::to_string(viewer.width) + "x" + std::to_string(viewer.height));
  EXPECT_EQ(helpDefault("render", "--samples"), std::to_string(sequence.samples));
  EXPECT_EQ(helpDefault("render", "--camera"), scene::cameraPresetName(sequence.camera.preset));
  EXPECT_EQ(helpDefault("render", "--hair-source"),
            scene::hairSourceName(sequence.playback.hairSource));
  EXPECT_EQ(helpDefault("render", "--shading"), scene::hairShadingName(sequence.look.hairShading));
}

// What a command needs beyond the option under test, on the small critter.
std::string requiredArgs(const std::string& command, const TempDir& dir) {
  if (command == "skin") return " --out " + dir.file("s.obj");
  if (command == "hair") return " --out " + dir.file("h.ply");
  if (command == "export") return " --format ply --out " + dir.file("e");
  if (command == "render") return " --out " + dir.file("r");
  if (command == "analyze") return " --out " + dir.file("a.csv");
  if (command == "view") return " --headless";
  return "";
}

struct BadValue {
  std::string option;  // the shared option (its commands from sharedOptions())
  std::string args;
  std::string expect;
};

TEST(SharedOptions, TheSameBadValueGivesTheSameMessageAndStatus2Everywhere) {
  TempDir dir;
  const std::string critter = PELAGE_TEST_CRITTER;
  const std::vector<BadValue> cases = {
      {"--threads", "--threads 2000", "--threads 2000 is out of range [0, 1024]"},
      {"--triangles", "--triangles 5", "--triangles 5 is out of range [2000, 2000000]"},
      {"--unit-scale", "--unit-scale -1", "--unit-scale -1 is out of range (0, 1000000]"},
      {"--no-fur", "--no-fur eyes", "apply to glTF models (.gltf/.glb) only"},
      {"--time", "--time -1", "--time -1 is out of range [0, 1000000] seconds"},
      {"--hairs", "--hairs -5", "hairs = -5 is out of range"},
      {"--style", "--style fuzzy", "unknown hair style 'fuzzy'"},
      {"--seed", "--seed -1", "--seed -1 is out of range [0, 2^53]"},
      {"--stiffness", "--stiffness 3", "stiffness = 3 is out of range [0, 1]"},
      {"--hair-width", "--hair-width 0", "--hair-width 0 mm is out of range [0.001, 20]"},
      {"--fur-set", "--fur-set nothing", "--fur-set 'nothing' is not FIELD=VALUE"},
      {"--fur-set", "--hairs 5000 --fur-set hairs=1000", "--hairs and --fur-set hairs=1000"},
      {"--frequency", "--dynamics on --frequency 0", "dynamics frequency 0 Hz is out of range"},
      {"--frequency", "--frequency 5", "--frequency needs --dynamics on"},
      {"--damping", "--damping 0.5", "--damping needs --dynamics on"},
      {"--preroll", "--dynamics on --preroll -5", "--preroll -5 is out of range"},
      {"--frames", "--frames 5:2", "--frames 5:2 is out of range"},
      {"--fps", "--fps 0", "--fps 0 is out of range [1, 1000]"},
      {"--size", "--size 8x8", "--size 8x8 is out of range [16, 16384] per side"},
      {"--samples", "--samples 99", "--samples 99 is out of range [-1, 64]"},
      {"--camera", "--camera overhead", "unknown camera preset 'overhead'"},
      {"--fov", "--fov 0", "--fov 0 is out of range (1, 179) degrees"},
      {"--hair-source", "--hair-source tpu", "--hair-source 'tpu' (accepted: gpu, cpu)"},
      {"--shading", "--shading flat", "unknown hair shading 'flat'"},
      {"--skin-color", "--skin-color 2 0 0", "--skin-color R = 2 is out of range [0, 1]"},
  };
  for (const BadValue& c : cases) {
    std::string first;
    for (const std::string& command : sharedOptions().at(c.option)) {
      SCOPED_TRACE(command + " " + c.args);
      const test::RunResult r =
          runPelage(command + " " + critter + " " + c.args + requiredArgs(command, dir));
      EXPECT_EQ(r.exitCode, 2) << r.output;
      const std::size_t at = r.output.find("pelage: error: ");
      ASSERT_NE(at, std::string::npos) << r.output;
      const std::string message = r.output.substr(at, r.output.find('\n', at) - at);
      EXPECT_NE(message.find(c.expect), std::string::npos) << message;
      if (first.empty()) first = message;
      EXPECT_EQ(message, first);
    }
  }
}

TEST(SharedOptions, ThreadsAreAcceptedBeforeAndAfterTheCommand) {
  const std::string critter = PELAGE_TEST_CRITTER;
  EXPECT_EQ(runPelage("--threads 1 info " + critter).exitCode, 0);
  EXPECT_EQ(runPelage("info " + critter + " --threads 1").exitCode, 0);
}

// A clip file for the critter (it has none of its own).
std::string critterClip(const TempDir& dir) {
  const std::string path = dir.file("nod.json");
  test::writeText(path, R"({ "name": "nod", "duration": 1.0, "channels": [
    { "segment": "head", "path": "rotate", "keys": [
      { "time": 0, "axis": [0, 1, 0], "degrees": 0 },
      { "time": 0.5, "axis": [0, 1, 0], "degrees": 30 },
      { "time": 1, "axis": [0, 1, 0], "degrees": 0 } ] } ] })");
  return path;
}

TEST(SharedOptions, OptionsWithSeveralValuesStopAtTheModel) {
  TempDir dir;
  const std::string critter = PELAGE_TEST_CRITTER;
  const std::string clip = critterClip(dir);
  struct Case {
    std::string line;
    std::string expect;  // in the output
  };
  std::vector<Case> cases = {
      {"hair --hairs 300 --fur-set overcoat.stiffness=0.7 seed=3 " + critter + " --out " +
           dir.file("a.ply"),
       "on critter"},
      {"hair --clip " + clip + " --dynamics on --frequency 5 6 " + critter + " --out " +
           dir.file("b.ply"),
       "dynamic fur: frame 0 of clip nod"},
      {"hair --clip " + clip + " --dynamics on --damping 0.3 " + critter + " --out " +
           dir.file("c.ply"),
       "on critter"},
      {"render --frames 0 --size 64x48 --skin-color 0.2 0.3 0.4 " + critter + " --out " +
           dir.file("r"),
       "render: critter"},
      {"view --headless --size 64x48 --benchmark --benchmark-frames 1 --benchmark-hairs 100 200 " +
           critter,
       "model critter"},
  };
  const std::string husky = PELAGE_SHARED_MODELS_DIR "/Husky/Husky.gltf";
  if (std::filesystem::exists(husky))
    cases.push_back({"info --no-fur Material.002 Material.003 " + husky, "Material.002 (no fur)"});
  else
    std::printf("note: %s is absent; --no-fur before a glTF model is not tried\n", husky.c_str());
  for (const Case& c : cases) {
    SCOPED_TRACE(c.line);
    const test::RunResult r = runPelage(c.line);
    EXPECT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find(c.expect), std::string::npos) << r.output;
  }
}

TEST(SharedOptions, UsageErrorsExitTwoWithThePrefix) {
  TempDir dir;
  const std::string critter = PELAGE_TEST_CRITTER;
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"", "A subcommand is required"},
      {"comb " + critter, "unknown command 'comb' (commands: info, skin, hair, groom, bench"},
      {"hair " + critter, "--out is required"},
      {"render " + critter + " --out " + dir.file("r") + " --colour red", "--colour"},
      {"hair " + critter + " --hairs lots --out " + dir.file("h.ply"), "lots"},
      {"export " + critter + " --format ply", "--out is required"},
      {"analyze " + critter + " --out " + dir.file("a.csv") + " --groups limbs", "limbs"},
      {"info " + critter + " " + critter, critter},
      {"hair " + critter + " --no-fur eyes --out " + dir.file("h.ply"), "glTF models"},
      {"view --headless " + critter + " --screenshot " + dir.file("s.bmp"), ".png or .jpg"},
      {"render " + critter + " --out " + dir.file("frame.png"), "names a file; --out is the dir"},
  };
  for (const auto& [args, expect] : cases) {
    SCOPED_TRACE(args);
    const test::RunResult r = runPelage(args);
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_EQ(r.output.rfind("pelage: error: ", 0), 0u) << r.output;
    EXPECT_NE(r.output.find(expect), std::string::npos) << r.output;
  }
}

TEST(SharedOptions, QuietPrintsNothingOnSuccess) {
  TempDir dir;
  const std::string critter = PELAGE_TEST_CRITTER;
  for (const std::string& line :
       {"skin " + critter + " --out " + dir.file("s.obj"),
        "hair " + critter + " --hairs 300 --out " + dir.file("h.ply"),
        "export " + critter + " --hairs 300 --format ply --out " + dir.file("e"),
        "render " + critter + " --hairs 300 --size 64x48 --out " + dir.file("r"),
        "analyze " + critter + " --hairs 300 --out " + dir.file("a.csv")}) {
    SCOPED_TRACE(line);
    const test::RunResult r = runPelage(line + " --quiet");
    EXPECT_EQ(r.exitCode, 0) << r.output;
    EXPECT_EQ(r.output, "");
  }
}

}  // namespace
}  // namespace pelage
