#include "pelage/skin/skin_mesh.h"

#include <algorithm>
#include <cmath>

#include "pelage/util/error.h"

namespace pelage::skin {

void addSkinProperties(SkinMesh& skin) {
  TriMesh& m = skin.mesh;
  if (!skin.binding.is_valid()) m.add_property(skin.binding, "pelage:binding");
  if (!skin.furLength.is_valid()) m.add_property(skin.furLength, "pelage:furLength");
  if (!skin.region.is_valid()) m.add_property(skin.region, "pelage:region");
  if (!skin.segmentDirection.is_valid())
    m.add_property(skin.segmentDirection, "pelage:segmentDirection");
  for (auto v : m.vertices()) {
    m.property(skin.binding, v) = Binding{};
    m.property(skin.furLength, v) = 0.0f;
    m.property(skin.region, v) = 0;
    m.property(skin.segmentDirection, v) = OpenMesh::Vec3f(0.0f, 0.0f, 0.0f);
  }
}

void finalizeSkin(SkinMesh& skin) {
  TriMesh& m = skin.mesh;
  PELAGE_CHECK(skin.binding.is_valid() && skin.furLength.is_valid() && skin.region.is_valid() &&
                   skin.segmentDirection.is_valid(),
               "addSkinProperties was not called");
  const int nV = static_cast<int>(m.n_vertices());
  const int nF = static_cast<int>(m.n_faces());
  skin.triangles.assign(static_cast<std::size_t>(nF) * 3, 0);
  std::vector<std::int32_t> degree(static_cast<std::size_t>(nV) + 1, 0);
  double area = 0.0;
  for (auto f : m.faces()) {
    PELAGE_CHECK(!m.status(f).deleted(), "deleted face: call garbage_collection first");
    int k = 0;
    std::int32_t idx[3] = {0, 0, 0};
    for (auto v : m.fv_range(f)) {
      PELAGE_CHECK(k < 3, "face ", f.idx(), " is not a triangle");
      idx[k++] = v.idx();
    }
    PELAGE_CHECK(k == 3, "face ", f.idx(), " has ", k, " vertices");
    for (int j = 0; j < 3; ++j) {
      skin.triangles[static_cast<std::size_t>(f.idx()) * 3 + static_cast<std::size_t>(j)] = idx[j];
      ++degree[static_cast<std::size_t>(idx[j]) + 1];
    }
    const auto& a = m.point(TriMesh::VertexHandle(idx[0]));
    const auto& b = m.point(TriMesh::VertexHandle(idx[1]));
    const auto& c = m.point(TriMesh::VertexHandle(idx[2]));
    area += 0.5 * static_cast<double>(OpenMesh::cross(b - a, c - a).norm());
  }
  skin.restArea = area;
  for (int v = 0; v < nV; ++v)
    degree[static_cast<std::size_t>(v) + 1] += degree[static_cast<std::size_t>(v)];
  skin.vertexFaceStart = degree;
  skin.vertexFaces.assign(static_cast<std::size_t>(degree.back()), 0);
  std::vector<std::int32_t> fill(degree.begin(), degree.end() - 1);
  for (int f = 0; f < nF; ++f)
    for (int j = 0; j < 3; ++j) {
      const auto v = static_cast<std::size_t>(
          skin.triangles[static_cast<std::size_t>(f) * 3 + static_cast<std::size_t>(j)]);
      skin.vertexFaces[static_cast<std::size_t>(fill[v]++)] = f;
    }
}

SkinStats skinStats(const SkinMesh& skin) {
  const TriMesh& m = skin.mesh;
  SkinStats s;
  s.vertices = skin.numVertices();
  s.triangles = skin.numTriangles();
  s.area = skin.restArea;
  if (s.vertices > 0) {
    Eigen::Map<const Eigen::Matrix<float, 3, Eigen::Dynamic>> P(skin.restPositions(), 3,
                                                                s.vertices);
    s.boundsMin = P.rowwise().minCoeff();
    s.boundsMax = P.rowwise().maxCoeff();
  }
  for (auto e : m.edges()) s.boundaryEdges += m.is_boundary(e) ? 1 : 0;
  for (auto v : m.vertices()) s.nonManifoldVertices += m.is_manifold(v) ? 0 : 1;
  double minAngle = 180.0;
  for (int f = 0; f < s.triangles; ++f) {
    Eigen::Vector3f p[3];
    for (int j = 0; j < 3; ++j)
      p[j] = Eigen::Map<const Eigen::Vector3f>(
          skin.restPositions() + 3 * skin.triangles[static_cast<std::size_t>(3 * f + j)]);
    for (int j = 0; j < 3; ++j) {
      const Eigen::Vector3f u = p[(j + 1) % 3] - p[j], w = p[(j + 2) % 3] - p[j];
      const double c = static_cast<double>(u.normalized().dot(w.normalized()));
      minAngle = std::min(minAngle, std::acos(std::clamp(c, -1.0, 1.0)) * 180.0 / M_PI);
    }
  }
  s.minAngleDegrees = s.triangles > 0 ? minAngle : 0.0;
  return s;
}

Eigen::Vector2f SkinMesh::uvAt(std::int32_t t, const float b[3]) const {
  if (cornerUv.empty()) return Eigen::Vector2f::Zero();
  const Eigen::Vector2f* c = cornerUv.data() + 3 * static_cast<std::size_t>(t);
  return (c[0] * b[0] + c[1] * b[1]) + c[2] * b[2];
}

Eigen::Vector4f SkinMesh::surfaceColorAt(std::int32_t t, const float b[3]) const {
  if (!hasSurfaceColor()) return {color.x(), color.y(), color.z(), 1.0f};
  Eigen::Vector4f c = Eigen::Vector4f::Ones();
  if (!materials.empty()) {
    const SkinMaterial& m =
        materials[static_cast<std::size_t>(triangleMaterial[static_cast<std::size_t>(t)])];
    c = m.baseColor;
    if (m.texture >= 0)
      c = c.cwiseProduct(textures[static_cast<std::size_t>(m.texture)].sample(uvAt(t, b)));
  }
  if (!vertexColor.empty()) {
    const std::int32_t* v = triangles.data() + 3 * static_cast<std::size_t>(t);
    const Eigen::Vector4f vc = (vertexColor[static_cast<std::size_t>(v[0])] * b[0] +
                                vertexColor[static_cast<std::size_t>(v[1])] * b[1]) +
                               vertexColor[static_cast<std::size_t>(v[2])] * b[2];
    c = c.cwiseProduct(vc);
  }
  return c;
}

void setCornerUvs(SkinMesh& skin, const std::vector<std::int32_t>& inputTriangles,
                  const std::vector<Eigen::Vector2f>& inputUv) {
  const std::size_t n = skin.triangles.size();
  PELAGE_CHECK(inputTriangles.size() == n && inputUv.size() == n, "corner UVs for ",
               inputTriangles.size() / 3, " faces, skin has ", n / 3);
  skin.cornerUv.assign(n, Eigen::Vector2f::Zero());
  for (std::size_t f = 0; f < n / 3; ++f)
    for (std::size_t j = 0; j < 3; ++j) {
      const std::int32_t v = skin.triangles[3 * f + j];
      std::size_t k = 0;
      while (k < 3 && inputTriangles[3 * f + k] != v) ++k;
      PELAGE_CHECK(k < 3, "face ", f, " has vertex ", v, " that its input corners lack");
      skin.cornerUv[3 * f + j] = inputUv[3 * f + k];
    }
}

void checkAppearance(const SkinMesh& skin) {
  const auto nT = static_cast<std::size_t>(skin.numTriangles());
  const auto nV = static_cast<std::size_t>(skin.numVertices());
  PELAGE_CHECK(skin.cornerUv.empty() || skin.cornerUv.size() == 3 * nT, "corner UVs");
  PELAGE_CHECK(skin.vertexColor.empty() || skin.vertexColor.size() == nV, "vertex colours");
  PELAGE_CHECK(skin.furColor.empty() || skin.furColor.size() == nV, "fur colours");
  if (skin.materials.empty()) return;
  PELAGE_CHECK(skin.triangleMaterial.size() == nT, "triangle materials");
  for (std::int32_t m : skin.triangleMaterial)
    PELAGE_CHECK(m >= 0 && static_cast<std::size_t>(m) < skin.materials.size(), "material ", m);
  for (const SkinMaterial& m : skin.materials)
    PELAGE_CHECK(m.texture < static_cast<int>(skin.textures.size()), "texture ", m.texture);
}

}  // namespace pelage::skin
