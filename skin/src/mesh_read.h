// What the mesh readers (mesh_io.cpp: OBJ, STL, OFF; mesh_ply.cpp: PLY) share. Private to
// pelage::skin.
#pragma once

#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

#include "pelage/skin/skin_mesh.h"

namespace pelage::skin::detail {

// The whole file; InputError naming it when it cannot be opened.
std::string readAll(const std::string& path);

// A count from a header must be a plain non-negative integer that the file can hold: each element
// needs at least `minBytes` bytes of the file, so a header claiming billions of elements in a small
// file is refused before anything is allocated for them.
long long headerCount(const std::string& path, const std::string& what, const std::string& token,
                      std::uintmax_t fileSize, double minBytes);

// Adds a polygon as a triangle fan; triangles with a repeated vertex or that would make the mesh
// non-manifold are counted in `skipped` instead.
void addPolygon(TriMesh& mesh, const std::vector<TriMesh::VertexHandle>& face, long long& skipped);

// Warns once about the triangles skipped.
void warnSkipped(const std::string& path, long long skipped);

// Reads the next three words of line `lineNo` as the coordinates of a vertex (OBJ, OFF, ASCII STL).
void readCoordinates(const std::string& path, long long lineNo, std::istringstream& words,
                     float* xyz);

// PLY (ascii, binary_little_endian, binary_big_endian 1.0): see mesh_ply.cpp.
void readPly(const std::string& path, TriMesh& mesh);

}  // namespace pelage::skin::detail
