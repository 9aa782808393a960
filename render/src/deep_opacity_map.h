// The fur's self-shadow: deep opacity maps (Yuksel and Keyser 2008). Private to the renderer: its
// targets, programs and the pass that draws the hairs seen from the light into them.
#pragma once

#include <array>
#include <cstdint>

#include "gl_program.h"
#include "pelage/render/hair_vertex_buffers.h"
#include "pelage/scene/draw_list.h"
#include "render_helpers.h"

namespace pelage::render::detail {

class DeepOpacityMap {
 public:
  DeepOpacityMap();  // compiles its programs (needs the current context)

  // The drawn hairs of `list` (in `coats`, the frame's vertex buffers) seen from the light: their
  // nearest depth (drawn with `depthProgram`), then their opacity added into four layers beyond it
  // (deep_opacity.frag), low-passed; binds texture units 5 (the depth) and 6 (the layers) for the
  // lighting (lighting.glsl furTransmittance). `anyVao` is bound for the full-screen pass.
  void draw(const scene::DrawList& list, const LightFrame& light, GLuint depthProgram,
            std::array<HairVertexBuffers, 2>& coats, GLuint anyVao);

 private:
  void ensure(int size);

  Program opacityProgram_, blurProgram_;
  Framebuffer hairDepthFbo_, opacityFbo_, blurFbo_;
  Texture hairDepth_, opacityMap_, opacityBlurred_, hairDepthBlurred_;
  int size_ = 0;
};

}  // namespace pelage::render::detail
