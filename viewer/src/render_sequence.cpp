#include "pelage/viewer/render_sequence.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <charconv>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <exception>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <thread>

#include "pelage/scene/dynamic_fur.h"
#include "pelage/util/atomic_file.h"
#include "pelage/util/error.h"
#include "pelage/util/json_reader.h"
#include "pelage/util/parallel.h"
#include "pelage/viewer/gl_context.h"

extern char** environ;

namespace pelage::viewer {
namespace fs = std::filesystem;

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

bool parseInt(std::string_view s, int& out) {
  if (s.empty()) return false;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), out);
  return r.ec == std::errc() && r.ptr == s.data() + s.size();
}

void defaultWrite(const std::string& path, const std::vector<std::uint8_t>& bytes) {
  AtomicFileWriter w(path);
  w.write(bytes.data(), bytes.size());
  w.commit();
}

// PNG encoders on worker threads: the main thread hands over rendered images (blocking while every
// image buffer is in use, which bounds memory) and gets the buffers back when the files are
// written.
class EncoderPool {
 public:
  EncoderPool(int threads, int width, int height, FileWriter writer,
              std::function<void(int)> onWritten)
      : writer_(std::move(writer)), onWritten_(std::move(onWritten)) {
    const int buffers = threads + 2;
    for (int i = 0; i < buffers; ++i) {
      auto img = std::make_unique<Image>();
      img->width = width;
      img->height = height;
      img->rgba.resize(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4);
      free_.push_back(std::move(img));
    }
    for (int i = 0; i < threads; ++i) workers_.emplace_back([this] { work(); });
  }
  ~EncoderPool() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
    }
    cv_.notify_all();
    for (std::thread& t : workers_) t.join();
  }

  // A free image buffer (waits for one); rethrows an encoder's error.
  std::unique_ptr<Image> acquire() {
    std::unique_lock<std::mutex> lock(mutex_);
    cv_.wait(lock, [this] { return !free_.empty() || error_; });
    if (error_) std::rethrow_exception(error_);
    std::unique_ptr<Image> img = std::move(free_.back());
    free_.pop_back();
    return img;
  }
  void submit(int frame, std::string path, std::unique_ptr<Image> image) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      jobs_.push_back(Job{frame, std::move(path), std::move(image)});
    }
    cv_.notify_all();
  }
  // Waits until every submitted frame is written; rethrows the first error.
  void drain() {
    std::unique_lock<std::mutex> lock(mutex_);
    cv_.wait(lock, [this] { return (jobs_.empty() && busy_ == 0) || error_; });
    if (error_) std::rethrow_exception(error_);
  }

 private:
  struct Job {
    int frame = 0;
    std::string path;
    std::unique_ptr<Image> image;
  };
  void work() {
    for (;;) {
      Job job;
      {
        std::unique_lock<std::mutex> lock(mutex_);
        cv_.wait(lock, [this] { return stop_ || (!jobs_.empty() && !error_); });
        if (stop_) return;
        job = std::move(jobs_.front());
        jobs_.pop_front();
        ++busy_;
      }
      std::exception_ptr err;
      try {
        const std::vector<std::uint8_t> png = encodePng(*job.image);
        writer_(job.path, png);
      } catch (...) {
        err = std::current_exception();
      }
      {
        std::lock_guard<std::mutex> lock(mutex_);
        --busy_;
        free_.push_back(std::move(job.image));
        if (err && !error_) error_ = err;
        if (!err) onWritten_(job.frame);  // under the lock: one progress report at a time
      }
      cv_.notify_all();
    }
  }

  FileWriter writer_;
  std::function<void(int)> onWritten_;
  std::mutex mutex_;
  std::condition_variable cv_;
  std::deque<Job> jobs_;
  std::vector<std::unique_ptr<Image>> free_;
  std::vector<std::thread> workers_;
  std::exception_ptr error_;
  int busy_ = 0;
  bool stop_ = false;
};

// Removes temporary files (".frame_00042.png.tmp-<pid>-<n>") that killed runs left for frames in
// `range`; returns how many.
int removeStaleTemporaries(const std::string& dir, const FrameRange& range) {
  int removed = 0;
  std::error_code ec;
  for (const fs::directory_entry& e : fs::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    if (name.rfind(".frame_", 0) != 0) continue;
    const std::size_t tmp = name.find(".png.tmp-");
    if (tmp == std::string::npos) continue;
    int frame = -1;
    if (!parseInt(std::string_view(name).substr(7, tmp - 7), frame)) continue;
    if (frame < range.first || frame > range.last) continue;
    std::error_code rec;
    if (fs::remove(e.path(), rec)) ++removed;
  }
  return removed;
}

}  // namespace

