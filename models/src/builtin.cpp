#include "pelage/models/builtin.h"

namespace pelage::models {

std::optional<std::string_view> builtinFile(std::string_view name) {
  for (std::size_t i = 0; i < detail::kFileCount; ++i)
    if (name == detail::kFiles[i].name) return std::string_view(detail::kFiles[i].text);
  return std::nullopt;
}

std::vector<std::string> builtinFileNames() {
  std::vector<std::string> out;
  for (std::size_t i = 0; i < detail::kFileCount; ++i) out.emplace_back(detail::kFiles[i].name);
  return out;
}

}  // namespace pelage::models
