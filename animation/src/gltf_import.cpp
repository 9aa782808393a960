// glTF 2.0 import: node tree -> Body, skinned and rigid meshes -> SkinMesh, animations -> Clips.
// See gltf_import.h for the conventions.
#include "pelage/animation/gltf_import.h"

#include <OpenMesh/Core/System/omstream.hh>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <unordered_map>

#include "gltf_reader.h"
#include "pelage/util/color.h"
#include "pelage/util/error.h"
#include "pelage/util/image.h"
#include "pelage/util/log.h"

namespace pelage::animation {
namespace {

using Affine3d = Eigen::Affine3d;
using Vec3d = Eigen::Vector3d;

// glTF (Y up, front +Z, left +X) -> pelage (Z up, front +X, left +Y): (x, y, z) -> (z, x, y).
Eigen::Matrix3d basisChange() {
  Eigen::Matrix3d c;
  c << 0, 0, 1, 1, 0, 0, 0, 1, 0;
  return c;
}

struct ImportContext {
  std::string path;
  const tinygltf::Model& model;
  gltf::Accessors acc;
  ImportContext(std::string p, const tinygltf::Model& m)
      : path(std::move(p)), model(m), acc(m, path) {}
  template <typename... Args>
  [[noreturn]] void fail(const Args&... args) const {
    inputError(path, ": ", args...);
  }
};

bool finite(const std::vector<double>& v) {
  for (double x : v)
    if (!std::isfinite(x)) return false;
  return true;
}

// A node's local transform as TRS. A matrix must be affine and decomposable: M = T R S with
// S = the column norms (one negated when det < 0) and R orthonormal (glTF forbids shear).
anatomy::Transform nodeTransform(const ImportContext& ctx, int index) {
  const tinygltf::Node& n = ctx.model.nodes[static_cast<std::size_t>(index)];
  anatomy::Transform t;
  if (!n.matrix.empty()) {
    if (n.matrix.size() != 16)
      ctx.fail("node ", index, " matrix has ", n.matrix.size(), " numbers (16 expected)");
    if (!finite(n.matrix)) ctx.fail("node ", index, " matrix has a NaN or infinite value");
    Eigen::Matrix4d m;
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) m(r, c) = n.matrix[static_cast<std::size_t>(c * 4 + r)];
    if ((m.row(3) - Eigen::RowVector4d(0, 0, 0, 1)).cwiseAbs().maxCoeff() > 1e-6)
      ctx.fail("node ", index, " matrix is not affine (last row must be 0 0 0 1)");
    Eigen::Matrix3d a = m.topLeftCorner<3, 3>();
    Vec3d s(a.col(0).norm(), a.col(1).norm(), a.col(2).norm());
    if (s.minCoeff() < 1e-12) ctx.fail("node ", index, " matrix is degenerate (a zero scale)");
    if (a.determinant() < 0.0) s.x() = -s.x();
    const Eigen::Matrix3d r = a * s.cwiseInverse().asDiagonal();
    if ((r.transpose() * r - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() > 1e-3)
      ctx.fail("node ", index,
               " matrix has shear, which glTF does not allow (it must be translation * rotation * "
               "scale)");
    t.rotation = Eigen::Quaternionf(Eigen::Quaterniond(r).normalized().cast<float>());
    t.translation = m.topRightCorner<3, 1>().cast<float>();
    t.scale = s.cast<float>();
    return t;
  }
  if (!n.translation.empty()) {
    if (n.translation.size() != 3 || !finite(n.translation))
      ctx.fail("node ", index, " translation must be 3 finite numbers");
    t.translation =
        Eigen::Vector3f(static_cast<float>(n.translation[0]), static_cast<float>(n.translation[1]),
                        static_cast<float>(n.translation[2]));
  }
  if (!n.rotation.empty()) {
    if (n.rotation.size() != 4 || !finite(n.rotation))
      ctx.fail("node ", index, " rotation must be 4 finite numbers");
    Eigen::Quaterniond q(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]);
    if (q.norm() < 1e-6) ctx.fail("node ", index, " rotation is a zero quaternion");
    t.rotation = Eigen::Quaternionf(q.normalized().cast<float>());
  }
  if (!n.scale.empty()) {
    if (n.scale.size() != 3 || !finite(n.scale))
      ctx.fail("node ", index, " scale must be 3 finite numbers");
    t.scale = Eigen::Vector3f(static_cast<float>(n.scale[0]), static_cast<float>(n.scale[1]),
                              static_cast<float>(n.scale[2]));
  }
  return t;
}

Affine3d toAffine(const anatomy::Transform& t) {
  return t.matrix().cast<double>();
}

// One influence list before welding.
struct RawVertex {
  Vec3d position;  // bind space, file units, glTF axes
  skin::Binding binding;
  int region = 0;
  Eigen::Vector2f uv = Eigen::Vector2f::Zero();     // TEXCOORD_0 (0 without)
  Eigen::Vector4f color = Eigen::Vector4f::Ones();  // COLOR_0, linear RGBA (1 without)
};

struct Primitives {
  std::vector<RawVertex> vertices;
  std::vector<std::array<std::int32_t, 3>> triangles;
  std::vector<std::string> regionNames{"body"};
  std::vector<int> regionMaterial{-1};  // a material per region (for the skin colour), -1 none
  std::vector<std::int64_t> regionTriangles{0};
  std::vector<int> triangleMaterial;     // per triangle: its primitive's glTF material, -1 none
  bool hasUv = false, hasColor = false;  // some primitive has TEXCOORD_0 / COLOR_0
  int degenerate = 0, zeroWeights = 0, skippedPrimitives = 0;
  int region(const std::string& name, int material) {
    for (std::size_t i = 0; i < regionNames.size(); ++i)
      if (regionNames[i] == name) return static_cast<int>(i);
    regionNames.push_back(name);
    regionMaterial.push_back(material);
    regionTriangles.push_back(0);
    return static_cast<int>(regionNames.size() - 1);
  }
};

// Triangles of a primitive's index list for mode 4 (list), 5 (strip) or 6 (fan).
void appendTriangles(const ImportContext& ctx, int mode, const std::vector<std::uint32_t>& idx,
                     std::int32_t base, const std::string& what, Primitives& out) {
  auto push = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    out.triangles.push_back({base + static_cast<std::int32_t>(a),
                             base + static_cast<std::int32_t>(b),
                             base + static_cast<std::int32_t>(c)});
  };
  const std::size_t n = idx.size();
  if (mode == TINYGLTF_MODE_TRIANGLES) {
    if (n % 3 != 0)
      warn(str(ctx.path, ": ", what, ": ", n, " indices is not a multiple of 3; the last ", n % 3,
               " ignored"));
    for (std::size_t i = 0; i + 2 < n; i += 3) push(idx[i], idx[i + 1], idx[i + 2]);
  } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
    for (std::size_t i = 0; i + 2 < n; ++i)
      (i % 2 == 0) ? push(idx[i], idx[i + 1], idx[i + 2]) : push(idx[i + 1], idx[i], idx[i + 2]);
  } else {  // fan
    for (std::size_t i = 1; i + 1 < n; ++i) push(idx[0], idx[i], idx[i + 1]);
  }
}

// Keeps the 4 largest influences, merges repeats of one segment, renormalises; segment[0] =
// largest.
bool makeBinding(std::vector<std::pair<float, int>>& infl, skin::Binding& b) {
  std::sort(infl.begin(), infl.end(),
            [](const auto& x, const auto& y) { return x.second < y.second; });
  std::vector<std::pair<float, int>> merged;
  for (const auto& [w, s] : infl) {
    if (!(w > 0.0f)) continue;
    if (!merged.empty() && merged.back().second == s)
      merged.back().first += w;
    else
      merged.emplace_back(w, s);
  }
  std::stable_sort(merged.begin(), merged.end(),
                   [](const auto& x, const auto& y) { return x.first > y.first; });
  if (merged.size() > 4) merged.resize(4);
  float sum = 0.0f;
  for (const auto& m : merged) sum += m.first;
  if (!(sum > 0.0f)) return false;
  b = skin::Binding{};
  b.weight[0] = 0.0f;
  for (std::size_t k = 0; k < merged.size(); ++k) {
    b.segment[k] = merged[k].second;
    b.weight[k] = merged[k].first / sum;
  }
  for (std::size_t k = merged.size(); k < 4; ++k) b.segment[k] = b.segment[0];
  return true;
}

