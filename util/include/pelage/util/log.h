// Warnings for the user (e.g. a clamped parameter, skipped degenerate triangles). They go to stderr
// by default; tests and the viewer can install their own sink.
#pragma once

#include <functional>
#include <string>

namespace pelage {

using WarningSink = std::function<void(const std::string&)>;

// Reports a warning through the current sink (stderr with a "pelage: warning: " prefix by default).
void warn(const std::string& message);

// Replaces the warning sink; returns the previous one. An empty sink restores the default.
WarningSink setWarningSink(WarningSink sink);

}  // namespace pelage