bool isCompletePng(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  unsigned char head[16] = {};
  if (!in.read(reinterpret_cast<char*>(head), 16)) return false;
  static const unsigned char sig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (std::memcmp(head, sig, 8) != 0 || std::memcmp(head + 12, "IHDR", 4) != 0) return false;
  in.seekg(-12, std::ios::end);
  unsigned char tail[12] = {};
  if (!in.read(reinterpret_cast<char*>(tail), 12)) return false;
  static const unsigned char iend[12] = {0, 0, 0, 0, 'I', 'E', 'N', 'D', 0xae, 0x42, 0x60, 0x82};
  return std::memcmp(tail, iend, 12) == 0;
}

CameraPath loadCameraFile(const std::string& path) {
  const nlohmann::json doc = JsonReader::parseFile(path);
  const JsonReader root(doc, path);
  if (!root.isObject()) root.fail("a camera file is a JSON object");
  CameraPath out;
  auto readKey = [](const JsonReader& j, CameraKey& k) {
    k.eye = j.vec3("eye");
    k.target = j.vec3("target");
    k.up = j.vec3("up", Eigen::Vector3f::UnitZ());
    k.fovYDegrees = static_cast<float>(j.number("fovYDegrees", 35.0, 1.0, 179.0));
    if ((k.eye - k.target).norm() < 1e-6f) j.fail("eye and target must differ");
    if (k.up.norm() < 1e-6f ||
        (k.eye - k.target).normalized().cross(k.up.normalized()).norm() < 1e-4f)
      j.fail("up must be non-zero and not parallel to the view direction");
  };
  if (root.has("keys")) {
    root.rejectUnknown({"keys", "track"});
    const JsonReader keys = root.at("keys");
    if (!keys.isArray() || keys.size() == 0) keys.fail("needs at least one key");
    for (std::size_t i = 0; i < keys.size(); ++i) {
      const JsonReader k = keys.at(i);
      k.rejectUnknown({"frame", "eye", "target", "up", "fovYDegrees"});
      CameraKey key;
      key.frame = static_cast<int>(k.integer("frame", 0, kMaxFrameNumber));
      readKey(k, key);
      if (!out.keys.empty() && key.frame <= out.keys.back().frame)
        k.fail("key frames must increase (" + std::to_string(key.frame) + " after " +
               std::to_string(out.keys.back().frame) + ")");
      out.keys.push_back(key);
    }
  } else {
    root.rejectUnknown({"eye", "target", "up", "fovYDegrees", "track"});
    CameraKey key;
    readKey(root, key);
    out.keys.push_back(key);
  }
  out.track = root.boolean("track", false);
  return out;
}

scene::Camera cameraOnPath(const CameraPath& path, int frame, int width, int height) {
  PELAGE_CHECK(!path.keys.empty());
  scene::Camera cam;
  cam.width = width;
  cam.height = height;
  const std::vector<CameraKey>& k = path.keys;
  std::size_t i = 0;
  while (i + 1 < k.size() && k[i + 1].frame <= frame) ++i;
  const CameraKey& a = k[i];
  if (frame <= a.frame || i + 1 == k.size()) {
    cam.eye = a.eye;
    cam.target = a.target;
    cam.up = a.up;
    cam.fovYDegrees = a.fovYDegrees;
    return cam;
  }
  const CameraKey& b = k[i + 1];
  const float s = static_cast<float>(frame - a.frame) / static_cast<float>(b.frame - a.frame);
  cam.eye = a.eye + s * (b.eye - a.eye);
  cam.target = a.target + s * (b.target - a.target);
  cam.up = (a.up + s * (b.up - a.up)).normalized();
  cam.fovYDegrees = a.fovYDegrees + s * (b.fovYDegrees - a.fovYDegrees);
  return cam;
}