struct SkinJoints {
  std::vector<int> segment;  // per joint of the skin: segment index
};

// Reads one primitive; `place` maps its stored positions into bind space (file units, glTF axes):
// the mesh node's global rest transform for a skinned mesh, the node's bind transform for a rigid
// one (bound to `rigidSegment`).
void readPrimitive(const ImportContext& ctx, int meshIndex, std::size_t primIndex,
                   const SkinJoints* joints, int rigidSegment, const Affine3d& place,
                   const std::string& rigidRegion, Primitives& out) {
  const tinygltf::Primitive& prim =
      ctx.model.meshes[static_cast<std::size_t>(meshIndex)].primitives[primIndex];
  const std::string what = str("mesh ", meshIndex, " primitive ", primIndex);
  const int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
  if (mode >= 0 && mode <= 3) {  // points, lines, line loop, line strip: no surface to grow fur on
    ++out.skippedPrimitives;
    return;
  }
  if (mode > 6) ctx.fail(what, ": invalid mode ", mode);
  if (!prim.targets.empty()) warn(str(ctx.path, ": ", what, ": morph targets are ignored"));
  const auto attr = [&](const char* name) {
    const auto it = prim.attributes.find(name);
    return it == prim.attributes.end() ? -1 : it->second;
  };
  const int posIdx = attr("POSITION");
  if (posIdx < 0) ctx.fail(what, " has no POSITION attribute");
  const std::vector<float> pos =
      ctx.acc.floats(posIdx, TINYGLTF_TYPE_VEC3, false, what + " POSITION");
  const std::size_t n = pos.size() / 3;
  if (n > static_cast<std::size_t>(INT32_MAX) - out.vertices.size())
    ctx.fail(what, ": too many vertices");

  int material = prim.material;
  if (material >= static_cast<int>(ctx.model.materials.size()))
    ctx.fail(what, " material ", material, " does not exist (", ctx.model.materials.size(),
             " materials)");
  std::string regionName = rigidRegion;
  if (regionName.empty())
    regionName =
        material >= 0 && !ctx.model.materials[static_cast<std::size_t>(material)].name.empty()
            ? ctx.model.materials[static_cast<std::size_t>(material)].name
            : std::string("body");
  const int region = out.region(regionName, material);

  // Influences: JOINTS_n / WEIGHTS_n pairs (n = 0, 1).
  std::vector<std::vector<std::uint32_t>> jointSets;
  std::vector<std::vector<float>> weightSets;
  if (joints) {
    for (int set = 0; set < 2; ++set) {
      const int j = attr(set == 0 ? "JOINTS_0" : "JOINTS_1");
      const int w = attr(set == 0 ? "WEIGHTS_0" : "WEIGHTS_1");
      if (j < 0 && w < 0 && set > 0) break;
      if (j < 0 || w < 0)
        ctx.fail(what, " is skinned but lacks ", j < 0 ? "JOINTS_" : "WEIGHTS_", set,
                 " (JOINTS_n and WEIGHTS_n come in pairs)");
      const std::string js = str(what, " JOINTS_", set), ws = str(what, " WEIGHTS_", set);
      jointSets.push_back(ctx.acc.uints(
          j, TINYGLTF_TYPE_VEC4,
          {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT}, js));
      weightSets.push_back(ctx.acc.floats(w, TINYGLTF_TYPE_VEC4, true, ws));
      if (jointSets.back().size() != 4 * n || weightSets.back().size() != 4 * n)
        ctx.fail(what, ": JOINTS_", set, "/WEIGHTS_", set, " have ", jointSets.back().size() / 4,
                 "/", weightSets.back().size() / 4, " elements but POSITION has ", n);
    }
  }

  // Appearance: TEXCOORD_0 (FLOAT or normalised unsigned integers) and COLOR_0 (VEC3 or VEC4).
  std::vector<float> uv, color;
  std::size_t colorComponents = 0;
  if (const int t = attr("TEXCOORD_0"); t >= 0) {
    uv = ctx.acc.floats(t, TINYGLTF_TYPE_VEC2, true, what + " TEXCOORD_0");
    if (uv.size() != 2 * n)
      ctx.fail(what, ": TEXCOORD_0 has ", uv.size() / 2, " elements but POSITION has ", n);
    out.hasUv = true;
  }
  if (const int c = attr("COLOR_0"); c >= 0) {
    ctx.acc.count(c, what + " COLOR_0");
    const int type = ctx.model.accessors[static_cast<std::size_t>(c)].type;
    if (type != TINYGLTF_TYPE_VEC3 && type != TINYGLTF_TYPE_VEC4)
      ctx.fail(what, ": COLOR_0 (accessor ", c, ") must be VEC3 or VEC4");
    color = ctx.acc.floats(c, type, true, what + " COLOR_0");
    colorComponents = type == TINYGLTF_TYPE_VEC3 ? 3 : 4;
    if (color.size() != colorComponents * n)
      ctx.fail(what, ": COLOR_0 has ", color.size() / colorComponents,
               " elements but POSITION has ", n);
    out.hasColor = true;
  }

  const std::int32_t base = static_cast<std::int32_t>(out.vertices.size());
  std::vector<std::pair<float, int>> infl;
  for (std::size_t v = 0; v < n; ++v) {
    RawVertex rv;
    const Vec3d p(pos[3 * v], pos[3 * v + 1], pos[3 * v + 2]);
    rv.region = region;
    rv.position = place * p;
    if (!uv.empty()) rv.uv = Eigen::Vector2f(uv[2 * v], uv[2 * v + 1]);
    for (std::size_t k = 0; k < colorComponents; ++k)
      rv.color[static_cast<int>(k)] = std::clamp(color[colorComponents * v + k], 0.0f, 1.0f);
    if (joints) {
      infl.clear();
      for (std::size_t set = 0; set < jointSets.size(); ++set)
        for (std::size_t k = 0; k < 4; ++k) {
          const float w = weightSets[set][4 * v + k];
          const std::uint32_t j = jointSets[set][4 * v + k];
          if (w < 0.0f)
            ctx.fail(what, " WEIGHTS_", set, " element ", v, " has a negative weight ", w);
          if (w == 0.0f) continue;
          if (j >= joints->segment.size())
            ctx.fail(what, " JOINTS_", set, " element ", v, " names joint ", j,
                     " but the skin has ", joints->segment.size(), " joints");
          infl.emplace_back(w, joints->segment[j]);
        }
      if (!makeBinding(infl, rv.binding)) {  // all-zero weights: follow the skin's first joint
        ++out.zeroWeights;
        rv.binding = skin::Binding{};
        rv.binding.segment = {joints->segment[0], joints->segment[0], joints->segment[0],
                              joints->segment[0]};
      }
    } else {
      rv.binding.segment = {rigidSegment, rigidSegment, rigidSegment, rigidSegment};
    }
    out.vertices.push_back(rv);
  }

  std::vector<std::uint32_t> indices;
  if (prim.indices >= 0) {
    indices = ctx.acc.uints(
        prim.indices, TINYGLTF_TYPE_SCALAR,
        {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
         TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT},
        what + " indices");
    for (std::size_t i = 0; i < indices.size(); ++i)
      if (indices[i] >= n)
        ctx.fail(what, " index ", i, " is ", indices[i], ", beyond the primitive's ", n,
                 " vertices");
  } else {
    indices.resize(n);
    for (std::size_t i = 0; i < n; ++i) indices[i] = static_cast<std::uint32_t>(i);
  }
  const std::size_t before = out.triangles.size();
  appendTriangles(ctx, mode, indices, base, what, out);
  out.regionTriangles[static_cast<std::size_t>(region)] +=
      static_cast<std::int64_t>(out.triangles.size() - before);
  out.triangleMaterial.resize(out.triangles.size(), material);
}

