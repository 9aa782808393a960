#include "pelage/util/error.h"

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
