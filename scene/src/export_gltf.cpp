#include "pelage/scene/export_gltf.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <fstream>
#include <limits>
#include <vector>

#include "hair_curves.h"
#include "pelage/fur/colors.h"
#include "pelage/fur/hair_ply.h"
#include "pelage/util/atomic_file.h"
#include "pelage/util/color.h"
#include "pelage/util/error.h"

namespace pelage::scene {
namespace {

constexpr int kFloat = 5126, kUint = 5125, kUnsignedByte = 5121;
constexpr int kArrayBuffer = 34962, kElementArrayBuffer = 34963;
constexpr int kModeLines = 1, kModeTriangles = 4;

struct CoatPart {
  int coat = 0;
  fur::HairLayout layout;
  std::int64_t hairs = 0;
  std::int64_t vertices = 0;  // hairs * K
  std::int64_t segments = 0;  // hairs * (K - 1)
};

std::vector<CoatPart> coatParts(const FrameState& state) {
  std::vector<CoatPart> parts;
  if (!state.cpuFur) return parts;
  for (int c = 0; c < fur::kCoatCount; ++c) {
    const fur::HairBuffers& b = state.fur.coats[static_cast<std::size_t>(c)];
    if (b.drawn == 0) continue;
    CoatPart p;
    p.coat = c;
    p.layout = b.layout;
    p.hairs = b.drawn;
    p.vertices = b.drawn * p.layout.strandPoints;
    p.segments = b.drawn * (p.layout.strandPoints - 1);
    parts.push_back(p);
  }
  return parts;
}

// Appends `points` xyz points (pelage axes) in glTF axes.
void putPoints(AtomicFileWriter& w, const float* xyz, std::size_t points) {
  float out[3 * 256];
  for (std::size_t i = 0; i < points; i += 256) {
    const std::size_t n = std::min<std::size_t>(256, points - i);
    for (std::size_t k = 0; k < n; ++k) {
      const float* p = xyz + 3 * (i + k);
      out[3 * k] = p[1];
      out[3 * k + 1] = p[2];
      out[3 * k + 2] = p[0];
    }
    w.write(out, n * 12);
  }
}

// glTF 2.0 is +Y up (front +Z); pelage is +Z up (front +X). A point goes to glTF axes by the
// rotation (x, y, z) -> (y, z, x), the inverse of the importer's change of basis, so a creature
// exported and imported again lands where it was.
Eigen::Vector3f toGltfAxes(const Eigen::Vector3f& v) {
  return {v.y(), v.z(), v.x()};
}

nlohmann::json vec(const Eigen::Vector3f& v) {
  return nlohmann::json::array({v.x(), v.y(), v.z()});
}

// An axis-aligned box in glTF axes.
Eigen::AlignedBox3f toGltfAxes(const Eigen::AlignedBox3f& box) {
  return Eigen::AlignedBox3f(toGltfAxes(box.min()), toGltfAxes(box.max()));
}

nlohmann::json material(const std::string& name, const Eigen::Vector3f& color) {
  return {{"name", name},
          {"pbrMetallicRoughness",
           {{"baseColorFactor", {color.x(), color.y(), color.z(), 1.0f}},
            {"metallicFactor", 0.0f},
            {"roughnessFactor", 0.8f}}}};
}

}  // namespace

GlbCounts glbCounts(const Model& model, const FrameState& state) {
  GlbCounts n;
  n.skinVertices = model.skin.numVertices();
  n.skinTriangles = model.skin.numTriangles();
  for (const CoatPart& p : coatParts(state)) {
    const auto c = static_cast<std::size_t>(p.coat);
    n.hairs[c] = p.hairs;
    n.hairVertices[c] = p.vertices;
    n.segments[c] = p.segments;
  }
  return n;
}

GlbCounts writeFrameGlb(const std::string& path, const Model& model, const Fur& fur,
                        const FrameState& state, const std::string& generator) {
  const fur::FurParams& params = fur.params;
  static_assert(std::endian::native == std::endian::little &&
                std::numeric_limits<float>::is_iec559);
  const skin::SkinMesh& skin = model.skin;
  const std::size_t nV = static_cast<std::size_t>(skin.numVertices());
  PELAGE_CHECK(state.skin.positions.size() == nV && state.skin.normals.size() == nV,
               "frame not evaluated");
  const std::vector<CoatPart> parts = coatParts(state);
  GlbCounts counts = glbCounts(model, state);

  // Buffer layout: skin positions, normals, indices; then per coat positions, indices, colours,
  // widths.
  nlohmann::json views = nlohmann::json::array(), accessors = nlohmann::json::array();
  std::uint64_t offset = 0;
  auto addView = [&](std::uint64_t bytes, int target) {
    views.push_back(
        {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bytes}, {"target", target}});
    offset += bytes;
    return static_cast<int>(views.size()) - 1;
  };
  auto addAccessor = [&](int view, int componentType, std::int64_t count, const char* type) {
    accessors.push_back(
        {{"bufferView", view}, {"componentType", componentType}, {"count", count}, {"type", type}});
    return static_cast<int>(accessors.size()) - 1;
  };
  auto setBounds = [&](int accessor, const Eigen::AlignedBox3f& box) {
    accessors[static_cast<std::size_t>(accessor)]["min"] = vec(box.min());
    accessors[static_cast<std::size_t>(accessor)]["max"] = vec(box.max());
  };

