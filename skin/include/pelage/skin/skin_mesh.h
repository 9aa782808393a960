// The skin: an OpenMesh triangle mesh in bind pose whose vertices the body segments deform
// (Van Gelder & Wilhelms 1997, sec. 3.2: "The skin covering is a triangle mesh").
// Per-vertex data lives in OpenMesh properties, stored contiguously so hot loops read them as flat
// arrays. Constant model: built once (then finalizeSkin), read-only during playback.
#pragma once

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "pelage/skin/texture.h"

namespace pelage::skin {

struct MeshTraits : public OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3f;
  using Normal = OpenMesh::Vec3f;
  VertexAttributes(OpenMesh::Attributes::Status);
  FaceAttributes(OpenMesh::Attributes::Status);
  EdgeAttributes(OpenMesh::Attributes::Status);
  HalfedgeAttributes(OpenMesh::Attributes::PrevHalfedge);
};
using TriMesh = OpenMesh::TriMesh_ArrayKernelT<MeshTraits>;

// A surface material of the skin (glTF pbrMetallicRoughness base colour): colour = baseColor x
// texture(uv) x vertex colour, linear RGBA.
struct SkinMaterial {
  std::string name;
  Eigen::Vector4f baseColor{1.0f, 1.0f, 1.0f, 1.0f};  // linear RGBA factor
  int texture = -1;                                   // index into SkinMesh::textures, or -1
};

// Up to 4 segment influences of one vertex; weights sum to 1, unused slots have weight 0.
// segment[0] is the closest segment (paper sec. 3.4), whose direction vector orients the fur.
struct Binding {
  std::array<std::int32_t, 4> segment{0, 0, 0, 0};
  std::array<float, 4> weight{1.0f, 0.0f, 0.0f, 0.0f};
};

struct SkinMesh {
  // Bind-pose geometry; points are the rest positions (metres, Z up).
  TriMesh mesh;
  // Vertex properties (added by addSkinProperties).
  OpenMesh::VPropHandleT<Binding> binding;
  OpenMesh::VPropHandleT<float> furLength;      // fur length at the vertex (metres), sec. 3.2
  OpenMesh::VPropHandleT<std::int32_t> region;  // index into regionNames
  OpenMesh::VPropHandleT<OpenMesh::Vec3f>
      segmentDirection;  // bind-pose segment direction (unit or 0)

  std::vector<std::string> regionNames{"body"};  // region 0 is the default region
  Eigen::Vector3f color{0.45f, 0.32f, 0.26f};    // skin diffuse colour, sRGB-encoded (typed)

  // Appearance, constant (deformation moves positions and normals only, so every pose carries
  // these unchanged). All empty for a creature without them (a static mesh, most built creatures).
  std::vector<SkinMaterial> materials;         // empty: the skin is `color` everywhere
  std::vector<std::int32_t> triangleMaterial;  // nT indices into materials (when non-empty)
  std::vector<Texture> textures;               // referenced by materials
  std::vector<Eigen::Vector2f> cornerUv;       // nT x 3 (TEXCOORD_0), aligned with `triangles`
  std::vector<Eigen::Vector4f> vertexColor;    // nV linear RGBA (glTF COLOR_0), surface colour
  std::vector<Eigen::Vector3f> furColor;       // nV linear RGB: fur colours of a creature file

  // Derived flat arrays, built by finalizeSkin():
  std::vector<std::int32_t> triangles;        // nT x 3 vertex indices, counter-clockwise outward
  std::vector<std::int32_t> vertexFaceStart;  // nV + 1 offsets into vertexFaces (CSR)
  std::vector<std::int32_t> vertexFaces;      // faces incident to each vertex
  double restArea = 0.0;                      // total bind-pose area (m^2)

  int numVertices() const { return static_cast<int>(mesh.n_vertices()); }
  int numTriangles() const { return static_cast<int>(triangles.size() / 3); }
  // Rest positions as a flat nV x 3 array.
  const float* restPositions() const { return mesh.points()->data(); }
  const Binding* bindings() const { return mesh.property(binding).data_vector().data(); }
  const float* furLengths() const { return mesh.property(furLength).data_vector().data(); }
  const std::int32_t* regions() const { return mesh.property(region).data_vector().data(); }
  const float* segmentDirections() const {
    return mesh.property(segmentDirection).data_vector().data()->data();
  }
  bool hasUv() const { return !cornerUv.empty(); }
  // True when the surface has colours of its own: materials, textures or vertex colours.
  bool hasSurfaceColor() const { return !materials.empty() || !vertexColor.empty(); }
  // Texture coordinates at barycentric point b of triangle t (0 without UVs).
  Eigen::Vector2f uvAt(std::int32_t t, const float b[3]) const;
  // The surface's linear RGBA at barycentric point b of triangle t: its material's base colour x
  // texture x interpolated vertex colour (each factor 1 where absent); `color` when the skin has
  // no materials and no vertex colours.
  Eigen::Vector4f surfaceColorAt(std::int32_t t, const float b[3]) const;
};

// Sets cornerUv from per-face input corners: face f (in the order faces were added, as `triangles`
// lists them) had vertices inputTriangles[3f..3f+2] with UVs inputUv[3f..3f+2]; the corners are
// matched by vertex, so the order finalizeSkin gives a face's vertices does not matter. Call after
// finalizeSkin.
void setCornerUvs(SkinMesh& skin, const std::vector<std::int32_t>& inputTriangles,
                  const std::vector<Eigen::Vector2f>& inputUv);

// Checks the appearance arrays' sizes and indices against the mesh (PELAGE_CHECK: a bug if not).
void checkAppearance(const SkinMesh& skin);

// Adds the pelage vertex properties to skin.mesh with neutral values (bound to segment 0, length
// 0, region 0, no direction).
void addSkinProperties(SkinMesh& skin);

// Builds the derived arrays (triangles, vertex->face adjacency, area). Call after the mesh is
// final; PELAGE_CHECK fails if the mesh is not a pure triangle mesh or has deleted elements.
void finalizeSkin(SkinMesh& skin);

// Summary facts for `pelage info`.
struct SkinStats {
  int vertices = 0;
  int triangles = 0;
  double area = 0.0;
  Eigen::Vector3f boundsMin = Eigen::Vector3f::Zero();
  Eigen::Vector3f boundsMax = Eigen::Vector3f::Zero();
  int boundaryEdges = 0;
  int nonManifoldVertices = 0;
  double minAngleDegrees = 0.0;
};
SkinStats skinStats(const SkinMesh& skin);

}  // namespace pelage::skin
