#include "pelage/render/renderer.h"
#include "pelage/util/color.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "deep_opacity_map.h"
#include "gl_program.h"
#include "pelage/render/gl_context.h"
#include "pelage/render/gpu_fur.h"
#include "pelage/render/hair_vertex_buffers.h"
#include "pelage/skin/texture.h"
#include "pelage/util/error.h"
#include "render_helpers.h"

namespace pelage::render {

using detail::Buffer;
using detail::Framebuffer;
using detail::LightFrame;
using detail::makeTexture;
using detail::ortho;
using detail::primitive;
using detail::Program;
using detail::Renderbuffer;
using detail::setFloat;
using detail::setInt;
using detail::setMaterial;
using detail::setMatrix;
using detail::setMatrix3;
using detail::setVec3;
using detail::Texture;
using detail::uniform;

namespace {

// Whether the skin's shadow map is drawn: when the light asks for it, and always under the
// physical fur model, whose fibre lobes (TT forward scattering above all) would otherwise light
// the coat through the body (measured against the path-traced references, scripts/reference/:
// without it, the views lit from behind come out 50 to 80 % too bright).
bool skinShadows(const scene::DrawList& list) {
  return list.light.shadows || list.hairShading == scene::HairShading::Physical;
}

// The physical model's coat light spread sideways (Light::coatSpread, coat_spread.frag): the share
// of the coat's direct light kept at each hair (k_d) and the share reaching the coat spread (k_s),
// fitted with lighting.glsl's g and k_a on the six committed reference views (README); 0.5 -> 0.425
// and 0.6 -> 0.51 with Light::lightAlongFibreDarkening (the coat's direct light was 1.2 to 1.3
// times Cycles' on every view, views.py parts); x 1.05 (0.446, 0.536) with
// Light::coatSpreadSkinNormal, which took 2 to 4 % off the front views' luminance; 0.138 and 0.607
// with Chiang's fibre (lighting.glsl, 2026-12-07), which now carries the light a fibre scatters
// once and forward through the coat (Cycles' light passes: the coat's direct light had stood in
// for it, at 1.4 to 1.6 times the light Cycles scatters many times, views.py passes, README).
constexpr float kCoatLightKept = 0.138f;
constexpr float kCoatLightSpread = 0.607f;
// The physical model's ambient by how the coat is seen (oit_composite.frag): the coat seen at a
// grazing angle shows its outer layer, whose hairs see the whole sky, and face-on its depths, so
// k_g La A (1 - |N.V|) more, N the skin's normal under the pixel. k_g fitted on the ambient's part
// of the seven reference views against Cycles' (views.py parts, README); 0.6 -> 0.52 with
// Light::coatSeenDepth, as lighting.glsl's k_a (the near strands, brighter, weigh more), and 0.52
// -> 0.546 with Light::lightAlongFibreDarkening (the ambient part was 0.83 to 0.89 times Cycles'),
// 0.412 with Chiang's fibre (lighting.glsl's k_a 0.604 -> 0.722 with it).
constexpr float kCoatGrazingAmbient = 0.412f;
// How far beyond the skin's outline, in hair lengths, the transparent strands' weights inside the
// coat (Light::coatSeenDepth) measure a fringe strand's depth from the nearest skin: the fringe's
// hairs reach up to one hair length beyond the outline, bent or not; with the margin of the
// search's eight directions, 1.5. Without it the weights stepped at the outline (a dark line along
// the skin's edge against the light).
constexpr float kFringeReach = 1.5f;

}  // namespace

struct Renderer::Impl {
  RendererOptions options;
  int samples = 0;
  int width = 0, height = 0;
  Eigen::Vector3f background = scene::kDefaultBackground;  // the last frame's (linear)

  Program skinProgram, skinTexturedProgram, hairProgram, strandProgram, strandOitProgram,
      compositeProgram, spreadProgram, skinMapsProgram, depthProgram;

  Framebuffer msaaFbo, resolveFbo, shadowFbo, oitFbo;
  Renderbuffer msaaColor, msaaDepth, resolveDepth;
  Texture resolveColor, shadowMap, oitAccum, oitReveal, oitCoat;
  // The skin's depth as a texture for the transparent strands' weights and the transparency
  // resolve (the coat's grazing ambient).
  Texture skinDepth;
  Framebuffer skinDepthFbo;
  bool skinDepthCopied = false;  // this frame's, before the transparent strands
  // The skin's depth beyond its outline and the skin's normal under each pixel (skin_maps.frag).
  Texture fringeDepth, skinNormal;
  Framebuffer skinMapsFbo;
  // The coat's spread light (coat_spread.frag): (E m, m) at half resolution or less, ping-ponged.
  Framebuffer spreadFbo[2];
  Texture spreadTarget[2];
  int shadowSize = 0;
  float spreadPixels = 0.0f;  // this frame's coat light spread, pixels (0: none)
  std::unique_ptr<detail::DeepOpacityMap> opacityMap;  // the fur's self-shadow (made on first use)

  detail::VertexArray skinVao;
  Buffer skinPositions, skinNormals, skinIndices;
  int skinVertices = -1;
  const std::vector<std::int32_t>* skinTrianglesSource = nullptr;
  std::size_t skinTrianglesSize = 0;
  int skinTriangleCount = 0;

  // The skin in its own colours: one vertex per corner (uv, colour, skin vertex), grouped by
  // material, and the materials' textures (built once per skin).
  struct CornerGroup {
    GLint first = 0;
    GLsizei count = 0;
    int texture = -1;  // index into appearanceTextures, or -1
  };
  const skin::SkinMesh* appearanceSource = nullptr;
  int appearanceTriangles = -1;
  detail::VertexArray appearanceVao;
  Buffer appearanceCorners;
  std::vector<CornerGroup> appearanceGroups;
  std::vector<Texture> appearanceTextures;
  Texture whiteTexture;  // bound where a coat or group has nothing of its own

  std::array<HairVertexBuffers, 2> coats;
  std::vector<float> tangentScratch;
  std::unique_ptr<GpuFur> gpuFur;  // created on first use (compiles the compute shaders)