  nlohmann::json meshes = nlohmann::json::array(), nodes = nlohmann::json::array();
  nlohmann::json materials = nlohmann::json::array();
  materials.push_back(material("skin", srgbToLinear(skin.color)));  // glTF factors are linear
  const int skinPos =
      addAccessor(addView(nV * 12, kArrayBuffer), kFloat, static_cast<std::int64_t>(nV), "VEC3");
  setBounds(skinPos, toGltfAxes(state.skinBounds));
  const int skinNrm =
      addAccessor(addView(nV * 12, kArrayBuffer), kFloat, static_cast<std::int64_t>(nV), "VEC3");
  const int skinIdx = addAccessor(addView(skin.triangles.size() * 4, kElementArrayBuffer), kUint,
                                  static_cast<std::int64_t>(skin.triangles.size()), "SCALAR");
  meshes.push_back({{"name", "skin"},
                    {"primitives",
                     {{{"attributes", {{"POSITION", skinPos}, {"NORMAL", skinNrm}}},
                       {"indices", skinIdx},
                       {"material", 0},
                       {"mode", kModeTriangles}}}}});
  nodes.push_back({{"name", "skin"}, {"mesh", 0}});

  // Hair bounds: one pass over the points (the accessor needs min/max).
  std::vector<float> line;
  for (const CoatPart& p : parts) {
    const fur::HairBuffers& b = state.fur.coats[static_cast<std::size_t>(p.coat)];
    const int K = p.layout.strandPoints;
    line.resize(static_cast<std::size_t>(K) * 3);
    Eigen::AlignedBox3f box;
    for (std::int64_t h = 0; h < p.hairs; ++h) {
      detail::hairCenterLine(b, h, line.data());
      for (int k = 0; k < K; ++k)
        box.extend(Eigen::Vector3f(line[static_cast<std::size_t>(k) * 3],
                                   line[static_cast<std::size_t>(k) * 3 + 1],
                                   line[static_cast<std::size_t>(k) * 3 + 2]));
    }
    const std::string name = p.coat == fur::kOvercoat ? "overcoat" : "undercoat";
    if (p.vertices > std::numeric_limits<std::uint32_t>::max())
      inputError(path, ": coat ", name, " has ", p.vertices,
                 " hair vertices, more than a glTF index can address");
    const int pos = addAccessor(addView(static_cast<std::uint64_t>(p.vertices) * 12, kArrayBuffer),
                                kFloat, p.vertices, "VEC3");
    setBounds(pos, toGltfAxes(box));
    const int idx =
        addAccessor(addView(static_cast<std::uint64_t>(p.segments) * 8, kElementArrayBuffer), kUint,
                    p.segments * 2, "SCALAR");
    // Each point's colour (linear, as COLOR_0 is; the material's factor is white).
    const int col = addAccessor(addView(static_cast<std::uint64_t>(p.vertices) * 4, kArrayBuffer),
                                kUnsignedByte, p.vertices, "VEC4");
    accessors[static_cast<std::size_t>(col)]["normalized"] = true;
    // _WIDTH (an application attribute, glTF 2.0 sec. 3.7.2.1): the hair's width at each point in
    // metres (fur::exportedWidth: tapering root to tip; a tube's diameter).
    const int width = addAccessor(addView(static_cast<std::uint64_t>(p.vertices) * 4, kArrayBuffer),
                                  kFloat, p.vertices, "SCALAR");
    materials.push_back(material(name, Eigen::Vector3f::Ones()));
    meshes.push_back({{"name", name},
                      {"primitives",
                       {{{"attributes", {{"POSITION", pos}, {"COLOR_0", col}, {"_WIDTH", width}}},
                         {"indices", idx},
                         {"material", static_cast<int>(materials.size()) - 1},
                         {"mode", kModeLines}}}}});
    nodes.push_back({{"name", name}, {"mesh", static_cast<int>(meshes.size()) - 1}});
  }
  const std::uint64_t binBytes = offset;  // every view is a multiple of 4 bytes
  nlohmann::json sceneNodes = nlohmann::json::array();
  for (std::size_t i = 0; i < nodes.size(); ++i) sceneNodes.push_back(i);
  // The asset says how pelage's coordinates were converted.
  const nlohmann::json asset = {
      {"version", "2.0"},
      {"generator", generator},
      {"extras",
       {{"up", "+Y"},
        {"units", "metres"},
        {"converted", "from pelage's +Z up: glTF (x, y, z) = pelage (y, z, x)"}}}};
  nlohmann::json root = {{"asset", asset},
                         {"scene", 0},
                         {"scenes", {{{"name", model.name}, {"nodes", sceneNodes}}}},
                         {"nodes", nodes},
                         {"meshes", meshes},
                         {"materials", materials},
                         {"accessors", accessors},
                         {"bufferViews", views},
                         {"buffers", {{{"byteLength", binBytes}}}}};
  std::string json = root.dump();
  while (json.size() % 4 != 0) json += ' ';
  const std::uint64_t total = 12 + 8 + json.size() + 8 + binBytes;
  if (total > std::numeric_limits<std::uint32_t>::max())
    inputError(path, ": the frame needs ", total,
               " bytes, over glTF binary's 4 GiB limit (export fewer hairs, or as USD or PLY)");
  counts.bytes = total;

