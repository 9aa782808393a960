// The fibre's scattering function of the physical fur model (render/src/shaders/hair_bsdf.glsl:
// Chiang et al. 2016, as Cycles' Principled Hair BSDF), run on the GL device through a compute
// shader and integrated over the sphere of incident directions here.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "gl_program.h"
#include "pelage/render/gl.h"
#include "pelage/render/gl_context.h"

namespace pelage::render {
namespace {

constexpr int kTheta = 96;  // incident longitudinal angles, midpoints over (-pi/2, pi/2)
constexpr int kPhi = 96;    // incident azimuths, midpoints over [0, 2 pi)

// One invocation per (outgoing direction, incident theta): the fibre's scattering summed over the
// incident azimuths, times cos(theta_i) dtheta dphi (dw = cos(theta_i) dtheta dphi), for the
// tangent T = x, V = (sin theta_o, cos theta_o, 0), L = (sin theta_i, cos theta_i cos phi, cos
// theta_i sin phi): the rgb of roughness a (Cycles' 0.3, 0.3) and of roughness b (0.6, 0.85).
const char* kIntegrate = R"(
layout(local_size_x = 32) in;
layout(std430, binding = 0) buffer Out { vec4 result[]; };
uniform vec3 uColor;
uniform int uOutgoing;
uniform float uThetaO[8];
uniform float uAlpha;
void main() {
  uint id = gl_GlobalInvocationID.x;
  int o = int(id) / NTHETA, t = int(id) % NTHETA;
  if (o >= uOutgoing) return;
  float dTheta = kHairPi / float(NTHETA), dPhi = 2.0 * kHairPi / float(NPHI);
  float thetaI = -0.5 * kHairPi + (float(t) + 0.5) * dTheta;
  vec3 T = vec3(1.0, 0.0, 0.0);
  vec3 V = vec3(sin(uThetaO[o]), cos(uThetaO[o]), 0.0);
  vec3 sigmaA = hairSigmaA(uColor, 0.3);
  vec3 sumA = vec3(0.0), sumB = vec3(0.0);
  for (int p = 0; p < NPHI; ++p) {
    float phi = (float(p) + 0.5) * dPhi;
    vec3 L = vec3(sin(thetaI), cos(thetaI) * cos(phi), cos(thetaI) * sin(phi));
    vec3 fa, fb;
    hairScattering(T, L, V, sigmaA, uAlpha, hairRoughness(0.3, 0.3),
                   hairRoughness(0.6, 0.85), fa, fb);
    sumA += fa;
    sumB += fb;
  }
  float w = cos(thetaI) * dTheta * dPhi;
  result[2 * id] = vec4(sumA * w, 0.0);
  result[2 * id + 1] = vec4(sumB * w, 0.0);
}
)";

class HairBsdfTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    context_ = createHeadlessContext();
    program_ = detail::buildProgram(
        "hair_bsdf.glsl's integral",
        {detail::ShaderStage{GL_COMPUTE_SHADER, {"hair_bsdf.glsl"}, kIntegrate}},
        "#define NTHETA " + std::to_string(kTheta) + "\n#define NPHI " + std::to_string(kPhi));
  }
  static void TearDownTestSuite() {
    glDeleteProgram(program_);
    context_.reset();
  }

  // The fibre's scattering integrated over every incident direction, for each outgoing theta:
  // {roughness a, roughness b} per outgoing direction, rgb.
  static std::vector<std::array<std::array<double, 3>, 2>> integrate(
      const std::array<float, 3>& color, const std::vector<float>& thetaO, float alphaDegrees) {
    const int outgoing = static_cast<int>(thetaO.size());
    const int invocations = outgoing * kTheta;
    GLuint buffer = 0;
    glCreateBuffers(1, &buffer);
    glNamedBufferData(buffer, static_cast<GLsizeiptr>(sizeof(float) * 8 * invocations), nullptr,
                      GL_DYNAMIC_READ);
    glUseProgram(program_);
    glUniform3f(glGetUniformLocation(program_, "uColor"), color[0], color[1], color[2]);
    glUniform1i(glGetUniformLocation(program_, "uOutgoing"), outgoing);
    glUniform1f(glGetUniformLocation(program_, "uAlpha"), alphaDegrees * 3.14159265f / 180.0f);
    glUniform1fv(glGetUniformLocation(program_, "uThetaO"), outgoing, thetaO.data());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, buffer);
    glDispatchCompute(static_cast<GLuint>((invocations + 31) / 32), 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<float> raw(static_cast<std::size_t>(8 * invocations));
    glGetNamedBufferSubData(buffer, 0, static_cast<GLsizeiptr>(sizeof(float) * raw.size()),
                            raw.data());
    glDeleteBuffers(1, &buffer);
    std::vector<std::array<std::array<double, 3>, 2>> out(thetaO.size());
    for (int o = 0; o < outgoing; ++o)
      for (int t = 0; t < kTheta; ++t)
        for (int r = 0; r < 2; ++r)
          for (int c = 0; c < 3; ++c)
            out[static_cast<std::size_t>(o)][static_cast<std::size_t>(r)]
               [static_cast<std::size_t>(c)] +=
                raw[static_cast<std::size_t>(8 * (o * kTheta + t) + 4 * r + c)];
    return out;
  }

  static std::unique_ptr<GlContext> context_;
  static GLuint program_;
};
std::unique_ptr<GlContext> HairBsdfTest::context_;
GLuint HairBsdfTest::program_ = 0;