// ---- The node tree -------------------------------------------------------------------------

struct Tree {
  std::vector<int> parent;
  std::vector<int> sceneNodes;  // reachable from the scene's roots, parents first
};

Tree buildTree(const ImportContext& ctx) {
  const tinygltf::Model& m = ctx.model;
  const int N = static_cast<int>(m.nodes.size());
  Tree t;
  t.parent.assign(static_cast<std::size_t>(N), -1);
  for (int i = 0; i < N; ++i)
    for (int c : m.nodes[static_cast<std::size_t>(i)].children) {
      if (c < 0 || c >= N)
        ctx.fail("node ", i, " has child ", c, ", which does not exist (", N, " nodes)");
      if (c == i) ctx.fail("node ", i, " is its own child");
      if (t.parent[static_cast<std::size_t>(c)] >= 0)
        ctx.fail("node ", c, " has two parents (nodes ", t.parent[static_cast<std::size_t>(c)],
                 " and ", i, "); glTF nodes form a tree");
      t.parent[static_cast<std::size_t>(c)] = i;
    }
  for (int i = 0; i < N; ++i) {  // every walk up must reach a root within N steps
    int steps = 0;
    for (int p = i; p >= 0; p = t.parent[static_cast<std::size_t>(p)])
      if (++steps > N) ctx.fail("the node hierarchy has a cycle through node ", i);
  }
  std::vector<int> roots;
  if (!m.scenes.empty()) {
    const int s = m.defaultScene >= 0 ? m.defaultScene : 0;
    if (s >= static_cast<int>(m.scenes.size())) ctx.fail("default scene ", s, " does not exist");
    for (int r : m.scenes[static_cast<std::size_t>(s)].nodes) {
      if (r < 0 || r >= N) ctx.fail("scene ", s, " lists node ", r, ", which does not exist");
      if (t.parent[static_cast<std::size_t>(r)] >= 0)
        ctx.fail("scene ", s, " root node ", r, " has a parent");
      roots.push_back(r);
    }
  } else {
    for (int i = 0; i < N; ++i)
      if (t.parent[static_cast<std::size_t>(i)] < 0) roots.push_back(i);
  }
  std::vector<bool> seen(static_cast<std::size_t>(N), false);
  for (int r : roots) {
    std::vector<int> stack{r};
    while (!stack.empty()) {
      const int n = stack.back();
      stack.pop_back();
      if (seen[static_cast<std::size_t>(n)]) continue;
      seen[static_cast<std::size_t>(n)] = true;
      t.sceneNodes.push_back(n);
      const auto& ch = m.nodes[static_cast<std::size_t>(n)].children;
      for (auto it = ch.rbegin(); it != ch.rend(); ++it) stack.push_back(*it);
    }
  }
  return t;
}

// ---- Welding and the OpenMesh skin ---------------------------------------------------------

bool sameBinding(const skin::Binding& a, const skin::Binding& b) {
  for (std::size_t k = 0; k < 4; ++k) {
    if (std::abs(a.weight[k] - b.weight[k]) > 1e-5f) return false;
    if (a.weight[k] > 0.0f && a.segment[k] != b.segment[k]) return false;
  }
  return true;
}

// RAII: silences OpenMesh's error stream (add_face reports rejected faces there; we handle them).
struct QuietOpenMesh {
  bool was = omerr().is_enabled();
  QuietOpenMesh() { omerr().disable(); }
  ~QuietOpenMesh() {
    if (was) omerr().enable();
  }
};

// ---- The stages of importGltf ------------------------------------------------------------

// 1. The mesh instances of the scene (mesh nodes reachable from its roots) and the skins they use.
struct Instance {
  int node, mesh, skin;
};
struct SceneMeshes {
  std::vector<Instance> instances;
  std::set<int> usedSkins;
};

SceneMeshes sceneMeshes(const ImportContext& ctx, const Tree& tree) {
  const tinygltf::Model& model = ctx.model;
  SceneMeshes out;
  std::vector<Instance>& instances = out.instances;
  for (int n : tree.sceneNodes) {
    const tinygltf::Node& node = model.nodes[static_cast<std::size_t>(n)];
    if (node.mesh < 0) continue;
    if (node.mesh >= static_cast<int>(model.meshes.size()))
      ctx.fail("node ", n, " uses mesh ", node.mesh, ", which does not exist (",
               model.meshes.size(), " meshes)");
    if (node.skin >= static_cast<int>(model.skins.size()))
      ctx.fail("node ", n, " uses skin ", node.skin, ", which does not exist (", model.skins.size(),
               " skins)");
    instances.push_back({n, node.mesh, node.skin});
  }
  if (instances.empty()) ctx.fail("the scene has no mesh");

  for (const Instance& in : instances)
    if (in.skin >= 0) out.usedSkins.insert(in.skin);
  return out;
}

// 2. The skeleton: the segments (joints of the used skins, rigid mesh nodes, and all their
// ancestors) in parents-first order, their rest transforms (file units), every node's global rest
// transform, and the segments' bind transforms (file units, glTF axes).
struct Skeleton {
  std::vector<int> order;                // segment -> node
  std::vector<int> segmentOf;            // node -> segment, or -1
  std::vector<anatomy::Transform> rest;  // per segment
  std::vector<Affine3d> global;          // per node
  std::vector<Affine3d> bind;            // per segment
  std::map<int, SkinJoints> skinJoints;  // per used skin
  int size() const { return static_cast<int>(order.size()); }
};

