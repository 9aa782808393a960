// Stopping a long operation cleanly (Ctrl-C, a scheduler's SIGTERM). Long loops (every frame the
// frame owner plays, every pre-roll step, every exported or rendered frame, every analysed frame)
// call checkInterrupt(); when a stop was asked for it throws Interrupted, whose unwinding removes
// what was half-written (temporary files, ffmpeg and its log) by the owners' destructors. The
// command line turns Interrupted into "interrupted" and exit status 128 + the signal (130, 143);
// the Python package into KeyboardInterrupt.
#pragma once

#include <stdexcept>

namespace pelage {

// A stop asked for by a signal (or a host such as Python) while a long operation ran.
class Interrupted : public std::runtime_error {
 public:
  explicit Interrupted(int signal) : std::runtime_error("interrupted"), signal_(signal) {}
  // The signal that asked for the stop (SIGINT, SIGTERM), or 0 when a host's poll asked.
  int signal() const { return signal_; }

 private:
  int signal_;
};

// Throws Interrupted when a stop was asked for: by a signal caught by catchInterrupts(), or by the
// installed poll. Cheap (an atomic load) unless a poll is installed.
void checkInterrupt();

// Catches SIGINT and SIGTERM for the rest of the process (the command line calls it once): the
// first one asks the running operation to stop at its next checkInterrupt(); a second one (an
// operation that does not get to a check) removes the registered temporary files
// (util/atomic_file.h) and ends the process at once with the signal's default action.
void catchInterrupts();

// Forgets a stop asked for before (a host that handled it, tests).
void clearInterrupt();

// A poll that checkInterrupt() also calls (the Python package: Python's pending signals, which
// only Python's main thread may look at). It throws to stop (its own exception, or Interrupted).
// nullptr removes it. Set before long operations start; not thread-safe with them.
using InterruptPoll = void (*)();
void setInterruptPoll(InterruptPoll poll);

}  // namespace pelage
