#include "pelage/skin/deform.h"

#include "pelage/util/error.h"
#include "pelage/util/parallel.h"

namespace pelage::skin {
namespace {
template <typename T>
void ensureSize(std::vector<T>& v, std::size_t n) {
  if (v.size() != n) v.resize(n);
}
}  // namespace

void computeVertexNormals(const SkinMesh& skin, const std::vector<Eigen::Vector3f>& positions,
                          std::vector<Eigen::Vector3f>& faceScratch,
                          std::vector<Eigen::Vector3f>& normals) {
  const std::int64_t nV = skin.numVertices();
  const std::int64_t nT = skin.numTriangles();
  PELAGE_CHECK(static_cast<std::int64_t>(positions.size()) == nV);
  ensureSize(faceScratch, static_cast<std::size_t>(nT));
  ensureSize(normals, static_cast<std::size_t>(nV));
  const std::int32_t* tri = skin.triangles.data();
  parallelFor(nT, 8192, [&](std::int64_t f) {
    const Eigen::Vector3f& a = positions[static_cast<std::size_t>(tri[3 * f])];
    const Eigen::Vector3f& b = positions[static_cast<std::size_t>(tri[3 * f + 1])];
    const Eigen::Vector3f& c = positions[static_cast<std::size_t>(tri[3 * f + 2])];
    faceScratch[static_cast<std::size_t>(f)] = (b - a).cross(c - a);
  });
  const std::int32_t* start = skin.vertexFaceStart.data();
  const std::int32_t* faces = skin.vertexFaces.data();
  parallelFor(nV, 8192, [&](std::int64_t v) {
    Eigen::Vector3f n = Eigen::Vector3f::Zero();
    for (std::int32_t k = start[v]; k < start[v + 1]; ++k)
      n += faceScratch[static_cast<std::size_t>(faces[k])];
    const float len = n.norm();
    normals[static_cast<std::size_t>(v)] =
        len > 0.0f ? Eigen::Vector3f(n / len) : Eigen::Vector3f(0.0f, 0.0f, 1.0f);
  });
}

void deformSkin(const SkinMesh& skin, const anatomy::BodyState& state, DeformedSkin& out) {
  const std::int64_t nV = skin.numVertices();
  ensureSize(out.positions, static_cast<std::size_t>(nV));
  ensureSize(out.directions, static_cast<std::size_t>(nV));
  const float* rest = skin.restPositions();
  const float* restDir = skin.segmentDirections();
  const Binding* bind = skin.bindings();
  const Eigen::Affine3f* S = state.skinning.data();
  const std::int64_t nS = static_cast<std::int64_t>(state.skinning.size());
  parallelForChunks(nV, 4096, [&](std::int64_t b, std::int64_t e) {
    for (std::int64_t v = b; v < e; ++v) {
      const Binding& bd = bind[v];
      const Eigen::Vector3f p = Eigen::Map<const Eigen::Vector3f>(rest + 3 * v);
      const Eigen::Vector3f d = Eigen::Map<const Eigen::Vector3f>(restDir + 3 * v);
      Eigen::Vector3f P = Eigen::Vector3f::Zero();
      Eigen::Vector3f D = Eigen::Vector3f::Zero();
      for (int k = 0; k < 4; ++k) {
        const float w = bd.weight[static_cast<std::size_t>(k)];
        if (w == 0.0f) continue;
        const std::int32_t s = bd.segment[static_cast<std::size_t>(k)];
        PELAGE_CHECK(s >= 0 && s < nS, "vertex ", v, " bound to segment ", s);
        const Eigen::Affine3f& M = S[s];
        P += w * (M.linear() * p + M.translation());
        D += w * (M.linear() * d);
      }
      out.positions[static_cast<std::size_t>(v)] = P;
      const float len = D.norm();
      out.directions[static_cast<std::size_t>(v)] =
          len > 1e-12f ? Eigen::Vector3f(D / len) : Eigen::Vector3f::Zero();
    }
  });
  computeVertexNormals(skin, out.positions, out.faceNormals, out.normals);
}

void restSkin(const SkinMesh& skin, DeformedSkin& out) {
  const std::size_t nV = static_cast<std::size_t>(skin.numVertices());
  out.positions.resize(nV);
  out.directions.resize(nV);
  for (std::size_t v = 0; v < nV; ++v) {
    out.positions[v] = Eigen::Map<const Eigen::Vector3f>(skin.restPositions() + 3 * v);
    out.directions[v] = Eigen::Map<const Eigen::Vector3f>(skin.segmentDirections() + 3 * v);
  }
  computeVertexNormals(skin, out.positions, out.faceNormals, out.normals);
}

}  // namespace pelage::skin