Skeleton buildSkeleton(const ImportContext& ctx, const Tree& tree, const SceneMeshes& meshes) {
  const tinygltf::Model& model = ctx.model;
  const int N = static_cast<int>(model.nodes.size());
  const std::vector<Instance>& instances = meshes.instances;
  Skeleton skel;
  // Segments: joints of the used skins, rigid mesh nodes, and all their ancestors.
  std::vector<bool> isSegment(static_cast<std::size_t>(N), false);
  auto markUp = [&](int n) {
    for (; n >= 0 && !isSegment[static_cast<std::size_t>(n)];
         n = tree.parent[static_cast<std::size_t>(n)])
      isSegment[static_cast<std::size_t>(n)] = true;
  };
  for (const Instance& in : instances) {
    if (in.skin < 0) {
      markUp(in.node);
      continue;
    }
    const tinygltf::Skin& s = model.skins[static_cast<std::size_t>(in.skin)];
    if (s.joints.empty()) ctx.fail("skin ", in.skin, " has no joints");
    for (int j : s.joints) {
      if (j < 0 || j >= N)
        ctx.fail("skin ", in.skin, " lists joint node ", j, ", which does not exist (", N,
                 " nodes)");
      markUp(j);
    }
  }
  // Parents-first order: a depth-first walk from the roots of the whole node forest.
  std::vector<int>& order = skel.order;
  std::vector<int>& segmentOf = skel.segmentOf;
  segmentOf.assign(static_cast<std::size_t>(N), -1);
  {
    std::vector<int> stack;
    for (int i = N - 1; i >= 0; --i)
      if (tree.parent[static_cast<std::size_t>(i)] < 0 && isSegment[static_cast<std::size_t>(i)])
        stack.push_back(i);
    while (!stack.empty()) {
      const int n = stack.back();
      stack.pop_back();
      segmentOf[static_cast<std::size_t>(n)] = static_cast<int>(order.size());
      order.push_back(n);
      const auto& ch = model.nodes[static_cast<std::size_t>(n)].children;
      for (auto it = ch.rbegin(); it != ch.rend(); ++it)
        if (isSegment[static_cast<std::size_t>(*it)]) stack.push_back(*it);
    }
  }
  const int nS = static_cast<int>(order.size());

  // Rest transforms (file units) and bind transforms.
  std::vector<anatomy::Transform>& rest = skel.rest;
  rest.resize(static_cast<std::size_t>(nS));
  for (int s = 0; s < nS; ++s)
    rest[static_cast<std::size_t>(s)] = nodeTransform(ctx, order[static_cast<std::size_t>(s)]);
  std::vector<bool> isJoint(static_cast<std::size_t>(nS), false);
  std::vector<Affine3d>& bind = skel.bind;
  bind.assign(static_cast<std::size_t>(nS), Affine3d::Identity());
  // Global rest transforms of all nodes (parents first).
  std::vector<Affine3d>& global = skel.global;
  global.assign(static_cast<std::size_t>(N), Affine3d::Identity());
  {
    std::vector<int> stack;
    for (int i = N - 1; i >= 0; --i)
      if (tree.parent[static_cast<std::size_t>(i)] < 0) stack.push_back(i);
    while (!stack.empty()) {
      const int n = stack.back();
      stack.pop_back();
      const int p = tree.parent[static_cast<std::size_t>(n)];
      const Affine3d local = toAffine(nodeTransform(ctx, n));
      global[static_cast<std::size_t>(n)] =
          p < 0 ? local : global[static_cast<std::size_t>(p)] * local;
      for (int c : model.nodes[static_cast<std::size_t>(n)].children) stack.push_back(c);
    }
  }
  // Joints: bind transform = (mesh node's global rest transform) * IBM^-1, so that bind space is
  // where the rest pose puts the mesh (skinning W IBM M^-1 (M p) = W IBM p, the glTF result).
  std::map<int, SkinJoints>& skinJoints = skel.skinJoints;
  std::map<int, std::vector<Eigen::Matrix4d>> ibms;
  for (int si : meshes.usedSkins) {
    const tinygltf::Skin& sk = model.skins[static_cast<std::size_t>(si)];
    std::vector<Eigen::Matrix4d>& list = ibms[si];
    std::vector<float> ibm;
    if (sk.inverseBindMatrices >= 0) {
      ibm = ctx.acc.floats(sk.inverseBindMatrices, TINYGLTF_TYPE_MAT4, false,
                           str("skin ", si, " inverseBindMatrices"));
      if (ibm.size() / 16 < sk.joints.size())
        ctx.fail("skin ", si, " has ", sk.joints.size(), " joints but ", ibm.size() / 16,
                 " inverse bind matrices");
    }
    SkinJoints& sj = skinJoints[si];
    for (std::size_t j = 0; j < sk.joints.size(); ++j) {
      Eigen::Matrix4d mm = Eigen::Matrix4d::Identity();
      if (!ibm.empty()) {
        for (int c = 0; c < 4; ++c)
          for (int r = 0; r < 4; ++r)
            mm(r, c) = static_cast<double>(ibm[j * 16 + static_cast<std::size_t>(c * 4 + r)]);
        if ((mm.row(3) - Eigen::RowVector4d(0, 0, 0, 1)).cwiseAbs().maxCoeff() > 1e-4)
          ctx.fail("skin ", si, " inverse bind matrix ", j, " is not affine");
        if (!(std::abs(mm.topLeftCorner<3, 3>().determinant()) > 1e-12))
          ctx.fail("skin ", si, " inverse bind matrix ", j, " is singular");
        mm.row(3) << 0, 0, 0, 1;
      }
      list.push_back(mm);
      sj.segment.push_back(segmentOf[static_cast<std::size_t>(sk.joints[j])]);
    }
  }
  for (const Instance& in : instances) {
    if (in.skin < 0) continue;
    const Affine3d& M = global[static_cast<std::size_t>(in.node)];
    const std::vector<Eigen::Matrix4d>& list = ibms.at(in.skin);
    const std::vector<int>& segs = skinJoints.at(in.skin).segment;
    for (std::size_t j = 0; j < segs.size(); ++j) {
      Affine3d ib;
      ib.matrix() = list[j];
      const Affine3d b = M * ib.inverse();
      const std::size_t seg = static_cast<std::size_t>(segs[j]);
      if (isJoint[seg] && !bind[seg].matrix().isApprox(b.matrix(), 1e-4))
        ctx.fail("joint node ", model.skins[static_cast<std::size_t>(in.skin)].joints[j],
                 " has two different bind transforms (shared by skins or mesh nodes that disagree; "
                 "not supported)");
      isJoint[seg] = true;
      bind[seg] = b;
    }
  }
  for (int s = 0; s < nS; ++s) {
    if (isJoint[static_cast<std::size_t>(s)]) continue;
    const int p = tree.parent[static_cast<std::size_t>(order[static_cast<std::size_t>(s)])];
    const Affine3d local = toAffine(rest[static_cast<std::size_t>(s)]);
    bind[static_cast<std::size_t>(s)] =
        p < 0 ? local
              : bind[static_cast<std::size_t>(segmentOf[static_cast<std::size_t>(p)])] * local;
  }

  return skel;
}

// 3. The geometry of every mesh instance in bind space (file units, glTF axes).
Primitives readGeometry(const ImportContext& ctx, const SceneMeshes& meshes, const Skeleton& sk) {
  const tinygltf::Model& model = ctx.model;
  const std::string& path = ctx.path;
  const std::vector<int>& segmentOf = sk.segmentOf;
  const std::vector<Affine3d>& global = sk.global;
  const std::vector<Affine3d>& bind = sk.bind;
  const std::map<int, SkinJoints>& skinJoints = sk.skinJoints;
  Primitives prims;
  for (const Instance& in : meshes.instances) {
    const tinygltf::Mesh& mesh = model.meshes[static_cast<std::size_t>(in.mesh)];
    const int seg = segmentOf[static_cast<std::size_t>(in.node)];
    const tinygltf::Node& node = model.nodes[static_cast<std::size_t>(in.node)];
    const std::string rigidRegion = node.name.empty() ? str("node", in.node) : node.name;
    for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
      if (in.skin >= 0) {
        readPrimitive(ctx, in.mesh, p, &skinJoints.at(in.skin), -1,
                      global[static_cast<std::size_t>(in.node)], "", prims);
      } else {
        if (std::abs(bind[static_cast<std::size_t>(seg)].linear().determinant()) < 1e-18) {
          warn(str(path, ": mesh node ", in.node, " has a zero scale in its bind pose; skipped"));
          continue;
        }
        readPrimitive(ctx, in.mesh, p, nullptr, seg, bind[static_cast<std::size_t>(seg)],
                      rigidRegion, prims);
      }
    }
  }
  if (prims.triangles.empty()) ctx.fail("the scene has no triangles (only points or lines)");
  if (prims.skippedPrimitives > 0)
    warn(str(path, ": skipped ", prims.skippedPrimitives,
             " point/line primitives (no surface for fur)"));
  if (prims.zeroWeights > 0)
    warn(str(path, ": ", prims.zeroWeights,
             " vertices have all-zero skin weights; bound to the skin's first joint"));

  return prims;
}

// 4. Units: metres per file unit (given, or detected from the bounds of the vertices the triangles
// use) and the map K from file units and glTF axes to metres and pelage's axes.
struct Units {
  float scale = 1.0f;
  std::string reason;
  Eigen::AlignedBox3d fileBox;  // of the used vertices, file units
  std::vector<bool> used;       // per raw vertex: some triangle uses it
  Eigen::Matrix3d C = basisChange();
  Affine3d K = Affine3d::Identity();
  Eigen::Quaterniond qC;
};

Units findUnits(const Primitives& prims, const GltfImportOptions& options) {
  Units u;
  u.used.assign(prims.vertices.size(), false);
  for (const auto& t : prims.triangles)
    for (std::int32_t v : t) u.used[static_cast<std::size_t>(v)] = true;
  for (std::size_t v = 0; v < prims.vertices.size(); ++v)
    if (u.used[v]) u.fileBox.extend(prims.vertices[v].position);
  const float longest = static_cast<float>(u.fileBox.sizes().maxCoeff());
  if (options.unitScale > 0.0f) {
    u.scale = options.unitScale;
    u.reason = str("given: ", options.unitScale, " m per unit");
  } else {
    u.scale = detectUnitScale(longest, &u.reason);
  }
  u.K.linear() = static_cast<double>(u.scale) * u.C;
  u.qC = Eigen::Quaterniond(u.C);
  return u;
}

