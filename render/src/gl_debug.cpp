#include "pelage/render/gl_debug.h"

#include <cstdio>

#include "pelage/render/gl.h"
#include "pelage/util/error.h"

namespace pelage::render {
namespace {

const char* severityName(unsigned s) {
  switch (s) {
    case GL_DEBUG_SEVERITY_HIGH:
      return "high";
    case GL_DEBUG_SEVERITY_MEDIUM:
      return "medium";
    case GL_DEBUG_SEVERITY_LOW:
      return "low";
    default:
      return "notification";
  }
}

const char* typeName(unsigned t) {
  switch (t) {
    case GL_DEBUG_TYPE_ERROR:
      return "error";
    case GL_DEBUG_TYPE_DEPRECATED_BEHAVIOR:
      return "deprecated";
    case GL_DEBUG_TYPE_UNDEFINED_BEHAVIOR:
      return "undefined behaviour";
    case GL_DEBUG_TYPE_PORTABILITY:
      return "portability";
    case GL_DEBUG_TYPE_PERFORMANCE:
      return "performance";
    default:
      return "other";
  }
}

void APIENTRY onMessage(GLenum source, GLenum type, GLuint id, GLenum severity, GLsizei length,
                        const GLchar* message, const void* user) {
  if (severity == GL_DEBUG_SEVERITY_NOTIFICATION) return;
  GlMessage m;
  m.source = source;
  m.type = type;
  m.id = id;
  m.severity = severity;
  m.text =
      length >= 0 ? std::string(message, static_cast<std::size_t>(length)) : std::string(message);
  static_cast<GlDebugLog*>(const_cast<void*>(user))->add(std::move(m));
}

const char* glErrorName(GLenum e) {
  switch (e) {
    case GL_INVALID_ENUM:
      return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE:
      return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION:
      return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION:
      return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY:
      return "GL_OUT_OF_MEMORY";
    case GL_STACK_OVERFLOW:
      return "GL_STACK_OVERFLOW";
    case GL_STACK_UNDERFLOW:
      return "GL_STACK_UNDERFLOW";
    default:
      return "GL error";
  }
}

}  // namespace

bool GlMessage::isError() const {
  return type == GL_DEBUG_TYPE_ERROR || type == GL_DEBUG_TYPE_UNDEFINED_BEHAVIOR ||
         severity == GL_DEBUG_SEVERITY_HIGH;
}

std::string GlMessage::describe() const {
  return str("GL ", typeName(type), " (", severityName(severity), ", id ", id, "): ", text);
}

GlDebugLog::GlDebugLog() {
  glEnable(GL_DEBUG_OUTPUT);
  glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
  glDebugMessageCallback(onMessage, this);
  glDebugMessageControl(GL_DONT_CARE, GL_DONT_CARE, GL_DEBUG_SEVERITY_NOTIFICATION, 0, nullptr,
                        GL_FALSE);
}

GlDebugLog::~GlDebugLog() {
  glDebugMessageCallback(nullptr, nullptr);
  glDisable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
}

void GlDebugLog::add(GlMessage m) {
  if (echo_) std::fprintf(stderr, "pelage: %s\n", m.describe().c_str());
  std::lock_guard<std::mutex> lock(mutex_);
  messages_.push_back(std::move(m));
}

std::vector<GlMessage> GlDebugLog::messages() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return messages_;
}

std::string GlDebugLog::errors() const {
  std::lock_guard<std::mutex> lock(mutex_);
  std::string out;
  for (const GlMessage& m : messages_)
    if (m.isError()) out += m.describe() + "\n";
  return out;
}

void GlDebugLog::clear() {
  std::lock_guard<std::mutex> lock(mutex_);
  messages_.clear();
}

void checkGlError(const char* where) {
  const GLenum e = glGetError();
  PELAGE_CHECK(e == GL_NO_ERROR, where, ": ", glErrorName(e));
}

}  // namespace pelage::render
