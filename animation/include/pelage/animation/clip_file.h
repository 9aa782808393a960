// Hand-authored clip files (JSON). Keys are relative to the rest pose, like pose files:
//   { "name": "wave", "loop": true, "duration": 2.0,
//     "rootMotion": { "segment": "pelvis", "translate": [0.2, 0, 0] },
//     "channels": [
//       { "segment": "l_forearm", "path": "rotate", "interpolation": "cubic",
//         "keys": [ { "time": 0, "axis": [0, 1, 0], "degrees": 0 },
//                   { "time": 1, "axis": [0, 1, 0], "degrees": -60 },
//                   { "time": 2, "axis": [0, 1, 0], "degrees": 0 } ] },
//       { "segment": "pelvis", "path": "translate", "keys": [ { "time": 0, "value": [0, 0, 0] } ]
//       }, { "segment": "head", "path": "scale", "interpolation": "step",
//         "keys": [ { "time": 0, "value": [1, 1, 1] } ] } ] }
// rotate:    local rotation = rest rotation * R(axis, degrees) (axis in the segment's frame);
// translate: value (metres) added to the rest local translation;
// scale:     value multiplies the rest scale (each factor in (0, 1000]).
// interpolation: "step", "linear" (default) or "cubic" (a smooth curve through the keys with
// Catmull-Rom tangents, periodic for a looping clip whose keys span [0, duration]; stored as a
// glTF CUBICSPLINE channel). duration defaults to the last key time; loop defaults to true.
#pragma once

#include <string>

#include "pelage/anatomy/body.h"
#include "pelage/animation/clip.h"

namespace pelage::animation {

// Parses a clip for `body`; errors name `source` and the field (unknown segment, unsorted
// times...).
Clip parseClip(const anatomy::Body& body, const std::string& jsonText, const std::string& source);
// Reads a clip file; the clip's name defaults to the file's stem.
Clip loadClip(const anatomy::Body& body, const std::string& path);

}  // namespace pelage::animation
