// Encoding frames to a video by piping raw RGBA to the ffmpeg program (run as a program, found on
// PATH): H.264 .mp4 or .gif. The output appears under its name only when ffmpeg succeeded.
#include "pelage/render/video_encoder.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string_view>

#include "pelage/util/atomic_file.h"
#include "pelage/util/error.h"

extern char** environ;

namespace pelage::render {
namespace fs = std::filesystem;

std::string findOnPath(const std::string& program) {
  if (program.find('/') != std::string::npos)
    return ::access(program.c_str(), X_OK) == 0 ? program : "";
  const char* env = std::getenv("PATH");
  if (!env) return "";
  std::string_view rest(env);
  while (true) {
    const std::size_t colon = rest.find(':');
    const std::string dir(rest.substr(0, colon));
    const std::string candidate = (dir.empty() ? std::string(".") : dir) + "/" + program;
    struct stat st {};
    if (::stat(candidate.c_str(), &st) == 0 && S_ISREG(st.st_mode) &&
        ::access(candidate.c_str(), X_OK) == 0)
      return candidate;
    if (colon == std::string_view::npos) return "";
    rest.remove_prefix(colon + 1);
  }
}

namespace {
// The last lines of a log file (ffmpeg's error messages).
std::string tailOf(const std::string& path, std::size_t bytes = 1500) {
  std::ifstream in(path, std::ios::binary);
  std::string s((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (s.size() > bytes) s = "..." + s.substr(s.size() - bytes);
  while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
  return s;
}
std::atomic<unsigned> videoCounter{0};
constexpr const char* kFfmpegLogName = "pelage-ffmpeg.log";
}  // namespace

VideoEncoder::VideoEncoder(const std::string& path, int width, int height, double fps)
    : path_(path), width_(width), height_(height) {
  const fs::path p(path);
  const std::string ext = p.extension().string();
  if (ext != ".mp4" && ext != ".gif")
    fieldError("video", path, ": the file must end in .mp4 or .gif");
  const std::string ffmpeg = findOnPath("ffmpeg");
  if (ffmpeg.empty())
    fieldError("video", path,
               " needs the ffmpeg program, which is not on PATH (Debian: apt-get install ffmpeg)");
  const fs::path dir = p.has_parent_path() ? p.parent_path() : fs::path(".");
  if (std::error_code ec; !fs::is_directory(dir, ec))
    fieldError("video", path, ": the directory ", dir.string(), " does not exist");
  if (::access(dir.c_str(), W_OK) != 0)
    fieldError("video", path, ": cannot write (permission denied)");
  // The temporary video and ffmpeg's log are named as util/atomic_file.h names temporaries
  // (".FINAL.tmp-PID-N"): the signal handlers remove them, and leftovers of a killed run (SIGKILL)
  // are removed here, by the next run for the same video.
  const std::string tag = std::to_string(::getpid()) + "-" + std::to_string(videoCounter++);
  const std::string name = p.filename().string();
  const fs::path logDir = fs::temp_directory_path();
  removedTemporaries_ =
      removeStaleTemporaries(dir.string(), [&](const std::string& f) { return f == name; }) +
      removeStaleTemporaries(logDir.string(),
                             [](const std::string& f) { return f == kFfmpegLogName; });
  tempPath_ = (dir / ("." + name + ".tmp-" + tag)).string();
  logPath_ = (logDir / ("." + std::string(kFfmpegLogName) + ".tmp-" + tag)).string();
  registerTemporary(tempPath_);
  registerTemporary(logPath_);
  // The file ffmpeg will write, made now: a place that cannot be written (/proc, a full disk's
  // quota) fails here, before the first frame is rendered, not when ffmpeg first writes.
  const int probe = ::open(tempPath_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (probe < 0) {
    const int err = errno;
    forgetTemporaries();
    fieldError("video", path, ": cannot write (", std::strerror(err), ")");
  }
  ::close(probe);

  char size[32], rate[32];
  std::snprintf(size, sizeof size, "%dx%d", width, height);
  std::snprintf(rate, sizeof rate, "%.6g", fps);
  std::vector<std::string> args = {
      ffmpeg,     "-nostdin", "-hide_banner", "-loglevel", "error",      "-y", "-f", "rawvideo",
      "-pix_fmt", "rgba",     "-s",           size,        "-framerate", rate, "-i", "-"};
  if (ext == ".mp4") {
    // H.264 needs even sizes in yuv420p: pad by one pixel where needed.
    for (const char* a :
         {"-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2", "-c:v", "libx264", "-preset", "fast", "-crf",
          "18", "-pix_fmt", "yuv420p", "-movflags", "+faststart", "-f", "mp4"})
      args.emplace_back(a);
  } else {
    // One palette per frame: no buffering of the whole clip (memory stays bounded).
    for (const char* a :
         {"-vf", "split[a][b];[a]palettegen=stats_mode=single[p];[b][p]paletteuse=new=1", "-loop",
          "0", "-f", "gif"})
      args.emplace_back(a);
  }
  args.push_back(tempPath_);

  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0)
    fieldError("video", ": cannot create a pipe to ffmpeg (", std::strerror(errno), ")");
  const int log = ::open(logPath_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  // ffmpeg in a process group of its own: a terminal's Ctrl-C reaches pelage only, which then
  // stops ffmpeg itself (rather than ffmpeg closing the pipe under a frame being written).
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETPGROUP);
  posix_spawnattr_setpgroup(&attr, 0);
  posix_spawn_file_actions_adddup2(&fa, fds[0], 0);
  if (log >= 0) {
    posix_spawn_file_actions_adddup2(&fa, log, 1);
    posix_spawn_file_actions_adddup2(&fa, log, 2);
  }
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = -1;
  const int rc = ::posix_spawn(&pid, ffmpeg.c_str(), &fa, &attr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  posix_spawnattr_destroy(&attr);
  ::close(fds[0]);
  if (log >= 0) ::close(log);
  if (rc != 0) {
    ::close(fds[1]);
    forgetTemporaries();
    fieldError("video", ": cannot start ", ffmpeg, " (", std::strerror(rc), ")");
  }
  pid_ = pid;
  pipe_ = fds[1];
}

VideoEncoder::~VideoEncoder() {
  if (!done_) stop();
  forgetTemporaries();
}

void VideoEncoder::forgetTemporaries() {
  std::remove(logPath_.c_str());
  unregisterTemporary(tempPath_);
  unregisterTemporary(logPath_);
}

void VideoEncoder::stop() {
  if (pipe_ >= 0) ::close(pipe_);
  pipe_ = -1;
  if (pid_ > 0) {
    ::kill(pid_, SIGKILL);
    int status = 0;
    ::waitpid(pid_, &status, 0);
    pid_ = -1;
  }
  std::remove(tempPath_.c_str());
  done_ = true;
}

void VideoEncoder::fail(const std::string& what) {
  const std::string log = tailOf(logPath_);
  stop();
  fieldError("video", path_, ": ", what, log.empty() ? std::string() : "; ffmpeg said:\n" + log);
}

void VideoEncoder::addFrame(const Image& image) {
  PELAGE_CHECK(!done_ && pipe_ >= 0, "VideoEncoder::addFrame after finish");
  PELAGE_CHECK(image.width == width_ && image.height == height_, "frame ", image.width, "x",
               image.height);
  // A write to a pipe whose reader died raises SIGPIPE: ignore it here and report EPIPE instead.
  struct sigaction ignore {
  }, old{};
  ignore.sa_handler = SIG_IGN;
  sigemptyset(&ignore.sa_mask);
  ::sigaction(SIGPIPE, &ignore, &old);
  const auto* p = image.rgba.data();
  std::size_t left = image.rgba.size();
  int err = 0;
  while (left > 0) {
    const ssize_t n = ::write(pipe_, p, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      err = errno;
      break;
    }
    p += n;
    left -= static_cast<std::size_t>(n);
  }
  ::sigaction(SIGPIPE, &old, nullptr);
  if (err != 0) {
    // Collect ffmpeg's exit before reporting.
    ::close(pipe_);
    pipe_ = -1;
    int status = 0;
    ::waitpid(pid_, &status, 0);
    pid_ = -1;
    fail(str("ffmpeg stopped reading frames (", std::strerror(err), ")"));
  }
  ++frames_;
}

void VideoEncoder::finish() {
  PELAGE_CHECK(!done_, "VideoEncoder::finish twice");
  ::close(pipe_);
  pipe_ = -1;
  int status = 0;
  while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
  }
  pid_ = -1;
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    fail(WIFEXITED(status) ? str("ffmpeg failed (exit status ", WEXITSTATUS(status), ")")
                           : str("ffmpeg was killed (signal ", WTERMSIG(status), ")"));
  if (std::rename(tempPath_.c_str(), path_.c_str()) != 0)
    fail(str("rename failed (", std::strerror(errno), ")"));
  done_ = true;
}

}  // namespace pelage::render