  explicit Impl(const RendererOptions& o) : options(o) {
    GLint maxSamples = 0;
    glGetIntegerv(GL_MAX_SAMPLES, &maxSamples);
    int asked = options.samples;
    if (asked < 0) {
      ContextInfo info;
      queryContextInfo(info);
      asked = info.software ? 0 : 4;
    }
    samples = asked > 1 ? std::min(asked, static_cast<int>(maxSamples)) : 0;
    if (samples < 2) samples = 0;

    using detail::ShaderStage;
    skinProgram.reset(detail::buildProgram(
        "skin",
        {ShaderStage{GL_VERTEX_SHADER, {"skin.vert"}},
         ShaderStage{GL_FRAGMENT_SHADER, {"hair_bsdf.glsl", "lighting.glsl", "skin.frag"}}}));
    skinTexturedProgram.reset(detail::buildProgram(
        "skin (textured)",
        {ShaderStage{GL_VERTEX_SHADER, {"skin_textured.vert"}},
         ShaderStage{GL_FRAGMENT_SHADER,
                     {"hair_bsdf.glsl", "lighting.glsl", "skin_textured.frag"}}}));
    hairProgram.reset(detail::buildProgram(
        "hair",
        {ShaderStage{GL_VERTEX_SHADER, {"color.glsl", "hair.vert"}},
         ShaderStage{GL_FRAGMENT_SHADER, {"hair_bsdf.glsl", "lighting.glsl", "hair.frag"}}}));
    const auto strand = [](const char* name, const char* defines) {
      return detail::buildProgram(
          name,
          {ShaderStage{GL_VERTEX_SHADER, {"color.glsl", "hair.vert"}},
           ShaderStage{GL_GEOMETRY_SHADER, {"hair_strand.geom"}},
           ShaderStage{GL_FRAGMENT_SHADER, {"hair_bsdf.glsl", "lighting.glsl", "hair.frag"}}},
          defines);
    };
    strandProgram.reset(strand("hair strands", "#define STRAND 1"));
    strandOitProgram.reset(strand("hair strands (transparent)", "#define STRAND 1\n#define OIT 1"));
    spreadProgram.reset(detail::buildProgram(
        "coat light spread", {ShaderStage{GL_VERTEX_SHADER, {"oit_composite.vert"}},
                              ShaderStage{GL_FRAGMENT_SHADER, {"coat_spread.frag"}}}));
    skinMapsProgram.reset(
        detail::buildProgram("skin maps", {ShaderStage{GL_VERTEX_SHADER, {"oit_composite.vert"}},
                                           ShaderStage{GL_FRAGMENT_SHADER, {"skin_maps.frag"}}}));
    compositeProgram.reset(detail::buildProgram(
        "transparency resolve", {ShaderStage{GL_VERTEX_SHADER, {"oit_composite.vert"}},
                                 ShaderStage{GL_FRAGMENT_SHADER, {"oit_composite.frag"}}}));
    depthProgram.reset(
        detail::buildProgram("depth", {ShaderStage{GL_VERTEX_SHADER, {"depth.vert"}},
                                       ShaderStage{GL_FRAGMENT_SHADER, {"depth.frag"}}}));

    GLuint vao = 0;
    glCreateVertexArrays(1, &vao);
    skinVao.reset(vao);
    glCreateVertexArrays(1, &vao);
    appearanceVao.reset(vao);
    GLuint tex = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &tex);
    whiteTexture.reset(tex);
    glTextureStorage2D(tex, 1, GL_RGBA8, 1, 1);
    const std::uint8_t white[4] = {255, 255, 255, 255};
    glTextureSubImage2D(tex, 0, 0, 0, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, white);
  }

