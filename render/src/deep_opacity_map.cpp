#include "deep_opacity_map.h"

#include <algorithm>

#include "pelage/util/error.h"

namespace pelage::render::detail {
namespace {

// The opacity map draws at most about kOpacityMapHairs hairs of a coat: every stride-th drawn
// hair, each adding the opacity of the stride hairs it stands for (the map estimates the coat's
// density over texels of millimetres, read low-passed; a uniform subsample weighted so gives the
// same expected opacity, as culling's widened hairs do on screen). Drawing hairs is what the map
// costs on a software rasteriser (about 100 ms for 32,768 polylines on llvmpipe, 2 cores).
constexpr std::int64_t kOpacityMapHairs = 32768;

int opacityStride(const scene::FurDrawItem& f) {
  return static_cast<int>(
      std::max<std::int64_t>(1, (f.drawnHairs + kOpacityMapHairs - 1) / kOpacityMapHairs));
}

void drawOpacityHairs(const scene::FurDrawItem& f, HairVertexBuffers& b, GLuint program) {
  if (b.capacity() == 0) return;
  glUseProgram(program);
  setInt(program, "uPointsPerStrand", b.layout().strandPoints);
  setInt(program, "uStrandStride", b.layout().ringSides);
  b.drawEvery(opacityStride(f), f.drawnHairs, primitive(b.layout()));
}

}  // namespace

DeepOpacityMap::DeepOpacityMap() {
  opacityProgram_.reset(buildProgram(
      "deep opacity", {ShaderStage{GL_VERTEX_SHADER, {"color.glsl", "deep_opacity.vert"}},
                       ShaderStage{GL_FRAGMENT_SHADER, {"deep_opacity.frag"}}}));
  blurProgram_.reset(buildProgram("deep opacity low-pass",
                                  {ShaderStage{GL_VERTEX_SHADER, {"oit_composite.vert"}},
                                   ShaderStage{GL_FRAGMENT_SHADER, {"opacity_blur.frag"}}}));
}

// The targets (size x size): the hairs' nearest depth from the light (z0) and the four opacity
// layers (RGBA16F, additive).
void DeepOpacityMap::ensure(int size) {
  if (size_ == size && opacityMap_) return;
  size_ = size;
  // z0 unfiltered (a texel with no hair is 1: mixing it in would move the layers); the layers
  // with one mipmap level, low-passed into a half-size map read bilinear.
  const int half = size / 2;
  hairDepth_ = makeTexture(GL_DEPTH_COMPONENT32F, 1, size, size, GL_NEAREST, GL_NEAREST);
  opacityMap_ = makeTexture(GL_RGBA16F, 2, size, size, GL_LINEAR_MIPMAP_LINEAR, GL_LINEAR);
  opacityBlurred_ = makeTexture(GL_RGBA16F, 1, half, half, GL_LINEAR, GL_LINEAR);
  hairDepthBlurred_ = makeTexture(GL_R32F, 1, half, half, GL_LINEAR, GL_LINEAR);
  GLuint id = 0;
  glCreateFramebuffers(1, &id);
  hairDepthFbo_.reset(id);
  glNamedFramebufferTexture(id, GL_DEPTH_ATTACHMENT, hairDepth_.get(), 0);
  glNamedFramebufferDrawBuffer(id, GL_NONE);
  glCreateFramebuffers(1, &id);
  opacityFbo_.reset(id);
  glNamedFramebufferTexture(id, GL_COLOR_ATTACHMENT0, opacityMap_.get(), 0);
  glCreateFramebuffers(1, &id);
  blurFbo_.reset(id);
  glNamedFramebufferTexture(id, GL_COLOR_ATTACHMENT0, opacityBlurred_.get(), 0);
  glNamedFramebufferTexture(id, GL_COLOR_ATTACHMENT1, hairDepthBlurred_.get(), 0);
  const GLenum both[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
  glNamedFramebufferDrawBuffers(id, 2, both);
  for (GLuint fb : {hairDepthFbo_.get(), opacityFbo_.get(), blurFbo_.get()})
    PELAGE_CHECK(glCheckNamedFramebufferStatus(fb, GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE,
                 "deep opacity framebuffer incomplete");
}

// Deep opacity maps (Yuksel and Keyser 2008; deep_opacity.frag): the drawn hairs' depth from the
// light, then their opacity added into four layers beyond it, bound for the lighting
// (lighting.glsl furTransmittance).
void DeepOpacityMap::draw(const scene::DrawList& list, const LightFrame& light, GLuint depthProgram,
                          std::array<HairVertexBuffers, 2>& coats, GLuint anyVao) {
  const auto buffers = [&](const scene::FurDrawItem& f) -> HairVertexBuffers& {
    return coats[static_cast<std::size_t>(f.coat)];
  };
  ensure(std::clamp(list.light.opacityMapSize, 64, 4096));
  glViewport(0, 0, size_, size_);
  glBindFramebuffer(GL_FRAMEBUFFER, hairDepthFbo_.get());
  glClear(GL_DEPTH_BUFFER_BIT);
  setMatrix(depthProgram, "uViewProj", light.viewProj);
  for (const scene::FurDrawItem& f : list.fur) drawOpacityHairs(f, buffers(f), depthProgram);

  glBindFramebuffer(GL_FRAMEBUFFER, opacityFbo_.get());
  const float zero[4] = {0, 0, 0, 0};
  glClearNamedFramebufferfv(opacityFbo_.get(), GL_COLOR, 0, zero);
  glDisable(GL_DEPTH_TEST);
  glEnable(GL_BLEND);
  glBlendFunc(GL_ONE, GL_ONE);
  glBindTextureUnit(5, hairDepth_.get());
  const GLuint p = opacityProgram_.get();
  setMatrix(p, "uViewProj", light.viewProj);
  glProgramUniform4fv(p, uniform(p, "uLayers"), 1, light.layerEnds.data());
  setFloat(p, "uDepthScale", light.depthScale);
  setFloat(p, "uTexelMeters", light.extent / static_cast<float>(size_));
  setFloat(p, "uFibreOpacity", light.fibreOpacity);
  for (const scene::FurDrawItem& f : list.fur) {
    setFloat(p, "uRootWidth", f.width.metersAt(0.0f));
    setFloat(p, "uTipWidth", f.width.metersAt(1.0f));
    setFloat(p, "uWiden", std::max(f.cullFactor, 1.0f));
    setFloat(p, "uStandsFor", static_cast<float>(opacityStride(f)));
    setInt(p, "uPerHairWidth", f.perHairWidth ? 1 : 0);
    glBindTextureUnit(1, buffers(f).colorTexture());
    drawOpacityHairs(f, buffers(f), p);
  }
  glDisable(GL_BLEND);
  glGenerateTextureMipmap(opacityMap_.get());
  glBindFramebuffer(GL_FRAMEBUFFER, blurFbo_.get());
  glViewport(0, 0, size_ / 2, size_ / 2);
  glBindTextureUnit(7, opacityMap_.get());
  glUseProgram(blurProgram_.get());
  glBindVertexArray(anyVao);  // any VAO: the triangle comes from gl_VertexID
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glEnable(GL_DEPTH_TEST);
  glBindTextureUnit(5, hairDepthBlurred_.get());
  glBindTextureUnit(6, opacityBlurred_.get());
}

}  // namespace pelage::render::detail
