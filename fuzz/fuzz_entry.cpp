#include "fuzz_entry.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "pelage/anatomy/creature.h"
#include "pelage/anatomy/pose_file.h"
#include "pelage/animation/clip_file.h"
#include "pelage/animation/gltf_import.h"
#include "pelage/fur/groom.h"
#include "pelage/fur/groom_strokes.h"
#include "pelage/fur/preset.h"
#include "pelage/models/builtin.h"
#include "pelage/skin/mesh_io.h"
#include "pelage/skin/texture.h"
#include "pelage/util/error.h"

namespace pelage::fuzz {
namespace {

constexpr const char* kMeshExtensions[] = {"obj", "ply", "off", "stl"};

// The built-in monkey's body: clip and pose files name its segments.
const anatomy::Body& monkeyBody() {
  static const anatomy::Body body = [] {
    auto text = models::builtinFile("monkey.json");
    if (!text) throw std::logic_error("built-in monkey.json missing");
    return anatomy::parseCreature(std::string(*text), "monkey.json").body;
  }();
  return body;
}

// Readers that take a path get the input through a file in a private temporary folder.
class ScratchFile {
 public:
  explicit ScratchFile(const std::string& extension) {
    std::filesystem::path dir =
        std::filesystem::exists("/dev/shm") ? "/dev/shm" : std::filesystem::temp_directory_path();
    path_ = (dir / ("pelage_fuzz_" + std::to_string(::getpid()) + "." + extension)).string();
  }
  ~ScratchFile() { std::remove(path_.c_str()); }
  ScratchFile(const ScratchFile&) = delete;
  ScratchFile& operator=(const ScratchFile&) = delete;
  const std::string& write(const std::uint8_t* data, std::size_t size) {
    std::ofstream out(path_, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    if (!out) throw std::runtime_error("cannot write " + path_);
    return path_;
  }

 private:
  std::string path_;
};

void runCreature(const std::uint8_t* data, std::size_t size) {
  anatomy::parseCreature(std::string(reinterpret_cast<const char*>(data), size), "fuzz.json");
}
void runPreset(const std::uint8_t* data, std::size_t size) {
  fur::FurParams params =
      fur::parseFurPreset(std::string(reinterpret_cast<const char*>(data), size), "fuzz.json");
  // A preset that loads must also round-trip through the writer.
  fur::parseFurPreset(fur::furPresetJson(params), "round trip");
}
void runClip(const std::uint8_t* data, std::size_t size) {
  animation::parseClip(monkeyBody(), std::string(reinterpret_cast<const char*>(data), size),
                       "fuzz.json");
}
void runPose(const std::uint8_t* data, std::size_t size) {
  anatomy::parsePose(monkeyBody(), std::string(reinterpret_cast<const char*>(data), size),
                     "fuzz.json");
}
void runGltf(const std::uint8_t* data, std::size_t size) {
  const bool glb =
      size >= 4 && data[0] == 'g' && data[1] == 'l' && data[2] == 'T' && data[3] == 'F';
  ScratchFile file(glb ? "glb" : "gltf");
  animation::importGltf(file.write(data, size));
}
void runMesh(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return;
  ScratchFile file(kMeshExtensions[data[0] % 4]);
  skin::readStaticMesh(file.write(data + 1, size - 1));
}

// An image as a glTF texture or groom map is read: decoded (limits smaller than the default so
// that a fuzz run stays in memory, the checks are the same), made a texture with the wrap, filter
// and encoding taken from the last byte, then sampled; every sample must be finite and in [0, 1].
// The groom target's mesh: a 3 x 3 grid of 1 cm squares (16 vertices, 18 triangles), fur 1 cm.
const skin::SkinMesh& groomMesh() {
  static const skin::SkinMesh mesh = [] {
    skin::SkinMesh s;
    std::vector<skin::TriMesh::VertexHandle> v;
    for (int j = 0; j <= 3; ++j)
      for (int i = 0; i <= 3; ++i)
        v.push_back(s.mesh.add_vertex(skin::TriMesh::Point(0.01f * static_cast<float>(i),
                                                           0.01f * static_cast<float>(j), 0.0f)));
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i) {
        const int a = j * 4 + i, b = a + 1, c = a + 4, d = c + 1;
        s.mesh.add_face(v[static_cast<std::size_t>(a)], v[static_cast<std::size_t>(b)],
                        v[static_cast<std::size_t>(d)]);
        s.mesh.add_face(v[static_cast<std::size_t>(a)], v[static_cast<std::size_t>(d)],
                        v[static_cast<std::size_t>(c)]);
      }
    skin::addSkinProperties(s);
    for (auto vh : s.mesh.vertices()) s.mesh.property(s.furLength, vh) = 0.01f;
    skin::finalizeSkin(s);
    return s;
  }();
  return mesh;
}

// A groom file read for the grid above; one that loads must write back to the same text.
void runGroom(const std::uint8_t* data, std::size_t size) {
  const fur::VertexGroom g = fur::parseGroomFile(
      std::string(reinterpret_cast<const char*>(data), size), "fuzz.json", groomMesh(), "grid");
  const std::string text = fur::groomFileJson(groomMesh(), g);
  if (fur::groomFileJson(groomMesh(),
                         fur::parseGroomFile(text, "round trip", groomMesh(), "grid")) != text)
    throw std::logic_error("groom file round trip differs");
}

// A strokes file: one that loads writes back to the same text, and applied to the grid above it
// keeps every groom value in its range (what a groom file accepts).
void runStrokes(const std::uint8_t* data, std::size_t size) {
  const std::vector<fur::GroomStroke> strokes =
      fur::parseGroomStrokes(std::string(reinterpret_cast<const char*>(data), size), "fuzz.json");
  const std::string text = fur::groomStrokesJson(strokes);
  if (fur::groomStrokesJson(fur::parseGroomStrokes(text, "round trip")) != text)
    throw std::logic_error("strokes round trip differs");
  fur::VertexGroom g;
  fur::applyGroomStrokes(groomMesh(), strokes, g);
  fur::parseGroomFile(fur::groomFileJson(groomMesh(), g), "brushed", groomMesh(), "grid");
}

void runImage(const std::uint8_t* data, std::size_t size) {
  const std::uint8_t mode = size > 0 ? data[size - 1] : 0;
  ImageLimits limits;
  limits.maxSide = 4096;
  limits.maxBytes = std::size_t{16} << 20;
  skin::Texture texture = skin::makeTexture(decodeImage(data, size, "fuzz image", limits),
                                            "fuzz image", (mode & 1) != 0);
  texture.wrapS = static_cast<skin::Wrap>((mode >> 1) % 3);
  texture.wrapT = static_cast<skin::Wrap>((mode >> 3) % 3);
  texture.filter = (mode & 0x20) != 0 ? skin::Filter::Nearest : skin::Filter::Linear;
  const float uvs[][2] = {{0.f, 0.f},    {0.5f, 0.5f}, {0.999f, 1.f},     {-1.25f, 2.75f},
                          {1e9f, -1e9f}, {-0.f, 3.f},  {INFINITY, 0.25f}, {NAN, NAN}};
  for (const auto& uv : uvs) {
    const Eigen::Vector4f c = texture.sample(Eigen::Vector2f(uv[0], uv[1]));
    for (int k = 0; k < 4; ++k) {
      if (!std::isfinite(c[k]) || c[k] < -1e-6f || c[k] > 1.f + 1e-6f)
        throw std::logic_error("texture sample out of [0, 1]");
    }
  }
}

}  // namespace

const std::vector<std::string>& targetNames() {
  static const std::vector<std::string> names = {"creature", "preset", "clip",  "pose",   "gltf",
                                                 "mesh",     "image",  "groom", "strokes"};
  return names;
}

bool runTarget(std::string_view name, const std::uint8_t* data, std::size_t size) {
  try {
    if (name == "creature")
      runCreature(data, size);
    else if (name == "preset")
      runPreset(data, size);
    else if (name == "clip")
      runClip(data, size);
    else if (name == "pose")
      runPose(data, size);
    else if (name == "gltf")
      runGltf(data, size);
    else if (name == "mesh")
      runMesh(data, size);
    else if (name == "image")
      runImage(data, size);
    else if (name == "groom")
      runGroom(data, size);
    else if (name == "strokes")
      runStrokes(data, size);
    else
      throw std::invalid_argument("unknown fuzz target " + std::string(name));
    return true;
  } catch (const InputError&) {
    return false;
  }
}

std::string groomExample() {
  fur::VertexGroom g;
  const auto n = static_cast<std::size_t>(groomMesh().numVertices());
  for (std::size_t v = 0; v < n; ++v) {
    g.length.push_back(0.001f * static_cast<float>(v) + 0.0123f);
    g.density.push_back(v % 3 == 0 ? 0.0f : 1.0f / 3.0f * static_cast<float>(v));
    g.tint.emplace_back(0.1f * static_cast<float>(v % 7), 1.0f, 0.7f);
    g.comb.emplace_back(0.125f * static_cast<float>(v % 5), -0.5f, 0.0f);
    g.clump.push_back(0.25f * static_cast<float>(v % 5));
    g.stiffness.emplace_back(0.125f * static_cast<float>(v % 9),
                             1.0f - 0.25f * static_cast<float>(v % 5));
    g.segmentDirectionWeight.emplace_back(0.25f * static_cast<float>(v % 5),
                                          0.125f * static_cast<float>(v % 9));
    g.curlRadius.emplace_back(0.0625f * static_cast<float>(v % 9), 0.25f);
    g.curlTurns.emplace_back(2.5f * static_cast<float>(v % 9), 0.5f * static_cast<float>(v % 3));
    g.widthScale.emplace_back(0.5f + 0.25f * static_cast<float>(v % 7), 1.5f);
    // The overcoat from its material to the texture along the mesh, the undercoat all creature.
    const float t = 0.25f * static_cast<float>(v % 5);
    for (int s = 0; s < fur::kColorSourceCount; ++s)
      g.colorSourceWeight[static_cast<std::size_t>(s)].emplace_back(
          s == 0 ? 1.0f - t : (s == 2 ? t : 0.0f), s == 1 ? 1.0f : 0.0f);
  }
  return fur::groomFileJson(groomMesh(), g);
}

std::string strokesExample() {
  fur::GroomStroke a;
  a.tool = fur::BrushTool::Length;
  a.points = {{0.005f, 0.01f, 0.002f}, {0.02f, 0.025f, 0.0f}, {0.03f, 0.03f, -0.001f}};
  a.radius = 0.012f;
  a.strength = 1.5f;
  a.mirrorAxis = 2;
  fur::GroomStroke b;
  b.tool = fur::BrushTool::Density;
  b.points = {{0.02f, 0.02f, 0.0f}};
  b.radius = 0.01f;
  b.strength = 0.25f;
  fur::GroomStroke c = b;
  c.tool = fur::BrushTool::Color;
  c.strength = 0.5f;
  c.color = {0.2f, 0.4f, 2.0f};
  fur::GroomStroke d = a;
  d.tool = fur::BrushTool::Comb;
  d.strength = 0.75f;
  fur::GroomStroke e = b;
  e.tool = fur::BrushTool::Cut;
  e.strength = 0.8f;
  e.cutLength = 0.004f;
  e.mirrorAxis = 0;
  fur::GroomStroke f = b;
  f.tool = fur::BrushTool::Clump;
  f.strength = 0.3f;
  return fur::groomStrokesJson({a, b, c, d, e, f});
}

std::string meshInput(std::string_view extension, std::string_view fileBytes) {
  for (int i = 0; i < 4; ++i) {
    if (extension == kMeshExtensions[i])
      return std::string(1, static_cast<char>(i)) + std::string(fileBytes);
  }
  throw std::invalid_argument("unknown mesh extension " + std::string(extension));
}

}  // namespace pelage::fuzz
