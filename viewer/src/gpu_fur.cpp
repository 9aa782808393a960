#include "pelage/viewer/gpu_fur.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstring>

#include "gl_program.h"
#include "pelage/fur/generate.h"
#include "pelage/fur/hair_math.h"
#include "pelage/util/error.h"
#include "pelage/util/random.h"
#include "pelage/viewer/hair_vertex_buffers.h"

namespace pelage::viewer {

using detail::Buffer;
using detail::Program;
using detail::uniform;

namespace {

// fur::CoatShape packed as the std430 block CoatShapeBlock of hair_math.glsl: only 4-byte scalars
// and arrays of them, so std430 puts every member at its C++ offset (checked against the linked
// program in checkShapeLayout).
struct GpuCoatShape {
  std::int32_t style, points, curvePoints, tubeSides;
  std::int32_t twist, curl, regionShape, pad0;
  float lengthMul, segmentWeight, endRandomize, floppiness;
  float up[3];
  float fallbackTangent[3];
  float regionCenter[3];
  float regionRadius2;
  float regionMin[3];
  float regionMax[3];
  float regionScale;
  float curlRadius;
  float polyA[fur::kPolylinePoints], polyB[fur::kPolylinePoints];
  float polyAlpha[fur::kPolylinePoints], polyBeta[fur::kPolylinePoints];
  float curveC1[fur::kMaxCurvePoints], curveC2[fur::kMaxCurvePoints];
  float curveDc1[fur::kMaxCurvePoints], curveDc2[fur::kMaxCurvePoints];
  float curlEnvelope[fur::kMaxCurvePoints], curlCos[fur::kMaxCurvePoints],
      curlSin[fur::kMaxCurvePoints];
  float tubeRadius[fur::kMaxCurvePoints];
  float ringCos[fur::kMaxTubeSides], ringSin[fur::kMaxTubeSides];
};

GpuCoatShape pack(const fur::CoatShape& c) {
  GpuCoatShape g{};
  g.style = static_cast<std::int32_t>(c.style);
  g.points = c.points;
  g.curvePoints = c.curvePoints;
  g.tubeSides = c.tubeSides;
  g.twist = c.twist ? 1 : 0;
  g.curl = c.curl ? 1 : 0;
  g.regionShape = static_cast<std::int32_t>(c.regionShape);
  g.lengthMul = c.lengthMul;
  g.segmentWeight = c.segmentWeight;
  g.endRandomize = c.endRandomize;
  g.floppiness = c.floppiness;
  std::memcpy(g.up, c.up, sizeof g.up);
  std::memcpy(g.fallbackTangent, c.fallbackTangent, sizeof g.fallbackTangent);
  std::memcpy(g.regionCenter, c.regionCenter, sizeof g.regionCenter);
  g.regionRadius2 = c.regionRadius2;
  std::memcpy(g.regionMin, c.regionMin, sizeof g.regionMin);
  std::memcpy(g.regionMax, c.regionMax, sizeof g.regionMax);
  g.regionScale = c.regionScale;
  g.curlRadius = c.curlRadius;
  std::memcpy(g.polyA, c.polyA, sizeof g.polyA);
  std::memcpy(g.polyB, c.polyB, sizeof g.polyB);
  std::memcpy(g.polyAlpha, c.polyAlpha, sizeof g.polyAlpha);
  std::memcpy(g.polyBeta, c.polyBeta, sizeof g.polyBeta);
  std::memcpy(g.curveC1, c.curveC1, sizeof g.curveC1);
  std::memcpy(g.curveC2, c.curveC2, sizeof g.curveC2);
  std::memcpy(g.curveDc1, c.curveDc1, sizeof g.curveDc1);
  std::memcpy(g.curveDc2, c.curveDc2, sizeof g.curveDc2);
  std::memcpy(g.curlEnvelope, c.curlEnvelope, sizeof g.curlEnvelope);
  std::memcpy(g.curlCos, c.curlCos, sizeof g.curlCos);
  std::memcpy(g.curlSin, c.curlSin, sizeof g.curlSin);
  std::memcpy(g.tubeRadius, c.tubeRadius, sizeof g.tubeRadius);
  std::memcpy(g.ringCos, c.ringCos, sizeof g.ringCos);
  std::memcpy(g.ringSin, c.ringSin, sizeof g.ringSin);
  return g;
}

// The std430 offsets the driver gave CoatShapeBlock must be the C++ offsets of GpuCoatShape.
void checkShapeLayout(GLuint program) {
  struct Member {
    const char* name;
    std::size_t offset;
  };
  const Member members[] = {
      {"CoatShapeBlock.style", offsetof(GpuCoatShape, style)},
      {"CoatShapeBlock.lengthMul", offsetof(GpuCoatShape, lengthMul)},
      {"CoatShapeBlock.up[0]", offsetof(GpuCoatShape, up)},
      {"CoatShapeBlock.regionRadius2", offsetof(GpuCoatShape, regionRadius2)},
      {"CoatShapeBlock.curlRadius", offsetof(GpuCoatShape, curlRadius)},
      {"CoatShapeBlock.polyA[0]", offsetof(GpuCoatShape, polyA)},
      {"CoatShapeBlock.polyBeta[0]", offsetof(GpuCoatShape, polyBeta)},
      {"CoatShapeBlock.curveC1[0]", offsetof(GpuCoatShape, curveC1)},
      {"CoatShapeBlock.tubeRadius[0]", offsetof(GpuCoatShape, tubeRadius)},
      {"CoatShapeBlock.ringSin[0]", offsetof(GpuCoatShape, ringSin)},
  };
  for (const Member& m : members) {
    const GLuint index = glGetProgramResourceIndex(program, GL_BUFFER_VARIABLE, m.name);
    if (index == GL_INVALID_INDEX) continue;  // not used by this program: optimised away
    const GLenum prop = GL_OFFSET;
    GLint offset = -1;
    glGetProgramResourceiv(program, GL_BUFFER_VARIABLE, index, 1, &prop, 1, nullptr, &offset);
    PELAGE_CHECK(offset == static_cast<GLint>(m.offset), "GLSL ", m.name, " at offset ", offset,
                 ", C++ at ", m.offset);
  }
}

Buffer makeBuffer(GLsizeiptr bytes, const void* data) {
  Buffer b = detail::createBuffer();
  glNamedBufferStorage(b.get(), std::max<GLsizeiptr>(bytes, 16), nullptr, GL_DYNAMIC_STORAGE_BIT);
  if (data && bytes > 0) glNamedBufferSubData(b.get(), 0, bytes, data);
  return b;
}

// Dispatches ceil(items / perGroup) groups, as a 2-D grid when there are more than maxPerDimension
// (GL guarantees 65535 per dimension); the shaders linearise (y * numGroups.x + x).
void dispatch1d(std::int64_t items, std::int64_t perGroup, std::int64_t maxPerDimension) {
  const std::int64_t groups = (items + perGroup - 1) / perGroup;
  if (groups <= 0) return;
  const std::int64_t x = std::min<std::int64_t>(groups, maxPerDimension);
  const std::int64_t y = (groups + x - 1) / x;
  glDispatchCompute(static_cast<GLuint>(x), static_cast<GLuint>(y), 1);
}

}  // namespace

struct GpuFur::Impl {
  GpuFurOptions options;
  std::int64_t maxBinding = 0;
  GLint alignment = 16;
  Program hairProgram, cullProgram, scanBlocksProgram, scanAddProgram, commandsProgram;

