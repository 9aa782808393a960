// The physical fur model's light laws (render/src/shaders/lighting.glsl), run on the GL device
// through a compute shader: the coat's response to the key light's incidence, k_n max(N.L, 0)^p,
// and the fibre part's terminator t, against their formulas on a few normals.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <vector>

#include "gl_program.h"
#include "pelage/render/gl.h"
#include "pelage/render/gl_context.h"

namespace pelage::render {
namespace {

// One invocation per normal: (coatIncidence(n), fibreTerminator(n)) for n at angle uAngle[i]
// from the light, in the plane of the light and x.
const char* kLaws = R"(
layout(local_size_x = 1) in;
layout(std430, binding = 0) buffer Out { vec2 result[]; };
uniform float uAngle[16];
void main() {
  uint i = gl_GlobalInvocationID.x;
  vec3 n = cos(uAngle[i]) * uLightDir + sin(uAngle[i]) * vec3(1.0, 0.0, 0.0);
  result[i] = vec2(coatIncidence(n), fibreTerminator(n));
}
)";

double smoothstep(double a, double b, double x) {
  const double t = std::clamp((x - a) / (b - a), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

TEST(LightingGlsl, CoatIncidenceAndFibreTerminatorFollowTheirFormulas) {
  const std::unique_ptr<GlContext> context = createHeadlessContext();
  const GLuint program = detail::buildProgram(
      "lighting.glsl's light laws",
      {detail::ShaderStage{GL_COMPUTE_SHADER, {"hair_bsdf.glsl", "lighting.glsl"}, kLaws}});
  // N.L from 1 to -1: facing the light, the two ends of the terminator's band (0.1, -0.3), past it.
  const std::vector<float> cosines = {1.0f, 0.9f,  0.5f,  0.3f,  0.1f, 0.02f,
                                      0.0f, -0.1f, -0.3f, -0.5f, -1.0f};
  std::vector<float> angles;
  for (float c : cosines) angles.push_back(std::acos(c));
  const int n = static_cast<int>(angles.size());
  GLuint buffer = 0;
  glCreateBuffers(1, &buffer);
  glNamedBufferData(buffer, static_cast<GLsizeiptr>(sizeof(float) * 2 * n), nullptr,
                    GL_DYNAMIC_READ);
  glUseProgram(program);
  // The light along y (x lies in the light's perpendicular plane, as the shader assumes).
  glUniform3f(glGetUniformLocation(program, "uLightDir"), 0.0f, 1.0f, 0.0f);
  glUniform1fv(glGetUniformLocation(program, "uAngle"), n, angles.data());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, buffer);
  glDispatchCompute(static_cast<GLuint>(n), 1, 1);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  std::vector<float> out(static_cast<std::size_t>(2 * n));
  glGetNamedBufferSubData(buffer, 0, static_cast<GLsizeiptr>(sizeof(float) * out.size()),
                          out.data());
  glDeleteBuffers(1, &buffer);
  glDeleteProgram(program);
  for (int i = 0; i < n; ++i) {
    const double c = cosines[static_cast<std::size_t>(i)];
    const double coat = out[static_cast<std::size_t>(2 * i)];
    const double terminator = out[static_cast<std::size_t>(2 * i + 1)];
    // k_n max(N.L, 0)^p, k_n = 0.8, p = 0.4: flatter than Lambert's N.L (0.3 keeps 0.64 of 0.9's).
    EXPECT_NEAR(coat, 0.8 * std::pow(std::max(c, 0.0), 0.4), 1e-4) << "N.L " << c;
    // t: smoothstep from N.L = -0.3 to 0.1.
    EXPECT_NEAR(terminator, smoothstep(-0.3, 0.1, c), 1e-4) << "N.L " << c;
  }
  EXPECT_EQ(out[2 * 6], 0.0f);      // no coat light at the terminator, N.L = 0
  EXPECT_EQ(out[2 * 8 + 1], 0.0f);  // no fibre light from N.L = -0.3 on
  EXPECT_EQ(out[2 * 4 + 1], 1.0f);  // all of it from N.L = 0.1 on
}

}  // namespace
}  // namespace pelage::render
