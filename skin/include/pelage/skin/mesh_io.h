// Static meshes in (OBJ, PLY, OFF, STL, read by pelage into an OpenMesh mesh) and out (OBJ, PLY).
#pragma once

#include <Eigen/Core>

#include <string>
#include <vector>

#include "pelage/skin/skin_mesh.h"

namespace pelage::skin {

// Reads a static mesh (OBJ/PLY/OFF/STL) as a skin bound rigidly to segment 0, polygons
// triangulated, coordinates times `unitScale` (metres per file unit), fur length
// `furLengthMeters` everywhere (if <= 0: 2% of the bounding-box diagonal, glTF creatures' rule).
// Throws InputError naming the file for a missing/unreadable/empty/non-finite mesh.
SkinMesh readStaticMesh(const std::string& path, float furLengthMeters = -1.0f,
                        float unitScale = 1.0f);

// Writes the skin with the given vertex positions and normals (nV each) to an OBJ or PLY file
// (chosen by extension), atomically; an OBJ also holds the skin's texture coordinates, one per
// triangle corner, v up (1 - glTF's v), when it has them. Throws InputError on an unsupported
// extension or a write failure.
void writeSkin(const std::string& path, const SkinMesh& skin,
               const std::vector<Eigen::Vector3f>& positions,
               const std::vector<Eigen::Vector3f>& normals);

}  // namespace pelage::skin
