// Small helpers of the renderer's passes (renderer.cpp, deep_opacity_map.cpp): uniforms, the
// primitive a hair layout draws, immutable textures, projections, and the light's view of a frame.
// Private to the renderer.
#pragma once

#include <Eigen/Core>

#include <array>

#include "gl_program.h"
#include "pelage/fur/hair_layout.h"
#include "pelage/render/gl.h"
#include "pelage/util/material.h"

namespace pelage::render::detail {

inline void setMatrix(GLuint program, const char* name, const Eigen::Matrix4f& m) {
  glProgramUniformMatrix4fv(program, uniform(program, name), 1, GL_FALSE, m.data());
}
inline void setMatrix3(GLuint program, const char* name, const Eigen::Matrix3f& m) {
  glProgramUniformMatrix3fv(program, uniform(program, name), 1, GL_FALSE, m.data());
}
inline void setVec3(GLuint program, const char* name, const Eigen::Vector3f& v) {
  glProgramUniform3f(program, uniform(program, name), v.x(), v.y(), v.z());
}
inline void setFloat(GLuint program, const char* name, float v) {
  glProgramUniform1f(program, uniform(program, name), v);
}
inline void setInt(GLuint program, const char* name, int v) {
  glProgramUniform1i(program, uniform(program, name), v);
}

inline void setMaterial(GLuint program, const Material& m) {
  setVec3(program, "uKa", m.ambient);
  setVec3(program, "uKd", m.diffuse);
  setVec3(program, "uKs", m.specular);
  setFloat(program, "uShininess", std::max(m.shininess, 1.0f));
}

// How a layout's index pattern is drawn (fur::hairIndexPattern).
inline GLenum primitive(const fur::HairLayout& layout) {
  switch (layout.topology) {
    case fur::HairTopology::Strand:
      return GL_LINE_STRIP;
    case fur::HairTopology::Rings:
      return GL_TRIANGLES;
  }
  return GL_LINE_STRIP;
}

// An immutable 2D texture (`levels` levels of width x height) in `format`; with a nonzero
// `minFilter`, sampled with (minFilter, magFilter) and clamped at its edges.
inline Texture makeTexture(GLenum format, int levels, int width, int height, GLenum minFilter = 0,
                           GLenum magFilter = 0) {
  GLuint t = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &t);
  glTextureStorage2D(t, levels, format, width, height);
  if (minFilter != 0) {
    glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, static_cast<GLint>(minFilter));
    glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, static_cast<GLint>(magFilter));
    glTextureParameteri(t, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(t, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  }
  return Texture(t);
}

// An orthographic projection of the box [l, r] x [b, t] x [-n, -f] (glOrtho's matrix).
inline Eigen::Matrix4f ortho(float l, float r, float b, float t, float n, float f) {
  Eigen::Matrix4f m = Eigen::Matrix4f::Identity();
  m(0, 0) = 2.0f / (r - l);
  m(1, 1) = 2.0f / (t - b);
  m(2, 2) = -2.0f / (f - n);
  m(0, 3) = -(r + l) / (r - l);
  m(1, 3) = -(t + b) / (t - b);
  m(2, 3) = -(f + n) / (f - n);
  return m;
}

// The light's view for one frame (Renderer::Impl::lightFrame).
struct LightFrame {
  Eigen::Matrix4f viewProj = Eigen::Matrix4f::Identity();
  float extent = 1.0f;      // the view's width and height, metres
  float depthScale = 1.0f;  // metres per unit of window depth
  bool selfShadow = false;  // the deep opacity map is drawn and read
  std::array<float, 4> layerEnds{};
  float fibreOpacity = 1.0f;  // scene::Light::fibreOpacity
};

}  // namespace pelage::render::detail
