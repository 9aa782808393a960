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
  Eigen::Vector3f color{0.45f, 0.32f, 0.26f};    // skin material diffuse colour

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
};

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
