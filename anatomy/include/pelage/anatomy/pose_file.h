// Pose files: JSON that bends named segments relative to their rest transforms, e.g.
//   { "pose": { "l_forearm": { "rotate": { "axis": [0, 1, 0], "degrees": 60 } },
//               "pelvis":    { "translate": [0, 0, 0.05] } } }
// rotate: local rotation = rest rotation * R(axis, degrees) (axis in the segment's frame);
// translate: added to the rest local translation (metres).
#pragma once

#include <string>

#include "pelage/anatomy/body.h"
#include "pelage/anatomy/pose.h"

namespace pelage::anatomy {

// Parses a pose for `body`; errors name `source` and the field (unknown segment, bad axis...).
Pose parsePose(const Body& body, const std::string& jsonText, const std::string& source);
// Reads a pose file.
Pose loadPose(const Body& body, const std::string& path);

}  // namespace pelage::anatomy
