#include "pelage/util/path.h"

#include <filesystem>

namespace pelage {

std::string lowerCase(std::string_view text) {
  std::string s(text);
  for (char& c : s)
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  return s;
}

bool globMatches(std::string_view pattern, std::string_view name) {
  const std::string p = lowerCase(pattern), s = lowerCase(name);
  // Greedy wildcard match with backtracking to the last '*'.
  std::size_t i = 0, j = 0, star = std::string::npos, mark = 0;
  while (j < s.size()) {
    if (i < p.size() && p[i] == '*') {
      star = i++;
      mark = j;
    } else if (i < p.size() && p[i] == s[j]) {
      ++i;
      ++j;
    } else if (star != std::string::npos) {
      i = star + 1;
      j = ++mark;
    } else {
      return false;
    }
  }
  while (i < p.size() && p[i] == '*') ++i;
  return i == p.size();
}

std::string lowerExtension(std::string_view path) {
  return lowerCase(std::filesystem::path(path).extension().string());
}

}  // namespace pelage
