#include "pelage/fur/hair_ply.h"

#include <algorithm>
#include <bit>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>
#include <vector>

#include "pelage/util/atomic_file.h"
#include "pelage/util/error.h"

namespace pelage::fur {

HairPlyCounts hairPlyCounts(const FurFrame& frame) {
  HairPlyCounts n;
  for (const HairBuffers& hb : frame.coats) {
    n.vertices += hb.drawn * hb.layout.pointsPerHair();
    n.edges += hb.drawn * hb.layout.segmentsPerHair();
    n.faces += hb.drawn * hb.layout.trianglesPerHair();
  }
  return n;
}

float exportedWidth(const FurFrame& frame, const FurParams& params, int coat, std::int64_t hair,
                    int k) {
  const HairBuffers& hb = frame.coats[static_cast<std::size_t>(coat)];
  const float w = params.coats[static_cast<std::size_t>(coat)].width.metersAt(hb.layout.along(k)) *
                  hb.widthScaleOf(hair);
  return hb.layout.topology == HairTopology::Strand ? w * std::max(frame.cullingFactor, 1.0f) : w;
}

HairPlyCounts writeHairPly(const std::string& path, const FurFrame& frame, const FurParams& params,
                           const std::string& comment, const FurColors* colors) {
  static_assert(std::numeric_limits<float>::is_iec559 && sizeof(float) == 4);
  static_assert(std::endian::native == std::endian::little,
                "PLY writer assumes a little-endian host");
  const HairPlyCounts n = hairPlyCounts(frame);
  if (n.vertices > std::numeric_limits<std::int32_t>::max())
    inputError(path, ": ", n.vertices,
               " hair points exceed the PLY int index range (at most 2147483647)");
  // Edges join the points of strand hairs, faces are the triangles of ring (tube) hairs; a frame
  // with no hairs still has an edge element.
  bool anyRings = false, anyStrand = false;
  for (const HairBuffers& hb : frame.coats)
    if (hb.drawn > 0) (hb.layout.topology == HairTopology::Rings ? anyRings : anyStrand) = true;
  std::ostringstream h;
  h << "ply\nformat binary_little_endian 1.0\ncomment pelage hairs (Van Gelder & Wilhelms 1997 "
       "fur)\n";
  std::istringstream lines(comment);
  for (std::string line; std::getline(lines, line);) h << "comment " << line << "\n";
  h << "element vertex " << n.vertices << "\nproperty float x\nproperty float y\nproperty float z\n"
    << "property float nx\nproperty float ny\nproperty float nz\nproperty int hair\nproperty uchar "
       "coat\nproperty float width\n";
  if (colors) h << "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  if (anyStrand || !anyRings)
    h << "element edge " << n.edges << "\nproperty int vertex1\nproperty int vertex2\n";
  if (anyRings) h << "element face " << n.faces << "\nproperty list uchar int vertex_indices\n";
  h << "end_header\n";

  AtomicFileWriter w(path);
  w.write(h.str());
  std::vector<std::uint8_t> rgb;
  std::vector<float> widths;
  for (int c = 0; c < kCoatCount; ++c) {
    const HairBuffers& hb = frame.coats[static_cast<std::size_t>(c)];
    const std::int64_t P = hb.layout.pointsPerHair();
    const auto coat = static_cast<std::uint8_t>(c);
    if (colors) pointColorsSrgb8(colors->coats[static_cast<std::size_t>(c)], hb, rgb);
    const std::size_t size = colors ? 36 : 33;
    widths.resize(static_cast<std::size_t>(P));
    const auto hairWidths = [&](std::int64_t i) {
      for (int k = 0; k < P; ++k)
        widths[static_cast<std::size_t>(k)] = exportedWidth(frame, params, c, i, k);
    };
    hairWidths(0);  // every hair's, unless the hairs have widths of their own
    for (std::int64_t i = 0; i < hb.drawn; ++i) {
      if (!hb.widthScales.empty()) hairWidths(i);
      for (std::int64_t k = 0; k < P; ++k) {
        char rec[36];  // 6 floats, int, uchar, float (and 3 uchar): little-endian like the host
        std::memcpy(rec, hb.positions.data() + (i * P + k) * 3, 12);
        std::memcpy(rec + 12, hb.normals.data() + (i * P + k) * 3, 12);
        std::memcpy(rec + 24, &hb.hairIds[static_cast<std::size_t>(i)], 4);
        rec[28] = static_cast<char>(coat);
        std::memcpy(rec + 29, &widths[static_cast<std::size_t>(k)], 4);
        if (colors) std::memcpy(rec + 33, rgb.data() + 3 * (i * P + k), 3);
        w.write(rec, size);
      }
    }
  }
  std::int32_t base = 0;
  for (const HairBuffers& hb : frame.coats) {  // edges
    const auto P = static_cast<std::int32_t>(hb.layout.pointsPerHair());
    if (hb.layout.segmentsPerHair() > 0)
      for (std::int64_t i = 0; i < hb.drawn; ++i)
        for (std::int32_t k = 0; k + 1 < P; ++k) {
          const std::int32_t v = base + static_cast<std::int32_t>(i) * P + k;
          w.put(v);
          w.put(static_cast<std::int32_t>(v + 1));
        }
    base += static_cast<std::int32_t>(hb.drawn * P);
  }
  base = 0;
  for (const HairBuffers& hb : frame.coats) {  // faces
    const auto P = static_cast<std::int32_t>(hb.layout.pointsPerHair());
    const std::vector<std::int32_t> pattern = hairTriangles(hb.layout);
    for (std::int64_t i = 0; i < hb.drawn && !pattern.empty(); ++i)
      for (std::size_t t = 0; t < pattern.size(); t += 3) {
        w.put(std::uint8_t{3});
        for (std::size_t k = 0; k < 3; ++k)
          w.put(static_cast<std::int32_t>(base + i * P + pattern[t + k]));
      }
    base += static_cast<std::int32_t>(hb.drawn * P);
  }
  w.commit();
  return n;
}

bool isCompleteHairPly(const std::string& path) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) return false;
  const auto size = static_cast<std::int64_t>(in.tellg());
  in.seekg(0);
  std::string line;
  if (!std::getline(in, line) || line != "ply") return false;
  std::int64_t vertices = -1, edges = 0, faces = 0, vertexBytes = 0;
  bool inVertex = false;
  while (std::getline(in, line) && line != "end_header") {
    std::istringstream words(line);
    std::string kind, what;
    std::int64_t n = -1;
    if (!(words >> kind)) continue;
    if (kind == "property" && inVertex && words >> what)
      vertexBytes += what == "uchar" ? 1 : 4;  // float, int or uchar: what writeHairPly writes
    if (kind != "element") continue;
    if (!(words >> what >> n) || n < 0) return false;
    inVertex = what == "vertex";
    if (what == "vertex") vertices = n;
    if (what == "edge") edges = n;
    if (what == "face") faces = n;
    if (in.tellg() > (1 << 16)) return false;
  }
  if (line != "end_header" || vertices < 0) return false;
  // Body: 33 or 36 bytes per vertex (6 floats, int, uchar, float, and the colour), 8 per edge, 13
  // per triangle face.
  if (vertexBytes != 33 && vertexBytes != 36) return false;
  const std::int64_t body = vertices * vertexBytes + edges * 8 + faces * 13;
  return static_cast<std::int64_t>(in.tellg()) + body == size;
}

}  // namespace pelage::fur
