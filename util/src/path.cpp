#include "pelage/util/path.h"

#include <filesystem>

namespace pelage {

std::string lowerCase(std::string_view text) {
  std::string s(text);
  for (char& c : s)
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  return s;
}

std::string lowerExtension(std::string_view path) {
  return lowerCase(std::filesystem::path(path).extension().string());
}

}  // namespace pelage
