// Output files that are never left half-written: data goes to a temporary file in the same
// directory, which is renamed onto the final name only when complete (commit()). A failed write
// (disk full, read-only directory) throws InputError naming the file and the reason.
#pragma once

#include <cstdio>
#include <string>
#include <string_view>

namespace pelage {

class AtomicFileWriter {
 public:
  // Opens `<dir>/.<name>.tmp-<pid>-<n>` for writing; throws InputError if that is impossible.
  explicit AtomicFileWriter(std::string path);
  ~AtomicFileWriter();
  AtomicFileWriter(const AtomicFileWriter&) = delete;
  AtomicFileWriter& operator=(const AtomicFileWriter&) = delete;

  void write(const void* data, std::size_t bytes);
  void write(std::string_view text) { write(text.data(), text.size()); }
  // Flushes, closes and renames onto the final path. Throws InputError on any failure.
  void commit();

  const std::string& path() const { return path_; }
  const std::string& tempPath() const { return tempPath_; }

 private:
  [[noreturn]] void failWith(const char* what, int err);
  std::string path_;
  std::string tempPath_;
  std::FILE* file_ = nullptr;
  bool committed_ = false;
};

// Writes `content` to `path` atomically (see AtomicFileWriter).
void writeFileAtomically(const std::string& path, std::string_view content);

// Creates a directory and its parents; throws InputError naming it if that fails or it is not
// writable.
void ensureWritableDirectory(const std::string& dir);

}  // namespace pelage
