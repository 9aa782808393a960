#include "pelage/util/parallel.h"

#include <omp.h>

#include <atomic>

namespace pelage {
namespace {
std::atomic<int>& threadSetting() {
  static std::atomic<int> n{0};
  return n;
}
}  // namespace

void setThreadCount(int threads) {
  threadSetting() = threads < 0 ? 0 : threads;
}

int threadCount() {
  const int n = threadSetting();
  return n > 0 ? n : omp_get_num_procs();
}

}  // namespace pelage
