// The hierarchical body (Van Gelder & Wilhelms 1997, sec. 3.4: "We use a hierarchical body, in
// which skin vertices are associated with the body segment to which they are closest").
// Constant model: built once, read-only during playback.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <string>
#include <string_view>
#include <vector>

#include "pelage/anatomy/transform.h"

namespace pelage::anatomy {

// One body segment (a bone / glTF node).
struct Segment {
  std::string name;
  // Index of the parent segment, or -1 for a root. Always smaller than this segment's index.
  int parent = -1;
  // Rest (bind) local transform relative to the parent (or to the world for a root).
  Transform rest;
  // The user-set segment direction vector (paper sec. 3.4), in bind-pose world coordinates; it
  // moves with the segment. Zero means "no segment direction": fur there follows the skin normal.
  Eigen::Vector3f direction = Eigen::Vector3f::Zero();
};

// Segments stored parent-before-child, so kinematics is one forward loop (as in MuJoCo).
struct Body {
  std::vector<Segment> segments;
  // Per segment: inverse of its bind-pose world transform (glTF inverseBindMatrices). Skin vertices
  // are stored in bind space; skinning matrix = world * inverseBind.
  std::vector<Eigen::Affine3f> inverseBind;

  int size() const { return static_cast<int>(segments.size()); }
  // Index of the segment called `name`, or -1.
  int find(std::string_view name) const;
};

// A segment as written in a description, with its parent named (any order).
struct SegmentSpec {
  std::string name;
  std::string parent;  // empty for a root
  Transform rest;
  Eigen::Vector3f direction = Eigen::Vector3f::Zero();
};

// Builds a Body from specs in any order: sorts parents before children; rejects duplicate names,
// unknown parents, cycles and non-finite values with InputError messages prefixed by `source`
// (a file name). inverseBind is set from the rest pose.
Body makeBody(const std::vector<SegmentSpec>& specs, const std::string& source);

// Bind-pose world transforms of every segment (forward kinematics of the rest transforms).
std::vector<Eigen::Affine3f> restWorldTransforms(const Body& body);

// Checks the structural invariants (parent order, sizes, finiteness); PELAGE_CHECK on failure.
void checkBody(const Body& body);

}  // namespace pelage::anatomy
