// A shape creature's fur regions and colours on its skin (skin/build_from_shapes.h,
// assignFurRegions and assignFurColors): region membership by segment and volume with blended
// borders, per-vertex fur lengths (Van Gelder & Wilhelms 1997, sec. 3.2 interpolates them), and
// countershaded colours.
#include <cstdint>
#include <string>
#include <vector>

#include "pelage/skin/build_from_shapes.h"
#include "pelage/util/color.h"
#include "pelage/util/error.h"
#include "pelage/util/parallel.h"
#include "shape_sdf.h"

namespace pelage::skin {

using Vec3 = Eigen::Vector3f;
using anatomy::Creature;
using detail::smoothstep01;

namespace {

// How much vertex v (bound to `bind`, at rest position p) belongs to region `reg`, in [0, 1]: 1 on
// its segments and inside its volumes, fading to 0 over `blend` metres outside the volumes.
float membership(const anatomy::FurRegion& reg, const Binding& bind, const Vec3& p) {
  float m = 0.0f;
  for (int s : reg.segments)
    if (bind.segment[0] == s) m = 1.0f;
  auto fade = [&](float outside) {
    if (outside <= 0.0f) return 1.0f;
    if (reg.blend <= 0.0f || outside >= reg.blend) return 0.0f;
    return smoothstep01(1.0f - outside / reg.blend);
  };
  for (const Eigen::Vector4f& sphere : reg.spheres)
    m = std::max(m, fade((p - Vec3(sphere.head<3>())).norm() - sphere[3]));
  for (const Eigen::AlignedBox3f& box : reg.boxes) m = std::max(m, fade(box.exteriorDistance(p)));
  return m;
}

}  // namespace

void assignFurRegions(const Creature& c, SkinMesh& skin) {
  skin.regionNames.assign(1, "body");
  for (const auto& r : c.regions) skin.regionNames.push_back(r.name);
  TriMesh& mesh = skin.mesh;
  const std::int64_t nV = static_cast<std::int64_t>(mesh.n_vertices());
  const Binding* bind = mesh.property(skin.binding).data_vector().data();
  float* lengths = mesh.property(skin.furLength).data_vector().data();
  std::int32_t* regions = mesh.property(skin.region).data_vector().data();
  const TriMesh::Point* pts = mesh.points();
  parallelFor(nV, 1024, [&](std::int64_t v) {
    const Vec3 p(pts[v][0], pts[v][1], pts[v][2]);
    float length = c.furLengthMeters;
    std::int32_t region = 0;
    for (std::size_t r = 0; r < c.regions.size(); ++r) {
      const float m = membership(c.regions[r], bind[v], p);
      // Later regions override earlier ones where they apply.
      length = length + m * (c.furLengthMeters * c.regions[r].lengthScale - length);
      if (m >= 0.5f) region = static_cast<std::int32_t>(r + 1);
    }
    lengths[v] = length;
    regions[v] = region;
  });
}

void assignFurColors(const Creature& c, SkinMesh& skin) {
  skin.furColor.clear();
  if (!c.furColor) return;
  PELAGE_CHECK(!skin.vertexFaceStart.empty(), "assignFurColors before finalizeSkin");
  const std::int64_t nV = skin.numVertices();
  skin.furColor.resize(static_cast<std::size_t>(nV));
  const Binding* bind = skin.bindings();
  const float* rest = skin.restPositions();
  const Vec3 back = srgbToLinear(c.furColor->back), belly = srgbToLinear(c.furColor->belly);
  parallelFor(nV, 1024, [&](std::int64_t v) {
    // The rest normal (area-weighted face normals) picks back or belly: countershading.
    Vec3 n = Vec3::Zero();
    for (std::int32_t k = skin.vertexFaceStart[static_cast<std::size_t>(v)];
         k < skin.vertexFaceStart[static_cast<std::size_t>(v) + 1]; ++k) {
      const std::int32_t* t =
          skin.triangles.data() + 3 * skin.vertexFaces[static_cast<std::size_t>(k)];
      const Vec3 a = Eigen::Map<const Vec3>(rest + 3 * t[0]);
      n += (Eigen::Map<const Vec3>(rest + 3 * t[1]) - a)
               .cross(Eigen::Map<const Vec3>(rest + 3 * t[2]) - a);
    }
    const float up = n.norm() > 0.0f ? n.normalized().z() : 0.0f;
    Vec3 color = belly + smoothstep01((up + c.furColor->spread) / (2.0f * c.furColor->spread)) *
                             (back - belly);
    const Vec3 p = Eigen::Map<const Vec3>(rest + 3 * v);
    for (const anatomy::FurRegion& reg : c.regions) {
      if (!reg.furColor) continue;
      color += membership(reg, bind[v], p) * (srgbToLinear(*reg.furColor) - color);
    }
    skin.furColor[static_cast<std::size_t>(v)] = color;
  });
}

}  // namespace pelage::skin