// 5. The body: roots take the change of basis and scale; every bind transform is K * bind.
void buildBody(const ImportContext& ctx, const Tree& tree, const Skeleton& sk, const Units& units,
               anatomy::Body& body) {
  const tinygltf::Model& model = ctx.model;
  const int nS = sk.size();
  const double s = static_cast<double>(units.scale);
  const Eigen::Matrix3d& C = units.C;
  std::set<std::string> names;
  for (int si = 0; si < nS; ++si) {
    const int n = sk.order[static_cast<std::size_t>(si)];
    anatomy::Segment seg;
    seg.name = model.nodes[static_cast<std::size_t>(n)].name.empty()
                   ? str("node", n)
                   : model.nodes[static_cast<std::size_t>(n)].name;
    if (!names.insert(seg.name).second) {
      seg.name = str(seg.name, "#", n);
      names.insert(seg.name);
    }
    const int p = tree.parent[static_cast<std::size_t>(n)];
    seg.parent = p < 0 ? -1 : sk.segmentOf[static_cast<std::size_t>(p)];
    seg.rest = sk.rest[static_cast<std::size_t>(si)];
    if (seg.parent < 0) {
      seg.rest.rotation = (units.qC.cast<float>() * seg.rest.rotation).normalized();
      seg.rest.translation = (s * C * seg.rest.translation.cast<double>()).cast<float>();
      seg.rest.scale *= units.scale;
    }
    body.segments.push_back(seg);
    const Affine3d b = units.K * sk.bind[static_cast<std::size_t>(si)];
    body.inverseBind.push_back(Eigen::Affine3f(b.inverse().cast<float>()));
  }
  anatomy::checkBody(body);
}

// 6. Welding: raw vertices with the same converted position (bitwise) and the same binding become
// one; a welded vertex shared with a bare region takes the bare region.
struct Weld {
  std::vector<Eigen::Vector3f> conv;  // per raw vertex: position in metres, pelage's axes
  std::vector<std::int32_t> weldOf;   // raw vertex -> welded vertex (-1: unused)
  std::vector<std::int32_t> welded;   // welded vertex -> representative raw vertex
  std::vector<int> weldRegion;        // welded vertex -> region
};

Weld weldVertices(const Primitives& prims, const Units& units,
                  const std::vector<bool>& bareRegion) {
  Weld wd;
  const std::vector<bool>& used = units.used;
  std::vector<Eigen::Vector3f>& conv = wd.conv;
  std::vector<std::int32_t>& weldOf = wd.weldOf;
  std::vector<std::int32_t>& welded = wd.welded;
  std::vector<int>& weldRegion = wd.weldRegion;
  const Affine3d& K = units.K;
  const std::size_t nRaw = prims.vertices.size();
  conv.resize(nRaw);
  for (std::size_t v = 0; v < nRaw; ++v) {
    conv[v] = (K * prims.vertices[v].position).cast<float>();
    conv[v] += Eigen::Vector3f::Zero();  // -0 -> +0 so that equal positions hash equally
  }
  struct Key {
    std::array<std::uint32_t, 3> bits;
    bool operator<(const Key& o) const { return bits < o.bits; }
  };
  std::map<Key, std::vector<std::int32_t>> buckets;
  weldOf.assign(nRaw, -1);
  for (std::size_t v = 0; v < nRaw; ++v) {
    if (!used[v]) continue;
    Key k;
    std::memcpy(k.bits.data(), conv[v].data(), 12);
    std::vector<std::int32_t>& bucket = buckets[k];
    std::int32_t found = -1;
    for (std::int32_t w : bucket)
      if (sameBinding(
              prims.vertices[static_cast<std::size_t>(welded[static_cast<std::size_t>(w)])].binding,
              prims.vertices[v].binding)) {
        found = w;
        break;
      }
    if (found < 0) {
      found = static_cast<std::int32_t>(welded.size());
      welded.push_back(static_cast<std::int32_t>(v));
      weldRegion.push_back(prims.vertices[v].region);
      bucket.push_back(found);
    } else {
      int& r = weldRegion[static_cast<std::size_t>(found)];
      const int other = prims.vertices[v].region;
      if (other != r && bareRegion[static_cast<std::size_t>(other)] &&
          !bareRegion[static_cast<std::size_t>(r)])
        r = other;
    }
    weldOf[v] = found;
  }

  return wd;
}

// 7. The triangles on welded vertices; degenerate ones dropped (counted in prims.degenerate).
// `kept` receives, per triangle returned, its index in prims.triangles.
std::vector<std::array<std::int32_t, 3>> weldedTriangles(const ImportContext& ctx,
                                                         Primitives& prims, const Weld& wd,
                                                         const Units& units,
                                                         std::vector<std::size_t>& kept) {
  const std::string& path = ctx.path;
  const std::vector<Eigen::Vector3f>& conv = wd.conv;
  const std::vector<std::int32_t>& weldOf = wd.weldOf;
  const std::vector<std::int32_t>& welded = wd.welded;
  const double s = static_cast<double>(units.scale);
  const Eigen::AlignedBox3d& fileBox = units.fileBox;
  const float diag = static_cast<float>(s * fileBox.diagonal().norm());
  const float minArea2 = 1e-12f * diag * diag;
  std::vector<std::array<std::int32_t, 3>> tris;
  tris.reserve(prims.triangles.size());
  kept.clear();
  for (std::size_t ti = 0; ti < prims.triangles.size(); ++ti) {
    const auto& t = prims.triangles[ti];
    const std::array<std::int32_t, 3> w = {weldOf[static_cast<std::size_t>(t[0])],
                                           weldOf[static_cast<std::size_t>(t[1])],
                                           weldOf[static_cast<std::size_t>(t[2])]};
    const Eigen::Vector3f& a =
        conv[static_cast<std::size_t>(welded[static_cast<std::size_t>(w[0])])];
    const Eigen::Vector3f& b =
        conv[static_cast<std::size_t>(welded[static_cast<std::size_t>(w[1])])];
    const Eigen::Vector3f& c =
        conv[static_cast<std::size_t>(welded[static_cast<std::size_t>(w[2])])];
    if (w[0] == w[1] || w[1] == w[2] || w[0] == w[2] || !((b - a).cross(c - a).norm() > minArea2)) {
      ++prims.degenerate;
      continue;
    }
    tris.push_back(w);
    kept.push_back(ti);
  }
  if (prims.degenerate > 0)
    warn(str(path, ": dropped ", prims.degenerate, " degenerate triangles"));
  if (tris.empty()) ctx.fail("every triangle is degenerate");

  return tris;
}

