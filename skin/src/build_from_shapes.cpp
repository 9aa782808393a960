#include "pelage/skin/build_from_shapes.h"

#include <OpenMesh/Tools/Decimater/DecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModAspectRatioT.hh>
#include <OpenMesh/Tools/Decimater/ModNormalFlippingT.hh>
#include <OpenMesh/Tools/Decimater/ModQuadricT.hh>
#include <OpenMesh/Tools/Smoother/JacobiLaplaceSmootherT.hh>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "pelage/util/error.h"
#include "pelage/util/parallel.h"
#include "shape_sdf.h"

namespace pelage::skin {
namespace {

using Vec3 = Eigen::Vector3f;
using anatomy::Creature;

// Below this many triangles, thin parts (tail tip, fingers) would be lost by a coarse grid, so the
// surface is polygonised at kDecimateFrom triangles and then decimated with OpenMesh.
constexpr int kDecimateBelow = 40000;
constexpr int kDecimateFrom = 80000;
constexpr int kBlock = 8;  // cells per block edge for the sparse grid

Vec3 fieldGradient(const Creature& c, const Vec3& p, float eps) {
  Vec3 g;
  for (int a = 0; a < 3; ++a) {
    Vec3 d = Vec3::Zero();
    d[a] = eps;
    g[a] = (creatureDistance(c, p + d) - creatureDistance(c, p - d)) / (2.0f * eps);
  }
  return g;
}

// Newton steps onto the zero level set along the gradient, each step at most maxStep long.
Vec3 projectToSurface(const Creature& c, Vec3 p, float eps, float maxStep) {
  for (int it = 0; it < 4; ++it) {
    const float f = creatureDistance(c, p);
    const Vec3 g = fieldGradient(c, p, eps);
    const float g2 = g.squaredNorm();
    if (g2 < 1e-12f) break;
    Vec3 step = g * (f / g2);
    const float len = step.norm();
    if (len > maxStep) step *= maxStep / len;
    p -= step;
    if (len < 1e-7f) break;
  }
  return p;
}

// Dual contouring without normals on a sparse grid: vertices inside the cells the surface crosses,
// one quad per crossing grid edge, oriented so that its normal points to the outside (positive
// distance).
struct SurfaceNet {
  std::vector<Vec3> vertices;
  std::vector<std::array<std::int32_t, 4>> quads;
  bool holes = false;  // a crossing edge whose four cells were not all found
};

SurfaceNet surfaceNets(const Creature& c, const Eigen::AlignedBox3f& bounds, float h) {
  const Vec3 origin = bounds.min() - Vec3::Constant(2.0f * h);
  const Eigen::Vector3i cells =
      ((bounds.sizes() + Vec3::Constant(4.0f * h)) / h).array().ceil().cast<int>();
  const Eigen::Vector3i nb = (cells.array() + kBlock - 1) / kBlock;
  const std::int64_t nBlocks = static_cast<std::int64_t>(nb.x()) * nb.y() * nb.z();
  auto blockId = [&](int bx, int by, int bz) {
    return (static_cast<std::int64_t>(bz) * nb.y() + by) * nb.x() + bx;
  };

  // 1. Blocks near the surface: |distance at the centre| within the block's reach (a factor 2
  // covers the approximate ellipsoid distance), then dilated by one block.
  const float halfDiag = 0.5f * std::sqrt(3.0f) * static_cast<float>(kBlock) * h;
  std::vector<std::uint8_t> near(static_cast<std::size_t>(nBlocks), 0);
  parallelFor(nBlocks, 64, [&](std::int64_t b) {
    const int bx = static_cast<int>(b % nb.x());
    const int by = static_cast<int>((b / nb.x()) % nb.y());
    const int bz = static_cast<int>(b / (static_cast<std::int64_t>(nb.x()) * nb.y()));
    const Vec3 ctr =
        origin + h * static_cast<float>(kBlock) *
                     (Vec3(static_cast<float>(bx), static_cast<float>(by), static_cast<float>(bz)) +
                      Vec3::Constant(0.5f));
    near[static_cast<std::size_t>(b)] = std::abs(creatureDistance(c, ctr)) <= 2.0f * halfDiag + h;
  });
  std::vector<std::int32_t> slot(static_cast<std::size_t>(nBlocks), -1);
  std::vector<Eigen::Vector3i> active;
  for (int bz = 0; bz < nb.z(); ++bz)
    for (int by = 0; by < nb.y(); ++by)
      for (int bx = 0; bx < nb.x(); ++bx) {
        bool on = false;
        for (int dz = -1; dz <= 1 && !on; ++dz)
          for (int dy = -1; dy <= 1 && !on; ++dy)
            for (int dx = -1; dx <= 1 && !on; ++dx) {
              const int x = bx + dx, y = by + dy, z = bz + dz;
              if (x < 0 || y < 0 || z < 0 || x >= nb.x() || y >= nb.y() || z >= nb.z()) continue;
              on = near[static_cast<std::size_t>(blockId(x, y, z))] != 0;
            }
        if (on) {
          slot[static_cast<std::size_t>(blockId(bx, by, bz))] =
              static_cast<std::int32_t>(active.size());
          active.emplace_back(bx, by, bz);
        }
      }

  // 2. Field values at block corners, then, per cell, one vertex per connected piece of surface
  // inside the cell (dual marching cubes, Nielson 2004): crossing edges are joined across each
  // cube face, an ambiguous face (4 crossings) resolved by the asymptotic decider so that the two
  // cells sharing it agree. This keeps the mesh manifold where plain surface nets would pinch.
  constexpr int kC = kBlock + 1;
  constexpr int kCells = kBlock * kBlock * kBlock;
  const std::size_t nActive = active.size();
  std::vector<std::vector<float>> values(nActive);
  std::vector<std::vector<std::int32_t>> cellFirst(nActive);  // B^3: first local vertex or -1
  std::vector<std::vector<std::array<std::int8_t, 12>>> cellEdgeComp(
      nActive);  // B^3 x 12: component of each crossing edge
  std::vector<std::vector<Vec3>> blockVerts(nActive);
  // Cell edges: start corner and axis. x: 0-3, y: 4-7, z: 8-11.
  static constexpr int kEdgeStart[12][3] = {{0, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, 1, 1},
                                            {0, 0, 0}, {1, 0, 0}, {0, 0, 1}, {1, 0, 1},
                                            {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
  static constexpr int kEdgeAxis[12] = {0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2, 2};
  // Cube faces: corners in cyclic order and the edges between consecutive corners (c0c1, c1c2,
  // c2c3, c3c0).
  static constexpr int kFaceCorner[6][4][3] = {
      {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}},
      {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}}, {{0, 1, 0}, {1, 1, 0}, {1, 1, 1}, {0, 1, 1}},
      {{0, 0, 0}, {0, 1, 0}, {0, 1, 1}, {0, 0, 1}}, {{1, 0, 0}, {1, 1, 0}, {1, 1, 1}, {1, 0, 1}}};
  static constexpr int kFaceEdge[6][4] = {{0, 5, 1, 4},   {2, 7, 3, 6},  {0, 9, 2, 8},
                                          {1, 11, 3, 10}, {4, 10, 6, 8}, {5, 11, 7, 9}};
  parallelFor(static_cast<std::int64_t>(nActive), 1, [&](std::int64_t s) {
    const std::size_t si = static_cast<std::size_t>(s);
    const Eigen::Vector3i& b = active[si];
    std::vector<float>& v = values[si];
    v.resize(kC * kC * kC);
    const Eigen::Vector3i base = b * kBlock;
    for (int z = 0; z < kC; ++z)
      for (int y = 0; y < kC; ++y)
        for (int x = 0; x < kC; ++x) {
          const Vec3 p =
              origin + h * Vec3(static_cast<float>(base.x() + x), static_cast<float>(base.y() + y),
                                static_cast<float>(base.z() + z));
          v[static_cast<std::size_t>((z * kC + y) * kC + x)] = creatureDistance(c, p);
        }
    auto val = [&](int x, int y, int z) {
      return v[static_cast<std::size_t>((z * kC + y) * kC + x)];
    };
    cellFirst[si].assign(kCells, -1);
    cellEdgeComp[si].resize(kCells);
    for (int z = 0; z < kBlock; ++z)
      for (int y = 0; y < kBlock; ++y)
        for (int x = 0; x < kBlock; ++x) {
          const int cell = (z * kBlock + y) * kBlock + x;
          float corner[2][2][2];
          for (int dz = 0; dz < 2; ++dz)
            for (int dy = 0; dy < 2; ++dy)
              for (int dx = 0; dx < 2; ++dx) corner[dx][dy][dz] = val(x + dx, y + dy, z + dz);
          auto inside = [](float f) { return f < 0.0f; };
          bool crossing[12];
          int nCross = 0;
          for (int e = 0; e < 12; ++e) {
            const int* a = kEdgeStart[e];
            int bb[3] = {a[0], a[1], a[2]};
            ++bb[kEdgeAxis[e]];
            crossing[e] = inside(corner[a[0]][a[1]][a[2]]) != inside(corner[bb[0]][bb[1]][bb[2]]);
            nCross += crossing[e];
          }
          auto& comp = cellEdgeComp[si][static_cast<std::size_t>(cell)];
          comp.fill(-1);
          if (nCross == 0) continue;
          // Union-find over the 12 edges, joined by the segments on each face.
          int parent[12];
          for (int e = 0; e < 12; ++e) parent[e] = e;
          auto findRoot = [&](int e) {
            while (parent[e] != e) e = parent[e] = parent[parent[e]];
            return e;
          };
          auto join = [&](int a, int b2) { parent[findRoot(a)] = findRoot(b2); };
          for (int f = 0; f < 6; ++f) {
            const int* fe = kFaceEdge[f];
            int cnt = 0;
            for (int k = 0; k < 4; ++k) cnt += crossing[fe[k]];
            if (cnt == 2) {
              int first = -1;
              for (int k = 0; k < 4; ++k)
                if (crossing[fe[k]]) {
                  if (first < 0)
                    first = fe[k];
                  else
                    join(first, fe[k]);
                }
            } else if (cnt == 4) {
              float fv[4];
              for (int k = 0; k < 4; ++k) {
                const int* q = kFaceCorner[f][k];
                fv[k] = corner[q[0]][q[1]][q[2]];
              }
              // Asymptotic decider: the bilinear interpolant's value at its saddle point.
              const float den = fv[0] + fv[2] - fv[1] - fv[3];
              const float saddle = den != 0.0f ? (fv[0] * fv[2] - fv[1] * fv[3]) / den : 0.0f;
              if (inside(saddle) == inside(fv[0])) {
                join(fe[0], fe[1]);  // corners 0 and 2 connected: cut around corners 1 and 3
                join(fe[2], fe[3]);
              } else {
                join(fe[3], fe[0]);  // cut around corners 0 and 2
                join(fe[1], fe[2]);
              }
            }
          }
          // One vertex per component, at the mean of its edge crossings.
          Vec3 sum[12];
          int count[12] = {0};
          std::int8_t compOfRoot[12];
          std::fill(std::begin(compOfRoot), std::end(compOfRoot), static_cast<std::int8_t>(-1));
          std::int8_t nComp = 0;
          for (int e = 0; e < 12; ++e) {
            if (!crossing[e]) continue;
            const int r = findRoot(e);
            if (compOfRoot[r] < 0) {
              compOfRoot[r] = nComp;
              sum[nComp] = Vec3::Zero();
              ++nComp;
            }
            const std::int8_t k = compOfRoot[r];
            comp[static_cast<std::size_t>(e)] = k;
            const int* a = kEdgeStart[e];
            int bb[3] = {a[0], a[1], a[2]};
            ++bb[kEdgeAxis[e]];
            const float f0 = corner[a[0]][a[1]][a[2]], f1 = corner[bb[0]][bb[1]][bb[2]];
            const float t = f0 / (f0 - f1);
            Vec3 pa(static_cast<float>(a[0]), static_cast<float>(a[1]), static_cast<float>(a[2]));
            pa[kEdgeAxis[e]] += t;
            sum[k] += pa;
            ++count[k];
          }
          cellFirst[si][static_cast<std::size_t>(cell)] =
              static_cast<std::int32_t>(blockVerts[si].size());
          const Vec3 cellOrigin(static_cast<float>(base.x() + x), static_cast<float>(base.y() + y),
                                static_cast<float>(base.z() + z));
          for (int k = 0; k < nComp; ++k)
            blockVerts[si].push_back(origin +
                                     h * (cellOrigin + sum[k] / static_cast<float>(count[k])));
        }
  });

  SurfaceNet net;
  std::vector<std::int32_t> blockFirst(nActive + 1, 0);
  for (std::size_t s = 0; s < nActive; ++s)
    blockFirst[s + 1] = blockFirst[s] + static_cast<std::int32_t>(blockVerts[s].size());
  net.vertices.reserve(static_cast<std::size_t>(blockFirst[nActive]));
  for (std::size_t s = 0; s < nActive; ++s)
    net.vertices.insert(net.vertices.end(), blockVerts[s].begin(), blockVerts[s].end());

  // Global (cell, local edge) -> vertex index, or -1.
  auto cellVertex = [&](int x, int y, int z, int edge) -> std::int32_t {
    if (x < 0 || y < 0 || z < 0) return -1;
    const int bx = x / kBlock, by = y / kBlock, bz = z / kBlock;
    if (bx >= nb.x() || by >= nb.y() || bz >= nb.z()) return -1;
    const std::int32_t sl = slot[static_cast<std::size_t>(blockId(bx, by, bz))];
    if (sl < 0) return -1;
    const std::size_t cell =
        static_cast<std::size_t>(((z % kBlock) * kBlock + (y % kBlock)) * kBlock + (x % kBlock));
    const std::int32_t first = cellFirst[static_cast<std::size_t>(sl)][cell];
    const std::int8_t k =
        cellEdgeComp[static_cast<std::size_t>(sl)][cell][static_cast<std::size_t>(edge)];
    return first < 0 || k < 0 ? -1 : blockFirst[static_cast<std::size_t>(sl)] + first + k;
  };

  // 3. One quad per crossing grid edge (edges from each cell's min corner along +x, +y, +z),
  // joining the vertices of the four cells around it.
  std::vector<std::vector<std::array<std::int32_t, 4>>> blockQuads(nActive);
  std::vector<std::uint8_t> blockHoles(nActive, 0);
  parallelFor(static_cast<std::int64_t>(nActive), 1, [&](std::int64_t s) {
    const Eigen::Vector3i base = active[static_cast<std::size_t>(s)] * kBlock;
    const std::vector<float>& v = values[static_cast<std::size_t>(s)];
    auto val = [&](int x, int y, int z) {
      return v[static_cast<std::size_t>((z * kC + y) * kC + x)];
    };
    auto& quads = blockQuads[static_cast<std::size_t>(s)];
    for (int z = 0; z < kBlock; ++z)
      for (int y = 0; y < kBlock; ++y)
        for (int x = 0; x < kBlock; ++x) {
          const float f0 = val(x, y, z);
          const int gx = base.x() + x, gy = base.y() + y, gz = base.z() + z;
          for (int axis = 0; axis < 3; ++axis) {
            const float f1 = axis == 0   ? val(x + 1, y, z)
                             : axis == 1 ? val(x, y + 1, z)
                                         : val(x, y, z + 1);
            if ((f0 < 0.0f) == (f1 < 0.0f)) continue;
            std::array<std::int32_t, 4> q;
            if (axis == 0) {
              q = {cellVertex(gx, gy - 1, gz - 1, 3), cellVertex(gx, gy, gz - 1, 2),
                   cellVertex(gx, gy, gz, 0), cellVertex(gx, gy - 1, gz, 1)};
            } else if (axis == 1) {
              q = {cellVertex(gx - 1, gy, gz - 1, 7), cellVertex(gx - 1, gy, gz, 5),
                   cellVertex(gx, gy, gz, 4), cellVertex(gx, gy, gz - 1, 6)};
            } else {
              q = {cellVertex(gx - 1, gy - 1, gz, 11), cellVertex(gx, gy - 1, gz, 10),
                   cellVertex(gx, gy, gz, 8), cellVertex(gx - 1, gy, gz, 9)};
            }
            if (q[0] < 0 || q[1] < 0 || q[2] < 0 || q[3] < 0) {
              blockHoles[static_cast<std::size_t>(s)] = 1;
              continue;
            }
            // The quad's normal points along +axis; flip it if the outside is at the start.
            if (f0 >= 0.0f) std::swap(q[1], q[3]);
            quads.push_back(q);
          }
        }
  });
  for (std::size_t s = 0; s < nActive; ++s) {
    net.quads.insert(net.quads.end(), blockQuads[s].begin(), blockQuads[s].end());
    net.holes = net.holes || blockHoles[s];
  }
  return net;
}

// Projects the net's vertices onto the surface and builds the OpenMesh triangle mesh (each quad
// split along its shorter diagonal). Returns false if the result is not a closed 2-manifold.
bool buildMesh(const Creature& c, SurfaceNet& net, float h, TriMesh& mesh) {
  parallelFor(static_cast<std::int64_t>(net.vertices.size()), 256, [&](std::int64_t i) {
    Vec3& p = net.vertices[static_cast<std::size_t>(i)];
    p = projectToSurface(c, p, 0.05f * h, 0.5f * h);
  });
  mesh.clear();
  std::vector<TriMesh::VertexHandle> vh;
  vh.reserve(net.vertices.size());
  for (const Vec3& p : net.vertices)
    vh.push_back(mesh.add_vertex(TriMesh::Point(p.x(), p.y(), p.z())));
  bool ok = !net.holes;
  for (const auto& q : net.quads) {
    const Vec3 &a = net.vertices[static_cast<std::size_t>(q[0])],
               &b = net.vertices[static_cast<std::size_t>(q[1])];
    const Vec3 &cc = net.vertices[static_cast<std::size_t>(q[2])],
               &d = net.vertices[static_cast<std::size_t>(q[3])];
    std::array<std::array<std::int32_t, 3>, 2> tris;
    if ((a - cc).squaredNorm() <= (b - d).squaredNorm())
      tris = {{{q[0], q[1], q[2]}, {q[0], q[2], q[3]}}};
    else
      tris = {{{q[0], q[1], q[3]}, {q[1], q[2], q[3]}}};
    for (const auto& t : tris) {
      if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) {
        ok = false;
        continue;
      }
      const auto f =
          mesh.add_face(vh[static_cast<std::size_t>(t[0])], vh[static_cast<std::size_t>(t[1])],
                        vh[static_cast<std::size_t>(t[2])]);
      if (!f.is_valid()) ok = false;
    }
  }
  if (!ok) return false;
  for (auto e : mesh.edges())
    if (mesh.is_boundary(e)) return false;
  for (auto v : mesh.vertices())
    if (!mesh.is_manifold(v) || mesh.is_isolated(v)) return false;
  return true;
}

// Tangential Laplacian relaxation with OpenMesh's smoother, then back onto the surface.
void relax(const Creature& c, TriMesh& mesh, float h, int iterations) {
  OpenMesh::Smoother::JacobiLaplaceSmootherT<TriMesh> smoother(mesh);
  smoother.initialize(OpenMesh::Smoother::SmootherT<TriMesh>::Tangential,
                      OpenMesh::Smoother::SmootherT<TriMesh>::C0);
  smoother.smooth(static_cast<unsigned>(iterations));
  const std::int64_t n = static_cast<std::int64_t>(mesh.n_vertices());
  TriMesh::Point* pts = const_cast<TriMesh::Point*>(mesh.points());  // contiguous point storage
  parallelFor(n, 256, [&](std::int64_t i) {
    TriMesh::Point& q = pts[i];
    const Vec3 p = projectToSurface(c, Vec3(q[0], q[1], q[2]), 0.05f * h, 0.5f * h);
    q = TriMesh::Point(p.x(), p.y(), p.z());
  });
}

// Polygonises at spacing h (retrying slightly finer spacings if a grid configuration produced a
// non-manifold spot), relaxes, and returns the mesh.
TriMesh polygonise(const Creature& c, const Eigen::AlignedBox3f& bounds, float h) {
  for (int attempt = 0; attempt < 8; ++attempt) {
    SurfaceNet net = surfaceNets(c, bounds, h);
    TriMesh mesh;
    if (buildMesh(c, net, h, mesh)) {
      relax(c, mesh, h, 3);
      return mesh;
    }
    h *= 0.985f;
  }
  throw InternalError(
      "skin: the body shapes could not be polygonised into a closed manifold surface");
}

}  // namespace

