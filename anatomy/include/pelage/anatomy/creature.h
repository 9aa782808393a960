// A creature description: the body of segments, the body shapes (ellipsoids and tapered capsules
// per segment) that the skin is built around, and the named fur-length regions (paper sec. 3.2:
// "a preprocessing procedure ... to reduce the length of fur automatically over the face and hands,
// and other desired areas"). Read from JSON; see models/monkey.json for the format.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <optional>
#include <string>
#include <vector>

#include "pelage/anatomy/body.h"

namespace pelage::anatomy {

// A body shape in bind-pose world coordinates (metres), owned by one segment.
struct Shape {
  enum class Kind { Ellipsoid, Capsule };
  Kind kind = Kind::Ellipsoid;
  int segment = 0;
  // Ellipsoid: centre, semi-axis radii along the rotated x, y, z axes.
  Eigen::Vector3f center = Eigen::Vector3f::Zero();
  Eigen::Vector3f radii = Eigen::Vector3f::Ones();
  Eigen::Quaternionf rotation = Eigen::Quaternionf::Identity();
  // Capsule (a round cone): segment from -> to with radius rFrom at `from`, rTo at `to`.
  Eigen::Vector3f from = Eigen::Vector3f::Zero();
  Eigen::Vector3f to = Eigen::Vector3f::Zero();
  float rFrom = 0.0f;
  float rTo = 0.0f;
  // Smooth-union radius with the shapes before it (metres); negative = creature default.
  float blend = -1.0f;
};

// A named fur-length region. A vertex belongs to it if its closest segment is listed, or it lies in
// one of the spheres or boxes (membership fades to zero over `blend` metres outside the volume).
struct FurRegion {
  std::string name;
  float lengthScale = 1.0f;  // fur length = creature furLength * lengthScale (0 = no fur)
  std::vector<int> segments;
  std::vector<Eigen::Vector4f> spheres;  // centre xyz, radius
  std::vector<Eigen::AlignedBox3f> boxes;
  float blend = 0.0f;
  std::optional<Eigen::Vector3f> furColor;  // sRGB as typed; replaces the body's fur colour here
};

// A creature's fur colours (sRGB as typed): countershading, `back` where the skin faces up (+Z),
// `belly` where it faces down, blended over normals whose up component lies in [-spread, spread].
struct CreatureFurColor {
  Eigen::Vector3f back{0.5f, 0.5f, 0.5f};
  Eigen::Vector3f belly{0.5f, 0.5f, 0.5f};
  float spread = 0.4f;  // (0, 1]
};

struct Creature {
  std::string name;
  std::string source;  // file name or "built-in <name>", for messages
  Body body;
  std::vector<Shape> shapes;
  std::vector<FurRegion> regions;
  float furLengthMeters = 0.02f;                   // default overcoat fur length at a skin vertex
  float blendRadiusMeters = 0.02f;                 // default smooth-union radius between shapes
  int defaultTriangles = 130000;                   // skin triangle count when the user gives none
  Eigen::Vector3f skinColor{0.45f, 0.32f, 0.26f};  // skin diffuse colour (sRGB as typed)
  std::optional<CreatureFurColor> furColor;        // absent: the fur presets' materials colour it
};

// Parses a creature from JSON text; `source` names it in error messages.
Creature parseCreature(const std::string& jsonText, const std::string& source);
// Reads and parses a creature file.
Creature loadCreature(const std::string& path);

}  // namespace pelage::anatomy
