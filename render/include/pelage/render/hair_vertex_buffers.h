// GPU buffers holding one coat's hair points for drawing: positions and shading vectors (3 floats
// per point, tightly packed, hair i's points at [i*P, (i+1)*P) as the CPU fur model writes them), a
// static index pattern (fur::hairIndexPattern: line strips with primitive restart, or the
// triangles between rings) and indirect draw
// commands. Filled either by uploading the CPU fur model's buffers or by the GPU fur pass.
//
// The buffers are split into chunks of whole hairs, each at most maxShaderStorageBlockSize bytes
// per array, because llvmpipe lets one shader-storage binding address only 128 MiB: the GPU pass
// writes each chunk through its own bound range, and each chunk is drawn by its own indirect
// command (baseVertex = the chunk's first point), so any hair count works on any driver.
#pragma once

#include <cstdint>
#include <vector>

#include "pelage/fur/hair_layout.h"
#include "pelage/render/gl.h"

namespace pelage::render {

// The layout of one hair's points (strand points, rings, topology) is fur::HairLayout.
using fur::HairLayout;

// One chunk: hairs [firstHair, firstHair + capacity) of the coat's slots.
struct HairChunk {
  std::int64_t firstHair = 0;
  std::int64_t capacity = 0;
};

// DrawElementsIndirectCommand (GL 4.0 indirect draw layout).
struct DrawCommand {
  std::uint32_t count = 0;
  std::uint32_t instanceCount = 1;
  std::uint32_t firstIndex = 0;
  std::int32_t baseVertex = 0;
  std::uint32_t baseInstance = 0;
};

class HairVertexBuffers {
 public:
  HairVertexBuffers();
  ~HairVertexBuffers();
  HairVertexBuffers(const HairVertexBuffers&) = delete;
  HairVertexBuffers& operator=(const HairVertexBuffers&) = delete;

  // Makes room for `hairs` hairs of `layout` (grows, never shrinks, unless the layout changes);
  // `maxChunkBytes` caps one chunk's array size (0 = the context's
  // GL_MAX_SHADER_STORAGE_BLOCK_SIZE).
  void reserve(std::int64_t hairs, const HairLayout& layout, std::int64_t maxChunkBytes = 0);
  // Uploads `hairs` hairs from CPU arrays (hairs * P * 3 floats each) and sets the draw commands.
  void upload(const float* positions, const float* shading, std::int64_t hairs);
  // Uploads `hairs` hairs' root and tip colours (2 packed values each, fur/colors.h).
  void uploadColors(const std::uint32_t* colors, std::int64_t hairs);
  // Reads back the drawn hairs' colours in hair order (tests: GPU/CPU parity). Uses the commands.
  void readBackColors(std::vector<std::uint32_t>& colors) const;

  // Reads back the drawn hairs' points in hair order (tests: GPU/CPU parity). Uses the commands.
  void readBack(std::vector<float>& positions, std::vector<float>& shading) const;
  // Hairs the current commands draw (reads the command buffer back; for tests and statistics).
  std::int64_t drawnHairsOnGpu() const;
  // Draws every `stride`-th of the first `hairs` hair slots (hairs 0, stride, 2 stride, ...: a
  // uniform subsample of the drawn hairs, which fill the slots from the first) with the bound
  // program, as GL `mode` primitives: for passes that estimate the coat's density (the deep
  // opacity map). Builds its strided index pattern on first use of a stride > 1.
  void drawEvery(int stride, std::int64_t hairs, GLenum mode);

  const HairLayout& layout() const { return layout_; }
  const std::vector<HairChunk>& chunks() const { return chunks_; }
  std::int64_t capacity() const { return capacity_; }
  GLuint positions() const { return positions_; }
  GLuint shading() const { return shading_; }
  // Per hair slot, its root and tip colour (8 bytes; written by uploadColors or the GPU pass), and
  // the same as a GL_RG32UI texture buffer the hair vertex shader reads.
  GLuint colors() const { return colors_; }
  GLuint colorTexture() const { return colorTexture_; }
  GLuint indices() const { return indices_; }
  GLuint commands() const { return commands_; }
  GLuint vertexArray() const { return vao_; }

 private:
  HairLayout layout_;
  std::int64_t capacity_ = 0;
  std::int64_t indexCapacity_ = 0;
  std::int64_t maxChunkBytes_ = 0;  // hairs the index pattern covers (the largest chunk)
  std::vector<HairChunk> chunks_;
  std::vector<DrawCommand> commandScratch_;
  GLuint positions_ = 0, shading_ = 0, indices_ = 0, commands_ = 0, vao_ = 0;
  GLuint strided_ = 0;  // drawEvery's index pattern for strideOf_ > 1 (stride 1: indices_)
  int strideOf_ = 0;
  void releaseStrided();
  GLuint colors_ = 0, colorTexture_ = 0;
};

// Unit tangents along each strand (Kajiya-Kay's T) of `hairs` hairs of `layout` from their points
// (hairs * P * 3 floats): the direction of the segment leaving each point, the last point repeating
// the one arriving. The GPU fur pass computes the same for its hairs.
void strandTangents(const float* positions, std::int64_t hairs, const HairLayout& layout,
                    std::vector<float>& out);

// The largest size in bytes one shader-storage binding may address on this context.
std::int64_t maxShaderStorageBlockSize();

}  // namespace pelage::render
