#include "pelage/skin/subdivide.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <utility>
#include <vector>

#include "pelage/util/error.h"

namespace pelage::skin {
namespace {

// One edge of the old mesh: its ends (a < b).
struct Edge {
  std::int32_t a = 0, b = 0;
};

std::uint64_t edgeKey(std::int32_t a, std::int32_t b) {
  if (a > b) std::swap(a, b);
  return static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32 |
         static_cast<std::uint32_t>(b);
}

SkinMesh subdivideOnce(const SkinMesh& in) {
  const std::int32_t nV = in.numVertices();
  const std::int32_t nT = in.numTriangles();
  const std::int32_t* tri = in.triangles.data();

  // Edges, in order of first appearance (deterministic), and each face's three edges.
  std::unordered_map<std::uint64_t, std::int32_t> edgeIndex;
  edgeIndex.reserve(static_cast<std::size_t>(nT) * 2);
  std::vector<Edge> edges;
  std::vector<std::int32_t> faceEdge(static_cast<std::size_t>(nT) * 3);
  for (std::int32_t t = 0; t < nT; ++t)
    for (int j = 0; j < 3; ++j) {
      const std::int32_t a = tri[3 * t + j], b = tri[3 * t + (j + 1) % 3];
      const auto [it, inserted] =
          edgeIndex.try_emplace(edgeKey(a, b), static_cast<std::int32_t>(edges.size()));
      if (inserted) {
        Edge e;
        e.a = std::min(a, b);
        e.b = std::max(a, b);
        edges.push_back(e);
      }
      faceEdge[static_cast<std::size_t>(3 * t + j)] = it->second;
    }
  const auto nE = static_cast<std::int32_t>(edges.size());

  // Values: each new vertex takes the mean of its two ends' (an old vertex is both its ends, so it
  // keeps its own exactly).
  std::vector<std::array<std::int32_t, 2>> ends(static_cast<std::size_t>(nV + nE));
  for (std::int32_t v = 0; v < nV; ++v) ends[static_cast<std::size_t>(v)] = {v, v};
  for (std::int32_t e = 0; e < nE; ++e) {
    const Edge& ed = edges[static_cast<std::size_t>(e)];
    ends[static_cast<std::size_t>(nV + e)] = {ed.a, ed.b};
  }
  // Positions: old vertices stay; an edge vertex is the midpoint of the PN triangles' cubic edge
  // curve (Vlachos et al. 2001) through its ends with their (area-weighted) vertex normals:
  // (P0 + 3 b1 + 3 b2 + P1) / 8, b1 = (2 P0 + P1 - ((P1 - P0).N0) N0) / 3, b2 likewise.
  const float* p = in.restPositions();
  std::vector<Eigen::Vector3d> normal(static_cast<std::size_t>(nV), Eigen::Vector3d::Zero());
  const auto P = [p](std::int32_t v) {
    return Eigen::Vector3d(p[3 * v], p[3 * v + 1], p[3 * v + 2]);
  };
  for (std::int32_t t = 0; t < nT; ++t) {
    const std::int32_t* v = tri + 3 * t;
    const Eigen::Vector3d n = (P(v[1]) - P(v[0])).cross(P(v[2]) - P(v[0]));
    for (int k = 0; k < 3; ++k) normal[static_cast<std::size_t>(v[k])] += n;
  }
  for (Eigen::Vector3d& n : normal) {
    const double l = n.norm();
    n = l > 0.0 ? Eigen::Vector3d(n / l) : Eigen::Vector3d::Zero();
  }
  std::vector<Eigen::Vector3d> position(static_cast<std::size_t>(nV + nE));
  for (std::int32_t v = 0; v < nV; ++v) position[static_cast<std::size_t>(v)] = P(v);
  for (std::int32_t e = 0; e < nE; ++e) {
    const Edge& ed = edges[static_cast<std::size_t>(e)];
    const Eigen::Vector3d p0 = P(ed.a), p1 = P(ed.b);
    const Eigen::Vector3d& n0 = normal[static_cast<std::size_t>(ed.a)];
    const Eigen::Vector3d& n1 = normal[static_cast<std::size_t>(ed.b)];
    const Eigen::Vector3d b1 = (2.0 * p0 + p1 - (p1 - p0).dot(n0) * n0) / 3.0;
    const Eigen::Vector3d b2 = (2.0 * p1 + p0 - (p0 - p1).dot(n1) * n1) / 3.0;
    position[static_cast<std::size_t>(nV + e)] = (p0 + 3.0 * b1 + 3.0 * b2 + p1) / 8.0;
  }

  // The new vertices' values.
  const std::int32_t nV2 = nV + nE;
  const float* len = in.furLengths();
  const float* dir = in.segmentDirections();
  const std::int32_t* region = in.regions();
  const Binding* bind = in.bindings();
  SkinMesh out;
  out.regionNames = in.regionNames;
  out.color = in.color;
  out.materials = in.materials;
  out.textures = in.textures;
  std::vector<TriMesh::VertexHandle> vh(static_cast<std::size_t>(nV2));
  for (std::int32_t v = 0; v < nV2; ++v) {
    const Eigen::Vector3d& x = position[static_cast<std::size_t>(v)];
    vh[static_cast<std::size_t>(v)] = out.mesh.add_vertex(TriMesh::Point(
        static_cast<float>(x.x()), static_cast<float>(x.y()), static_cast<float>(x.z())));
  }
  std::vector<std::array<std::int32_t, 3>> faces;
  faces.reserve(static_cast<std::size_t>(nT) * 4);
  std::vector<std::int32_t> inputTriangles;
  std::vector<Eigen::Vector2f> inputUv;
  const bool uv = in.hasUv();
  for (std::int32_t t = 0; t < nT; ++t) {
    const std::int32_t* v = tri + 3 * t;
    const std::int32_t e[3] = {
        nV + faceEdge[static_cast<std::size_t>(3 * t)],
        nV + faceEdge[static_cast<std::size_t>(3 * t + 1)],
        nV + faceEdge[static_cast<std::size_t>(3 * t + 2)]};  // e[j]: v[j]-v[j+1]
    faces.push_back({v[0], e[0], e[2]});
    faces.push_back({v[1], e[1], e[0]});
    faces.push_back({v[2], e[2], e[1]});
    faces.push_back({e[0], e[1], e[2]});
    if (uv) {
      const Eigen::Vector2f* c = in.cornerUv.data() + 3 * static_cast<std::size_t>(t);
      const Eigen::Vector2f m[3] = {0.5f * (c[0] + c[1]), 0.5f * (c[1] + c[2]),
                                    0.5f * (c[2] + c[0])};
      for (const Eigen::Vector2f& q :
           {c[0], m[0], m[2], c[1], m[1], m[0], c[2], m[2], m[1], m[0], m[1], m[2]})
        inputUv.push_back(q);
    }
  }
  for (const auto& f : faces) {
    const auto fh =
        out.mesh.add_face(vh[static_cast<std::size_t>(f[0])], vh[static_cast<std::size_t>(f[1])],
                          vh[static_cast<std::size_t>(f[2])]);
    PELAGE_CHECK(fh.is_valid(), "subdivision made a face OpenMesh refuses");
    inputTriangles.insert(inputTriangles.end(), f.begin(), f.end());
  }
  addSkinProperties(out);
  for (std::int32_t v = 0; v < nV2; ++v) {
    const auto [ea, eb] = ends[static_cast<std::size_t>(v)];
    const TriMesh::VertexHandle h = vh[static_cast<std::size_t>(v)];
    // Fur length: bare stays bare; the region of the barer end.
    double length = 0.0;
    Eigen::Vector3d d = Eigen::Vector3d::Zero();
    for (const std::int32_t u : {ea, eb}) {
      length += 0.5 * static_cast<double>(len[u]);
      for (int k = 0; k < 3; ++k) d[k] += 0.5 * static_cast<double>(dir[3 * u + k]);
    }
    const bool bare = len[ea] == 0.0f || len[eb] == 0.0f;
    const std::int32_t r = len[ea] != 0.0f && len[eb] == 0.0f ? region[eb] : region[ea];
    out.mesh.property(out.furLength, h) = bare ? 0.0f : static_cast<float>(std::max(0.0, length));
    out.mesh.property(out.region, h) = r;
    const double dn = d.norm();
    const Eigen::Vector3f df =
        dn > 1e-6 ? Eigen::Vector3f((d / dn).cast<float>()) : Eigen::Vector3f::Zero();
    out.mesh.property(out.segmentDirection, h) = OpenMesh::Vec3f(df.x(), df.y(), df.z());
    // Skin weights: summed per segment, the 4 largest (ties: the lower segment) renormalised.
    std::vector<std::pair<std::int32_t, double>> sum;
    for (const std::int32_t u : {ea, eb})
      for (std::size_t k = 0; k < 4; ++k) {
        const float bw = bind[u].weight[k];
        if (bw == 0.0f) continue;
        const std::int32_t s = bind[u].segment[k];
        auto it = std::find_if(sum.begin(), sum.end(), [s](const auto& e) { return e.first == s; });
        if (it == sum.end())
          sum.push_back({s, 0.5 * static_cast<double>(bw)});
        else
          it->second += 0.5 * static_cast<double>(bw);
      }
    std::sort(sum.begin(), sum.end(), [](const auto& x, const auto& y) {
      return x.second != y.second ? x.second > y.second : x.first < y.first;
    });
    Binding b;
    b.weight = {0.0f, 0.0f, 0.0f, 0.0f};
    double total = 0.0;
    for (std::size_t k = 0; k < sum.size() && k < 4; ++k) total += std::max(0.0, sum[k].second);
    for (std::size_t k = 0; k < sum.size() && k < 4; ++k) {
      b.segment[k] = sum[k].first;
      b.weight[k] = total > 0.0 ? static_cast<float>(std::max(0.0, sum[k].second) / total) : 0.0f;
    }
    if (!(total > 0.0)) b = bind[ea];
    out.mesh.property(out.binding, h) = b;
  }
  const auto carry = [&](const auto& values, auto& result) {
    if (values.empty()) return;
    using V = typename std::decay_t<decltype(values)>::value_type;
    result.assign(static_cast<std::size_t>(nV2), V::Zero());
    for (std::int32_t v = 0; v < nV2; ++v)
      for (const std::int32_t u : ends[static_cast<std::size_t>(v)])
        result[static_cast<std::size_t>(v)] += 0.5f * values[static_cast<std::size_t>(u)];
  };
  carry(in.vertexColor, out.vertexColor);
  carry(in.furColor, out.furColor);
  finalizeSkin(out);
  if (uv) setCornerUvs(out, inputTriangles, inputUv);
  if (!in.triangleMaterial.empty()) {
    out.triangleMaterial.resize(static_cast<std::size_t>(nT) * 4);
    for (std::int32_t t = 0; t < 4 * nT; ++t)
      out.triangleMaterial[static_cast<std::size_t>(t)] =
          in.triangleMaterial[static_cast<std::size_t>(t / 4)];
  }
  checkAppearance(out);
  return out;
}

}  // namespace

int autoSubdivisionLevels(int triangles) {
  int levels = 0;
  for (long long t = triangles; t > 0 && t < kSmoothSkinTriangles && levels < kMaxSubdivisionLevels;
       t *= 4)
    ++levels;
  return levels;
}

SkinMesh subdivideSkin(const SkinMesh& skin, int levels) {
  PELAGE_CHECK(levels >= 0 && levels <= kMaxSubdivisionLevels, "subdivision levels ", levels);
  SkinMesh s = levels == 0 ? skin : subdivideOnce(skin);
  for (int l = 1; l < levels; ++l) s = subdivideOnce(s);
  return s;
}

}  // namespace pelage::skin
