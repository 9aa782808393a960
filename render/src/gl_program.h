// Compiling and linking GLSL programs from the embedded shader files, and small RAII holders for
// GL objects. Private to the renderer.
#pragma once

#include <initializer_list>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "pelage/render/gl.h"

namespace pelage::render::detail {

// One stage: its GL type and the embedded files concatenated after the version line and defines
// (e.g. {"lighting.glsl", "skin.frag"}).
struct ShaderStage {
  GLenum type;
  std::vector<std::string_view> files;
  std::string_view source = {};  // more text after the files (a test's own entry point)
};

// Compiles and links; on failure PELAGE_CHECK fails with the file names and the driver's log
// (shaders are part of pelage, so a compile error is a bug, not bad input).
GLuint buildProgram(const std::string& name, std::initializer_list<ShaderStage> stages,
                    const std::string& defines = "");

// A GL object name with its deleter; movable, not copyable.
template <void (*Delete)(GLuint)>
class GlHandle {
 public:
  GlHandle() = default;
  explicit GlHandle(GLuint id) : id_(id) {}
  ~GlHandle() { reset(); }
  GlHandle(GlHandle&& o) noexcept : id_(std::exchange(o.id_, 0)) {}
  GlHandle& operator=(GlHandle&& o) noexcept {
    if (this != &o) {
      reset();
      id_ = std::exchange(o.id_, 0);
    }
    return *this;
  }
  GlHandle(const GlHandle&) = delete;
  GlHandle& operator=(const GlHandle&) = delete;
  GLuint get() const { return id_; }
  explicit operator bool() const { return id_ != 0; }
  void reset(GLuint id = 0) {
    if (id_) Delete(id_);
    id_ = id;
  }

 private:
  GLuint id_ = 0;
};

inline void deleteBuffer(GLuint id) {
  glDeleteBuffers(1, &id);
}
inline void deleteVertexArray(GLuint id) {
  glDeleteVertexArrays(1, &id);
}
inline void deleteTexture(GLuint id) {
  glDeleteTextures(1, &id);
}
inline void deleteRenderbuffer(GLuint id) {
  glDeleteRenderbuffers(1, &id);
}
inline void deleteFramebuffer(GLuint id) {
  glDeleteFramebuffers(1, &id);
}
inline void deleteProgram(GLuint id) {
  glDeleteProgram(id);
}

using Buffer = GlHandle<deleteBuffer>;
using VertexArray = GlHandle<deleteVertexArray>;
using Texture = GlHandle<deleteTexture>;
using Renderbuffer = GlHandle<deleteRenderbuffer>;
using Framebuffer = GlHandle<deleteFramebuffer>;
using Program = GlHandle<deleteProgram>;

inline Buffer createBuffer() {
  GLuint id = 0;
  glCreateBuffers(1, &id);
  return Buffer(id);
}

// Uniform location by name (-1 if the program does not use it; setting -1 is a no-op in GL).
inline GLint uniform(GLuint program, const char* name) {
  return glGetUniformLocation(program, name);
}

}  // namespace pelage::render::detail
