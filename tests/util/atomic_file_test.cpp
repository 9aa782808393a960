#include "pelage/util/atomic_file.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>

#include <filesystem>

#include "pelage/util/error.h"
#include "support/files.h"

namespace pelage {
namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;

int filesIn(const fs::path& dir) {
  int n = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++n;
  return n;
}

TEST(AtomicFile, CommitWritesWholeFile) {
  test::TempDir dir;
  writeFileAtomically(dir.file("a.txt"), "hello");
  EXPECT_EQ(test::readText(dir.file("a.txt")), "hello");
  EXPECT_EQ(filesIn(dir.path()), 1);
}

TEST(AtomicFile, AbandonedWriteLeavesNothing) {
  test::TempDir dir;
  {
    AtomicFileWriter w(dir.file("b.txt"));
    w.write("partial");
  }  // destroyed without commit, as when an exception unwinds
  EXPECT_FALSE(fs::exists(dir.file("b.txt")));
  EXPECT_EQ(filesIn(dir.path()), 0);
}

TEST(AtomicFile, ReplacesOldFileOnlyOnCommit) {
  test::TempDir dir;
  writeFileAtomically(dir.file("c.txt"), "old");
  {
    AtomicFileWriter w(dir.file("c.txt"));
    w.write("new");
    EXPECT_EQ(test::readText(dir.file("c.txt")), "old");
    w.commit();
  }
  EXPECT_EQ(test::readText(dir.file("c.txt")), "new");
}

// Small values are gathered in the writer's buffer, pieces larger than it go through: the file
// holds every byte in the order written, whatever the sizes, and only after commit.
TEST(AtomicFile, BufferedWritesKeepEveryByteInOrder) {
  test::TempDir dir;
  const std::string path = dir.file("mixed.bin");
  std::string expected;
  AtomicFileWriter w(path);
  auto putInt = [&](std::int32_t v) {
    w.put(v);
    expected.append(reinterpret_cast<const char*>(&v), 4);
  };
  putInt(7);
  const std::string big(AtomicFileWriter::kBufferBytes + 5, 'b');
  w.write(big);
  expected += big;
  for (std::int32_t k = 0; k < 300000; ++k) putInt(k);  // more than one buffer's worth
  const std::string fits(AtomicFileWriter::kBufferBytes - 3, 'f');
  w.write(fits);
  expected += fits;
  w.write("", 0);
  putInt(-1);
  EXPECT_FALSE(fs::exists(path));
  w.commit();
  EXPECT_EQ(test::readText(path), expected);
}

TEST(AtomicFile, MissingDirectoryIsAClearError) {
  try {
    writeFileAtomically("/nonexistent-dir-pelage/x.ply", "x");
    FAIL() << "expected an error";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("/nonexistent-dir-pelage/x.ply: cannot write"));
  }
}

// A full disk is simulated with a file-size limit (RLIMIT_FSIZE) in a child process: the write
// fails part-way exactly as with ENOSPC. The writer must report the file and leave nothing behind.
TEST(AtomicFile, FailedWriteIsAClearErrorAndLeavesNothing) {
  test::TempDir dir;
  const std::string path = dir.file("big.bin");
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    ::signal(SIGXFSZ, SIG_IGN);
    rlimit lim{4096, 4096};
    ::setrlimit(RLIMIT_FSIZE, &lim);
    int code = 1;
    try {
      AtomicFileWriter w(path);
      const std::string chunk(1 << 16, 'x');
      for (int i = 0; i < 64; ++i) w.write(chunk);
      w.commit();
    } catch (const InputError& e) {
      const std::string msg = e.what();
      code = msg.find(path) != std::string::npos && msg.find("failed") != std::string::npos ? 0 : 2;
    }
    ::_exit(code);
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0) << "1: no error raised, 2: message lacks the path";
  EXPECT_EQ(filesIn(dir.path()), 0) << "a partial or temporary file was left behind";
}

TEST(AtomicFile, UnwritableDirectoryIsAClearError) {
  // Nobody, not even root, can create files in /proc.
  EXPECT_THROW(writeFileAtomically("/proc/pelage-test.txt", "x"), InputError);
  EXPECT_THROW(ensureWritableDirectory("/proc/self/pelage-out"), InputError);
  if (::geteuid() != 0) {
    test::TempDir dir;
    fs::permissions(dir.path(), fs::perms::owner_read | fs::perms::owner_exec);
    EXPECT_THROW(writeFileAtomically(dir.file("d.txt"), "x"), InputError);
  }
}

}  // namespace
}  // namespace pelage
