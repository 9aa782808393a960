// glTF 2.0 import: node tree -> Body, skinned and rigid meshes -> SkinMesh, animations -> Clips.
// See gltf_import.h for the conventions; the stages are in gltf_stages.h, one file each.
#include "pelage/animation/gltf_import.h"

#include <filesystem>

#include "gltf_stages.h"
#include "pelage/util/color.h"
#include "pelage/util/error.h"
#include "pelage/util/path.h"

namespace pelage::animation {

using namespace detail;

// The stages, in order (gltf_stages.h): the node tree, 1. the scene's meshes, 2. the skeleton,
// 3. the geometry, 4. the units, 5. the body, 6. welding, 7. triangles, 8. the OpenMesh skin,
// 9. vertex properties, 10. the skin colour, 11. the appearance, 12. the clips.
GltfCreature importGltf(const std::string& path, const GltfImportOptions& options) {
  if (options.unitScale != 0.0f && !(options.unitScale >= 1e-6f && options.unitScale <= 1e6f))
    inputError("unit scale ", options.unitScale,
               " is out of range [1e-6, 1e6] metres per file unit");
  if (options.furLengthMeters != 0.0f &&
      !(options.furLengthMeters > 0.0f && options.furLengthMeters <= 10.0f))
    inputError("fur length ", options.furLengthMeters, " m is out of range (0, 10]");
  const tinygltf::Model model = gltf::loadModelFile(path);
  const ImportContext ctx(path, model);
  const Tree tree = buildTree(ctx);
  const SceneMeshes meshes = sceneMeshes(ctx, tree);
  const Skeleton skeleton = buildSkeleton(ctx, tree, meshes);
  const int nS = skeleton.size();
  Primitives prims = readGeometry(ctx, meshes, skeleton);
  const Units units = findUnits(prims, options);
  GltfCreature out;
  out.name = std::filesystem::path(path).stem().string();
  out.unitScale = units.scale;
  out.unitScaleReason = units.reason;
  anatomy::Body& body = out.body;
  buildBody(ctx, tree, skeleton, units, body);

  const std::vector<std::string>& noFur =
      options.noFurRegions ? *options.noFurRegions : defaultNoFurRegions();
  std::vector<bool> bareRegion(prims.regionNames.size(), false);
  for (std::size_t r = 0; r < prims.regionNames.size(); ++r)
    for (const std::string& pat : noFur)
      bareRegion[r] = bareRegion[r] || globMatches(pat, prims.regionNames[r]);
  // Patterns the user gave must each match a region: a typo would otherwise replace the default
  // list and grow fur on eyes and antlers without a word.
  if (options.noFurRegions)
    for (const std::string& pat : *options.noFurRegions) {
      bool matched = false;
      for (const std::string& name : prims.regionNames) matched = matched || globMatches(pat, name);
      if (!matched) {
        std::string names;
        for (const std::string& name : prims.regionNames)
          names += (names.empty() ? "" : ", ") + name;
        fieldError("no fur", "'", pat, "' matches no region of ", path, " (its regions: ", names,
                   ")");
      }
    }
  const Weld weld = weldVertices(prims, units, bareRegion);
  std::vector<std::size_t> kept;
  const std::vector<std::array<std::int32_t, 3>> tris =
      weldedTriangles(ctx, prims, weld, units, kept);
  skin::SkinMesh& sk = out.skin;
  std::vector<std::int32_t> faceVertices;
  const std::vector<std::int32_t> source = buildSkinMesh(path, tris, weld, sk, faceVertices);
  const std::vector<std::int32_t>& welded = weld.welded;
  const std::vector<int>& weldRegion = weld.weldRegion;
  const float diag =
      static_cast<float>(static_cast<double>(units.scale) * units.fileBox.diagonal().norm());

  // 9. Vertex properties: bindings, regions, fur lengths, segment directions.
  skin::addSkinProperties(sk);
  sk.regionNames = prims.regionNames;
  std::vector<bool> bound(static_cast<std::size_t>(nS), false);
  for (std::int32_t w : source)
    for (std::size_t k = 0; k < 4; ++k) {
      const skin::Binding& b =
          prims.vertices[static_cast<std::size_t>(welded[static_cast<std::size_t>(w)])].binding;
      if (b.weight[k] > 0.0f) bound[static_cast<std::size_t>(b.segment[k])] = true;
    }
  std::vector<Eigen::Vector3f> bindJoints(static_cast<std::size_t>(nS));
  for (int si = 0; si < nS; ++si)
    bindJoints[static_cast<std::size_t>(si)] =
        body.inverseBind[static_cast<std::size_t>(si)].inverse().translation();
  const std::vector<Eigen::Vector3f> dirs = headToTailDirections(body, bindJoints, bound);
  for (int si = 0; si < nS; ++si)
    body.segments[static_cast<std::size_t>(si)].direction = dirs[static_cast<std::size_t>(si)];
  std::string sideFile = options.segmentDirections;
  if (sideFile.empty()) {
    const std::filesystem::path auto_ =
        std::filesystem::path(path).replace_extension(".directions.json");
    std::error_code ec;
    if (std::filesystem::is_regular_file(auto_, ec)) sideFile = auto_.string();
  }
  if (!sideFile.empty()) applyDirectionFile(body, sideFile);

  const float furLength = options.furLengthMeters > 0.0f ? options.furLengthMeters : 0.02f * diag;
  for (auto vh : sk.mesh.vertices()) {
    const std::int32_t w = source[static_cast<std::size_t>(vh.idx())];
    const RawVertex& rv =
        prims.vertices[static_cast<std::size_t>(welded[static_cast<std::size_t>(w)])];
    const int region = weldRegion[static_cast<std::size_t>(w)];
    sk.mesh.property(sk.binding, vh) = rv.binding;
    sk.mesh.property(sk.region, vh) = region;
    sk.mesh.property(sk.furLength, vh) =
        bareRegion[static_cast<std::size_t>(region)] ? 0.0f : furLength;
    const Eigen::Vector3f& d =
        body.segments[static_cast<std::size_t>(rv.binding.segment[0])].direction;
    sk.mesh.property(sk.segmentDirection, vh) = OpenMesh::Vec3f(d.x(), d.y(), d.z());
  }
  // 10. Skin colour (the skin's one colour where it is drawn without materials, and the colour of
  // triangles without a material): the base colour of the untextured furred region with the most
  // triangles. A textured material's factor only tints its texture (the Fox: factor 1, colour in
  // the texture), so such materials leave the skin's default colour.
  std::int64_t most = -1;
  for (std::size_t r = 0; r < prims.regionNames.size(); ++r) {
    const int mat = prims.regionMaterial[r];
    if (bareRegion[r] || mat < 0 || prims.regionTriangles[r] <= most) continue;
    const auto& pbr = model.materials[static_cast<std::size_t>(mat)].pbrMetallicRoughness;
    if (pbr.baseColorTexture.index >= 0) continue;
    const std::vector<double>& f = pbr.baseColorFactor;
    if (f.size() >= 3 && finite(f)) {
      most = prims.regionTriangles[r];
      // glTF factors are linear; skin.color is sRGB-encoded, as typed (util/color.h).
      sk.color = Eigen::Vector3f(linearToSrgb(static_cast<float>(f[0])),
                                 linearToSrgb(static_cast<float>(f[1])),
                                 linearToSrgb(static_cast<float>(f[2])));
    }
  }
  skin::finalizeSkin(sk);
  readAppearance(ctx, prims, kept, faceVertices, weld, source, sk);

  out.clips = readClips(ctx, skeleton, units, body);
  return out;
}

}  // namespace pelage::animation
