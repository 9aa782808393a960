// OpenGL debug output (KHR_debug, core in 4.3): messages from the driver go to a callback that
// records them. The renderer installs it when the context is a debug context; tests assert that no
// error was recorded, turning any GL error into a test failure.
#pragma once

#include <mutex>
#include <string>
#include <vector>

namespace pelage::render {

struct GlMessage {
  unsigned source = 0, type = 0, id = 0, severity = 0;
  std::string text;
  bool isError() const;  // GL_DEBUG_TYPE_ERROR, or high severity
  std::string describe() const;
};

// Collects debug messages of the current context from construction to destruction (one per
// context). Notifications are dropped; performance warnings are kept but are not errors.
class GlDebugLog {
 public:
  GlDebugLog();
  ~GlDebugLog();
  GlDebugLog(const GlDebugLog&) = delete;
  GlDebugLog& operator=(const GlDebugLog&) = delete;

  // Messages recorded so far (a copy; thread-safe).
  std::vector<GlMessage> messages() const;
  // The recorded errors, one per line; empty when there were none.
  std::string errors() const;
  // Also print every kept message to stderr as it arrives.
  void setEcho(bool echo) { echo_ = echo; }
  void clear();

  void add(GlMessage m);

 private:
  mutable std::mutex mutex_;
  std::vector<GlMessage> messages_;
  bool echo_ = false;
};

// Checks glGetError and throws InternalError naming `where` if an error is pending.
void checkGlError(const char* where);

}  // namespace pelage::render
