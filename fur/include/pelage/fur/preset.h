// Fur preset files (JSON): every FurParams field, validated on load with errors that name the file,
// the field and the accepted range; unknown fields are rejected. Built-in presets live in
// models/presets/ (embedded in the binary): "default", and the paper's Figure 2 parameter sets
// "fig8" and "fig9" (Van Gelder & Wilhelms 1997). Format: see models/presets/README.md.
#pragma once

#include <string>
#include <vector>

#include "pelage/fur/fur_params.h"

namespace pelage::fur {

// The built-in preset used when none is named.
inline constexpr const char* kDefaultPreset = "default";

// Names of the built-in presets ("default", "fig8", "fig9").
std::vector<std::string> builtinPresetNames();

// Inheritance: a preset file or text states only what differs from the preset it stands on: its
// "base" (a built-in name or a file, relative to its own folder), else the built-in "default". The
// built-in presets stand on nothing (every field of FurParams' own values unless they name one).
// Each field given replaces the one below it, group and coat fields one by one; a coat states
// what differs from the base's coat ("hairs" and "density" replace each other). A base chain
// that loops, or deeper than 16, is an error.

// Parses preset JSON text; `source` names it in messages. Validates (validateFurParams).
FurParams parseFurPreset(const std::string& jsonText, const std::string& source);

// `base` with the preset fields of `jsonText` set on it (a "base" field there replaces `base`):
// what --fur-set and Python's keyword fields apply. Validates; `source` names it in messages.
FurParams applyFurPresetFields(const FurParams& base, const std::string& jsonText,
                               const std::string& source);

// Loads a preset by built-in name ("fig9") or by path ("my_fur.json").
FurParams loadFurPreset(const std::string& nameOrPath);

// The preset file text for `params`, every field resolved (round-trips through parseFurPreset).
std::string furPresetJson(const FurParams& params);

// Writes furPresetJson(params) to `path` atomically.
void saveFurPreset(const std::string& path, const FurParams& params);

}  // namespace pelage::fur
