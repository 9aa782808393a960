#include "pelage/render/hair_vertex_buffers.h"

#include <algorithm>
#include <cstring>

#include <Eigen/Core>

#include "pelage/util/error.h"

namespace pelage::render {
namespace {

constexpr std::uint32_t kRestart = 0xFFFFFFFFu;  // GL_PRIMITIVE_RESTART_FIXED_INDEX for uint

void deleteAll(GLuint& a, GLuint& b, GLuint& c, GLuint& d) {
  for (GLuint* id : {&a, &b, &c, &d})
    if (*id) {
      glDeleteBuffers(1, id);
      *id = 0;
    }
}

// An index buffer of hairs 0, stride, 2 stride, ... below `hairs` of `layout`: each one's pattern
// (fur::hairIndexPattern) offset by its first point.
GLuint stridedIndices(const fur::HairLayout& layout, std::int64_t hairs, int stride) {
  const std::int64_t P = layout.pointsPerHair();
  const int perHair = layout.indicesPerHair();
  const std::vector<std::uint32_t> pattern = fur::hairIndexPattern(layout, kRestart);
  const std::int64_t n = (hairs + stride - 1) / stride;
  std::vector<std::uint32_t> indices(static_cast<std::size_t>(n * perHair));
  for (std::int64_t j = 0; j < n; ++j)
    for (int i = 0; i < perHair; ++i) {
      const std::uint32_t v = pattern[static_cast<std::size_t>(i)];
      indices[static_cast<std::size_t>(j * perHair + i)] =
          v == kRestart ? kRestart : static_cast<std::uint32_t>(j * stride * P) + v;
    }
  GLuint id = 0;
  glCreateBuffers(1, &id);
  glNamedBufferStorage(id, static_cast<GLsizeiptr>(indices.size() * sizeof(std::uint32_t)),
                       indices.data(), 0);
  return id;
}

}  // namespace

std::int64_t maxShaderStorageBlockSize() {
  GLint64 v = 0;
  glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &v);
  return v > 0 ? static_cast<std::int64_t>(v) : std::int64_t{1} << 27;
}

HairVertexBuffers::HairVertexBuffers() {
  glCreateVertexArrays(1, &vao_);
}

HairVertexBuffers::~HairVertexBuffers() {
  deleteAll(positions_, shading_, indices_, commands_);
  releaseStrided();
  if (colors_) glDeleteBuffers(1, &colors_);
  if (colorTexture_) glDeleteTextures(1, &colorTexture_);
  glDeleteVertexArrays(1, &vao_);
}

