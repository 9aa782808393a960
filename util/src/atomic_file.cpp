#include "pelage/util/atomic_file.h"

#include <signal.h>
#include <sys/types.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <mutex>

#include "pelage/util/error.h"
#include "temporaries.h"

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

// The registered temporaries: fixed slots the signal handler reads without locks (async-signal-
// safe: it only reads the flags and paths and calls unlink).
constexpr std::size_t kPathBytes = 4096;
struct Slot {
  std::atomic<bool> used{false};
  char path[kPathBytes] = {};
};
Slot gSlots[kMaxTemporaries];
std::mutex gSlotMutex;  // registration only (never taken in the handler)

extern "C" void onFatalSignal(int sig) {
  detail::removeTemporariesAndDie(sig);
}

void installHandlers() {
  static const bool installed = [] {
    for (int sig : {SIGINT, SIGTERM, SIGHUP, SIGQUIT}) {
      struct sigaction old {};
      ::sigaction(sig, nullptr, &old);
      if (old.sa_handler != SIG_DFL) continue;  // the program handles (or ignores) it itself
      struct sigaction sa {};
      sa.sa_handler = onFatalSignal;
      sigemptyset(&sa.sa_mask);
      ::sigaction(sig, &sa, nullptr);
    }
    return true;
  }();
  (void)installed;
}

bool processRuns(long pid) {
  return pid > 0 && (::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM);
}
}  // namespace

void detail::unlinkRegisteredTemporaries() {
  for (Slot& s : gSlots)
    if (s.used.load(std::memory_order_acquire)) ::unlink(s.path);
}

void detail::removeTemporariesAndDie(int sig) {
  unlinkRegisteredTemporaries();
  ::signal(sig, SIG_DFL);
  ::raise(sig);
  // Inside a handler the signal is blocked: unblock it, and its default action ends the process.
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, sig);
  ::sigprocmask(SIG_UNBLOCK, &set, nullptr);
  ::_exit(128 + sig);
}

void registerTemporary(const std::string& path) {
  if (path.size() + 1 > kPathBytes) return;
  installHandlers();
  std::lock_guard<std::mutex> lock(gSlotMutex);
  for (Slot& s : gSlots)
    if (!s.used.load(std::memory_order_relaxed)) {
      std::memcpy(s.path, path.c_str(), path.size() + 1);
      s.used.store(true, std::memory_order_release);
      return;
    }
}

void unregisterTemporary(const std::string& path) {
  std::lock_guard<std::mutex> lock(gSlotMutex);
  for (Slot& s : gSlots)
    if (s.used.load(std::memory_order_relaxed) && path == s.path) {
      s.used.store(false, std::memory_order_release);
      return;
    }
}

int removeStaleTemporaries(const std::string& dir,
                           const std::function<bool(const std::string& finalName)>& matches) {
  int removed = 0;
  std::error_code ec;
  for (const fs::directory_entry& e : fs::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    if (name.size() < 2 || name[0] != '.') continue;
    std::size_t kind = std::string::npos;
    for (const char* k : {".tmp-", ".spool-"}) kind = std::min(kind, name.find(k, 1));
    if (kind == std::string::npos) continue;
    // ...-<pid>-<n>: the pid is the second number from the end.
    const std::size_t lastDash = name.rfind('-');
    const std::size_t pidDash = lastDash == std::string::npos || lastDash == 0
                                    ? std::string::npos
                                    : name.rfind('-', lastDash - 1);
    if (pidDash == std::string::npos || pidDash < kind) continue;
    const std::string pidText = name.substr(pidDash + 1, lastDash - pidDash - 1);
    if (pidText.empty() || pidText.find_first_not_of("0123456789") != std::string::npos) continue;
    const long pid = std::stol(pidText);
    if (pid == static_cast<long>(::getpid()) || processRuns(pid)) continue;  // still in use
    if (!matches(name.substr(1, kind - 1))) continue;
    std::error_code rec;
    if (fs::remove(e.path(), rec)) ++removed;
  }
  return removed;
}

AtomicFileWriter::AtomicFileWriter(std::string path) : path_(std::move(path)) {
  const fs::path p(path_);
  const fs::path dir = p.has_parent_path() ? p.parent_path() : fs::path(".");
  tempPath_ = (dir / ("." + p.filename().string() + ".tmp-" + std::to_string(::getpid()) + "-" +
                      std::to_string(tempCounter++)))
                  .string();
  registerTemporary(tempPath_);  // before it exists: see registerTemporary
  file_ = std::fopen(tempPath_.c_str(), "wb");
  if (!file_) {
    const int err = errno;
    unregisterTemporary(tempPath_);
    inputError(path_, ": cannot write (", reason(err), ")");
  }
  std::setvbuf(file_, nullptr, _IOFBF, 1 << 20);
}

AtomicFileWriter::~AtomicFileWriter() {
  if (file_) std::fclose(file_);
  if (!committed_) std::remove(tempPath_.c_str());
  unregisterTemporary(tempPath_);
}

void AtomicFileWriter::failWith(const char* what, int err) {
  if (file_) std::fclose(file_);
  file_ = nullptr;
  buffer_.reset();
  capacity_ = used_ = 0;
  std::remove(tempPath_.c_str());
  committed_ = true;  // nothing left to clean up
  inputError(path_, ": ", what, " failed (", reason(err), "); no file was written");
}

void AtomicFileWriter::flushBuffer() {
  if (used_ > 0 && std::fwrite(buffer_.get(), 1, used_, file_) != used_) failWith("write", errno);
  used_ = 0;
}

void AtomicFileWriter::writeThrough(const void* data, std::size_t bytes) {
  PELAGE_CHECK(file_ && !committed_, "write after commit");
  if (bytes == 0) return;
  if (!buffer_) {
    buffer_ = std::make_unique<char[]>(kBufferBytes);
    capacity_ = kBufferBytes;
  }
  flushBuffer();
  if (bytes < capacity_) {
    std::memcpy(buffer_.get(), data, bytes);
    used_ = bytes;
  } else if (std::fwrite(data, 1, bytes, file_) != bytes) {
    failWith("write", errno);
  }
}

void AtomicFileWriter::commit() {
  PELAGE_CHECK(file_ && !committed_, "double commit");
  flushBuffer();
  buffer_.reset();
  capacity_ = 0;
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

std::string readTextFile(const std::string& path) {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) inputError(path, ": cannot read (", reason(errno), ")");
  std::string text;
  char buf[1 << 16];
  std::size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, f)) > 0) text.append(buf, n);
  const bool failed = std::ferror(f) != 0;
  std::fclose(f);
  if (failed) inputError(path, ": read failed");
  return text;
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
