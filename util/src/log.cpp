#include "pelage/util/log.h"

#include <cstdio>
#include <mutex>

namespace pelage {
namespace {
std::mutex& sinkMutex() {
  static std::mutex m;
  return m;
}
WarningSink& currentSink() {
  static WarningSink sink;
  return sink;
}
}  // namespace

void warn(const std::string& message) {
  std::lock_guard<std::mutex> lock(sinkMutex());
  if (currentSink()) {
    currentSink()(message);
  } else {
    std::fprintf(stderr, "pelage: warning: %s\n", message.c_str());
  }
}

WarningSink setWarningSink(WarningSink sink) {
  std::lock_guard<std::mutex> lock(sinkMutex());
  WarningSink old = std::move(currentSink());
  currentSink() = std::move(sink);
  return old;
}

}  // namespace pelage