// 8. The OpenMesh skin: a triangle whose edge is already used in its direction, or whose addition
// OpenMesh rejects (non-manifold), gets its own copies of its vertices. Returns, per mesh vertex,
// its welded vertex; `faceVertices` receives each face's three mesh vertices in the order given.
std::vector<std::int32_t> buildSkinMesh(const std::string& path,
                                        const std::vector<std::array<std::int32_t, 3>>& tris,
                                        const Weld& wd, skin::SkinMesh& sk,
                                        std::vector<std::int32_t>& faceVertices) {
  const std::vector<Eigen::Vector3f>& conv = wd.conv;
  const std::vector<std::int32_t>& welded = wd.welded;
  std::vector<std::int32_t> source;  // mesh vertex -> welded vertex
  std::vector<std::int32_t> meshOf(welded.size(), -1);
  auto vertexFor = [&](std::int32_t w, bool fresh) -> skin::TriMesh::VertexHandle {
    if (fresh || meshOf[static_cast<std::size_t>(w)] < 0) {
      const Eigen::Vector3f& p =
          conv[static_cast<std::size_t>(welded[static_cast<std::size_t>(w)])];
      const auto vh = sk.mesh.add_vertex(skin::TriMesh::Point(p.x(), p.y(), p.z()));
      source.push_back(w);
      if (!fresh) meshOf[static_cast<std::size_t>(w)] = vh.idx();
      return vh;
    }
    return skin::TriMesh::VertexHandle(meshOf[static_cast<std::size_t>(w)]);
  };
  {
    const QuietOpenMesh quiet;
    std::set<std::pair<std::int32_t, std::int32_t>> directed;
    int split = 0;
    for (const auto& t : tris) {
      bool clash = false;
      for (int e = 0; e < 3; ++e)
        clash = clash || directed.count({t[static_cast<std::size_t>(e)],
                                         t[static_cast<std::size_t>((e + 1) % 3)]}) > 0;
      skin::TriMesh::FaceHandle fh;
      std::array<skin::TriMesh::VertexHandle, 3> vh;
      if (!clash) {
        vh = {vertexFor(t[0], false), vertexFor(t[1], false), vertexFor(t[2], false)};
        fh = sk.mesh.add_face(vh[0], vh[1], vh[2]);
      }
      if (!fh.is_valid()) {
        vh = {vertexFor(t[0], true), vertexFor(t[1], true), vertexFor(t[2], true)};
        fh = sk.mesh.add_face(vh[0], vh[1], vh[2]);
        ++split;
      }
      PELAGE_CHECK(fh.is_valid(), "an isolated triangle was rejected");
      for (const auto& v : vh) faceVertices.push_back(v.idx());
      if (!clash)
        for (int e = 0; e < 3; ++e)
          directed.insert(
              {t[static_cast<std::size_t>(e)], t[static_cast<std::size_t>((e + 1) % 3)]});
    }
    if (split > 0)
      warn(str(path, ": ", split,
               " triangles on non-manifold edges or vertices got their own vertices"));
  }

  return source;
}

// 12. Appearance (after finalizeSkin): per-corner UVs, vertex colours, the materials' base colours
// and their textures. Problems with an image (missing, corrupt, too large, a texture without UVs)
// leave that material untextured with a warning naming the image; the geometry still loads.

// Decoded image bytes allowed for one creature's textures, all images together.
constexpr std::size_t kMaxTextureBytes = std::size_t{1} << 30;

skin::Wrap wrapMode(int gl) {
  if (gl == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE) return skin::Wrap::ClampToEdge;
  if (gl == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT) return skin::Wrap::MirroredRepeat;
  return skin::Wrap::Repeat;
}

// The encoded bytes of image `i`: its bufferView (validated by loadModelFile), its data URI's bytes
// (kept by the reader), or the file its uri names beside the .gltf. `bytes` may point into `file`.
// InputError naming the image when it has none or its file cannot be used.
void imageBytes(const ImportContext& ctx, int i, const std::string& what,
                std::vector<std::uint8_t>& file, const std::uint8_t*& bytes, std::size_t& size) {
  const tinygltf::Image& img = ctx.model.images[static_cast<std::size_t>(i)];
  if (img.bufferView >= 0) {
    if (static_cast<std::size_t>(img.bufferView) >= ctx.model.bufferViews.size())
      inputError(what, ": bufferView ", img.bufferView, " does not exist");
    const tinygltf::BufferView& bv =
        ctx.model.bufferViews[static_cast<std::size_t>(img.bufferView)];
    bytes = ctx.model.buffers[static_cast<std::size_t>(bv.buffer)].data.data() + bv.byteOffset;
    size = bv.byteLength;
    return;
  }
  if (!img.image.empty()) {
    bytes = img.image.data();
    size = img.image.size();
    return;
  }
  if (img.uri.empty()) inputError(what, ": has neither a bufferView nor a uri");
  // An external file, relative to the .gltf and inside its folder (no scheme, no absolute path,
  // no '..'): a downloaded model cannot make pelage read files elsewhere.
  const std::string uri = img.uri;
  const std::filesystem::path rel(uri);
  bool inside = uri.find("://") == std::string::npos && !rel.is_absolute();
  for (const auto& part : rel) inside = inside && part != "..";
  if (!inside)
    inputError(what, ": uri '", uri,
               "' is not a relative path inside the model's folder (only those are read)");
  std::string decoded;  // %XX escapes (glTF uris are URI-encoded)
  for (std::size_t k = 0; k < uri.size(); ++k) {
    if (uri[k] == '%' && k + 2 < uri.size() &&
        std::isxdigit(static_cast<unsigned char>(uri[k + 1])) &&
        std::isxdigit(static_cast<unsigned char>(uri[k + 2]))) {
      decoded += static_cast<char>(std::stoi(uri.substr(k + 1, 2), nullptr, 16));
      k += 2;
    } else {
      decoded += uri[k];
    }
  }
  const std::filesystem::path full = std::filesystem::path(ctx.path).parent_path() / decoded;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(full, ec))
    inputError(what, ": its file ", full.string(), " does not exist");
  const std::uintmax_t n = std::filesystem::file_size(full, ec);
  if (ec || n > (std::size_t{512} << 20))
    inputError(what, ": its file ", full.string(), " is unreadable or over 512 MiB");
  file.resize(static_cast<std::size_t>(n));
  std::ifstream in(full, std::ios::binary);
  in.read(reinterpret_cast<char*>(file.data()), static_cast<std::streamsize>(file.size()));
  if (static_cast<std::size_t>(in.gcount()) != file.size())
    inputError(what, ": cannot read its file ", full.string());
  bytes = file.data();
  size = file.size();
}

void readAppearance(const ImportContext& ctx, const Primitives& prims,
                    const std::vector<std::size_t>& kept,
                    const std::vector<std::int32_t>& faceVertices, const Weld& wd,
                    const std::vector<std::int32_t>& source, skin::SkinMesh& sk) {
  const tinygltf::Model& model = ctx.model;
  const std::size_t nF = kept.size();
  if (prims.hasUv) {
    std::vector<Eigen::Vector2f> inputUv(3 * nF);
    for (std::size_t f = 0; f < nF; ++f)
      for (std::size_t j = 0; j < 3; ++j)
        inputUv[3 * f + j] =
            prims.vertices[static_cast<std::size_t>(prims.triangles[kept[f]][j])].uv;
    skin::setCornerUvs(sk, faceVertices, inputUv);
  }
  if (prims.hasColor) {
    sk.vertexColor.resize(source.size());
    for (std::size_t v = 0; v < source.size(); ++v)
      sk.vertexColor[v] =
          prims.vertices[static_cast<std::size_t>(wd.welded[static_cast<std::size_t>(source[v])])]
              .color;
  }
  bool anyMaterial = false, anyDefault = false;
  for (std::size_t f = 0; f < nF; ++f) {
    const bool has = prims.triangleMaterial[kept[f]] >= 0;
    anyMaterial = anyMaterial || has;
    anyDefault = anyDefault || !has;
  }
  if (!anyMaterial) return;
  // Every glTF material in file order, then (if some triangle has none) a default of the skin's
  // colour.
  std::map<int, int> textureOf;  // glTF texture -> skin texture (-1: unusable)
  std::size_t textureBytes = 0;
  for (std::size_t m = 0; m < model.materials.size(); ++m) {
    const tinygltf::Material& gm = model.materials[m];
    skin::SkinMaterial sm;
    sm.name = gm.name.empty() ? str("material", m) : gm.name;
    const std::vector<double>& f = gm.pbrMetallicRoughness.baseColorFactor;
    if (f.size() == 4 && finite(f))
      for (int k = 0; k < 4; ++k)
        sm.baseColor[k] = static_cast<float>(std::clamp(f[static_cast<std::size_t>(k)], 0.0, 1.0));
    const tinygltf::TextureInfo& ti = gm.pbrMetallicRoughness.baseColorTexture;
    const std::string what =
        str(ctx.path, ": material ", m, " '", sm.name, "' base colour texture");
    if (ti.index >= 0) {
      if (ti.texCoord != 0) {
        warn(str(what, " uses TEXCOORD_", ti.texCoord, "; only TEXCOORD_0 is read: not textured"));
      } else if (!prims.hasUv) {
        warn(str(what, ": the mesh has no TEXCOORD_0, so it cannot be textured"));
      } else if (auto it = textureOf.find(ti.index); it != textureOf.end()) {
        sm.texture = it->second;
      } else {
        int made = -1;
        try {
          if (static_cast<std::size_t>(ti.index) >= model.textures.size())
            inputError(what, ": texture ", ti.index, " does not exist (", model.textures.size(),
                       " textures)");
          const tinygltf::Texture& gt = model.textures[static_cast<std::size_t>(ti.index)];
          if (gt.source < 0 || static_cast<std::size_t>(gt.source) >= model.images.size())
            inputError(what, ": texture ", ti.index, " has no image (source ", gt.source, ")");
          const tinygltf::Image& gi = model.images[static_cast<std::size_t>(gt.source)];
          const std::string imageName =
              str(ctx.path, ": image ", gt.source, gi.name.empty() ? "" : " '" + gi.name + "'");
          std::vector<std::uint8_t> file;
          const std::uint8_t* bytes = nullptr;
          std::size_t size = 0;
          imageBytes(ctx, gt.source, imageName, file, bytes, size);
          ImageLimits limits;
          limits.maxBytes = std::min(limits.maxBytes, kMaxTextureBytes - textureBytes);
          skin::Texture tex =
              skin::makeTexture(decodeImage(bytes, size, imageName, limits), imageName, true);
          if (gt.sampler >= 0 && static_cast<std::size_t>(gt.sampler) < model.samplers.size()) {
            const tinygltf::Sampler& s = model.samplers[static_cast<std::size_t>(gt.sampler)];
            tex.wrapS = wrapMode(s.wrapS);
            tex.wrapT = wrapMode(s.wrapT);
            tex.filter = s.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST ? skin::Filter::Nearest
                                                                        : skin::Filter::Linear;
          }
          if (!ti.extensions.empty())
            warn(
                str(what, ": texture extensions (", ti.extensions.begin()->first, ") are ignored"));
          textureBytes += tex.bytes();
          made = static_cast<int>(sk.textures.size());
          sk.textures.push_back(std::move(tex));
        } catch (const InputError& e) {
          warn(str(e.what(), "; the material is drawn with its base colour only"));
        }
        textureOf[ti.index] = made;
        sm.texture = made;
      }
    }
    sk.materials.push_back(std::move(sm));
  }
  const int fallback = static_cast<int>(sk.materials.size());
  if (anyDefault) {
    skin::SkinMaterial d;
    d.name = "(no material)";
    const Eigen::Vector3f linear = srgbToLinear(sk.color);
    d.baseColor = Eigen::Vector4f(linear.x(), linear.y(), linear.z(), 1.0f);
    sk.materials.push_back(d);
  }
  sk.triangleMaterial.resize(nF);
  for (std::size_t f = 0; f < nF; ++f) {
    const int m = prims.triangleMaterial[kept[f]];
    sk.triangleMaterial[f] = m >= 0 ? m : fallback;
  }
  skin::checkAppearance(sk);
}

