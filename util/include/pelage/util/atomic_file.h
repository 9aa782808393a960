// Output files that are never left half-written: data goes to a temporary file in the same
// directory, which is renamed onto the final name only when complete (commit()). A failed write
// (disk full, read-only directory) throws InputError naming the file and the reason.
#pragma once

#include <cstdio>
#include <cstring>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <type_traits>

namespace pelage {

class AtomicFileWriter {
 public:
  // Opens `<dir>/.<name>.tmp-<pid>-<n>` for writing; throws InputError if that is impossible.
  explicit AtomicFileWriter(std::string path);
  ~AtomicFileWriter();
  AtomicFileWriter(const AtomicFileWriter&) = delete;
  AtomicFileWriter& operator=(const AtomicFileWriter&) = delete;

  // Appends bytes. Small writes (a binary exporter's values) are gathered into pieces of
  // kBufferBytes before they reach the file.
  void write(const void* data, std::size_t bytes) {
    if (bytes != 0 && bytes <= capacity_ - used_) {
      std::memcpy(buffer_.get() + used_, data, bytes);
      used_ += bytes;
      return;
    }
    writeThrough(data, bytes);
  }
  void write(std::string_view text) { write(text.data(), text.size()); }
  // Appends the bytes of `value`, a trivially copyable value (binary formats, little-endian here).
  template <class T>
  void put(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    write(&value, sizeof(T));
  }
  // Flushes, closes and renames onto the final path. Throws InputError on any failure.
  void commit();

  static constexpr std::size_t kBufferBytes = std::size_t{1} << 22;

  const std::string& path() const { return path_; }
  const std::string& tempPath() const { return tempPath_; }

 private:
  [[noreturn]] void failWith(const char* what, int err);
  void writeThrough(const void* data, std::size_t bytes);  // flushes the buffer, then writes
  void flushBuffer();
  std::string path_;
  std::string tempPath_;
  std::FILE* file_ = nullptr;
  std::unique_ptr<char[]> buffer_;  // kBufferBytes once anything is written; none after commit
  std::size_t capacity_ = 0, used_ = 0;
  bool committed_ = false;
};

// The whole content of a file; InputError naming it when it cannot be read.
std::string readTextFile(const std::string& path);

// Writes `content` to `path` atomically (see AtomicFileWriter).
void writeFileAtomically(const std::string& path, std::string_view content);

// Temporary files (an AtomicFileWriter's, an exporter's spools) registered here are removed when
// the process is stopped by SIGINT, SIGTERM, SIGHUP or SIGQUIT: the handler unlinks them, then the
// signal takes its default action. (SIGKILL cannot be caught: removeStaleTemporaries cleans up
// after such a run.) At most kMaxTemporaries at a time; more are simply not covered. Register a
// path before creating the file: a signal between creation and registration would leave it.
inline constexpr int kMaxTemporaries = 256;
void registerTemporary(const std::string& path);
void unregisterTemporary(const std::string& path);

// Removes the temporary files that stopped processes left in `dir`: names of the form
// ".<final>.<kind>-...-<pid>-<n>" (kind "tmp" or "spool") whose process no longer runs and whose
// final name satisfies `matches` (e.g. the frames of one range, so shards writing other frames
// into a shared directory are left alone). Returns how many were removed.
int removeStaleTemporaries(const std::string& dir,
                           const std::function<bool(const std::string& finalName)>& matches);

// Creates a directory and its parents; throws InputError naming it if that fails or it is not
// writable.
void ensureWritableDirectory(const std::string& dir);

}  // namespace pelage
