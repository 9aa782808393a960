#include "pelage/scene/model.h"

#include "pelage/skin/subdivide.h"

#include <algorithm>
#include <filesystem>

#include "pelage/animation/clip_file.h"
#include "pelage/animation/gltf_import.h"
#include "pelage/animation/procedural.h"
#include "pelage/models/builtin.h"
#include "pelage/skin/build_from_shapes.h"
#include "pelage/skin/mesh_io.h"
#include "pelage/util/error.h"
#include "pelage/util/path.h"

namespace pelage::scene {
namespace {

Model fromCreature(const anatomy::Creature& c, const LoadOptions& options) {
  Model m;
  m.name = c.name;
  m.source = c.source;
  m.body = c.body;
  skin::SkinBuildOptions opt;
  opt.triangles = options.triangles > 0 ? options.triangles : c.defaultTriangles;
  m.skin = skin::buildSkin(c, opt);
  // Creatures with the monkey's skeleton (the built-in one, or a user's variant of it) get the
  // procedural clips, baked for this body.
  if (animation::missingMonkeySegment(m.body).empty()) m.clips = animation::monkeyClips(c);
  return m;
}

// The skin after the load options' subdivision (skin/subdivide.h).
skin::SkinMesh subdivided(skin::SkinMesh skin, const LoadOptions& options) {
  const int levels =
      options.subdivide < 0 ? skin::autoSubdivisionLevels(skin.numTriangles()) : options.subdivide;
  return levels == 0 ? std::move(skin) : skin::subdivideSkin(skin, levels);
}

Model fromGltf(const std::string& path, const LoadOptions& options) {
  animation::GltfImportOptions opt;
  opt.unitScale = options.unitScale;
  opt.noFurRegions = options.noFurRegions;
  opt.segmentDirections = options.segmentDirections;
  animation::GltfCreature g = animation::importGltf(path, opt);
  Model m;
  m.name = g.name;
  m.source = path;
  m.body = std::move(g.body);
  m.skin = subdivided(std::move(g.skin), options);
  m.clips = std::move(g.clips);
  m.unitScale = g.unitScale;
  return m;
}

}  // namespace

anatomy::Creature builtinCreature(const std::string& name) {
  const auto text = models::builtinFile(name + ".json");
  if (!text) inputError("unknown built-in model '", name, "' (built-in: monkey)");
  return anatomy::parseCreature(std::string(*text), "built-in " + name);
}

ModelFileKind modelFileKind(std::string_view path) {
  const std::string ext = lowerExtension(path);
  if (ext == ".gltf" || ext == ".glb") return ModelFileKind::Gltf;
  if (ext == ".obj" || ext == ".ply" || ext == ".off" || ext == ".stl") return ModelFileKind::Mesh;
  if (ext == ".json") return ModelFileKind::Creature;
  return ModelFileKind::None;
}

Model loadModel(const std::string& spec, const LoadOptions& options) {
  if (options.triangles != 0 && (options.triangles < 2000 || options.triangles > 2000000))
    fieldError("triangles", options.triangles, " is out of range [2000, 2000000]");
  if (options.subdivide < -1 || options.subdivide > skin::kMaxSubdivisionLevels)
    fieldError("subdivide", options.subdivide, " is out of range [0, ", skin::kMaxSubdivisionLevels,
               "] levels (or auto)");
  const ModelFileKind kind = modelFileKind(spec);
  const bool gltf = kind == ModelFileKind::Gltf;
  const bool mesh = kind == ModelFileKind::Mesh;
  if (!gltf && (options.noFurRegions || !options.segmentDirections.empty()))
    inputError(spec.empty() ? std::string(kDefaultModel) : spec,
               ": no-fur regions and segment directions apply to glTF models (.gltf/.glb) "
               "only");
  if (!gltf && !mesh && options.subdivide > 0)
    inputError(spec.empty() ? std::string(kDefaultModel) : spec,
               ": subdivision applies to glTF models and static meshes only (creatures built "
               "from shapes take a triangle count)");
  if (!gltf && !mesh && options.unitScale != 0.0f)
    inputError(spec, ": a unit scale applies to glTF models and static meshes only");
  if (gltf) return fromGltf(spec, options);
  if (spec.empty() || spec == kDefaultModel)
    return fromCreature(builtinCreature(kDefaultModel), options);
  if (kind == ModelFileKind::Creature) return fromCreature(anatomy::loadCreature(spec), options);
  if (mesh) {
    Model m;
    m.name = std::filesystem::path(spec).stem().string();
    m.source = spec;
    m.unitScale = options.unitScale > 0.0f ? options.unitScale : 1.0f;
    m.skin = subdivided(skin::readStaticMesh(spec, -1.0f, m.unitScale), options);
    anatomy::SegmentSpec root;
    root.name = "root";
    m.body = anatomy::makeBody({root}, spec);
    return m;
  }
  if (!std::filesystem::exists(spec))
    throw MissingFileError(spec + ": no such file, and not a built-in model (built-in: monkey)");
  inputError(spec, ": unsupported model format '", lowerExtension(spec),
             "' (accepted: monkey, .json creature, .gltf/.glb, .obj .ply .off .stl mesh)");
}

float modelSizeMeters(const Model& model) {
  const float* p = model.skin.restPositions();
  Eigen::AlignedBox3f box;
  for (int v = 0; v < model.skin.numVertices(); ++v)
    box.extend(Eigen::Vector3f(p[3 * v], p[3 * v + 1], p[3 * v + 2]));
  return box.isEmpty() ? 0.0f : box.sizes().maxCoeff();
}

int resolveClip(Model& model, const std::string& spec) {
  if (spec.empty()) return model.clips.empty() ? -1 : 0;
  const int c = model.findClip(spec);
  if (c >= 0) return c;
  if (lowerExtension(spec) == ".json") {
    model.clips.push_back(animation::loadClip(model.body, spec));
    return static_cast<int>(model.clips.size()) - 1;
  }
  std::string names;
  for (const animation::Clip& k : model.clips) names += (names.empty() ? "" : ", ") + k.name;
  fieldError("clip", ": model '", model.name, "' has no clip '", spec, "' (",
             names.empty() ? std::string("it has no clips") : "its clips: " + names,
             "; or give a clip .json file)");
}

}  // namespace pelage::scene