  // Shared by the coats.
  const skin::SkinMesh* skin = nullptr;
  std::int32_t triangleCount = 0;
  Buffer triangles, lengths, directions, barycentric;
  std::int32_t vertexCount = 0;
  GLuint skinPositions = 0, skinNormals = 0;
  const fur::FurRoots* roots = nullptr;
  const fur::FurParams* params = nullptr;
  std::uint64_t generation = ~std::uint64_t{0};
  float cullFactor = 1.0f;

  struct Coat {
    std::int64_t rootCount = 0;
    Buffer rootData, jitter, triangleStart, drawnStart, cullU, blockSums, twist, shape;
    float twistAmount = -1.0f;
    std::uint64_t twistSeed = 0;
    std::vector<float> twistTable;
  };
  std::array<Coat, fur::kCoatCount> coats;

  explicit Impl(const GpuFurOptions& o) : options(o) {
    maxBinding =
        options.maxBindingBytes > 0 ? options.maxBindingBytes : maxShaderStorageBlockSize();
    PELAGE_CHECK(options.maxGroupsPerDimension >= 1 && options.maxGroupsPerDimension <= 65535,
                 "maxGroupsPerDimension ", options.maxGroupsPerDimension);
    glGetIntegerv(GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT, &alignment);
    using detail::ShaderStage;
    hairProgram.reset(detail::buildProgram(
        "fur hair", {ShaderStage{GL_COMPUTE_SHADER, {"hair_math.glsl", "fur_hair.comp"}}}));
    checkShapeLayout(hairProgram.get());
    cullProgram.reset(
        detail::buildProgram("fur cull", {ShaderStage{GL_COMPUTE_SHADER, {"fur_cull.comp"}}}));
    scanBlocksProgram.reset(detail::buildProgram(
        "fur scan 1", {ShaderStage{GL_COMPUTE_SHADER, {"fur_scan.comp"}}}, "#define PASS 1"));
    scanAddProgram.reset(detail::buildProgram(
        "fur scan 2", {ShaderStage{GL_COMPUTE_SHADER, {"fur_scan.comp"}}}, "#define PASS 2"));
    commandsProgram.reset(detail::buildProgram(
        "fur commands", {ShaderStage{GL_COMPUTE_SHADER, {"fur_commands.comp"}}}));
    static_assert(sizeof(GpuCoatShape) % 4 == 0);
  }

