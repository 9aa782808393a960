// A frame for a path tracer (reference_scene.h).
#include "pelage/scene/reference_scene.h"

#include <nlohmann/json.hpp>

#include <bit>
#include <cstdint>
#include <cstring>

#include "hair_curves.h"
#include "pelage/fur/colors.h"
#include "pelage/util/atomic_file.h"
#include "pelage/util/error.h"

namespace pelage::scene {
namespace {

constexpr char kMagic[9] = "PLGSCN01";

// The arrays after the header, 4-byte values appended in order.
struct Blobs {
  std::string bytes;
  nlohmann::json add(const void* data, std::size_t count) {
    const nlohmann::json at = {{"offset", bytes.size()}, {"count", count}};
    bytes.append(static_cast<const char*>(data), count * 4);
    return at;
  }
};

nlohmann::json vec3(const Eigen::Vector3f& v) {
  return {v.x(), v.y(), v.z()};
}

}  // namespace

std::string referenceSceneBytes(const DrawList& list, const fur::FurFrame& hairs) {
  static_assert(sizeof(float) == 4 && sizeof(std::uint32_t) == 4);
  static_assert(std::endian::native == std::endian::little,
                "the reference scene is written little-endian, as the host's bytes");
  Blobs blobs;
  nlohmann::json h;
  h["format"] = "pelage reference scene";
  h["version"] = kReferenceSceneVersion;
  const Camera& cam = list.camera;
  h["camera"] = {{"eye", vec3(cam.eye)}, {"target", vec3(cam.target)},
                 {"up", vec3(cam.up)},   {"fovYDegrees", cam.fovYDegrees},
                 {"width", cam.width},   {"height", cam.height}};
  h["light"] = {{"direction", vec3(list.light.direction.normalized())},
                {"color", vec3(list.light.color)},
                {"ambient", vec3(list.light.ambient)}};
  h["background"] = vec3(list.background);

  const SkinDrawItem& skin = list.skin;
  nlohmann::json s = {{"vertices", 0}, {"triangles", 0}};
  if (skin.positions && skin.triangles) {
    const auto nV = static_cast<std::size_t>(skin.vertices);
    const auto nT = static_cast<std::size_t>(skin.triangleCount);
    PELAGE_CHECK(skin.positions->size() == nV && skin.triangles->size() == 3 * nT, "skin item of ",
                 nV, " vertices and ", nT, " triangles");
    std::vector<float> positions(3 * nV);
    for (std::size_t v = 0; v < nV; ++v)
      for (int a = 0; a < 3; ++a)
        positions[3 * v + static_cast<std::size_t>(a)] = (*skin.positions)[v][a];
    std::vector<std::uint32_t> indices(skin.triangles->begin(), skin.triangles->end());
    // Each corner's colour: the surface's own (materials, texture, vertex colours) or the one
    // material's diffuse.
    std::vector<float> corners(9 * nT);
    for (std::size_t t = 0; t < nT; ++t)
      for (int k = 0; k < 3; ++k) {
        float b[3] = {0.0f, 0.0f, 0.0f};
        b[k] = 1.0f;
        const Eigen::Vector3f c =
            skin.appearance
                ? Eigen::Vector3f(
                      skin.appearance->surfaceColorAt(static_cast<std::int32_t>(t), b).head<3>())
                : skin.material.diffuse;
        for (int a = 0; a < 3; ++a)
          corners[9 * t + 3 * static_cast<std::size_t>(k) + static_cast<std::size_t>(a)] = c[a];
      }
    s = {{"vertices", nV},
         {"triangles", nT},
         {"positions", blobs.add(positions.data(), positions.size())},
         {"indices", blobs.add(indices.data(), indices.size())},
         {"cornerColors", blobs.add(corners.data(), corners.size())}};
  }
  h["skin"] = s;

  nlohmann::json coats = nlohmann::json::array();
  for (const FurDrawItem& item : list.fur) {
    PELAGE_CHECK(item.source == HairSource::Cpu, "a reference scene needs the CPU's hairs");
    const fur::HairBuffers& b = hairs.coats[static_cast<std::size_t>(item.coat)];
    PELAGE_CHECK(b.drawn == item.drawnHairs && b.positions.data() == item.positions, "coat ",
                 item.coat, ": the draw list points at other hairs");
    const int K = b.layout.strandPoints;
    const auto n = static_cast<std::size_t>(b.drawn);
    std::vector<float> widths(static_cast<std::size_t>(K));
    for (int k = 0; k < K; ++k)
      widths[static_cast<std::size_t>(k)] =
          item.width.metersAt(b.layout.along(k * b.layout.ringSides));
    std::vector<float> centres(n * static_cast<std::size_t>(3 * K));
    std::vector<float> colors(6 * n);
    for (std::size_t i = 0; i < n; ++i) {
      detail::hairCenterLine(b, static_cast<std::int64_t>(i),
                             centres.data() + i * static_cast<std::size_t>(3 * K));
      for (int end = 0; end < 2; ++end) {
        const Eigen::Vector3f c =
            item.perHairColor ? fur::unpackSrgb8(item.colors[2 * i + static_cast<std::size_t>(end)])
                              : item.material.diffuse;
        for (int a = 0; a < 3; ++a)
          colors[6 * i + 3 * static_cast<std::size_t>(end) + static_cast<std::size_t>(a)] = c[a];
      }
    }
    nlohmann::json coat = {{"coat", item.coat},
                           {"hairs", n},
                           {"points", K},
                           {"cullFactor", item.cullFactor},
                           {"widths", blobs.add(widths.data(), widths.size())},
                           {"positions", blobs.add(centres.data(), centres.size())},
                           {"colors", blobs.add(colors.data(), colors.size())}};
    if (!b.widthScales.empty())
      coat["widthScales"] = blobs.add(b.widthScales.data(), b.widthScales.size());
    coats.push_back(std::move(coat));
  }
  h["coats"] = coats;

  const std::string header = h.dump();
  std::string out(kMagic, 8);
  const std::uint64_t length = header.size();
  char lengthBytes[8];
  std::memcpy(lengthBytes, &length, 8);
  out.append(lengthBytes, 8);
  out += header;
  out += blobs.bytes;
  return out;
}

void writeReferenceScene(const std::string& path, const DrawList& list,
                         const fur::FurFrame& hairs) {
  writeFileAtomically(path, referenceSceneBytes(list, hairs));
}

}  // namespace pelage::scene