SkinMesh buildSkin(const Creature& c, const SkinBuildOptions& options) {
  if (options.triangles < 2000 || options.triangles > 2000000)
    inputError(c.source, ": skin triangle count ", options.triangles,
               " is out of range [2000, 2000000]");
  PELAGE_CHECK(!c.shapes.empty(), "creature without shapes");
  // Shape bounds, grown by what a smooth union can add (at most k/4 for blend radius k).
  Eigen::AlignedBox3f bounds;
  float maxBlend = c.blendRadiusMeters;
  for (const auto& s : c.shapes) {
    bounds.extend(detail::shapeBounds(s));
    maxBlend = std::max(maxBlend, detail::shapeBlend(c, s));
  }
  bounds.min() -= Vec3::Constant(0.5f * maxBlend);
  bounds.max() += Vec3::Constant(0.5f * maxBlend);
  const float diag = bounds.diagonal().norm();

  // Calibrate the grid spacing: polygonise coarsely, then scale h so that the triangle count
  // (proportional to 1/h^2) meets the target.
  const int generate = options.triangles < kDecimateBelow ? kDecimateFrom : options.triangles;
  const float h0 = diag / 60.0f;
  const SurfaceNet coarse = surfaceNets(c, bounds, h0);
  PELAGE_CHECK(!coarse.quads.empty(), "no surface found: shapes too small for the grid");
  const float h =
      h0 * std::sqrt(2.0f * static_cast<float>(coarse.quads.size()) / static_cast<float>(generate));

  SkinMesh skin;
  skin.mesh = polygonise(c, bounds, h);
  TriMesh& mesh = skin.mesh;

  if (static_cast<int>(mesh.n_faces()) > options.triangles * 103 / 100) {
    // Simplify to the target with OpenMesh's decimater: quadric error, no normal flips, no slivers.
    mesh.request_vertex_status();
    mesh.request_edge_status();
    mesh.request_face_status();
    mesh.request_face_normals();
    mesh.update_face_normals();
    OpenMesh::Decimater::DecimaterT<TriMesh> dec(mesh);
    OpenMesh::Decimater::ModQuadricT<TriMesh>::Handle quadric;
    OpenMesh::Decimater::ModNormalFlippingT<TriMesh>::Handle flips;
    OpenMesh::Decimater::ModAspectRatioT<TriMesh>::Handle aspect;
    dec.add(quadric);
    dec.add(flips);
    dec.add(aspect);
    dec.module(quadric).unset_max_err();
    dec.module(flips).set_max_normal_deviation(30.0);
    dec.module(aspect).set_aspect_ratio(4.0f);
    dec.initialize();
    dec.decimate_to_faces(0, static_cast<std::size_t>(options.triangles));
    mesh.garbage_collection();
    relax(c, mesh,
          h * std::sqrt(static_cast<float>(generate) / static_cast<float>(options.triangles)), 2);
  }

  addSkinProperties(skin);
  skin.color = c.skinColor;
  bindToSegments(c, skin);
  assignFurRegions(c, skin);
  finalizeSkin(skin);
  assignFurColors(c, skin);
  return skin;
}

}  // namespace pelage::skin