  void uploadSkin(const skin::SkinMesh& s) {
    skin = &s;
    triangleCount = s.numTriangles();
    vertexCount = s.numVertices();
    triangles = makeBuffer(static_cast<GLsizeiptr>(s.triangles.size() * sizeof(std::int32_t)),
                           s.triangles.data());
    lengths = makeBuffer(static_cast<GLsizeiptr>(vertexCount) * 4, s.furLengths());
    directions = makeBuffer(static_cast<GLsizeiptr>(vertexCount) * 12, nullptr);
  }

  void uploadRoots(const fur::FurRoots& r) {
    PELAGE_CHECK(r.triangleCount == triangleCount, "roots grown on ", r.triangleCount,
                 " triangles, skin has ", triangleCount);
    barycentric = makeBuffer(static_cast<GLsizeiptr>(r.barycentric.size() * sizeof(float)),
                             r.barycentric.data());
    for (int c = 0; c < fur::kCoatCount; ++c) {
      const fur::CoatRoots& cr = r.coats[static_cast<std::size_t>(c)];
      Coat& g = coats[static_cast<std::size_t>(c)];
      g.rootCount = cr.size();
      std::vector<std::int32_t> packed(static_cast<std::size_t>(2 * g.rootCount));
      for (std::int64_t j = 0; j < g.rootCount; ++j) {
        packed[static_cast<std::size_t>(2 * j)] = cr.triangle[static_cast<std::size_t>(j)];
        packed[static_cast<std::size_t>(2 * j + 1)] = cr.tableIndex[static_cast<std::size_t>(j)];
      }
      g.rootData = makeBuffer(static_cast<GLsizeiptr>(packed.size() * 4), packed.data());
      g.jitter = makeBuffer(static_cast<GLsizeiptr>(cr.jitter.size() * 4), cr.jitter.data());
      g.triangleStart =
          makeBuffer(static_cast<GLsizeiptr>(cr.triangleStart.size() * 4), cr.triangleStart.data());
      g.drawnStart = makeBuffer(static_cast<GLsizeiptr>(cr.triangleStart.size() * 4), nullptr);
      // Sec. 3.3's u_t, exactly as fur::computeDrawnStart draws it.
      const std::uint64_t seed = fur::coatSeed(r.seed, c);
      std::vector<float> u(static_cast<std::size_t>(triangleCount));
      for (std::int32_t t = 0; t < triangleCount; ++t)
        u[static_cast<std::size_t>(t)] =
            uniform01(seed, kStreamCulling, static_cast<std::uint64_t>(t));
      g.cullU = makeBuffer(static_cast<GLsizeiptr>(u.size() * 4), u.data());
      g.blockSums =
          makeBuffer(static_cast<GLsizeiptr>((triangleCount + 255) / 256 + 1) * 4, nullptr);
      g.shape = makeBuffer(sizeof(GpuCoatShape), nullptr);
      g.twistAmount = -1.0f;
    }
  }

