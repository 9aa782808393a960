// Per-frame skin deformation: linear blend skinning of the bind-pose vertices by the segments'
// skinning matrices (the paper uses an anatomical method, refs [16, 17]; "Each vertex of the skin's
// triangle mesh is transformed to its present position", sec. 3.2), then vertex normals.
#pragma once

#include <Eigen/Core>

#include <vector>

#include "pelage/anatomy/pose.h"
#include "pelage/skin/skin_mesh.h"

namespace pelage::skin {

// Per-frame skin state. Flat arrays, shape in the comment; sized on first use, then reused.
struct DeformedSkin {
  std::vector<Eigen::Vector3f> positions;    // nV: world positions
  std::vector<Eigen::Vector3f> normals;      // nV: unit outward vertex normals
  std::vector<Eigen::Vector3f> directions;   // nV: world segment direction vectors (unit, or 0)
  std::vector<Eigen::Vector3f> faceNormals;  // nT: area-weighted face normals (2 x area), scratch
};

// Deforms the skin for one body state: positions p = sum_i w_i S_i p_rest, segment directions
// d = normalize(sum_i w_i L_i d_rest) (L_i the linear part of S_i), then normals. Parallel over
// vertices; no allocation after the first call with a given mesh.
void deformSkin(const SkinMesh& skin, const anatomy::BodyState& state, DeformedSkin& out);

// Vertex normals of `positions` (nV): the normalised sum of the incident faces' area-weighted
// normals. `faceScratch` (nT) receives the face normals. Deterministic whatever the thread count.
void computeVertexNormals(const SkinMesh& skin, const std::vector<Eigen::Vector3f>& positions,
                          std::vector<Eigen::Vector3f>& faceScratch,
                          std::vector<Eigen::Vector3f>& normals);

// The bind pose as a DeformedSkin (rest positions, their normals, rest directions).
void restSkin(const SkinMesh& skin, DeformedSkin& out);

}  // namespace pelage::skin