void HairVertexBuffers::reserve(std::int64_t hairs, const HairLayout& layout,
                                std::int64_t maxChunkBytes) {
  PELAGE_CHECK(hairs >= 0 && layout.strandPoints >= 2 && layout.ringSides >= 1);
  if (maxChunkBytes <= 0) maxChunkBytes = maxShaderStorageBlockSize();
  const bool layoutChanged = !(layout == layout_) || maxChunkBytes != maxChunkBytes_;
  if (!layoutChanged && hairs <= capacity_ && positions_ != 0) return;
  maxChunkBytes_ = maxChunkBytes;
  const std::int64_t P = layout.pointsPerHair();
  const std::int64_t bytesPerHair = P * 3 * static_cast<std::int64_t>(sizeof(float));
  GLint align = 16;
  glGetIntegerv(GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT, &align);
  // Whole hairs per chunk, a multiple of `align` hairs so every chunk's byte offset is aligned.
  std::int64_t perChunk = maxChunkBytes / bytesPerHair;
  perChunk -= perChunk % std::max<std::int64_t>(align, 1);
  PELAGE_CHECK(perChunk > 0, "a chunk of ", maxChunkBytes, " bytes cannot hold ", align, " hairs");
  // Grow with headroom so that small increases of the hair count do not reallocate every time.
  const std::int64_t capacity =
      std::max<std::int64_t>(layoutChanged ? hairs : hairs + hairs / 4, 1);

  deleteAll(positions_, shading_, indices_, commands_);
  releaseStrided();
  if (colors_) glDeleteBuffers(1, &colors_);
  if (colorTexture_) glDeleteTextures(1, &colorTexture_);
  colors_ = colorTexture_ = 0;
  layout_ = layout;
  capacity_ = capacity;
  chunks_.clear();
  for (std::int64_t first = 0; first < capacity; first += perChunk)
    chunks_.push_back({first, std::min(perChunk, capacity - first)});

  const auto bytes = static_cast<GLsizeiptr>(capacity * bytesPerHair);
  glCreateBuffers(1, &positions_);
  glNamedBufferStorage(positions_, bytes, nullptr, GL_DYNAMIC_STORAGE_BIT);
  glCreateBuffers(1, &shading_);
  glNamedBufferStorage(shading_, bytes, nullptr, GL_DYNAMIC_STORAGE_BIT);
  GLint maxTexels = 0;
  glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &maxTexels);
  PELAGE_CHECK(capacity <= maxTexels, capacity, " hairs exceed the texture buffer limit of ",
               maxTexels, " (GL_MAX_TEXTURE_BUFFER_SIZE)");
  glCreateBuffers(1, &colors_);
  glNamedBufferStorage(colors_, static_cast<GLsizeiptr>(capacity * 8), nullptr,
                       GL_DYNAMIC_STORAGE_BIT);
  glCreateTextures(GL_TEXTURE_BUFFER, 1, &colorTexture_);
  glTextureBuffer(colorTexture_, GL_RG32UI, colors_);

  // The index pattern of one hair, repeated for the largest chunk; chunks reuse it through
  // baseVertex, so the indices stay below 2^32 whatever the total hair count.
  indexCapacity_ = chunks_.front().capacity;
  indices_ = stridedIndices(layout, indexCapacity_, 1);
  glCreateBuffers(1, &commands_);
  const std::vector<DrawCommand> zero(chunks_.size());
  glNamedBufferStorage(commands_, static_cast<GLsizeiptr>(zero.size() * sizeof(DrawCommand)),
                       zero.data(), GL_DYNAMIC_STORAGE_BIT);

  glVertexArrayVertexBuffer(vao_, 0, positions_, 0, 3 * sizeof(float));
  glVertexArrayVertexBuffer(vao_, 1, shading_, 0, 3 * sizeof(float));
  for (GLuint a : {0u, 1u}) {
    glEnableVertexArrayAttrib(vao_, a);
    glVertexArrayAttribFormat(vao_, a, 3, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(vao_, a, a);
  }
  glVertexArrayElementBuffer(vao_, indices_);
}

void HairVertexBuffers::upload(const float* positions, const float* shading, std::int64_t hairs) {
  PELAGE_CHECK(hairs <= capacity_, hairs, " hairs > capacity ", capacity_);
  const std::int64_t P = layout_.pointsPerHair();
  const std::int64_t bytes = hairs * P * 3 * static_cast<std::int64_t>(sizeof(float));
  if (bytes > 0) {
    glNamedBufferSubData(positions_, 0, static_cast<GLsizeiptr>(bytes), positions);
    glNamedBufferSubData(shading_, 0, static_cast<GLsizeiptr>(bytes), shading);
  }
  std::vector<DrawCommand>& cmds = commandScratch_;
  cmds.assign(chunks_.size(), DrawCommand{});
  for (std::size_t c = 0; c < chunks_.size(); ++c) {
    const std::int64_t n =
        std::clamp<std::int64_t>(hairs - chunks_[c].firstHair, 0, chunks_[c].capacity);
    cmds[c].count = static_cast<std::uint32_t>(n * layout_.indicesPerHair());
    cmds[c].baseVertex = static_cast<std::int32_t>(chunks_[c].firstHair * P);
  }
  glNamedBufferSubData(commands_, 0, static_cast<GLsizeiptr>(cmds.size() * sizeof(DrawCommand)),
                       cmds.data());
}

void HairVertexBuffers::uploadColors(const std::uint32_t* colors, std::int64_t hairs) {
  PELAGE_CHECK(hairs <= capacity_, hairs, " hairs > capacity ", capacity_);
  if (hairs > 0) glNamedBufferSubData(colors_, 0, static_cast<GLsizeiptr>(hairs * 8), colors);
}

void HairVertexBuffers::readBackColors(std::vector<std::uint32_t>& colors) const {
  std::vector<DrawCommand> cmds(chunks_.size());
  glGetNamedBufferSubData(commands_, 0, static_cast<GLsizeiptr>(cmds.size() * sizeof(DrawCommand)),
                          cmds.data());
  colors.clear();
  for (std::size_t c = 0; c < chunks_.size(); ++c) {
    const std::int64_t n = cmds[c].count / static_cast<std::uint32_t>(layout_.indicesPerHair());
    const std::size_t at = colors.size();
    colors.resize(at + static_cast<std::size_t>(2 * n));
    if (n > 0)
      glGetNamedBufferSubData(colors_, chunks_[c].firstHair * 8, static_cast<GLsizeiptr>(n * 8),
                              colors.data() + at);
  }
}

