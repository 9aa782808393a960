#include "pelage/util/interrupt.h"

#include <signal.h>

#include <atomic>

#include "temporaries.h"

namespace pelage {
namespace {

std::atomic<int> gStop{0};  // the signal that asked for a stop; 0: none
std::atomic<InterruptPoll> gPoll{nullptr};

extern "C" void onStopSignal(int sig) {
  int none = 0;
  // The first signal asks for a stop; one more (the operation did not get to a check) ends us.
  if (!gStop.compare_exchange_strong(none, sig)) detail::removeTemporariesAndDie(sig);
}

}  // namespace

void checkInterrupt() {
  if (const int sig = gStop.load(std::memory_order_relaxed); sig != 0) throw Interrupted(sig);
  if (const InterruptPoll poll = gPoll.load(std::memory_order_acquire)) poll();
}

void catchInterrupts() {
  for (int sig : {SIGINT, SIGTERM}) {
    struct sigaction sa {};
    sa.sa_handler = onStopSignal;
    sa.sa_flags = SA_RESTART;  // reads and writes go on; the next check stops the operation
    sigemptyset(&sa.sa_mask);
    ::sigaction(sig, &sa, nullptr);
  }
}

void clearInterrupt() {
  gStop.store(0);
}

void setInterruptPoll(InterruptPoll poll) {
  gPoll.store(poll, std::memory_order_release);
}

}  // namespace pelage