// 11. The clips: every animation, its root channels taken to pelage's axes and units.
std::vector<Clip> readClips(const ImportContext& ctx, const Skeleton& skel, const Units& units,
                            const anatomy::Body& body) {
  const tinygltf::Model& model = ctx.model;
  const std::string& path = ctx.path;
  const int N = static_cast<int>(model.nodes.size());
  const std::vector<int>& segmentOf = skel.segmentOf;
  const double s = static_cast<double>(units.scale);
  const Eigen::Matrix3d& C = units.C;
  const Eigen::Quaterniond& qC = units.qC;
  std::vector<Clip> clips;
  std::set<std::string> clipNames;
  bool warnedWeights = false;
  for (std::size_t ai = 0; ai < model.animations.size(); ++ai) {
    const tinygltf::Animation& an = model.animations[ai];
    Clip clip;
    clip.name = an.name.empty() ? str("clip", ai) : an.name;
    if (!clipNames.insert(clip.name).second) {
      const std::string renamed = str(clip.name, "_", ai);
      warn(str(path, ": two animations are called '", clip.name, "'; the second is '", renamed,
               "'"));
      clip.name = renamed;
      clipNames.insert(renamed);
    }
    clip.loop = true;
    float duration = 0.0f;
    for (std::size_t ci = 0; ci < an.channels.size(); ++ci) {
      const tinygltf::AnimationChannel& ch = an.channels[ci];
      const std::string what = str("animation ", ai, " channel ", ci);
      if (ch.sampler < 0 || ch.sampler >= static_cast<int>(an.samplers.size()))
        ctx.fail(what, " uses sampler ", ch.sampler, ", which does not exist (", an.samplers.size(),
                 " samplers)");
      if (ch.target_node >= N)
        ctx.fail(what, " targets node ", ch.target_node, ", which does not exist (", N, " nodes)");
      const tinygltf::AnimationSampler& sm = an.samplers[static_cast<std::size_t>(ch.sampler)];
      Channel chOut;
      if (ch.target_path == "translation")
        chOut.path = ChannelPath::Translation;
      else if (ch.target_path == "rotation")
        chOut.path = ChannelPath::Rotation;
      else if (ch.target_path == "scale")
        chOut.path = ChannelPath::Scale;
      else if (ch.target_path == "weights") {
        if (!warnedWeights)
          warn(str(path, ": morph-target (weights) animation channels are ignored"));
        warnedWeights = true;
        continue;
      } else {
        ctx.fail(what, " has an unknown target path '", ch.target_path, "'");
      }
      if (sm.interpolation.empty() || sm.interpolation == "LINEAR")
        chOut.interpolation = Interpolation::Linear;
      else if (sm.interpolation == "STEP")
        chOut.interpolation = Interpolation::Step;
      else if (sm.interpolation == "CUBICSPLINE")
        chOut.interpolation = Interpolation::CubicSpline;
      else
        ctx.fail(what, " sampler has an unknown interpolation '", sm.interpolation, "'");
      chOut.times = ctx.acc.floats(sm.input, TINYGLTF_TYPE_SCALAR, false, what + " input (times)");
      for (std::size_t k = 0; k < chOut.times.size(); ++k) {
        if (chOut.times[k] < 0.0f)
          ctx.fail(what, " key time ", k, " is negative (", chOut.times[k], " s)");
        if (chOut.times[k] > 1e6f)
          ctx.fail(what, " key time ", k, " is ", chOut.times[k], " s (limit 1e6)");
        if (k > 0 && chOut.times[k] < chOut.times[k - 1])
          ctx.fail(what, " key times decrease at key ", k, " (", chOut.times[k - 1], " then ",
                   chOut.times[k], " s)");
      }
      const bool cubic = chOut.interpolation == Interpolation::CubicSpline;
      const int nc = chOut.components();
      chOut.values = ctx.acc.floats(sm.output, nc == 4 ? TINYGLTF_TYPE_VEC4 : TINYGLTF_TYPE_VEC3,
                                    nc == 4, what + " output (values)");
      const std::size_t expect =
          chOut.times.size() * (cubic ? 3u : 1u) * static_cast<std::size_t>(nc);
      if (chOut.values.size() != expect)
        ctx.fail(what, ": ", chOut.times.size(), " key times need ",
                 expect / static_cast<std::size_t>(nc), " output values, found ",
                 chOut.values.size() / static_cast<std::size_t>(nc));
      duration = std::max(duration, chOut.times.back());
      if (ch.target_node < 0 || segmentOf[static_cast<std::size_t>(ch.target_node)] < 0)
        continue;  // no effect
      chOut.segment = segmentOf[static_cast<std::size_t>(ch.target_node)];
      const std::size_t nK = chOut.times.size();
      if (nc == 4)  // unit quaternions for the values (not the tangents)
        for (std::size_t k = 0; k < nK; ++k) {
          float* q = chOut.values.data() + (cubic ? (3 * k + 1) * 4 : k * 4);
          const float len = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
          if (!(len > 1e-6f)) ctx.fail(what, " key ", k, " is a zero quaternion");
          for (int i = 0; i < 4; ++i) q[i] /= len;
        }
      if (body.segments[static_cast<std::size_t>(chOut.segment)].parent < 0) {
        // A root: apply the change of basis to values and tangents alike (both transform linearly).
        for (std::size_t e = 0; e < chOut.values.size() / static_cast<std::size_t>(nc); ++e) {
          float* v = chOut.values.data() + e * static_cast<std::size_t>(nc);
          if (nc == 4) {
            const Eigen::Quaternionf q =
                qC.cast<float>() * Eigen::Quaternionf(v[3], v[0], v[1], v[2]);
            v[0] = q.x();
            v[1] = q.y();
            v[2] = q.z();
            v[3] = q.w();
          } else if (chOut.path == ChannelPath::Translation) {
            const Eigen::Vector3f t = (s * C * Eigen::Vector3d(v[0], v[1], v[2])).cast<float>();
            v[0] = t.x();
            v[1] = t.y();
            v[2] = t.z();
          } else {
            for (int i = 0; i < 3; ++i) v[i] *= units.scale;
          }
        }
      }
      clip.channels.push_back(std::move(chOut));
    }
    clip.duration = duration;
    checkClip(clip, body);
    clips.push_back(std::move(clip));
  }
  return clips;
}

}  // namespace