void validateSequenceOptions(const SequenceOptions& o) {
  if (o.width < 16 || o.width > 16384 || o.height < 16 || o.height > 16384)
    inputError("--size ", o.width, "x", o.height, " is out of range [16, 16384] per side");
  if (!(o.framesPerSecond >= 1.0 && o.framesPerSecond <= 1000.0))
    inputError("--fps ", o.framesPerSecond, " is out of range [1, 1000]");
  if (o.frames.first < 0 || o.frames.first > o.frames.last || o.frames.last > kMaxFrameNumber)
    inputError("--frames ", o.frames.first, ":", o.frames.last,
               " is out of range: need 0 <= FIRST <= LAST <= ", kMaxFrameNumber);
  if (o.samples < -1 || o.samples > 64)
    inputError("--samples ", o.samples, " is out of range [-1, 64]");
  if (o.encoderThreads < 0 || o.encoderThreads > 256)
    inputError("--encoders ", o.encoderThreads, " is out of range [0, 256]");
  if (!(o.camera.fovYDegrees > 1.0f && o.camera.fovYDegrees < 179.0f))
    inputError("--fov ", o.camera.fovYDegrees, " is out of range (1, 179) degrees");
  if (o.outDir.empty()) inputError("--out: an output directory is required");
  if (o.dynamics) {
    if (o.clip < 0) inputError("--dynamics on needs a clip (--clip): the rest pose does not move");
    fur::validateDynamicsParams(o.dynamicsParams, "--frequency/--damping");
    if (o.preRollFrames < -1 || o.preRollFrames > 10000000)
      inputError("--preroll ", o.preRollFrames, " is out of range [0, 10000000] frames");
  }
  if (!o.video.empty()) {
    const std::string ext = fs::path(o.video).extension().string();
    if (ext != ".mp4" && ext != ".gif")
      inputError("--video ", o.video, ": the file must end in .mp4 or .gif");
  }
}

// ---- SequenceRenderer -------------------------------------------------------------------------

struct SequenceRenderer::Impl {
  const scene::Model& model;
  const scene::Fur& fur;
  SequenceOptions options;
  anatomy::Pose restPose;
  scene::FrameState state;
  scene::Framing framing0;  // clip time 0: every frame's preset camera comes from it
  scene::DrawList list;
  std::unique_ptr<Renderer> renderer;
  float hairPad = 0.0f;
  // Dynamic fur: the springs' state, the frame it is ready to step to, and pre-roll scratch.
  fur::FurDynamicsState dynamics;
  int nextDynamicFrame = -1;
  scene::FrameState preRollScratch;

  Impl(const scene::Model& m, const scene::Fur& f, const SequenceOptions& o)
      : model(m), fur(f), options(o) {}

  void evaluate(int frame) {
    if (options.clip >= 0)
      scene::evaluateClipFrame(model, options.clip,
                               static_cast<double>(frame) / options.framesPerSecond, state);
    else
      scene::evaluateFrame(model, restPose, state);
  }

  // The camera of the evaluated frame `frame`.
  scene::Camera camera(int frame) {
    const SequenceCamera& sc = options.camera;
    scene::Camera cam;
    bool track = sc.track;
    if (sc.path) {
      cam = cameraOnPath(*sc.path, frame, options.width, options.height);
      track = track || sc.path->track;
    } else {
      cam = scene::presetCamera(framing0, sc.preset, options.width, options.height, sc.fovYDegrees);
      track = track || sc.preset == scene::CameraPreset::Follow;
    }
    const scene::Framing f = scene::framingOf(model, state, hairPad);
    if (track) {
      Eigen::Vector3f d = f.rootPosition - framing0.rootPosition;
      d.z() = 0.0f;
      cam.eye += d;
      cam.target += d;
    }
    // Clip planes around this frame's creature (as the viewer does).
    const float dist = (cam.eye - f.center).norm();
    cam.nearMeters = std::max((dist - f.radius) * 0.5f, f.radius * 0.002f);
    cam.farMeters = dist + f.radius * 2.0f;
    return cam;
  }
};