  // A texture of the skin as a GL sRGB texture with mipmaps, its wrap modes and filter.
  static Texture uploadTexture(const skin::Texture& t) {
    GLuint id = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &id);
    Texture tex(id);
    int levels = 1;
    while ((std::max(t.width, t.height) >> levels) > 0) ++levels;
    glTextureStorage2D(id, levels, t.srgb ? GL_SRGB8_ALPHA8 : GL_RGBA8, t.width, t.height);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTextureSubImage2D(id, 0, 0, 0, t.width, t.height, GL_RGBA, GL_UNSIGNED_BYTE, t.rgba.data());
    glGenerateTextureMipmap(id);
    const auto wrap = [](skin::Wrap w) {
      return w == skin::Wrap::ClampToEdge      ? GL_CLAMP_TO_EDGE
             : w == skin::Wrap::MirroredRepeat ? GL_MIRRORED_REPEAT
                                               : GL_REPEAT;
    };
    glTextureParameteri(id, GL_TEXTURE_WRAP_S, wrap(t.wrapS));
    glTextureParameteri(id, GL_TEXTURE_WRAP_T, wrap(t.wrapT));
    const bool nearest = t.filter == skin::Filter::Nearest;
    glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, nearest ? GL_NEAREST : GL_LINEAR);
    glTextureParameteri(id, GL_TEXTURE_MIN_FILTER,
                        nearest ? GL_NEAREST_MIPMAP_NEAREST : GL_LINEAR_MIPMAP_LINEAR);
    return tex;
  }

  // The per-corner arrays and textures of `s` (once per skin): corners grouped by material, each
  // corner's colour = its material's base colour (the skin's colour without materials) x its
  // vertex colour.
  void uploadAppearance(const skin::SkinMesh& s) {
    if (appearanceSource == &s && appearanceTriangles == s.numTriangles()) return;
    appearanceSource = &s;
    appearanceTriangles = s.numTriangles();
    struct Corner {
      float u, v;
      float r, g, b, a;
      std::int32_t vertex;
    };
    static_assert(sizeof(Corner) == 28);
    const int nT = s.numTriangles();
    const int groups = std::max<int>(1, static_cast<int>(s.materials.size()));
    std::vector<std::vector<std::int32_t>> byMaterial(static_cast<std::size_t>(groups));
    for (int t = 0; t < nT; ++t)
      byMaterial[s.materials.empty()
                     ? 0
                     : static_cast<std::size_t>(s.triangleMaterial[static_cast<std::size_t>(t)])]
          .push_back(t);
    std::vector<Corner> corners;
    corners.reserve(static_cast<std::size_t>(nT) * 3);
    appearanceGroups.clear();
    appearanceTextures.clear();
    for (const skin::Texture& t : s.textures) appearanceTextures.push_back(uploadTexture(t));
    for (int m = 0; m < groups; ++m) {
      CornerGroup g;
      g.first = static_cast<GLint>(corners.size());
      Eigen::Vector4f base(s.color.x(), s.color.y(), s.color.z(), 1.0f);
      if (!s.materials.empty()) {
        base = s.materials[static_cast<std::size_t>(m)].baseColor;
        g.texture = s.hasUv() ? s.materials[static_cast<std::size_t>(m)].texture : -1;
      } else if (!s.vertexColor.empty()) {
        base = Eigen::Vector4f::Ones();
      }
      for (std::int32_t t : byMaterial[static_cast<std::size_t>(m)])
        for (int j = 0; j < 3; ++j) {
          const auto k = static_cast<std::size_t>(3 * t + j);
          const std::int32_t v = s.triangles[k];
          const Eigen::Vector2f uv = s.hasUv() ? s.cornerUv[k] : Eigen::Vector2f::Zero();
          const Eigen::Vector4f c =
              s.vertexColor.empty()
                  ? base
                  : Eigen::Vector4f(base.cwiseProduct(s.vertexColor[static_cast<std::size_t>(v)]));
          corners.push_back({uv.x(), uv.y(), c.x(), c.y(), c.z(), c.w(), v});
        }
      g.count = static_cast<GLsizei>(corners.size()) - g.first;
      if (g.count > 0) appearanceGroups.push_back(g);
    }
    appearanceCorners = detail::createBuffer();
    glNamedBufferStorage(
        appearanceCorners.get(),
        static_cast<GLsizeiptr>(std::max<std::size_t>(corners.size(), 1) * sizeof(Corner)),
        corners.empty() ? nullptr : corners.data(), 0);
    const GLuint vao = appearanceVao.get();
    glVertexArrayVertexBuffer(vao, 0, appearanceCorners.get(), 0, sizeof(Corner));
    glEnableVertexArrayAttrib(vao, 0);
    glVertexArrayAttribFormat(vao, 0, 2, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(vao, 0, 0);
    glEnableVertexArrayAttrib(vao, 1);
    glVertexArrayAttribFormat(vao, 1, 4, GL_FLOAT, GL_FALSE, 8);
    glVertexArrayAttribBinding(vao, 1, 0);
    glEnableVertexArrayAttrib(vao, 2);
    glVertexArrayAttribIFormat(vao, 2, 1, GL_INT, 24);
    glVertexArrayAttribBinding(vao, 2, 0);
  }

  void drawSkinAppearance(GLuint program) {
    glUseProgram(program);
    glBindVertexArray(appearanceVao.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, skinPositions.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, skinNormals.get());
    for (const CornerGroup& g : appearanceGroups) {
      const bool textured =
          g.texture >= 0 && appearanceTextures[static_cast<std::size_t>(g.texture)];
      setInt(program, "uTextured", textured ? 1 : 0);
      glBindTextureUnit(2, textured ? appearanceTextures[static_cast<std::size_t>(g.texture)].get()
                                    : whiteTexture.get());
      glDrawArrays(GL_TRIANGLES, g.first, g.count);
    }
  }

  void resize(int w, int h) {
    PELAGE_CHECK(w > 0 && h > 0 && w <= 16384 && h <= 16384, "framebuffer ", w, "x", h);
    if (w == width && h == height && resolveFbo) return;
    width = w;
    height = h;
    GLuint id = 0;
    msaaFbo.reset();
    msaaColor.reset();
    msaaDepth.reset();
    resolveFbo.reset();
    resolveColor.reset();
    resolveDepth.reset();
    oitFbo.reset();
    oitAccum.reset();
    oitReveal.reset();
    oitCoat.reset();

    const auto texture = [&](GLenum format) { return makeTexture(format, 1, w, h); };
    // sRGB colour: shading is in linear space, the framebuffer encodes (GL_FRAMEBUFFER_SRGB while
    // drawing), and read-back pixels are sRGB bytes, as image files and displays expect.
    resolveColor = texture(GL_SRGB8_ALPHA8);
    glCreateFramebuffers(1, &id);
    resolveFbo.reset(id);
    glNamedFramebufferTexture(id, GL_COLOR_ATTACHMENT0, resolveColor.get(), 0);
    // Single-sample depth: the depth buffer without MSAA, and the depth the transparent strands
    // are tested against (resolved from the multisampled one) with it.
    glCreateRenderbuffers(1, &id);
    resolveDepth.reset(id);
    glNamedRenderbufferStorage(id, GL_DEPTH_COMPONENT24, w, h);
    glNamedFramebufferRenderbuffer(resolveFbo.get(), GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, id);
    PELAGE_CHECK(
        glCheckNamedFramebufferStatus(resolveFbo.get(), GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE,
        "resolve framebuffer incomplete");
    // Weighted blended OIT targets: the weighted colour sum (RGBA32F: thousands of fragments per
    // pixel at 5 million hairs stay exact enough) and the revealage (R32F).
    oitAccum = texture(GL_RGBA32F);
    oitReveal = texture(GL_R32F);
    oitCoat = texture(GL_RGBA32F);  // the physical model's coat albedo and irradiance, weighted
    skinDepth = makeTexture(GL_DEPTH_COMPONENT24, 1, w, h, GL_NEAREST, GL_NEAREST);
    glCreateFramebuffers(1, &id);
    skinDepthFbo.reset(id);
    glNamedFramebufferTexture(id, GL_DEPTH_ATTACHMENT, skinDepth.get(), 0);
    glNamedFramebufferDrawBuffer(id, GL_NONE);
    fringeDepth = makeTexture(GL_R32F, 1, w, h, GL_NEAREST, GL_NEAREST);
    skinNormal = makeTexture(GL_RGBA32F, 1, w, h, GL_NEAREST, GL_NEAREST);
    glCreateFramebuffers(1, &id);
    skinMapsFbo.reset(id);
    glNamedFramebufferTexture(id, GL_COLOR_ATTACHMENT0, fringeDepth.get(), 0);
    glNamedFramebufferTexture(id, GL_COLOR_ATTACHMENT1, skinNormal.get(), 0);
    const GLenum skinMaps[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    glNamedFramebufferDrawBuffers(id, 2, skinMaps);
    PELAGE_CHECK(glCheckNamedFramebufferStatus(id, GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE,
                 "skin maps framebuffer incomplete");
    glCreateFramebuffers(1, &id);
    oitFbo.reset(id);
    glNamedFramebufferTexture(id, GL_COLOR_ATTACHMENT0, oitAccum.get(), 0);
    glNamedFramebufferTexture(id, GL_COLOR_ATTACHMENT1, oitReveal.get(), 0);
    glNamedFramebufferTexture(id, GL_COLOR_ATTACHMENT2, oitCoat.get(), 0);
    glNamedFramebufferRenderbuffer(id, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, resolveDepth.get());
    const GLenum buffers[3] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2};
    glNamedFramebufferDrawBuffers(id, 3, buffers);
    PELAGE_CHECK(glCheckNamedFramebufferStatus(id, GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE,
                 "transparency framebuffer incomplete");
    for (int i = 0; i < 2; ++i) {
      spreadTarget[i] = makeTexture(GL_RG32F, 1, (w + 1) / 2, (h + 1) / 2, GL_LINEAR, GL_LINEAR);
      glCreateFramebuffers(1, &id);
      spreadFbo[i].reset(id);
      glNamedFramebufferTexture(id, GL_COLOR_ATTACHMENT0, spreadTarget[i].get(), 0);
      PELAGE_CHECK(glCheckNamedFramebufferStatus(id, GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE,
                   "coat spread framebuffer incomplete");
    }
    if (samples > 0) {
      glCreateRenderbuffers(1, &id);
      msaaColor.reset(id);
      glNamedRenderbufferStorageMultisample(id, samples, GL_SRGB8_ALPHA8, w, h);
      glCreateRenderbuffers(1, &id);
      msaaDepth.reset(id);
      glNamedRenderbufferStorageMultisample(id, samples, GL_DEPTH_COMPONENT24, w, h);
      glCreateFramebuffers(1, &id);
      msaaFbo.reset(id);
      glNamedFramebufferRenderbuffer(id, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, msaaColor.get());
      glNamedFramebufferRenderbuffer(id, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, msaaDepth.get());
      PELAGE_CHECK(glCheckNamedFramebufferStatus(id, GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE,
                   "multisample framebuffer incomplete");
    }
  }

  void ensureShadowMap(int size) {
    if (shadowSize == size && shadowMap) return;
    shadowSize = size;
    shadowMap = makeTexture(GL_DEPTH_COMPONENT24, 1, size, size, GL_LINEAR, GL_LINEAR);
    GLuint id = shadowMap.get();
    glTextureParameteri(id, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    glTextureParameteri(id, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
    glCreateFramebuffers(1, &id);
    shadowFbo.reset(id);
    glNamedFramebufferTexture(id, GL_DEPTH_ATTACHMENT, shadowMap.get(), 0);
    glNamedFramebufferDrawBuffer(id, GL_NONE);
    PELAGE_CHECK(glCheckNamedFramebufferStatus(id, GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE,
                 "shadow framebuffer incomplete");
  }

  // The deformed skin's positions and normals (nV x 3 floats each), drawn as the skin and read by
  // the GPU fur pass.
  void uploadSkinArrays(const std::vector<Eigen::Vector3f>& positions,
                        const std::vector<Eigen::Vector3f>& normals) {
    const int vertices = static_cast<int>(positions.size());
    PELAGE_CHECK(normals.size() == positions.size());
    const auto bytes =
        static_cast<GLsizeiptr>(static_cast<std::size_t>(vertices) * 3 * sizeof(float));
    if (vertices != skinVertices) {
      skinVertices = vertices;
      skinPositions = detail::createBuffer();
      skinNormals = detail::createBuffer();
      glNamedBufferStorage(skinPositions.get(), bytes, nullptr, GL_DYNAMIC_STORAGE_BIT);
      glNamedBufferStorage(skinNormals.get(), bytes, nullptr, GL_DYNAMIC_STORAGE_BIT);
      const GLuint vao = skinVao.get();
      glVertexArrayVertexBuffer(vao, 0, skinPositions.get(), 0, 3 * sizeof(float));
      glVertexArrayVertexBuffer(vao, 1, skinNormals.get(), 0, 3 * sizeof(float));
      for (GLuint a : {0u, 1u}) {
        glEnableVertexArrayAttrib(vao, a);
        glVertexArrayAttribFormat(vao, a, 3, GL_FLOAT, GL_FALSE, 0);
        glVertexArrayAttribBinding(vao, a, a);
      }
    }
    static_assert(sizeof(Eigen::Vector3f) == 3 * sizeof(float));
    glNamedBufferSubData(skinPositions.get(), 0, bytes, positions.data());
    glNamedBufferSubData(skinNormals.get(), 0, bytes, normals.data());
  }

  void uploadSkin(const scene::SkinDrawItem& s) {
    if (!s.positions || s.triangleCount == 0) return;
    PELAGE_CHECK(static_cast<int>(s.positions->size()) == s.vertices);
    uploadSkinArrays(*s.positions, *s.normals);
    if (s.triangles != skinTrianglesSource || s.triangles->size() != skinTrianglesSize) {
      skinTrianglesSource = s.triangles;
      skinTrianglesSize = s.triangles->size();
      skinIndices = detail::createBuffer();
      glNamedBufferStorage(skinIndices.get(),
                           static_cast<GLsizeiptr>(skinTrianglesSize * sizeof(std::int32_t)),
                           s.triangles->data(), 0);
      glVertexArrayElementBuffer(skinVao.get(), skinIndices.get());
    }
  }

  void uploadCpuHairs(const scene::FurDrawItem& f, scene::HairShading shading) {
    HairVertexBuffers& b = coats[static_cast<std::size_t>(f.coat)];
    const fur::HairLayout& layout = f.layout;
    b.reserve(f.drawnHairs, layout);
    const float* shade = f.normals;
    if (scene::shadesWithTangents(shading)) {
      strandTangents(f.positions, f.drawnHairs, layout, tangentScratch);
      shade = tangentScratch.data();
    }
    b.upload(f.positions, shade, f.drawnHairs);
    if (f.perHairColor) {
      PELAGE_CHECK(f.colors || f.drawnHairs == 0, "per-hair colours without the frame's colours");
      b.uploadColors(f.colors, f.drawnHairs);
    }
  }

  void drawSkin(GLuint program) {
    if (skinTriangleCount == 0) return;
    glUseProgram(program);
    glBindVertexArray(skinVao.get());
    glDrawElements(GL_TRIANGLES, skinTriangleCount * 3, GL_UNSIGNED_INT, nullptr);
  }

  void drawHairs(const HairVertexBuffers& b, GLuint program) {
    if (b.capacity() == 0) return;
    glUseProgram(program);
    setInt(program, "uPointsPerStrand", b.layout().strandPoints);
    setInt(program, "uStrandStride", b.layout().ringSides);
    glBindVertexArray(b.vertexArray());
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, b.commands());
    glMultiDrawElementsIndirect(primitive(b.layout()), GL_UNSIGNED_INT, nullptr,
                                static_cast<GLsizei>(b.chunks().size()), sizeof(DrawCommand));
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
  }

  void setLighting(GLuint program, const scene::DrawList& list, const LightFrame& light,
                   float bias) {
    setVec3(program, "uLightDir", list.light.direction.normalized());
    setVec3(program, "uLightColor", list.light.color);
    setVec3(program, "uAmbientLight", list.light.ambient);
    setVec3(program, "uEye", list.camera.eye);
    setFloat(program, "uAlongFibreDarkening", list.light.alongFibreDarkening);
    setFloat(program, "uAlongFibreSaturation", list.light.alongFibreSaturation);
    setFloat(program, "uLightAlongFibreDarkening", list.light.lightAlongFibreDarkening);
    setFloat(program, "uCoatBacklitDarkening", list.light.coatBacklitDarkening);
    // The fibre's light through the fur at Light::fibreLobeOpacity a crossing where the map
    // counts Light::fibreOpacity: its transmittance to the power of their ratio (lighting.glsl).
    setFloat(program, "uFibreLobeShadowPower",
             list.light.fibreOpacity > 0.0f
                 ? std::max(list.light.fibreLobeOpacity, 0.0f) / list.light.fibreOpacity
                 : 1.0f);
    setInt(program, "uLightPass", static_cast<int>(list.lightPass));
    setInt(program, "uShadows", skinShadows(list) ? 1 : 0);
    setMatrix(program, "uLightViewProj", light.viewProj);
    setFloat(program, "uShadowBias", bias);
    setInt(program, "uSelfShadow", light.selfShadow ? 1 : 0);
    glProgramUniform4fv(program, uniform(program, "uOpacityLayerEnds"), 1, light.layerEnds.data());
    setFloat(program, "uOpacityDepthScale", light.depthScale);
    setMatrix(program, "uViewProj", list.camera.viewProjection());
  }

  // Pixels per metre across the view at unit distance from the eye (0.5 H P11).
  float projScale(const scene::DrawList& list) const {
    return 0.5f * static_cast<float>(height) * list.camera.projection()(1, 1);
  }
  // The distance from the eye to the creature's bounds' centre (1 without bounds).
  static float creatureDistance(const scene::DrawList& list) {
    return list.bounds.isEmpty() ? 1.0f : (list.bounds.center() - list.camera.eye).norm();
  }

  // Draws coat `f` with `program` (lines, tubes, or strands with or without transparency).
  void drawFurItem(const scene::FurDrawItem& f, GLuint p, const scene::DrawList& list,
                   const LightFrame& light, float bias) {
    const HairVertexBuffers& b = coats[static_cast<std::size_t>(f.coat)];
    setLighting(p, list, light, bias * 2.0f);
    setMaterial(p, f.material);
    setInt(p, "uShading", static_cast<int>(list.hairShading));
    setInt(p, "uPerHairColor", f.perHairColor ? 1 : 0);
    setInt(p, "uPerHairWidth", f.perHairWidth ? 1 : 0);
    setFloat(p, "uAmbientRatio", f.ambientRatio);
    setFloat(p, "uCoatDirect",
             p == strandOitProgram.get() && spreadPixels > 0.0f ? kCoatLightKept : 1.0f);
    glBindTextureUnit(1, b.colorTexture());
    if (p == strandProgram.get() || p == strandOitProgram.get()) {
      glProgramUniform2f(p, uniform(p, "uViewport"), static_cast<float>(width),
                         static_cast<float>(height));
      setFloat(p, "uRootWidth", 1e-3f * f.width.rootMm);
      setFloat(p, "uTipWidth", 1e-3f * f.width.tipMm);
      setFloat(p, "uWiden", std::max(f.cullFactor, 1.0f));
      setFloat(p, "uProjScale", projScale(list));
      if (p == strandOitProgram.get()) {
        // The creature's bounds as seen from the eye: the weights' depth range.
        const Eigen::AlignedBox3f& box = list.bounds;
        const float dist = creatureDistance(list);
        const float r = box.isEmpty() ? 1.0f : 0.5f * box.diagonal().norm();
        glProgramUniform2f(p, uniform(p, "uDepthRange"), std::max(dist - r, 0.0f), dist + r);
        // Light::coatSeenDepth: lambda of the weights inside the coat (0: off; needs the skin's
        // depth, copySkinDepth).
        setFloat(
            p, "uFrontDepth",
            skinDepthCopied ? std::max(list.light.coatSeenDepth, 0.0f) * list.hairLength : 0.0f);
        const Eigen::Matrix4f proj = list.camera.projection();
        glProgramUniform2f(p, uniform(p, "uDepthUnproject"), proj(2, 2), proj(2, 3));
        // Light::coatSpreadSkinNormal: the spread light's normal turned towards the skin's, from
        // its depth (needs the skin's maps, copySkinDepth).
        setFloat(p, "uSpreadSkinNormal",
                 physicalOverSkin(list) ? std::clamp(list.light.coatSpreadSkinNormal, 0.0f, 1.0f)
                                        : 0.0f);
        // Whether the skin's depth tells the fibre's terminator where the skin lies behind a
        // hair (lighting.glsl; needs the skin's depth, copySkinDepth).
        setInt(p, "uSkinBehindKnown", physicalOverSkin(list) ? 1 : 0);
      }
    }
    drawHairs(b, p);
  }

  // The light's view of the frame: an orthographic view-projection (a directional light) fitting
  // the scene bounds, shared by the shadow map and the deep opacity map.
  LightFrame lightFrame(const scene::DrawList& list) const {
    Eigen::AlignedBox3f box = list.bounds;
    if (box.isEmpty())
      box = Eigen::AlignedBox3f(Eigen::Vector3f::Constant(-1), Eigen::Vector3f::Constant(1));
    const Eigen::Vector3f c = box.center();
    const float r = std::max(0.5f * box.diagonal().norm(), 1e-3f);
    scene::Camera lc;
    lc.target = c;
    lc.eye = c + list.light.direction.normalized() * (2.0f * r);
    lc.up = std::abs(list.light.direction.normalized().z()) > 0.99f ? Eigen::Vector3f::UnitX()
                                                                    : Eigen::Vector3f::UnitZ();
    LightFrame l;
    l.viewProj = ortho(-r, r, -r, r, r * 0.5f, r * 3.5f) * lc.view();
    l.extent = 2.0f * r;
    l.depthScale = 3.0f * r;
    l.selfShadow = list.light.selfShadowing && !list.fur.empty() && list.hairLength > 0.0f;
    // Layers reaching a quarter, half, one and two hair lengths past the first hair: the coat
    // itself (light crossing it at a slant), then what lies under it.
    const float L = list.hairLength;
    l.layerEnds = {0.25f * L, 0.5f * L, L, 2.0f * L};
    l.fibreOpacity = list.light.fibreOpacity;
    return l;
  }

  // How far beyond the skin's outline the transparent strands' weights look for the skin
  // (skin_maps.frag's uReach): kFringeReach times the longest hair seen at the creature's
  // distance, in pixels, [1, 64].
  float fringeReachPixels(const scene::DrawList& list) const {
    if (!(list.hairLength > 0.0f) || list.bounds.isEmpty()) return 1.0f;
    const float px =
        kFringeReach * list.hairLength * projScale(list) / std::max(creatureDistance(list), 1e-6f);
    return std::clamp(px, 1.0f, 64.0f);
  }

  // The coat light's spread for this frame in pixels: Light::coatSpread hair lengths seen at the
  // creature's distance; 0 without the physical model's transparent strands.
  float coatSpreadPixels(const scene::DrawList& list, bool transparentStrands) const {
    if (!transparentStrands || list.hairShading != scene::HairShading::Physical ||
        !(list.light.coatSpread > 0.0f) || !(list.hairLength > 0.0f) || list.bounds.isEmpty())
      return 0.0f;
    return std::min(list.light.coatSpread * list.hairLength * projScale(list) /
                        std::max(creatureDistance(list), 1e-6f),
                    1000.0f);
  }

  // The coat's direct irradiance spread sideways (coat_spread.frag) from the transparent strands'
  // targets into spreadTarget[0]; sets the resolve's uniforms.
  void spreadCoatLight(const scene::DrawList& list) {
    const GLuint composite = compositeProgram.get();
    setFloat(
        composite, "uCoatSpreadShare",
        spreadPixels > 0.0f && scene::showsCoatLight(list.lightPass) ? kCoatLightSpread : 0.0f);
    setVec3(composite, "uLightColor", list.light.color);
    setVec3(composite, "uAmbientLight", list.light.ambient);
    glBindTextureUnit(9, oitCoat.get());
    glBindTextureUnit(10, spreadTarget[0].get());  // bound, unread without the spread
    if (!(spreadPixels > 0.0f)) return;
    // At 1 / factor resolution (2 to 16), the Gaussian about 3 low-resolution pixels wide or more.
    const int factor = std::clamp(static_cast<int>(spreadPixels / 3.0f), 2, 16);
    const int lw = (width + factor - 1) / factor, lh = (height + factor - 1) / factor;
    const GLuint p = spreadProgram.get();
    glUseProgram(p);
    setInt(p, "uFactor", factor);
    glProgramUniform2i(p, uniform(p, "uSize"), lw, lh);
    setFloat(p, "uSigma", std::max(spreadPixels / static_cast<float>(factor), 0.5f));
    glBindTextureUnit(3, oitAccum.get());
    glViewport(0, 0, lw, lh);
    const int dirs[3][2] = {{0, 0}, {1, 0}, {0, 1}};
    for (int pass = 0; pass < 3; ++pass) {
      const int to = pass == 1 ? 1 : 0;  // average -> 0, blur x -> 1, blur y -> 0
      if (pass > 0) glBindTextureUnit(10, spreadTarget[1 - to].get());
      glBindFramebuffer(GL_FRAMEBUFFER, spreadFbo[to].get());
      setInt(p, "uPass", pass);
      glProgramUniform2i(p, uniform(p, "uDir"), dirs[pass][0], dirs[pass][1]);
      glDrawArrays(GL_TRIANGLES, 0, 3);
    }
    glViewport(0, 0, width, height);
    glBindTextureUnit(10, spreadTarget[0].get());
    setFloat(composite, "uSpreadFactor", static_cast<float>(factor));
    glProgramUniform2f(composite, uniform(composite, "uSpreadSize"), static_cast<float>(lw),
                       static_cast<float>(lh));
  }

  // The skin's depth, as the opaque pass left it, copied for the transparent strands' weights
  // (skinDepthCopied; none without a skin), and the skin's maps from it (skin_maps.frag): its
  // depth beyond its outline for the weights and its normal under each pixel for the spread light
  // and the resolve's grazing ambient, once per frame.
  void copySkinDepth(const scene::DrawList& list) {
    skinDepthCopied = list.skin.positions != nullptr;
    if (!skinDepthCopied) return;
    glBlitNamedFramebuffer(resolveFbo.get(), skinDepthFbo.get(), 0, 0, width, height, 0, 0, width,
                           height, GL_DEPTH_BUFFER_BIT, GL_NEAREST);
    glBindTextureUnit(11, skinDepth.get());
    const GLuint p = skinMapsProgram.get();
    glUseProgram(p);
    setFloat(p, "uReach", fringeReachPixels(list));
    setMatrix(p, "uInverseProjection", list.camera.projection().inverse());
    setMatrix3(p, "uEyeToWorld", list.camera.view().topLeftCorner<3, 3>().inverse().eval());
    glBindFramebuffer(GL_FRAMEBUFFER, skinMapsFbo.get());
    glDisable(GL_DEPTH_TEST);
    glBindVertexArray(skinVao.get());  // any VAO: the triangle comes from gl_VertexID
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glEnable(GL_DEPTH_TEST);
    glBindTextureUnit(12, fringeDepth.get());
    glBindTextureUnit(13, skinNormal.get());
  }

  // The physical model's grazing ambient (kCoatGrazingAmbient): the resolve takes the skin's
  // normal under each pixel (copySkinDepth's skin maps); off without the physical model or a skin.
  void seeCoatGrazing(const scene::DrawList& list) {
    setFloat(compositeProgram.get(), "uCoatGrazing",
             physicalOverSkin(list) && scene::showsCoatLight(list.lightPass) ? kCoatGrazingAmbient
                                                                             : 0.0f);
  }

  // Whether this frame's physical fur model has the skin's maps under it (copySkinDepth): its
  // spread light and grazing ambient take the skin's normal from them.
  bool physicalOverSkin(const scene::DrawList& list) const {
    return skinDepthCopied && list.hairShading == scene::HairShading::Physical;
  }

  RenderStats render(const scene::DrawList& list) {
    resize(list.camera.width, list.camera.height);
    RenderStats stats;
    uploadSkin(list.skin);
    skinTriangleCount = list.skin.positions ? list.skin.triangleCount : 0;
    std::array<bool, 2> drawCoat{false, false};
    bool gpuBegun = false;
    const bool tangents = scene::shadesWithTangents(list.hairShading);
    for (const scene::FurDrawItem& f : list.fur) {
      PELAGE_CHECK(f.coat == 0 || f.coat == 1, "coat ", f.coat);
      if (f.source == scene::HairSource::Cpu) {
        uploadCpuHairs(f, list.hairShading);
      } else {
        if (!gpuBegun) {
          const scene::GpuFurInputs& in = list.gpuFur;
          PELAGE_CHECK(in.params && in.roots && in.skin && in.deformed,
                       "GPU hair source without its inputs");
          if (!list.skin.positions) uploadSkinArrays(in.deformed->positions, in.deformed->normals);
          if (!gpuFur) gpuFur = std::make_unique<GpuFur>(options.gpuFur);
          GpuFurFrame g;
          g.inputs = in;
          g.skinPositions = skinPositions.get();
          g.skinNormals = skinNormals.get();
          g.cullFactor = f.cullFactor;
          gpuFur->beginFrame(g);
          gpuBegun = true;
        }
        gpuFur->generate(f.coat, f.layout, tangents, coats[static_cast<std::size_t>(f.coat)]);
      }
      drawCoat[static_cast<std::size_t>(f.coat)] = true;
      stats.hairsDrawn += f.drawnHairs;
    }
    stats.skinTriangles = skinTriangleCount;

    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glEnable(GL_PRIMITIVE_RESTART_FIXED_INDEX);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    glDisable(GL_SCISSOR_TEST);
    glDepthMask(GL_TRUE);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);

    const LightFrame light = lightFrame(list);
    if (skinShadows(list)) {
      ensureShadowMap(std::clamp(list.light.shadowMapSize, 256, 8192));
      glBindFramebuffer(GL_FRAMEBUFFER, shadowFbo.get());
      glViewport(0, 0, shadowSize, shadowSize);
      glClear(GL_DEPTH_BUFFER_BIT);
      setMatrix(depthProgram.get(), "uViewProj", light.viewProj);
      glEnable(GL_POLYGON_OFFSET_FILL);
      glPolygonOffset(2.0f, 4.0f);
      if (list.skin.positions) drawSkin(depthProgram.get());
      glDisable(GL_POLYGON_OFFSET_FILL);
      // With self-shadowing the hairs' shadow is the deep opacity map's, soft; without, hard.
      for (std::size_t c = 0; c < 2 && !light.selfShadow; ++c)
        if (drawCoat[c]) drawHairs(coats[c], depthProgram.get());
      glBindTextureUnit(0, shadowMap.get());
    } else {
      if (!shadowMap)
        ensureShadowMap(256);  // a bound sampler keeps every driver happy; uShadows = 0 skips it
      glBindTextureUnit(0, shadowMap.get());
    }
    if (light.selfShadow) {
      if (!opacityMap) opacityMap = std::make_unique<detail::DeepOpacityMap>();
      opacityMap->draw(list, light, depthProgram.get(), coats, skinVao.get());
    } else {
      glBindTextureUnit(5, whiteTexture.get());  // bound, unread: uSelfShadow = 0
      glBindTextureUnit(6, whiteTexture.get());
    }

    const GLuint target = samples > 0 ? msaaFbo.get() : resolveFbo.get();
    glBindFramebuffer(GL_FRAMEBUFFER, target);
    glViewport(0, 0, width, height);
    // The background's sRGB code, written as it is (whether a driver encodes clear colours under
    // GL_FRAMEBUFFER_SRGB varies); everything drawn after is encoded by the framebuffer.
    glDisable(GL_FRAMEBUFFER_SRGB);
    // Alpha 0: every surface drawn writes 1, the strands' resolve the coverage of what they cover
    // (composite over), so the alpha channel holds each pixel's coverage (readPixels).
    glClearColor(linearToSrgb(list.background.x()), linearToSrgb(list.background.y()),
                 linearToSrgb(list.background.z()), 0.0f);
    background = list.background;
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_FRAMEBUFFER_SRGB);

    const float bias = 3.0f / static_cast<float>(std::max(shadowSize, 1));
    if (list.skin.positions) {
      const bool own = list.skin.appearance != nullptr;
      if (own) uploadAppearance(*list.skin.appearance);
      const GLuint p = own ? skinTexturedProgram.get() : skinProgram.get();
      setLighting(p, list, light, bias * 0.5f);
      setMaterial(p, list.skin.material);
      // Hairs start on the skin: push the skin back a little so their roots are not hidden.
      glEnable(GL_POLYGON_OFFSET_FILL);
      glPolygonOffset(1.0f, 2.0f);
      if (own)
        drawSkinAppearance(p);
      else
        drawSkin(p);
      glDisable(GL_POLYGON_OFFSET_FILL);
    }
    // Opaque hairs first (1-pixel lines, tubes, strands without transparency), then the
    // transparent strands over everything opaque.
    const bool strands = list.hairWidth == scene::HairWidth::Strands;
    const auto isTransparent = [&](const scene::FurDrawItem& f) {
      return strands && list.transparency &&
             coats[static_cast<std::size_t>(f.coat)].layout().topology == fur::HairTopology::Strand;
    };
    bool anyTransparent = false;
    for (const scene::FurDrawItem& f : list.fur)
      anyTransparent = anyTransparent || isTransparent(f);
    spreadPixels = coatSpreadPixels(list, anyTransparent);
    for (const scene::FurDrawItem& f : list.fur) {
      if (isTransparent(f)) continue;
      const HairVertexBuffers& b = coats[static_cast<std::size_t>(f.coat)];
      const bool strand = strands && b.layout().topology == fur::HairTopology::Strand;
      drawFurItem(f, strand ? strandProgram.get() : hairProgram.get(), list, light, bias);
    }
    // (MSAA resolved in linear space where the driver follows GL 4.4+; the depth too, for the
    // transparent strands.)
    if (samples > 0)
      glBlitNamedFramebuffer(
          msaaFbo.get(), resolveFbo.get(), 0, 0, width, height, 0, 0, width, height,
          GL_COLOR_BUFFER_BIT | (anyTransparent ? GL_DEPTH_BUFFER_BIT : 0), GL_NEAREST);
    if (anyTransparent) {
      copySkinDepth(list);
      glBindFramebuffer(GL_FRAMEBUFFER, oitFbo.get());
      const float zero[4] = {0, 0, 0, 0}, one[4] = {1, 1, 1, 1};
      glClearNamedFramebufferfv(oitFbo.get(), GL_COLOR, 0, zero);
      glClearNamedFramebufferfv(oitFbo.get(), GL_COLOR, 1, one);
      glClearNamedFramebufferfv(oitFbo.get(), GL_COLOR, 2, zero);
      glDepthMask(GL_FALSE);
      glEnable(GL_BLEND);
      glBlendFunci(0, GL_ONE, GL_ONE);
      glBlendFunci(1, GL_ZERO, GL_ONE_MINUS_SRC_COLOR);
      glBlendFunci(2, GL_ONE, GL_ONE);
      for (const scene::FurDrawItem& f : list.fur)
        if (isTransparent(f)) drawFurItem(f, strandOitProgram.get(), list, light, bias);
      seeCoatGrazing(list);
      glDisable(GL_DEPTH_TEST);
      glDisable(GL_BLEND);
      glBindVertexArray(skinVao.get());  // any VAO: the triangles come from gl_VertexID
      spreadCoatLight(list);
      glEnable(GL_BLEND);
      glBindFramebuffer(GL_FRAMEBUFFER, resolveFbo.get());
      // Colour: the strands' mean over what lies behind (c a + dst (1 - a)); alpha: coverage
      // composited over (a + dst_a (1 - a)), a = 1 - revealage.
      glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
      glBindTextureUnit(3, oitAccum.get());
      glBindTextureUnit(4, oitReveal.get());
      glUseProgram(compositeProgram.get());
      glBindVertexArray(skinVao.get());  // any VAO: the triangle comes from gl_VertexID
      glDrawArrays(GL_TRIANGLES, 0, 3);
      glDisable(GL_BLEND);
      glDepthMask(GL_TRUE);
      glEnable(GL_DEPTH_TEST);
    }
    glBindVertexArray(0);
    glUseProgram(0);
    glDisable(
        GL_PRIMITIVE_RESTART_FIXED_INDEX);  // others (the UI) draw 16-bit indices up to 0xFFFF

    glDisable(GL_FRAMEBUFFER_SRGB);  // the window and the UI draw unencoded
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    return stats;
  }
};

Renderer::Renderer(const RendererOptions& options) : impl_(std::make_unique<Impl>(options)) {}
Renderer::~Renderer() = default;

RenderStats Renderer::render(const scene::DrawList& list) {
  return impl_->render(list);
}

void Renderer::readPixels(Image& out, FrameAlpha alpha) {
  PELAGE_CHECK(impl_->width > 0, "readPixels before render");
  const int w = impl_->width, h = impl_->height;
  out.width = w;
  out.height = h;
  const std::size_t row = static_cast<std::size_t>(w) * 4;
  out.rgba.resize(row * static_cast<std::size_t>(h));
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glNamedFramebufferReadBuffer(impl_->resolveFbo.get(), GL_COLOR_ATTACHMENT0);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, impl_->resolveFbo.get());
  glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, out.rgba.data());
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  // GL's rows are bottom-up; images are top-down.
  for (int y = 0; y < h / 2; ++y)
    std::swap_ranges(
        out.rgba.begin() + static_cast<std::ptrdiff_t>(row * static_cast<std::size_t>(y)),
        out.rgba.begin() + static_cast<std::ptrdiff_t>(row * static_cast<std::size_t>(y + 1)),
        out.rgba.begin() + static_cast<std::ptrdiff_t>(row * static_cast<std::size_t>(h - 1 - y)));
  if (alpha == FrameAlpha::Opaque)
    makeOpaque(out);
  else
    unblendBackground(out, impl_->background);
}

Image Renderer::readPixels(FrameAlpha alpha) {
  Image img;
  readPixels(img, alpha);
  return img;
}

void Renderer::blitTo(GLuint target, int x, int y, int width, int height) {
  glBlitNamedFramebuffer(impl_->resolveFbo.get(), target, 0, 0, impl_->width, impl_->height, x, y,
                         x + width, y + height, GL_COLOR_BUFFER_BIT, GL_LINEAR);
}

void Renderer::finish() {
  glFinish();
}
int Renderer::samples() const {
  return impl_->samples;
}
int Renderer::width() const {
  return impl_->width;
}
int Renderer::height() const {
  return impl_->height;
}
const HairVertexBuffers& Renderer::coatBuffers(int coat) const {
  PELAGE_CHECK(coat == 0 || coat == 1);
  return impl_->coats[static_cast<std::size_t>(coat)];
}

}  // namespace pelage::render