std::int64_t HairVertexBuffers::drawnHairsOnGpu() const {
  std::vector<DrawCommand> cmds(chunks_.size());
  glGetNamedBufferSubData(commands_, 0, static_cast<GLsizeiptr>(cmds.size() * sizeof(DrawCommand)),
                          cmds.data());
  std::int64_t n = 0;
  for (const DrawCommand& c : cmds)
    n += c.count / static_cast<std::uint32_t>(layout_.indicesPerHair());
  return n;
}

void HairVertexBuffers::readBack(std::vector<float>& positions, std::vector<float>& shading) const {
  std::vector<DrawCommand> cmds(chunks_.size());
  glGetNamedBufferSubData(commands_, 0, static_cast<GLsizeiptr>(cmds.size() * sizeof(DrawCommand)),
                          cmds.data());
  const std::int64_t P = layout_.pointsPerHair();
  positions.clear();
  shading.clear();
  for (std::size_t c = 0; c < chunks_.size(); ++c) {
    const std::int64_t n = cmds[c].count / static_cast<std::uint32_t>(layout_.indicesPerHair());
    const std::int64_t floats = n * P * 3;
    const std::int64_t offset =
        chunks_[c].firstHair * P * 3 * static_cast<std::int64_t>(sizeof(float));
    const std::size_t at = positions.size();
    positions.resize(at + static_cast<std::size_t>(floats));
    shading.resize(at + static_cast<std::size_t>(floats));
    if (floats == 0) continue;
    glGetNamedBufferSubData(positions_, offset, static_cast<GLsizeiptr>(floats * 4),
                            positions.data() + at);
    glGetNamedBufferSubData(shading_, offset, static_cast<GLsizeiptr>(floats * 4),
                            shading.data() + at);
  }
}

void strandTangents(const float* positions, std::int64_t hairs, const HairLayout& layout,
                    std::vector<float>& out) {
  const int K = layout.strandPoints, M = layout.ringSides, P = layout.pointsPerHair();
  out.resize(static_cast<std::size_t>(hairs * P * 3));
  for (std::int64_t h = 0; h < hairs; ++h) {
    const float* p = positions + h * P * 3;
    float* t = out.data() + h * P * 3;
    for (int k = 0; k < K; ++k)
      for (int m = 0; m < M; ++m) {
        const int a = (k + 1 < K ? k : k - 1) * M + m, b = a + M;
        Eigen::Vector3f d(p[3 * b] - p[3 * a], p[3 * b + 1] - p[3 * a + 1],
                          p[3 * b + 2] - p[3 * a + 2]);
        const float len = d.norm();
        d = len > 0.0f ? Eigen::Vector3f(d / len) : Eigen::Vector3f::UnitZ();
        float* o = t + (k * M + m) * 3;
        o[0] = d.x();
        o[1] = d.y();
        o[2] = d.z();
      }
  }
}

void HairVertexBuffers::drawEvery(int stride, std::int64_t hairs, GLenum mode) {
  PELAGE_CHECK(stride >= 1 && hairs >= 0 && hairs <= capacity_);
  if (positions_ == 0 || hairs == 0) return;
  if (stride > 1 && stride != strideOf_) {
    releaseStrided();
    strided_ = stridedIndices(layout_, indexCapacity_, stride);
    strideOf_ = stride;
  }
  const std::int64_t P = layout_.pointsPerHair();
  glVertexArrayElementBuffer(vao_, stride > 1 ? strided_ : indices_);
  glBindVertexArray(vao_);
  for (const HairChunk& c : chunks_) {
    const std::int64_t n = std::clamp<std::int64_t>(hairs - c.firstHair, 0, c.capacity);
    const std::int64_t m = (n + stride - 1) / stride;
    if (m > 0)
      glDrawElementsBaseVertex(mode, static_cast<GLsizei>(m * layout_.indicesPerHair()),
                               GL_UNSIGNED_INT, nullptr, static_cast<GLint>(c.firstHair * P));
  }
  glVertexArrayElementBuffer(vao_, indices_);
}

void HairVertexBuffers::releaseStrided() {
  if (strided_) glDeleteBuffers(1, &strided_);
  strided_ = 0;
  strideOf_ = 0;
}

}  // namespace pelage::render
