#include "pelage/render/gpu_fur.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cstddef>
#include <cstring>
#include <string>

#include "gl_program.h"
#include "pelage/fur/generate.h"
#include "pelage/fur/hair_math.h"
#include "pelage/render/hair_vertex_buffers.h"
#include "pelage/util/error.h"
#include "pelage/util/random.h"

namespace pelage::render {

using detail::Buffer;
using detail::Program;
using detail::uniform;

namespace {

// A coat's tables buffer (fur_hair.comp Tables): the barycentric table, then the twist table.
constexpr int kTwistFloatsAt = 4 * fur::kBarycentricTableSize;
constexpr int kTableFloats = kTwistFloatsAt + 2 * fur::kPolylinePoints * fur::kBarycentricTableSize;

// The GLSL side of fur::CoatShape, generated from its member list (PELAGE_COAT_SHAPE_MEMBERS in
// hair_math.h): the style and region constants, the array sizes and the std430 block `cs` that
// hair_math.glsl reads. Every member is a 4-byte scalar or an array of them, so std430 puts each at
// its C++ offset (checked against the linked program by checkShapeLayout) and the struct is
// uploaded as it is.
std::string coatShapeGlsl() {
  std::string s = "// Generated from fur::CoatShape (fur/hair_math.h) by gpu_fur.cpp.\n";
  auto define = [&s](const char* name, int value) {
    s += "#define " + std::string(name) + " " + std::to_string(value) + "\n";
  };
  define("STYLE_LINE", static_cast<int>(fur::HairStyle::Line));
  define("STYLE_POLYLINE", static_cast<int>(fur::HairStyle::Polyline));
  define("STYLE_CURVE", static_cast<int>(fur::HairStyle::Curve));
  define("STYLE_TUBE", static_cast<int>(fur::HairStyle::Tube));
  define("REGION_NONE", static_cast<int>(fur::RegionShape::None));
  define("REGION_SPHERE", static_cast<int>(fur::RegionShape::Sphere));
  define("REGION_BOX", static_cast<int>(fur::RegionShape::Box));
  define("POLYLINE_POINTS", fur::kPolylinePoints);
  define("MAX_CURVE_POINTS", fur::kMaxCurvePoints);
  define("MAX_TUBE_SIDES", fur::kMaxTubeSides);
  define("TWIST_FLOATS_AT", kTwistFloatsAt);
  s += "layout(std430, binding = 0) readonly buffer CoatShapeBlock {\n";
#define PELAGE_GLSL_SCALAR(cpp, glsl, name) s += "  " #glsl " " #name ";\n";
#define PELAGE_GLSL_ARRAY(cpp, glsl, name, size) \
  s += "  " #glsl " " #name "[" + std::to_string(size) + "];\n";
  PELAGE_COAT_SHAPE_MEMBERS(PELAGE_GLSL_SCALAR, PELAGE_GLSL_ARRAY)
#undef PELAGE_GLSL_SCALAR
#undef PELAGE_GLSL_ARRAY
  s += "} cs;\n";
  return s;
}

// Every member of the linked program's CoatShapeBlock must sit at its fur::CoatShape offset, with
// arrays of 4-byte stride, and the block must be as large as the struct.
void checkShapeLayout(GLuint program) {
  auto property = [program](GLenum interface, GLuint index, GLenum prop) {
    GLint v = -1;
    glGetProgramResourceiv(program, interface, index, 1, &prop, 1, nullptr, &v);
    return v;
  };
  auto check = [&](const std::string& name, std::size_t offset, bool array) {
    const GLuint index = glGetProgramResourceIndex(program, GL_BUFFER_VARIABLE, name.c_str());
    if (index == GL_INVALID_INDEX) return;  // not used by this program: optimised away
    const GLint at = property(GL_BUFFER_VARIABLE, index, GL_OFFSET);
    PELAGE_CHECK(at == static_cast<GLint>(offset), "GLSL ", name, " at offset ", at, ", C++ at ",
                 offset);
    if (array) {
      const GLint stride = property(GL_BUFFER_VARIABLE, index, GL_ARRAY_STRIDE);
      PELAGE_CHECK(stride == 4, "GLSL ", name, " has an array stride of ", stride, " bytes");
    }
  };
#define PELAGE_CHECK_SCALAR(cpp, glsl, name) \
  check("CoatShapeBlock." #name, offsetof(fur::CoatShape, name), false);
#define PELAGE_CHECK_ARRAY(cpp, glsl, name, size) \
  check("CoatShapeBlock." #name "[0]", offsetof(fur::CoatShape, name), true);
  PELAGE_COAT_SHAPE_MEMBERS(PELAGE_CHECK_SCALAR, PELAGE_CHECK_ARRAY)
#undef PELAGE_CHECK_SCALAR
#undef PELAGE_CHECK_ARRAY
  const GLuint block =
      glGetProgramResourceIndex(program, GL_SHADER_STORAGE_BLOCK, "CoatShapeBlock");
  PELAGE_CHECK(block != GL_INVALID_INDEX, "the fur program has no CoatShapeBlock");
  // Drivers may round the block's size up (llvmpipe: to 16 bytes); nothing may be missing.
  const GLint size = property(GL_SHADER_STORAGE_BLOCK, block, GL_BUFFER_DATA_SIZE);
  const auto bytes = static_cast<GLint>(sizeof(fur::CoatShape));
  PELAGE_CHECK(size >= bytes && size <= (bytes + 15) / 16 * 16, "GLSL CoatShapeBlock is ", size,
               " bytes, fur::CoatShape ", bytes);
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
  Buffer triangles;
  Buffer
      vertexData;  // nV x 3 segment directions (each frame), then nV fur lengths (with the roots)
  std::int32_t vertexCount = 0;
  GpuFurFrame frame;  // beginFrame's: the fur, roots, skin buffers and culling this frame draws
  std::uint64_t generation = ~std::uint64_t{0};
  std::uint64_t colorGeneration = ~std::uint64_t{0};

  struct Coat {
    std::int64_t rootCount = 0;
    Buffer rootData, jitter, triangleStart, drawnStart, cullU, blockSums, shape;
    Buffer tables;  // the barycentric table, then the twist table (kTableFloats)
    Buffer colors;  // per root: root and tip colours
    bool perHairColor = false;
    float twistAmount = -1.0f;
    std::uint64_t twistSeed = 0;
    std::vector<float> twistTable;
    // Per root (uploadRoots: clump slot and scale, floppiness, segment direction weight, and a
    // second ivec4 with the helix where the roots carry a groom's curl; empty when the coat needs
    // none),
    // and clumping's centre strand points of this frame (grown as needed).
    Buffer rootExtras, clumpCentres;
    bool hasRootExtras = false;
    int extrasStride = 1;  // ivec4s per root in rootExtras
    std::int64_t clumpCentreBytes = 0;
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
        "fur hair", {ShaderStage{GL_COMPUTE_SHADER, {"hair_math.glsl", "fur_hair.comp"}}},
        coatShapeGlsl()));
    checkShapeLayout(hairProgram.get());
    cullProgram.reset(
        detail::buildProgram("fur cull", {ShaderStage{GL_COMPUTE_SHADER, {"fur_cull.comp"}}}));
    scanBlocksProgram.reset(detail::buildProgram(
        "fur scan 1", {ShaderStage{GL_COMPUTE_SHADER, {"fur_scan.comp"}}}, "#define PASS 1"));
    scanAddProgram.reset(detail::buildProgram(
        "fur scan 2", {ShaderStage{GL_COMPUTE_SHADER, {"fur_scan.comp"}}}, "#define PASS 2"));
    commandsProgram.reset(detail::buildProgram(
        "fur commands", {ShaderStage{GL_COMPUTE_SHADER, {"fur_commands.comp"}}}));
  }

  void uploadSkin(const skin::SkinMesh& s) {
    skin = &s;
    triangleCount = s.numTriangles();
    vertexCount = s.numVertices();
    triangles = makeBuffer(static_cast<GLsizeiptr>(s.triangles.size() * sizeof(std::int32_t)),
                           s.triangles.data());
    vertexData = makeBuffer(static_cast<GLsizeiptr>(vertexCount) * 16, nullptr);
  }

  void uploadRoots(const fur::FurRoots& r) {
    PELAGE_CHECK(r.triangleCount == triangleCount, "roots grown on ", r.triangleCount,
                 " triangles, skin has ", triangleCount);
    PELAGE_CHECK(r.barycentric.size() == static_cast<std::size_t>(kTwistFloatsAt),
                 "a barycentric table of ", r.barycentric.size(), " floats");
    // The vertex lengths the hairs interpolate (FurRoots::lengths: a groom's, else the skin's);
    // uploaded with the roots, which every new skin is followed by.
    glNamedBufferSubData(vertexData.get(), static_cast<GLintptr>(vertexCount) * 12,
                         static_cast<GLsizeiptr>(vertexCount) * 4, r.lengths(*skin));
    for (int c = 0; c < fur::kCoatCount; ++c) {
      const fur::CoatRoots& cr = r.coats[static_cast<std::size_t>(c)];
      Coat& g = coats[static_cast<std::size_t>(c)];
      g.rootCount = cr.size();
      // Per root (triangle, table index, length-map scale as float bits, packed comb): one
      // storage block, as GL guarantees few per compute shader.
      const bool hasLengthScale = !cr.lengthScale.empty();
      const bool hasComb = !cr.comb.empty();
      std::vector<std::int32_t> packed(static_cast<std::size_t>(4 * g.rootCount));
      for (std::int64_t j = 0; j < g.rootCount; ++j) {
        const auto k = static_cast<std::size_t>(j);
        packed[4 * k] = cr.triangle[k];
        packed[4 * k + 1] = cr.tableIndex[k];
        packed[4 * k + 2] = std::bit_cast<std::int32_t>(hasLengthScale ? cr.lengthScale[k] : 1.0f);
        packed[4 * k + 3] = std::bit_cast<std::int32_t>(hasComb ? cr.comb[k] : 0u);
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
      g.shape = makeBuffer(sizeof(fur::CoatShape), nullptr);
      g.tables = makeBuffer(kTableFloats * 4, nullptr);
      glNamedBufferSubData(g.tables.get(), 0, kTwistFloatsAt * 4, r.barycentric.data());
      g.twistAmount = -1.0f;
      // Per root, as the shader's RootExtras: (clump slot, clump scale bits, floppiness bits,
      // segment direction weight bits), then (curl radius bits, curl turns bits, width scale
      // bits, 0) where the roots carry a groom's curl or width scale;
      // a root in a clump other than its own (generateFur's test) gets its slot, others -1.
      std::vector<std::int32_t> extras;
      const bool curled = !cr.curlRadius.empty(), widths = !cr.widthScale.empty();
      g.extrasStride = curled || widths ? 2 : 1;
      if (!cr.clumpSlot.empty() || !cr.floppiness.empty() || !cr.segmentWeight.empty() ||
          g.extrasStride == 2) {
        const auto stride = static_cast<std::size_t>(4 * g.extrasStride);
        extras.assign(stride * static_cast<std::size_t>(g.rootCount), 0);
        for (std::int64_t j = 0; j < g.rootCount; ++j) {
          const auto k = static_cast<std::size_t>(j);
          std::int32_t* x = extras.data() + stride * k;
          const std::int32_t slot = cr.clumpSlot.empty() ? -1 : cr.clumpSlot[k];
          const bool centre = slot < 0 || cr.clumpCentres[static_cast<std::size_t>(slot)] == j;
          x[0] = centre ? -1 : slot;
          x[1] = std::bit_cast<std::int32_t>(cr.clumpScale.empty() ? 1.0f : cr.clumpScale[k]);
          x[2] = std::bit_cast<std::int32_t>(cr.floppiness.empty() ? 0.0f : cr.floppiness[k]);
          x[3] = std::bit_cast<std::int32_t>(cr.segmentWeight.empty() ? 0.0f : cr.segmentWeight[k]);
          if (curled) {
            x[4] = std::bit_cast<std::int32_t>(cr.curlRadius[k]);
            x[5] = std::bit_cast<std::int32_t>(cr.curlTurns[k]);
          }
          if (widths) x[6] = std::bit_cast<std::int32_t>(cr.widthScale[k]);
        }
      }
      g.rootExtras = makeBuffer(static_cast<GLsizeiptr>(extras.size() * 4), extras.data());
      g.hasRootExtras = !extras.empty();
      g.clumpCentreBytes = 0;
    }
  }

  void uploadColors(const fur::FurColors* colors) {
    for (int c = 0; c < fur::kCoatCount; ++c) {
      Coat& g = coats[static_cast<std::size_t>(c)];
      const fur::CoatColors* cc = colors ? &colors->coats[static_cast<std::size_t>(c)] : nullptr;
      g.perHairColor = cc && cc->perHair;
      if (g.perHairColor)
        PELAGE_CHECK(cc->packed.size() == static_cast<std::size_t>(2 * g.rootCount), "colours of ",
                     cc->packed.size() / 2, " roots for ", g.rootCount);
      g.colors = makeBuffer(g.perHairColor ? static_cast<GLsizeiptr>(cc->packed.size() * 4) : 0,
                            g.perHairColor ? cc->packed.data() : nullptr);
    }
  }

  void ensureTwist(int c) {
    Coat& g = coats[static_cast<std::size_t>(c)];
    const float r = frame.inputs.params->coats[static_cast<std::size_t>(c)].normalRandomize;
    const std::uint64_t seed = fur::coatSeed(frame.inputs.roots->seed, c);
    if (g.twistAmount == r && g.twistSeed == seed) return;
    fur::makeTwistTable(seed, r, g.twistTable);
    PELAGE_CHECK(g.twistTable.size() == static_cast<std::size_t>(kTableFloats - kTwistFloatsAt),
                 "a twist table of ", g.twistTable.size(), " floats");
    glNamedBufferSubData(g.tables.get(), kTwistFloatsAt * 4,
                         static_cast<GLsizeiptr>(g.twistTable.size() * 4), g.twistTable.data());
    g.twistAmount = r;
    g.twistSeed = seed;
  }
};

GpuFur::GpuFur(const GpuFurOptions& options) : impl_(std::make_unique<Impl>(options)) {}
GpuFur::~GpuFur() = default;

void GpuFur::beginFrame(const GpuFurFrame& f) {
  const scene::GpuFurInputs& in = f.inputs;
  PELAGE_CHECK(in.skin && in.roots && in.params && in.deformed && f.skinPositions && f.skinNormals,
               "incomplete GPU fur frame");
  Impl& m = *impl_;
  if (m.skin != in.skin || m.triangleCount != in.skin->numTriangles() ||
      m.vertexCount != in.skin->numVertices()) {
    m.uploadSkin(*in.skin);
    m.generation = ~std::uint64_t{0};
  }
  if (m.generation != in.rootsGeneration || m.frame.inputs.roots != in.roots) {
    m.uploadRoots(*in.roots);
    m.generation = in.rootsGeneration;
    m.colorGeneration = ~std::uint64_t{0};
  }
  const std::uint64_t colorGeneration = in.colors ? in.colorGeneration : 0;
  if (m.colorGeneration != colorGeneration) {
    m.uploadColors(in.colors);
    m.colorGeneration = colorGeneration;
  }
  m.frame = f;
  PELAGE_CHECK(in.deformed->directions.size() == static_cast<std::size_t>(m.vertexCount));
  glNamedBufferSubData(m.vertexData.get(), 0, static_cast<GLsizeiptr>(m.vertexCount) * 12,
                       in.deformed->directions.data());
}

void GpuFur::generate(int coat, const fur::HairLayout& layout, bool tangents,
                      HairVertexBuffers& out) {
  Impl& m = *impl_;
  const scene::GpuFurInputs& in = m.frame.inputs;
  PELAGE_CHECK(coat >= 0 && coat < fur::kCoatCount && in.params, "generate before beginFrame");
  Impl::Coat& g = m.coats[static_cast<std::size_t>(coat)];
  const fur::CoatShape shape = fur::makeCoatShape(*in.params, *in.roots, coat);
  PELAGE_CHECK(layout == fur::coatLayout(*in.params, *in.roots, coat), "a layout of ",
               layout.pointsPerHair(), " points for a coat of ", shape.points);
  out.reserve(g.rootCount, layout, m.maxBinding);
  glNamedBufferSubData(g.shape.get(), 0, sizeof shape, &shape);
  if (shape.twist) m.ensureTwist(coat);
  lastDispatches_ = 0;

  // Clumping: this frame's centre strand points (fur::generateClumpCentres), and the weights.
  const fur::Clump& clump = in.params->coats[static_cast<std::size_t>(coat)].clump;
  const bool clumps = fur::coatClumps(*in.params, *in.roots, coat);
  std::array<float, fur::kMaxCurvePoints> clumpWeights{};
  if (clumps) {
    const std::vector<float>* centres =
        in.clumpCentres ? &(*in.clumpCentres)[static_cast<std::size_t>(coat)] : nullptr;
    const std::size_t expected =
        in.roots->coats[static_cast<std::size_t>(coat)].clumpCentres.size() * 3 *
        static_cast<std::size_t>(layout.strandPoints);
    PELAGE_CHECK(centres && centres->size() == expected, "coat ", coat,
                 " clumps but its frame has ", centres ? centres->size() : 0,
                 " clump centre floats, not ", expected);
    const auto bytes = static_cast<std::int64_t>(expected * sizeof(float));
    // Bound whole (any hair may clump to any centre): the driver's limit, not the windows' size.
    PELAGE_CHECK(bytes <= maxShaderStorageBlockSize(), "the clump centres' ", bytes,
                 " bytes exceed a storage block (", maxShaderStorageBlockSize(), ")");
    if (bytes > g.clumpCentreBytes) {
      g.clumpCentres = makeBuffer(static_cast<GLsizeiptr>(bytes), nullptr);
      g.clumpCentreBytes = bytes;
    }
    glNamedBufferSubData(g.clumpCentres.get(), 0, static_cast<GLsizeiptr>(bytes), centres->data());
    clumpWeights = fur::clumpWeights(clump, layout.strandPoints);
  }

  // Sec. 3.3: drawnStart on the GPU when culling, else the roots' own triangleStart.
  const bool culling = m.frame.cullFactor > 1.0f;
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
    glUniform1f(uniform(m.cullProgram.get(), "uFactor"), m.frame.cullFactor);
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
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 6, g.tables.get());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 8, m.frame.skinPositions);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 9, m.frame.skinNormals);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 10, m.vertexData.get());
  glUniform1i(uniform(hp, "uTangents"), tangents ? 1 : 0);
  glUniform1i(uniform(hp, "uStrandStride"), layout.ringSides);
  glUniform1i(uniform(hp, "uColors"), g.perHairColor ? 1 : 0);
  glUniform1i(uniform(hp, "uVertexCount"), m.vertexCount);
  glUniform1i(uniform(hp, "uClump"), clumps ? 1 : 0);
  if (clumps) glUniform1fv(uniform(hp, "uClumpWeights"), fur::kMaxCurvePoints, clumpWeights.data());
  // (Unused bindings still need a buffer bound.)
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 11, clumps ? g.clumpCentres.get() : g.tables.get());
  glUniform1i(uniform(hp, "uRootExtras"), g.hasRootExtras ? 1 : 0);
  glUniform1i(uniform(hp, "uExtrasStride"), g.extrasStride);
  if (!g.hasRootExtras) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 7, g.tables.get());
  if (!g.perHairColor) {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 16, g.tables.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 17, out.colors());
  }
  const std::int64_t P = layout.pointsPerHair();
  const std::int64_t pointBytes = P * 3 * static_cast<std::int64_t>(sizeof(float));
  // Roots per window: the root data and jitter (16 bytes per root) are the widest root inputs but
  // for the extras of a groom's curl (32).
  std::int64_t window = m.maxBinding / (16 * g.extrasStride);
  window -= window % std::max<std::int64_t>(m.alignment, 256);
  PELAGE_CHECK(window > 0, "binding size ", m.maxBinding, " too small");
  for (const HairChunk& chunk : out.chunks()) {
    if (chunk.firstHair >= g.rootCount) break;
    glBindBufferRange(GL_SHADER_STORAGE_BUFFER, 12, out.positions(), chunk.firstHair * pointBytes,
                      chunk.capacity * pointBytes);
    glBindBufferRange(GL_SHADER_STORAGE_BUFFER, 13, out.shading(), chunk.firstHair * pointBytes,
                      chunk.capacity * pointBytes);
    if (g.perHairColor)
      glBindBufferRange(GL_SHADER_STORAGE_BUFFER, 17, out.colors(), chunk.firstHair * 8,
                        chunk.capacity * 8);
    glUniform1i(uniform(hp, "uChunkFirst"), static_cast<GLint>(chunk.firstHair));
    glUniform1i(uniform(hp, "uChunkCount"), static_cast<GLint>(chunk.capacity));
    const std::int64_t rootEnd =
        culling ? g.rootCount : std::min(g.rootCount, chunk.firstHair + chunk.capacity);
    for (std::int64_t first = chunk.firstHair; first < rootEnd; first += window) {
      const std::int64_t count = std::min(window, rootEnd - first);
      glBindBufferRange(GL_SHADER_STORAGE_BUFFER, 4, g.rootData.get(), first * 16, count * 16);
      glBindBufferRange(GL_SHADER_STORAGE_BUFFER, 5, g.jitter.get(), first * 16, count * 16);
      if (g.perHairColor)
        glBindBufferRange(GL_SHADER_STORAGE_BUFFER, 16, g.colors.get(), first * 8, count * 8);
      if (g.hasRootExtras)
        glBindBufferRange(GL_SHADER_STORAGE_BUFFER, 7, g.rootExtras.get(),
                          first * 16 * g.extrasStride, count * 16 * g.extrasStride);
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

}  // namespace pelage::render
