// Loading a creature from what the user names: the built-in monkey, a creature JSON file, a
// glTF 2.0 creature (.gltf/.glb, with its animations as clips), or a static mesh (OBJ/PLY/OFF/STL).
// A Model is constant during playback.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "pelage/anatomy/body.h"
#include "pelage/anatomy/creature.h"
#include "pelage/animation/clip.h"
#include "pelage/skin/skin_mesh.h"

namespace pelage::scene {

struct Model {
  std::string name;    // e.g. "monkey", or the file's stem
  std::string source;  // "built-in monkey" or the path
  anatomy::Body body;
  skin::SkinMesh skin;
  // Animation clips: a glTF file's animations, or the procedural clips of a creature with the
  // built-in monkey's segments (walk, tumble, hang, shake, idle).
  std::vector<animation::Clip> clips;
  float unitScale = 1.0f;  // metres per unit of the source file (glTF: detected or given)

  // Index of the clip called `name`, or -1.
  int findClip(std::string_view clipName) const { return animation::findClip(clips, clipName); }
};

struct LoadOptions {
  // Skin triangles for creatures built from shapes; 0 = the creature's default. Range [2000, 2e6].
  int triangles = 0;
  // glTF only (InputError when given for another kind of model):
  float unitScale = 0.0f;  // metres per file unit; 0 = detect from the bounding box
  std::optional<std::vector<std::string>>
      noFurRegions;  // region patterns without fur; nullopt = defaults
  std::string
      segmentDirections;  // per-joint direction side file; "" = <model>.directions.json if present
  // glTF creatures and static meshes: subdivision levels of the skin (skin/subdivide.h), so
  // roots grow on a smooth surface; -1 = auto (skin::autoSubdivisionLevels: a skin under
  // skin::kSmoothSkinTriangles triangles is subdivided until it has that many, at most 3 levels);
  // [0, 3] levels. The drawn skin is the subdivided one.
  int subdivide = -1;
};

// The built-in creature's name.
inline constexpr const char* kDefaultModel = "monkey";

// What a model file is, by its extension (any case): a glTF creature (.gltf, .glb), a static
// mesh (.obj, .ply, .off, .stl), a creature file (.json), or none of these.
enum class ModelFileKind { None, Gltf, Mesh, Creature };
ModelFileKind modelFileKind(std::string_view path);

// Loads `spec`: "" or "monkey" (built-in), a .json creature, a .gltf/.glb creature, or a
// .obj/.ply/.off/.stl mesh.
// Throws InputError naming the file for anything missing or malformed.
Model loadModel(const std::string& spec, const LoadOptions& options = {});

// The longest side (m) of the rest skin's bounding box.
float modelSizeMeters(const Model& model);
// Longest sides (m) outside which a creature is implausible for an animal (its file is probably
// not in metres): applications warn and suggest a unit scale.
inline constexpr float kPlausibleSizeMeters[2] = {0.02f, 3.0f};

// The clip `spec` names: one of model.clips by name, or a clip .json file (loaded for the model's
// body and appended to model.clips); "" gives the model's first clip, or -1 (the still pose) when
// it has none. InputError naming field "clip" and listing the model's clips otherwise. The one
// place a clip is looked up from what a user typed.
int resolveClip(Model& model, const std::string& spec);

// The built-in creature description.
anatomy::Creature builtinCreature(const std::string& name);

}  // namespace pelage::scene
