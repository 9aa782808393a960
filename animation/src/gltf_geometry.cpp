// importGltf's geometry stages (gltf_stages.h): primitives read in bind space, units, welding,
// the triangles and the OpenMesh skin.
#include <OpenMesh/Core/System/omstream.hh>

#include <algorithm>
#include <cmath>
#include <set>

#include "gltf_stages.h"
#include "pelage/util/log.h"

namespace pelage::animation::detail {
namespace {

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
}  // namespace

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
}  // namespace pelage::animation::detail
