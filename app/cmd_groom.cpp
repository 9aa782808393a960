// `pelage groom MODEL --strokes FILE [--groom IN] --out GROOM`: grooming strokes
// (fur/groom_strokes.h) applied without a display to the fur's per-vertex groom (the --groom file,
// or the preset's, with the preset's regions), written as a groom file that every fur command reads
// with --groom.
#include <cstdio>
#include <memory>
#include <string>

#include "commands.h"
#include "options.h"
#include "pelage/fur/groom.h"
#include "pelage/fur/groom_strokes.h"
#include "pelage/scene/groom_editor.h"
#include "pelage/util/error.h"
#include "pelage/util/path.h"

namespace pelage::app {

void addGroomCommand(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "groom",
      "Apply grooming strokes (length, density, colour brushes) to a fur's per-vertex "
      "groom and write it as a groom file");
  auto model = std::make_shared<ModelOptions>();
  auto furArgs = std::make_shared<FurOptions>();
  auto common = std::make_shared<CommonOptions>();
  auto strokes = std::make_shared<std::string>();
  auto out = std::make_shared<std::string>();
  model->add(*cmd);
  furArgs->add(*cmd);
  cmd->add_option("--strokes", *strokes,
                  "Strokes file (JSON: {\"strokes\": [{\"tool\", \"points\", \"radius\", "
                  "\"strength\", ...}]}, points in the model's rest pose, metres)")
      ->required();
  cmd->add_option("--out", *out, "Output groom file (.json)")->required();
  common->add(*cmd, true);
  cmd->callback([=] {
    if (lowerExtension(*out) != ".json")
      inputError("--out ", *out, ": a groom file is JSON; the file must end in .json");
    // Options and strokes first: bad input fails before the model is built.
    const fur::FurParams params = furArgs->resolve();
    const std::vector<fur::GroomStroke> list = fur::readGroomStrokes(*strokes);
    const scene::Model m = model->load();
    fur::VertexGroom groom = scene::startingGroom(m, params, "fur '" + params.name + "'");
    const fur::VertexGroom before = groom;
    fur::applyGroomStrokes(m.skin, list, groom);
    fur::writeGroomFile(*out, m.skin, groom);
    if (common->quiet) return;
    // Vertices whose value the strokes changed (an array the groom lacked stood at `none`).
    const auto changed = [](const auto& after, const auto& was, const auto& none) {
      long long n = 0;
      for (std::size_t i = 0; i < after.size(); ++i) n += after[i] != (was.empty() ? none : was[i]);
      return n;
    };
    std::printf(
        "%s: %zu stroke(s) on %s (%d vertices): length changed at %lld vertices, density "
        "at %lld, tint at %lld, comb at %lld, clump at %lld\n",
        out->c_str(), list.size(), m.name.c_str(), m.skin.numVertices(),
        changed(groom.length, before.length, 0.0f), changed(groom.density, before.density, 1.0f),
        changed(groom.tint, before.tint, Eigen::Vector3f(Eigen::Vector3f::Ones())),
        changed(groom.comb, before.comb, Eigen::Vector3f(Eigen::Vector3f::Zero())),
        changed(groom.clump, before.clump, 1.0f));
  });
}

}  // namespace pelage::app