SequenceRenderer::SequenceRenderer(const scene::Model& model, const scene::Fur& fur,
                                   const SequenceOptions& options)
    : impl_(std::make_unique<Impl>(model, fur, options)) {
  validateSequenceOptions(options);
  Impl& m = *impl_;
  PELAGE_CHECK(options.clip < static_cast<int>(model.clips.size()), "clip ", options.clip);
  m.restPose = anatomy::restPose(model.body);
  m.hairPad = scene::maxHairLength(model, fur.params);
  if (options.clip >= 0)
    scene::evaluateClipFrame(model, options.clip, 0.0, m.state);
  else
    scene::evaluateFrame(model, m.restPose, m.state);
  m.framing0 = scene::framingOf(model, m.state, m.hairPad);
  RendererOptions ro;
  ro.samples = options.samples;
  if (ro.samples < 0) {
    // MSAA costs ~2.3x on llvmpipe (../shared/docs/headless-gl.md): keep software rasterisers fast.
    ContextInfo info;
    queryContextInfo(info);
    ro.samples = info.software ? 0 : 4;
  }
  m.renderer = std::make_unique<Renderer>(ro);
}

SequenceRenderer::~SequenceRenderer() = default;

scene::Camera SequenceRenderer::camera(int frame) {
  impl_->evaluate(frame);
  return impl_->camera(frame);
}

RenderStats SequenceRenderer::render(int frame, Image& out) {
  Impl& m = *impl_;
  m.evaluate(frame);
  const scene::Camera cam = m.camera(frame);
  const bool cpu = m.options.hairSource == scene::HairSource::Cpu || m.options.dynamics;
  if (m.options.dynamics) {
    scene::DynamicsClock clock;
    clock.fps = m.options.framesPerSecond;
    clock.preRollFrames = m.options.preRollFrames;
    // Frames come in order; any other frame (the first, or one after frames skipped by --resume)
    // is reached by pre-rolling, exactly as a whole run reaches it.
    if (frame != m.nextDynamicFrame)
      scene::preRollDynamics(m.model, m.fur, m.options.dynamicsParams, m.options.clip, frame, clock,
                             m.dynamics, m.preRollScratch);
    scene::stepClipDynamics(m.model, m.fur, m.options.dynamicsParams, clock, cam.eye, true,
                            m.dynamics, m.state);
    m.nextDynamicFrame = frame + 1;
  } else {
    scene::evaluateFur(m.model, m.fur, cam.eye, cpu, m.state);
  }
  scene::Light light;
  light.direction = scene::lightDirection(35.0f, 50.0f);  // the viewer's default key light
  light.shadows = m.options.shadows;
  scene::DrawOptions opt;
  opt.hairSource = cpu ? scene::HairSource::Cpu : m.options.hairSource;
  opt.hairShading = m.options.shading;
  opt.hairWidth = m.options.hairWidth;
  scene::buildDrawList(m.model, m.state, &m.fur, cam, light, opt, m.list);
  m.list.background = m.options.background;
  const RenderStats stats = m.renderer->render(m.list);
  m.renderer->readPixels(out);
  return stats;
}

// ---- renderSequence ---------------------------------------------------------------------------