TEST_F(HairBsdfTest, ALosslessFibreScattersAllTheLightItMeets) {
  // A white fibre absorbs nothing (sigma_a = 0: Chiang's eq. 9 at c = 1): the attenuations A_p
  // sum to 1 at every offset h (A_3 the geometric series of the rest), each M_p integrates to 1
  // over cos(theta_i) dtheta_i and each N_p to 1 over phi, so the light scattered from every
  // incident direction integrates to 1, at either roughness (the white furnace test of Chiang et
  // al. 2016, sec. 6): within 1 % with an untilted cuticle (0.25 % on llvmpipe: the quadrature).
  // The cuticle's tilt (Cycles' 2 degrees) shifts the lobes in theta_i, which M_p's normalisation
  // does not follow: then within 5 %, as pbrt's own furnace test of this function allows.
  const std::vector<float> thetaO{-1.2f, -0.6f, -0.2f, 0.0f, 0.3f, 0.8f, 1.3f};
  for (const float alpha : {0.0f, 2.0f}) {
    const auto got = integrate({1.0f, 1.0f, 1.0f}, thetaO, alpha);
    for (std::size_t o = 0; o < thetaO.size(); ++o)
      for (std::size_t r = 0; r < 2; ++r) {
        const double e = got[o][r][0];
        std::printf("alpha %.0f, theta_o %+.1f, roughness %s: %.4f\n", alpha, thetaO[o],
                    r == 0 ? "a" : "b", e);
        EXPECT_NEAR(e, 1.0, alpha == 0.0f ? 0.01 : 0.05)
            << "alpha " << alpha << ", theta_o " << thetaO[o] << ", roughness " << r;
        EXPECT_EQ(got[o][r][1], e);  // grey: the channels alike
      }
  }
}

TEST_F(HairBsdfTest, ADarkerFibreScattersLessAndTheRReflectionStays) {
  // Absorbing fibres keep less of what they meet than the lossless one, the darker the colour the
  // less, channel by channel; what is left of a nearly black fibre is its surface's reflection R,
  // the Fresnel reflectance of index 1.55 averaged over the fibre's width (about 0.05 to 0.1 at
  // these angles), which absorption does not touch.
  const std::vector<float> thetaO{0.0f, 0.5f};
  const auto white = integrate({1.0f, 1.0f, 1.0f}, thetaO, 2.0f);
  const auto pale = integrate({0.9f, 0.6f, 0.3f}, thetaO, 2.0f);
  const auto black = integrate({1e-4f, 1e-4f, 1e-4f}, thetaO, 2.0f);
  for (std::size_t o = 0; o < thetaO.size(); ++o) {
    const auto& e = pale[o][0];
    std::printf(
        "theta_o %.1f: colour (0.9, 0.6, 0.3) keeps %.3f %.3f %.3f of white's %.3f, "
        "black %.3f\n",
        thetaO[o], e[0], e[1], e[2], white[o][0][0], black[o][0][0]);
    EXPECT_LT(e[0], white[o][0][0]);
    EXPECT_GT(e[0], e[1]);
    EXPECT_GT(e[1], e[2]);
    EXPECT_GT(e[2], black[o][0][0]);
    EXPECT_GT(black[o][0][0], 0.03);
    EXPECT_LT(black[o][0][0], 0.12);
  }
}

}  // namespace
}  // namespace pelage::render
