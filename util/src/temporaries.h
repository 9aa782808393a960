// The registered temporary files (atomic_file.cpp) as the signal handlers see them.
#pragma once

namespace pelage::detail {

// Unlinks every registered temporary file. Async-signal-safe (reads fixed slots, calls unlink).
void unlinkRegisteredTemporaries();

// Unlinks the registered temporaries, restores the signal's default action and raises it again:
// the process ends as the signal would have ended it. Async-signal-safe.
[[noreturn]] void removeTemporariesAndDie(int sig);

}  // namespace pelage::detail