SequenceReport renderSequence(const scene::Model& model, const scene::Fur& fur,
                              const SequenceOptions& options, const ProgressCallback& progress,
                              const FileWriter& writer) {
  validateSequenceOptions(options);
  ensureWritableDirectory(options.outDir);
  SequenceReport report;
  const Clock::time_point t0 = Clock::now();
  if (options.resume)
    report.removedTemporaries = removeStaleTemporaries(options.outDir, options.frames);

  // Which frames are already complete (--resume).
  const int total = options.frames.count();
  std::vector<char> done(static_cast<std::size_t>(total), 0);
  auto framePath = [&](int frame) {
    return (fs::path(options.outDir) / frameFileName(frame, ".png")).string();
  };
  if (options.resume)
    for (int i = 0; i < total; ++i)
      if (isCompletePng(framePath(options.frames.first + i))) {
        done[static_cast<std::size_t>(i)] = 1;
        ++report.skipped;
      }

  std::unique_ptr<VideoEncoder> video;
  if (!options.video.empty())
    video = std::make_unique<VideoEncoder>(options.video, options.width, options.height,
                                           options.framesPerSecond);

  SequenceRenderer sequence(model, fur, options);
  const int toRender = total - report.skipped;
  int finished = report.skipped;
  int written = 0;
  auto onWritten = [&](int frame) {
    ++written;
    ++finished;
    if (!progress) return;
    SequenceProgress p;
    p.done = finished;
    p.total = total;
    p.skipped = report.skipped;
    p.frame = frame;
    p.elapsedSeconds = secondsSince(t0);
    p.framesPerSecond = p.elapsedSeconds > 0.0 ? written / p.elapsedSeconds : 0.0;
    p.secondsLeft = p.framesPerSecond > 0.0 ? (toRender - written) / p.framesPerSecond : 0.0;
    progress(p);
  };
  if (progress && report.skipped > 0) {
    SequenceProgress p;
    p.done = finished;
    p.total = total;
    p.skipped = report.skipped;
    p.frame = options.frames.first;
    progress(p);
  }
  const int threads =
      options.encoderThreads > 0 ? options.encoderThreads : std::max(1, threadCount());
  EncoderPool pool(threads, options.width, options.height,
                   writer ? writer : FileWriter(defaultWrite), onWritten);
  for (int i = 0; i < total; ++i) {
    const int frame = options.frames.first + i;
    if (done[static_cast<std::size_t>(i)]) {
      if (video) {
        const Image img = readPng(framePath(frame));
        if (img.width != options.width || img.height != options.height)
          inputError(framePath(frame), ": --resume found a ", img.width, "x", img.height,
                     " frame, not ", options.width, "x", options.height,
                     " (render into an empty directory, or without --resume)");
        video->addFrame(img);
      }
      continue;
    }
    std::unique_ptr<Image> img = pool.acquire();
    report.hairsDrawn = sequence.render(frame, *img).hairsDrawn;
    if (video) video->addFrame(*img);
    pool.submit(frame, framePath(frame), std::move(img));
    ++report.rendered;
  }
  pool.drain();
  if (video) video->finish();
  report.seconds = secondsSince(t0);
  return report;
}

// ---- ffmpeg -----------------------------------------------------------------------------------

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
}  // namespace

VideoEncoder::VideoEncoder(const std::string& path, int width, int height, double fps)
    : path_(path), width_(width), height_(height) {
  const fs::path p(path);
  const std::string ext = p.extension().string();
  if (ext != ".mp4" && ext != ".gif")
    inputError("--video ", path, ": the file must end in .mp4 or .gif");
  const std::string ffmpeg = findOnPath("ffmpeg");
  if (ffmpeg.empty())
    inputError("--video ", path,
               " needs the ffmpeg program, which is not on PATH (Debian: apt-get install ffmpeg)");
  const fs::path dir = p.has_parent_path() ? p.parent_path() : fs::path(".");
  if (!fs::is_directory(dir))
    inputError("--video ", path, ": the directory ", dir.string(), " does not exist");
  if (::access(dir.c_str(), W_OK) != 0)
    inputError("--video ", path, ": cannot write (permission denied)");
  const std::string tag = std::to_string(::getpid()) + "-" + std::to_string(videoCounter++);
  tempPath_ = (dir / ("." + p.stem().string() + ".tmp-" + tag + ext)).string();
  logPath_ = (fs::temp_directory_path() / ("pelage-ffmpeg-" + tag + ".log")).string();

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
    inputError("--video: cannot create a pipe to ffmpeg (", std::strerror(errno), ")");
  const int log = ::open(logPath_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_adddup2(&fa, fds[0], 0);
  if (log >= 0) {
    posix_spawn_file_actions_adddup2(&fa, log, 1);
    posix_spawn_file_actions_adddup2(&fa, log, 2);
  }
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = -1;
  const int rc = ::posix_spawn(&pid, ffmpeg.c_str(), &fa, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  ::close(fds[0]);
  if (log >= 0) ::close(log);
  if (rc != 0) {
    ::close(fds[1]);
    std::remove(logPath_.c_str());
    inputError("--video: cannot start ", ffmpeg, " (", std::strerror(rc), ")");
  }
  pid_ = pid;
  pipe_ = fds[1];
}

VideoEncoder::~VideoEncoder() {
  if (!done_) {
    if (pipe_ >= 0) ::close(pipe_);
    pipe_ = -1;
    if (pid_ > 0) {
      ::kill(pid_, SIGKILL);
      int status = 0;
      ::waitpid(pid_, &status, 0);
    }
    std::remove(tempPath_.c_str());
  }
  std::remove(logPath_.c_str());
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
  inputError("--video ", path_, ": ", what, log.empty() ? std::string() : "; ffmpeg said:\n" + log);
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

}  // namespace pelage::viewer