  AtomicFileWriter w(path);
  w.put<std::uint32_t>(0x46546C67u);  // "glTF"
  w.put<std::uint32_t>(2);
  w.put<std::uint32_t>(static_cast<std::uint32_t>(total));
  w.put<std::uint32_t>(static_cast<std::uint32_t>(json.size()));
  w.put<std::uint32_t>(0x4E4F534Au);  // "JSON"
  w.write(json.data(), json.size());
  w.put<std::uint32_t>(static_cast<std::uint32_t>(binBytes));
  w.put<std::uint32_t>(0x004E4942u);  // "BIN\0"
  static_assert(sizeof(Eigen::Vector3f) == 12);
  putPoints(w, state.skin.positions.front().data(), nV);
  putPoints(w, state.skin.normals.front().data(), nV);
  w.write(skin.triangles.data(), skin.triangles.size() * 4);
  std::vector<std::uint32_t> idx;
  for (const CoatPart& p : parts) {
    const fur::HairBuffers& b = state.fur.coats[static_cast<std::size_t>(p.coat)];
    const int K = p.layout.strandPoints;
    if (p.layout.ringSides == 1) {
      putPoints(w, b.positions.data(), static_cast<std::size_t>(p.vertices));
    } else {
      line.resize(static_cast<std::size_t>(K) * 3);
      for (std::int64_t h = 0; h < p.hairs; ++h) {
        detail::hairCenterLine(b, h, line.data());
        putPoints(w, line.data(), static_cast<std::size_t>(K));
      }
    }
    idx.clear();
    for (std::int64_t h = 0; h < p.hairs; ++h) {
      const auto base = static_cast<std::uint32_t>(h * K);
      for (int k = 0; k + 1 < K; ++k) {
        idx.push_back(base + static_cast<std::uint32_t>(k));
        idx.push_back(base + static_cast<std::uint32_t>(k + 1));
      }
      if (idx.size() >= (1u << 20)) {
        w.write(idx.data(), idx.size() * 4);
        idx.clear();
      }
    }
    w.write(idx.data(), idx.size() * 4);
    // COLOR_0: the hair's root and tip colours graded along its centre line, RGBA8 linear.
    const fur::CoatColors& cc = fur.colors.coats[static_cast<std::size_t>(p.coat)];
    std::vector<std::uint8_t> rgba(static_cast<std::size_t>(K) * 4);
    for (std::int64_t h = 0; h < p.hairs; ++h) {
      for (int k = 0; k < K; ++k) {
        const float t = K > 1 ? static_cast<float>(k) / static_cast<float>(K - 1) : 0.0f;
        const Eigen::Vector3f c = fur::drawnHairColorAt(cc, b, h, t).cwiseMax(0.0f).cwiseMin(1.0f);
        for (int j = 0; j < 3; ++j)
          rgba[static_cast<std::size_t>(4 * k + j)] =
              static_cast<std::uint8_t>(std::lround(c[j] * 255.0f));
        rgba[static_cast<std::size_t>(4 * k + 3)] = 255;
      }
      w.write(rgba.data(), rgba.size());
    }
    std::vector<float> widths(static_cast<std::size_t>(K));
    const auto hairWidths = [&](std::int64_t h) {
      for (int k = 0; k < K; ++k)
        widths[static_cast<std::size_t>(k)] =
            fur::exportedWidth(state.fur, params, p.coat, h, k * p.layout.ringSides);
    };
    hairWidths(0);  // every hair's, unless the hairs have widths of their own
    const bool own = !state.fur.coats[static_cast<std::size_t>(p.coat)].widthScales.empty();
    for (std::int64_t h = 0; h < p.hairs; ++h) {
      if (own) hairWidths(h);
      w.write(widths.data(), widths.size() * 4);
    }
  }
  w.commit();
  return counts;
}

bool isCompleteGlb(const std::string& path) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) return false;
  const auto size = static_cast<std::uint64_t>(in.tellg());
  in.seekg(0);
  unsigned char h[12] = {};
  if (!in.read(reinterpret_cast<char*>(h), 12)) return false;
  auto u32 = [&](int at) {
    return static_cast<std::uint32_t>(h[at]) | static_cast<std::uint32_t>(h[at + 1]) << 8 |
           static_cast<std::uint32_t>(h[at + 2]) << 16 |
           static_cast<std::uint32_t>(h[at + 3]) << 24;
  };
  return u32(0) == 0x46546C67u && u32(4) == 2 && u32(8) == size;
}

}  // namespace pelage::scene