// The stages, in order: the node tree, the scene's meshes, the skeleton, the geometry, the units,
// the body, welding, triangles, the OpenMesh skin, vertex properties, the skin colour, the clips.
GltfCreature importGltf(const std::string& path, const GltfImportOptions& options) {
  if (options.unitScale != 0.0f && !(options.unitScale >= 1e-6f && options.unitScale <= 1e6f))
    inputError("unit scale ", options.unitScale,
               " is out of range [1e-6, 1e6] metres per file unit");
  if (options.furLengthMeters != 0.0f &&
      !(options.furLengthMeters > 0.0f && options.furLengthMeters <= 10.0f))
    inputError("fur length ", options.furLengthMeters, " m is out of range (0, 10]");
  const tinygltf::Model model = gltf::loadModelFile(path);
  const ImportContext ctx(path, model);
  const Tree tree = buildTree(ctx);
  const SceneMeshes meshes = sceneMeshes(ctx, tree);
  const Skeleton skeleton = buildSkeleton(ctx, tree, meshes);
  const int nS = skeleton.size();
  Primitives prims = readGeometry(ctx, meshes, skeleton);
  const Units units = findUnits(prims, options);
  GltfCreature out;
  out.name = std::filesystem::path(path).stem().string();
  out.unitScale = units.scale;
  out.unitScaleReason = units.reason;
  anatomy::Body& body = out.body;
  buildBody(ctx, tree, skeleton, units, body);

  const std::vector<std::string>& noFur =
      options.noFurRegions ? *options.noFurRegions : defaultNoFurRegions();
  std::vector<bool> bareRegion(prims.regionNames.size(), false);
  for (std::size_t r = 0; r < prims.regionNames.size(); ++r)
    for (const std::string& pat : noFur)
      bareRegion[r] = bareRegion[r] || regionMatches(pat, prims.regionNames[r]);
  // Patterns the user gave must each match a region: a typo would otherwise replace the default
  // list and grow fur on eyes and antlers without a word.
  if (options.noFurRegions)
    for (const std::string& pat : *options.noFurRegions) {
      bool matched = false;
      for (const std::string& name : prims.regionNames)
        matched = matched || regionMatches(pat, name);
      if (!matched) {
        std::string names;
        for (const std::string& name : prims.regionNames)
          names += (names.empty() ? "" : ", ") + name;
        fieldError("no fur", "'", pat, "' matches no region of ", path, " (its regions: ", names,
                   ")");
      }
    }
  const Weld weld = weldVertices(prims, units, bareRegion);
  std::vector<std::size_t> kept;
  const std::vector<std::array<std::int32_t, 3>> tris =
      weldedTriangles(ctx, prims, weld, units, kept);
  skin::SkinMesh& sk = out.skin;
  std::vector<std::int32_t> faceVertices;
  const std::vector<std::int32_t> source = buildSkinMesh(path, tris, weld, sk, faceVertices);
  const std::vector<std::int32_t>& welded = weld.welded;
  const std::vector<int>& weldRegion = weld.weldRegion;
  const float diag =
      static_cast<float>(static_cast<double>(units.scale) * units.fileBox.diagonal().norm());

  // 9. Vertex properties: bindings, regions, fur lengths, segment directions.
  skin::addSkinProperties(sk);
  sk.regionNames = prims.regionNames;
  std::vector<bool> bound(static_cast<std::size_t>(nS), false);
  for (std::int32_t w : source)
    for (std::size_t k = 0; k < 4; ++k) {
      const skin::Binding& b =
          prims.vertices[static_cast<std::size_t>(welded[static_cast<std::size_t>(w)])].binding;
      if (b.weight[k] > 0.0f) bound[static_cast<std::size_t>(b.segment[k])] = true;
    }
  std::vector<Eigen::Vector3f> bindJoints(static_cast<std::size_t>(nS));
  for (int si = 0; si < nS; ++si)
    bindJoints[static_cast<std::size_t>(si)] =
        body.inverseBind[static_cast<std::size_t>(si)].inverse().translation();
  const std::vector<Eigen::Vector3f> dirs = headToTailDirections(body, bindJoints, bound);
  for (int si = 0; si < nS; ++si)
    body.segments[static_cast<std::size_t>(si)].direction = dirs[static_cast<std::size_t>(si)];
  std::string sideFile = options.segmentDirections;
  if (sideFile.empty()) {
    const std::filesystem::path auto_ =
        std::filesystem::path(path).replace_extension(".directions.json");
    std::error_code ec;
    if (std::filesystem::is_regular_file(auto_, ec)) sideFile = auto_.string();
  }
  if (!sideFile.empty()) applyDirectionFile(body, sideFile);

  const float furLength = options.furLengthMeters > 0.0f ? options.furLengthMeters : 0.02f * diag;
  for (auto vh : sk.mesh.vertices()) {
    const std::int32_t w = source[static_cast<std::size_t>(vh.idx())];
    const RawVertex& rv =
        prims.vertices[static_cast<std::size_t>(welded[static_cast<std::size_t>(w)])];
    const int region = weldRegion[static_cast<std::size_t>(w)];
    sk.mesh.property(sk.binding, vh) = rv.binding;
    sk.mesh.property(sk.region, vh) = region;
    sk.mesh.property(sk.furLength, vh) =
        bareRegion[static_cast<std::size_t>(region)] ? 0.0f : furLength;
    const Eigen::Vector3f& d =
        body.segments[static_cast<std::size_t>(rv.binding.segment[0])].direction;
    sk.mesh.property(sk.segmentDirection, vh) = OpenMesh::Vec3f(d.x(), d.y(), d.z());
  }
  // 10. Skin colour (the skin's one colour where it is drawn without materials, and the colour of
  // triangles without a material): the base colour of the untextured furred region with the most
  // triangles. A textured material's factor only tints its texture (the Fox: factor 1, colour in
  // the texture), so such materials leave the skin's default colour.
  std::int64_t most = -1;
  for (std::size_t r = 0; r < prims.regionNames.size(); ++r) {
    const int mat = prims.regionMaterial[r];
    if (bareRegion[r] || mat < 0 || prims.regionTriangles[r] <= most) continue;
    const auto& pbr = model.materials[static_cast<std::size_t>(mat)].pbrMetallicRoughness;
    if (pbr.baseColorTexture.index >= 0) continue;
    const std::vector<double>& f = pbr.baseColorFactor;
    if (f.size() >= 3 && finite(f)) {
      most = prims.regionTriangles[r];
      // glTF factors are linear; skin.color is sRGB-encoded, as typed (util/color.h).
      sk.color = Eigen::Vector3f(linearToSrgb(static_cast<float>(f[0])),
                                 linearToSrgb(static_cast<float>(f[1])),
                                 linearToSrgb(static_cast<float>(f[2])));
    }
  }
  skin::finalizeSkin(sk);
  readAppearance(ctx, prims, kept, faceVertices, weld, source, sk);

  out.clips = readClips(ctx, skeleton, units, body);
  return out;
}

}  // namespace pelage::animation
