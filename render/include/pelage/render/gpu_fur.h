// GPU fur: the per-frame work of the fur model (Van Gelder & Wilhelms 1997, sec. 3.2 to 3.8:
// interpolation at the root, weightless direction, gravity, each style's geometry; and sec. 3.3
// distance culling) in compute shaders, reading the roots (uploaded once per root set) and the
// deformed skin (uploaded each frame) from shader-storage buffers, writing the vertex buffers the
// renderer draws. The shaders mirror fur/hair_math.h function for function
// (shaders/hair_math.glsl).
//
// Random numbers: nothing random is computed on the GPU. Every random value of the CPU model is
// already a per-root or per-table-entry constant there (CoatRoots::jitter: the hair-end offset and
// helix phase; the barycentric table; the polyline twist table) or a per-triangle constant (the
// culling u_t), so the GPU reads the very same floats, uploaded once: exact parity of the random
// inputs by construction, no 64-bit integer maths (GL_ARB_gpu_shader_int64 is optional), and
// 20 bytes per root, which the CPU model keeps anyway.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "pelage/fur/colors.h"
#include "pelage/fur/fur_params.h"
#include "pelage/fur/hair_layout.h"
#include "pelage/fur/roots.h"
#include "pelage/render/gl.h"
#include "pelage/scene/draw_list.h"
#include "pelage/skin/deform.h"
#include "pelage/skin/skin_mesh.h"

namespace pelage::render {

class HairVertexBuffers;

struct GpuFurOptions {
  // Largest byte range bound to one shader-storage binding; 0 = GL_MAX_SHADER_STORAGE_BLOCK_SIZE
  // (128 MiB on llvmpipe). Outputs and root inputs are split into chunks/windows below it. Tests
  // lower it to exercise the splitting.
  std::int64_t maxBindingBytes = 0;
  // Work groups per dispatch dimension before a dispatch becomes 2-D (llvmpipe's limit is 65535;
  // tests lower it to exercise the 2-D path).
  int maxGroupsPerDimension = 65535;
};

// What one frame of GPU fur reads.
struct GpuFurFrame {
  // The fur, its roots (re-uploaded when their generation changes), colours, clump centres, the
  // skin and its deformation (whose segment directions beginFrame uploads): the draw list's.
  scene::GpuFurInputs inputs;
  GLuint skinPositions = 0;  // the deformed positions and normals already on the GPU (nV x 3)
  GLuint skinNormals = 0;
  float cullFactor = 1.0f;  // c of sec. 3.3 (1: every hair)
};

class GpuFur {
 public:
  explicit GpuFur(const GpuFurOptions& options = {});
  ~GpuFur();
  GpuFur(const GpuFur&) = delete;
  GpuFur& operator=(const GpuFur&) = delete;

  // Uploads what changed: the roots (when their generation changes), the twist tables (when a
  // coat's normal randomize changes) and, every frame, the skin's segment directions.
  void beginFrame(const GpuFurFrame& frame);
  // Regenerates coat `coat` into `out` (sized for every root of the coat) with `layout` (the coat's
  // style's: scene::FurDrawItem's): the drawn hairs' points and shading vectors (the style's
  // normals, or unit tangents when `tangents`), and the indirect draw commands. No CPU-GPU
  // synchronisation.
  void generate(int coat, const fur::HairLayout& layout, bool tangents, HairVertexBuffers& out);

  // Dispatches of the last generate() call (windows x chunks, for tests of the splitting).
  int lastDispatches() const { return lastDispatches_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  int lastDispatches_ = 0;
};

}  // namespace pelage::render
