#include "pelage/util/atomic_file.h"

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>

#include "pelage/util/error.h"

namespace pelage {
namespace fs = std::filesystem;

namespace {
std::string reason(int err) {
  if (err == ENOSPC) return "no space left on device (disk full)";
  if (err == EDQUOT) return "disk quota exceeded";
  if (err == EROFS) return "read-only file system";
  if (err == EACCES || err == EPERM) return "permission denied";
  if (err == ENOENT) return "directory does not exist";
  return std::strerror(err);
}
std::atomic<unsigned> tempCounter{0};
}  // namespace

AtomicFileWriter::AtomicFileWriter(std::string path) : path_(std::move(path)) {
  const fs::path p(path_);
  const fs::path dir = p.has_parent_path() ? p.parent_path() : fs::path(".");
  tempPath_ = (dir / ("." + p.filename().string() + ".tmp-" + std::to_string(::getpid()) + "-" +
                      std::to_string(tempCounter++)))
                  .string();
  file_ = std::fopen(tempPath_.c_str(), "wb");
  if (!file_) {
    const int err = errno;
    inputError(path_, ": cannot write (", reason(err), ")");
  }
  std::setvbuf(file_, nullptr, _IOFBF, 1 << 20);
}

AtomicFileWriter::~AtomicFileWriter() {
  if (file_) std::fclose(file_);
  if (!committed_) std::remove(tempPath_.c_str());
}

void AtomicFileWriter::failWith(const char* what, int err) {
  if (file_) std::fclose(file_);
  file_ = nullptr;
  std::remove(tempPath_.c_str());
  committed_ = true;  // nothing left to clean up
  inputError(path_, ": ", what, " failed (", reason(err), "); no file was written");
}

void AtomicFileWriter::write(const void* data, std::size_t bytes) {
  PELAGE_CHECK(file_ && !committed_, "write after commit");
  if (bytes == 0) return;
  if (std::fwrite(data, 1, bytes, file_) != bytes) failWith("write", errno);
}

void AtomicFileWriter::commit() {
  PELAGE_CHECK(file_ && !committed_, "double commit");
  if (std::fflush(file_) != 0) failWith("write", errno);
  if (std::ferror(file_)) failWith("write", errno ? errno : EIO);
  std::FILE* f = file_;
  file_ = nullptr;
  if (std::fclose(f) != 0) {
    const int err = errno;
    std::remove(tempPath_.c_str());
    committed_ = true;
    inputError(path_, ": close failed (", reason(err), "); no file was written");
  }
  if (std::rename(tempPath_.c_str(), path_.c_str()) != 0) {
    const int err = errno;
    std::remove(tempPath_.c_str());
    committed_ = true;
    inputError(path_, ": rename from temporary file failed (", reason(err), ")");
  }
  committed_ = true;
}

void writeFileAtomically(const std::string& path, std::string_view content) {
  AtomicFileWriter w(path);
  w.write(content);
  w.commit();
}

void ensureWritableDirectory(const std::string& dir) {
  std::error_code ec;
  if (!fs::exists(dir, ec)) {
    fs::create_directories(dir, ec);
    if (ec) inputError(dir, ": cannot create output directory (", ec.message(), ")");
  } else if (!fs::is_directory(dir, ec)) {
    inputError(dir, ": exists and is not a directory");
  }
  if (::access(dir.c_str(), W_OK) != 0) {
    inputError(dir, ": output directory is not writable (", reason(errno), ")");
  }
}

}  // namespace pelage
