// Small helpers shared by the test suites: temporary directories, reading and writing files, the
// test inputs' paths (the critter, the shared glTF models), running the pelage binary, and the
// vertices of an OBJ it wrote.
#pragma once

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <Eigen/Core>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "pelage/util/error.h"

extern char** environ;

// The test critter's creature file (support/models.h builds it once per suite).
#define PELAGE_TEST_CRITTER PELAGE_SOURCE_DIR "/tests/support/critter.json"

namespace pelage::test {

inline std::string sharedModel(const std::string& rel) {
  return std::string(PELAGE_SHARED_MODELS_DIR) + "/" + rel;
}

inline bool haveSharedModels() {
  return std::filesystem::is_directory(PELAGE_SHARED_MODELS_DIR);
}

#define PELAGE_REQUIRE_SHARED_MODELS()                                               \
  do {                                                                               \
    if (!::pelage::test::haveSharedModels())                                         \
      GTEST_SKIP() << "shared glTF models not found at " << PELAGE_SHARED_MODELS_DIR \
                   << " (tests skipped)";                                            \
  } while (0)

// A fresh directory under the system temp dir, removed with its contents on destruction.
class TempDir {
 public:
  TempDir() {
    std::random_device rd;
    path_ = std::filesystem::temp_directory_path() /
            ("pelage-test-" + std::to_string(::getpid()) + "-" + std::to_string(rd()));
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::permissions(path_, std::filesystem::perms::owner_all, ec);
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  std::string file(const std::string& name) const { return (path_ / name).string(); }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

inline void writeText(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

// Expects `run()` to throw InputError whose message holds every one of `parts`.
template <class Run>
void expectInputError(Run&& run, std::initializer_list<std::string> parts) {
  try {
    run();
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    const std::string m = e.what();
    for (const std::string& p : parts) EXPECT_NE(m.find(p), std::string::npos) << p << " in: " << m;
  }
}

inline std::string readText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

struct RunResult {
  int exitCode = -1;
  std::string output;  // stdout and stderr together
};

// Runs a shell command line, capturing its output (stdout and stderr) and exit status (128 + the
// signal for a killed process).
inline RunResult runShell(const std::string& command) {
  RunResult r;
  FILE* p = ::popen((command + " 2>&1").c_str(), "r");
  if (!p) return r;
  std::array<char, 4096> buf;
  std::size_t n;
  while ((n = std::fread(buf.data(), 1, buf.size(), p)) > 0) r.output.append(buf.data(), n);
  const int status = ::pclose(p);
  r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  return r;
}

// Runs `build/bin/pelage <args>` through the shell, capturing output and exit status.
inline RunResult runPelage(const std::string& args) {
  return runShell(std::string(PELAGE_BIN_DIR) + "/pelage " + args);
}

// Starts `build/bin/pelage <args...>` without a shell, stdout and stderr to `log`, with the
// environment plus `env` ("NAME=value" each, replacing a variable of that name); returns its pid.
inline pid_t spawnPelage(std::vector<std::string> args, const std::string& log,
                         const std::vector<std::string>& env = {}) {
  args.insert(args.begin(), std::string(PELAGE_BIN_DIR) + "/pelage");
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  std::vector<std::string> vars = env;
  for (char** e = environ; *e; ++e) {
    const std::string v(*e);
    bool replaced = false;
    for (const std::string& x : env)
      replaced = replaced || v.rfind(x.substr(0, x.find('=') + 1), 0) == 0;
    if (!replaced) vars.push_back(v);
  }
  std::vector<char*> envp;
  for (std::string& v : vars) envp.push_back(v.data());
  envp.push_back(nullptr);
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&fa, 1, 2);
  pid_t pid = -1;
  if (posix_spawn(&pid, argv[0], &fa, nullptr, argv.data(), envp.data()) != 0) pid = -1;
  posix_spawn_file_actions_destroy(&fa);
  return pid;
}

// Waits for `pid`; its exit status, or 128 + the signal that killed it.
inline int waitExit(pid_t pid) {
  int status = 0;
  ::waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

// Vertex positions of an OBJ written by `pelage skin`.
inline std::vector<Eigen::Vector3f> objVertices(const std::string& path) {
  std::istringstream in(readText(path));
  std::vector<Eigen::Vector3f> v;
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("v ", 0) == 0) {
      std::istringstream l(line.substr(2));
      Eigen::Vector3f p;
      l >> p.x() >> p.y() >> p.z();
      v.push_back(p);
    }
  return v;
}

}  // namespace pelage::test
