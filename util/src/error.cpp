#include "pelage/util/error.h"

#include <cstdio>
#include <filesystem>

namespace pelage {

void requireExistingFile(const std::string& path, const std::string& what) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec))
    throw MissingFileError(path + ": " + what + " does not exist");
}

}  // namespace pelage

namespace pelage::detail {

void checkFailed(const char* file, int line, const char* cond, const std::string& msg) {
  std::ostringstream os;
  os << "internal error at " << file << ":" << line << ": check failed: " << cond;
  if (!msg.empty()) os << " (" << msg << ")";
  throw InternalError(os.str());
}

}  // namespace pelage::detail

namespace pelage {

std::string excerpt(std::string_view text, std::size_t maxChars) {
  std::string out;
  std::size_t shown = 0;
  for (const char ch : text) {
    if (shown == maxChars) {
      out += "... (" + std::to_string(text.size()) + " bytes)";
      return out;
    }
    const auto c = static_cast<unsigned char>(ch);
    if (c < 0x20 || c == 0x7f) {  // (UTF-8 sequences stay as they are)
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02x", c);
      out += hex;
    } else {
      out += ch;
    }
    ++shown;
  }
  return out;
}

std::string shortenLongWords(std::string_view message) {
  std::string out;
  std::size_t i = 0;
  while (i < message.size()) {
    const auto blank = [&](std::size_t k) {
      return message[k] == ' ' || message[k] == '\n' || message[k] == '\t' || message[k] == '\r';
    };
    std::size_t j = i;
    while (j < message.size() && !blank(j)) ++j;
    out += j - i > kMaxQuotedChars ? excerpt(message.substr(i, j - i))
                                   : std::string(message.substr(i, j - i));
    while (j < message.size() && blank(j)) out += message[j++];
    i = j;
  }
  return out;
}

}  // namespace pelage