  void ensureTwist(int c) {
    Coat& g = coats[static_cast<std::size_t>(c)];
    const float r = params->coats[static_cast<std::size_t>(c)].normalRandomize;
    const std::uint64_t seed = fur::coatSeed(roots->seed, c);
    if (g.twist && g.twistAmount == r && g.twistSeed == seed) return;
    fur::makeTwistTable(seed, r, g.twistTable);
    g.twist = makeBuffer(static_cast<GLsizeiptr>(g.twistTable.size() * 4), g.twistTable.data());
    g.twistAmount = r;
    g.twistSeed = seed;
  }
};

GpuFur::GpuFur(const GpuFurOptions& options) : impl_(std::make_unique<Impl>(options)) {}
GpuFur::~GpuFur() = default;

void GpuFur::beginFrame(const GpuFurFrame& f) {
  PELAGE_CHECK(f.skin && f.roots && f.params && f.deformed && f.skinPositions && f.skinNormals,
               "incomplete GPU fur frame");
  Impl& m = *impl_;
  if (m.skin != f.skin || m.triangleCount != f.skin->numTriangles() ||
      m.vertexCount != f.skin->numVertices()) {
    m.uploadSkin(*f.skin);
    m.generation = ~std::uint64_t{0};
  }
  if (m.generation != f.rootsGeneration || m.roots != f.roots) {
    m.uploadRoots(*f.roots);
    m.generation = f.rootsGeneration;
  }
  m.roots = f.roots;
  m.params = f.params;
  m.skinPositions = f.skinPositions;
  m.skinNormals = f.skinNormals;
  m.cullFactor = f.cullFactor;
  PELAGE_CHECK(f.deformed->directions.size() == static_cast<std::size_t>(m.vertexCount));
  glNamedBufferSubData(m.directions.get(), 0, static_cast<GLsizeiptr>(m.vertexCount) * 12,
                       f.deformed->directions.data());
}

void GpuFur::generate(int coat, const HairLayout& layout, bool tangents, HairVertexBuffers& out) {
  Impl& m = *impl_;
  PELAGE_CHECK(coat >= 0 && coat < fur::kCoatCount && m.params, "generate before beginFrame");
  Impl::Coat& g = m.coats[static_cast<std::size_t>(coat)];
  const fur::CoatShape shape = fur::makeCoatShape(*m.params, coat);
  PELAGE_CHECK(layout.pointsPerHair() == shape.points &&
                   layout.triangles == (shape.style == fur::HairStyle::Tube),
               "layout of ", layout.pointsPerHair(), " points for a coat of ", shape.points);
  out.reserve(g.rootCount, layout, m.maxBinding);
  const GpuCoatShape packed = pack(shape);
  glNamedBufferSubData(g.shape.get(), 0, sizeof packed, &packed);
  if (shape.twist) m.ensureTwist(coat);
  lastDispatches_ = 0;

  // Sec. 3.3: drawnStart on the GPU when culling, else the roots' own triangleStart.
  const bool culling = m.cullFactor > 1.0f;
  GLuint drawnStart = g.triangleStart.get();
  const std::int64_t nT = m.triangleCount;
  if (culling && nT > 0) {
    const std::int64_t blocks = (nT + 255) / 256;
    PELAGE_CHECK(blocks <= 65535, nT, " triangles exceed the culling pass's 1-D dispatch");
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, g.triangleStart.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, g.drawnStart.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 14, g.cullU.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 15, g.blockSums.get());
    glUseProgram(m.cullProgram.get());
    glUniform1i(uniform(m.cullProgram.get(), "uTriangles"), static_cast<GLint>(nT));
    glUniform1f(uniform(m.cullProgram.get(), "uFactor"), m.cullFactor);
    glDispatchCompute(static_cast<GLuint>(blocks), 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    glUseProgram(m.scanBlocksProgram.get());
    glUniform1i(uniform(m.scanBlocksProgram.get(), "uBlocks"), static_cast<GLint>(blocks));
    glDispatchCompute(1, 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    glUseProgram(m.scanAddProgram.get());
    glUniform1i(uniform(m.scanAddProgram.get(), "uTriangles"), static_cast<GLint>(nT));
    glDispatchCompute(static_cast<GLuint>(blocks), 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    drawnStart = g.drawnStart.get();
  }

  // The hairs, chunk by chunk of output slots and window by window of roots, each binding no more
  // than maxBinding bytes. A root j lands in slot i <= j, so chunk k's roots are at j >= its first
  // slot; without culling, i = j exactly.
  const GLuint hp = m.hairProgram.get();
  glUseProgram(hp);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, g.shape.get());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, m.triangles.get());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, g.triangleStart.get());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, drawnStart);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 6, m.barycentric.get());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 7, shape.twist ? g.twist.get() : m.barycentric.get());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 8, m.skinPositions);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 9, m.skinNormals);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 10, m.directions.get());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 11, m.lengths.get());
  glUniform1i(uniform(hp, "uTangents"), tangents ? 1 : 0);
  glUniform1i(uniform(hp, "uStrandStride"), layout.strandStride);
  const std::int64_t P = layout.pointsPerHair();
  const std::int64_t pointBytes = P * 3 * static_cast<std::int64_t>(sizeof(float));
  // Roots per window: the jitter (16 bytes per root) is the widest root-indexed input.
  std::int64_t window = m.maxBinding / 16;
  window -= window % std::max<std::int64_t>(m.alignment, 256);
  PELAGE_CHECK(window > 0, "binding size ", m.maxBinding, " too small");
  for (const HairChunk& chunk : out.chunks()) {
    if (chunk.firstHair >= g.rootCount) break;
    glBindBufferRange(GL_SHADER_STORAGE_BUFFER, 12, out.positions(), chunk.firstHair * pointBytes,
                      chunk.capacity * pointBytes);
    glBindBufferRange(GL_SHADER_STORAGE_BUFFER, 13, out.shading(), chunk.firstHair * pointBytes,
                      chunk.capacity * pointBytes);
    glUniform1i(uniform(hp, "uChunkFirst"), static_cast<GLint>(chunk.firstHair));
    glUniform1i(uniform(hp, "uChunkCount"), static_cast<GLint>(chunk.capacity));
    const std::int64_t rootEnd =
        culling ? g.rootCount : std::min(g.rootCount, chunk.firstHair + chunk.capacity);
    for (std::int64_t first = chunk.firstHair; first < rootEnd; first += window) {
      const std::int64_t count = std::min(window, rootEnd - first);
      glBindBufferRange(GL_SHADER_STORAGE_BUFFER, 4, g.rootData.get(), first * 8, count * 8);
      glBindBufferRange(GL_SHADER_STORAGE_BUFFER, 5, g.jitter.get(), first * 16, count * 16);
      glUniform1i(uniform(hp, "uWindowFirst"), static_cast<GLint>(first));
      glUniform1i(uniform(hp, "uWindowCount"), static_cast<GLint>(count));
      dispatch1d(count, 64, m.options.maxGroupsPerDimension);
      ++lastDispatches_;
    }
  }
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);

  // One indirect command per chunk.
  const GLuint cp = m.commandsProgram.get();
  glUseProgram(cp);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, drawnStart);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 12, out.commands());
  glUniform1i(uniform(cp, "uTriangles"), static_cast<GLint>(nT));
  glUniform1i(uniform(cp, "uChunks"), static_cast<GLint>(out.chunks().size()));
  glUniform1i(uniform(cp, "uChunkCapacity"), static_cast<GLint>(out.chunks().front().capacity));
  glUniform1i(uniform(cp, "uPointsPerHair"), static_cast<GLint>(P));
  glUniform1i(uniform(cp, "uIndicesPerHair"), layout.indicesPerHair());
  dispatch1d(static_cast<std::int64_t>(out.chunks().size()), 64, m.options.maxGroupsPerDimension);
  glMemoryBarrier(GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT | GL_COMMAND_BARRIER_BIT |
                  GL_BUFFER_UPDATE_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
  glUseProgram(0);
}

}  // namespace pelage::viewer
