// Files built into the pelage binary (models/*.json): the default creature and the fur presets.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace pelage::models {

// The text of built-in file `name` (e.g. "monkey.json", "presets/fig9.json"), if there is one.
std::optional<std::string_view> builtinFile(std::string_view name);
// Names of all built-in files.
std::vector<std::string> builtinFileNames();

namespace detail {
struct BuiltinFile {
  const char* name;
  const char* text;
};
extern const BuiltinFile kFiles[];
extern const std::size_t kFileCount;
}  // namespace detail

}  // namespace pelage::models
