// The stages of importGltf (gltf_import.cpp), one file each: the skeleton (gltf_skeleton.cpp:
// the node tree, the scene's meshes, the segments, the body), the geometry (gltf_geometry.cpp:
// primitives, units, welding, the OpenMesh skin), the appearance (gltf_appearance.cpp: UVs,
// colours, materials, textures) and the clips (gltf_clips.cpp). Private to pelage::animation; the
// data the stages hand on is declared here, in the order importGltf runs them.
#pragma once

#include <Eigen/Geometry>

#include <array>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "gltf_reader.h"
#include "pelage/anatomy/body.h"
#include "pelage/animation/gltf_import.h"
#include "pelage/skin/skin_mesh.h"
#include "pelage/util/error.h"

namespace pelage::animation::detail {

using Affine3d = Eigen::Affine3d;
using Vec3d = Eigen::Vector3d;

// glTF (Y up, front +Z, left +X) -> pelage (Z up, front +X, left +Y): (x, y, z) -> (z, x, y).
inline Eigen::Matrix3d basisChange() {
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

inline bool finite(const std::vector<double>& v) {
  for (double x : v)
    if (!std::isfinite(x)) return false;
  return true;
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

struct SkinJoints {
  std::vector<int> segment;  // per joint of the skin: segment index
};
// ---- The node tree -------------------------------------------------------------------------

struct Tree {
  std::vector<int> parent;
  std::vector<int> sceneNodes;  // reachable from the scene's roots, parents first
};
Tree buildTree(const ImportContext& ctx);

// 1. The mesh instances of the scene (mesh nodes reachable from its roots) and the skins they use.
struct Instance {
  int node, mesh, skin;
};
struct SceneMeshes {
  std::vector<Instance> instances;
  std::set<int> usedSkins;
};
SceneMeshes sceneMeshes(const ImportContext& ctx, const Tree& tree);

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
Skeleton buildSkeleton(const ImportContext& ctx, const Tree& tree, const SceneMeshes& meshes);

// 3. The geometry of every mesh instance in bind space (file units, glTF axes).
Primitives readGeometry(const ImportContext& ctx, const SceneMeshes& meshes, const Skeleton& sk);

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
Units findUnits(const Primitives& prims, const GltfImportOptions& options);

// 5. The body: roots take the change of basis and scale; every bind transform is K * bind.
void buildBody(const ImportContext& ctx, const Tree& tree, const Skeleton& sk, const Units& units,
               anatomy::Body& body);

// 6. Welding: raw vertices with the same converted position (bitwise) and the same binding become
// one; a welded vertex shared with a bare region takes the bare region.
struct Weld {
  std::vector<Eigen::Vector3f> conv;  // per raw vertex: position in metres, pelage's axes
  std::vector<std::int32_t> weldOf;   // raw vertex -> welded vertex (-1: unused)
  std::vector<std::int32_t> welded;   // welded vertex -> representative raw vertex
  std::vector<int> weldRegion;        // welded vertex -> region
};
Weld weldVertices(const Primitives& prims, const Units& units, const std::vector<bool>& bareRegion);

// 7. The triangles on welded vertices; degenerate ones dropped (counted in prims.degenerate).
// `kept` receives, per triangle returned, its index in prims.triangles.
std::vector<std::array<std::int32_t, 3>> weldedTriangles(const ImportContext& ctx,
                                                         Primitives& prims, const Weld& wd,
                                                         const Units& units,
                                                         std::vector<std::size_t>& kept);

// 8. The OpenMesh skin: a triangle whose edge is already used in its direction, or whose addition
// OpenMesh rejects (non-manifold), gets its own copies of its vertices. Returns, per mesh vertex,
// its welded vertex; `faceVertices` receives each face's three mesh vertices in the order given.
std::vector<std::int32_t> buildSkinMesh(const std::string& path,
                                        const std::vector<std::array<std::int32_t, 3>>& tris,
                                        const Weld& wd, skin::SkinMesh& sk,
                                        std::vector<std::int32_t>& faceVertices);

// (9. vertex properties and 10. the skin colour: in importGltf.)

// 11. Appearance (after finalizeSkin): per-corner UVs, vertex colours, the materials' base colours
// and their textures. Problems with an image (missing, corrupt, too large, a texture without UVs)
// leave that material untextured with a warning naming the image; the geometry still loads.
void readAppearance(const ImportContext& ctx, const Primitives& prims,
                    const std::vector<std::size_t>& kept,
                    const std::vector<std::int32_t>& faceVertices, const Weld& wd,
                    const std::vector<std::int32_t>& source, skin::SkinMesh& sk);

// 12. The clips: every animation, its root channels taken to pelage's axes and units.
std::vector<Clip> readClips(const ImportContext& ctx, const Skeleton& skel, const Units& units,
                            const anatomy::Body& body);

}  // namespace pelage::animation::detail
