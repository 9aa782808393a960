// glTF appearance on the shared models and on edited copies of them: the Fox's texture (a PNG in
// a .glb buffer view) and CesiumMan's (a JPEG) decode to exactly the image's pixels with their
// samplers; the same image given as a data URI or as a file beside the model loads identically;
// the Husky's materials are its base colour factors; a missing, truncated, corrupt or outside
// image, or a texture on a mesh without TEXCOORD_0, leaves the material untextured with a warning
// naming the image, and the geometry loads.
#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "pelage/animation/gltf_import.h"
#include "pelage/util/error.h"
#include "pelage/util/image.h"
#include "pelage/util/log.h"
#include "support/files.h"
#include "support/gltf.h"

namespace pelage::animation {
namespace {

using test::sharedModel;

// The encoded bytes of image `i` held in a buffer view.
std::vector<unsigned char> embeddedImage(const test::GltfParts& g, std::size_t i) {
  const auto& view = g.json["bufferViews"][g.json["images"][i]["bufferView"].get<std::size_t>()];
  const auto& buffer = g.buffers[view["buffer"].get<std::size_t>()];
  const std::size_t at = view.value("byteOffset", std::size_t{0});
  return {buffer.begin() + static_cast<long>(at),
          buffer.begin() + static_cast<long>(at + view["byteLength"].get<std::size_t>())};
}

// Imports `path` collecting its warnings.
GltfCreature importCollecting(const std::string& path, std::vector<std::string>& warnings) {
  const WarningSink old = setWarningSink([&](const std::string& w) { warnings.push_back(w); });
  try {
    GltfCreature c = importGltf(path);
    setWarningSink(old);
    return c;
  } catch (...) {
    setWarningSink(old);
    throw;
  }
}

// The texture of a loaded model equals image `bytes` decoded, texel for texel.
void expectTextureIs(const skin::Texture& t, const std::vector<unsigned char>& bytes) {
  const Rgba8Image image = decodeImage(bytes.data(), bytes.size(), "expected");
  ASSERT_EQ(t.width, image.width);
  ASSERT_EQ(t.height, image.height);
  EXPECT_TRUE(t.rgba == image.rgba);
}

TEST(GltfAppearance, FoxTextureIsItsPngWithUvsOnEveryCorner) {
  PELAGE_REQUIRE_SHARED_MODELS();
  const test::GltfParts g = test::GltfParts::read(sharedModel("Fox/Fox.glb"));
  const GltfCreature fox = importGltf(sharedModel("Fox/Fox.glb"));
  const skin::SkinMesh& sk = fox.skin;
  ASSERT_EQ(sk.textures.size(), 1u);
  expectTextureIs(sk.textures[0], embeddedImage(g, 0));
  EXPECT_TRUE(sk.textures[0].srgb);
  EXPECT_EQ(sk.textures[0].filter, skin::Filter::Linear);  // magFilter 9729
  EXPECT_EQ(sk.textures[0].wrapS, skin::Wrap::Repeat);     // glTF's default
  ASSERT_EQ(sk.materials.size(), 1u);
  EXPECT_EQ(sk.materials[0].name, "fox_material");
  EXPECT_EQ(sk.materials[0].texture, 0);
  EXPECT_TRUE(sk.materials[0].baseColor.isApprox(Eigen::Vector4f::Ones()));
  ASSERT_EQ(sk.cornerUv.size(), 3u * static_cast<std::size_t>(sk.numTriangles()));
  for (const Eigen::Vector2f& uv : sk.cornerUv) {
    ASSERT_TRUE(uv.allFinite());
    EXPECT_GE(uv.minCoeff(), 0.0f);
    EXPECT_LE(uv.maxCoeff(), 1.0f);
  }
  // The surface colour at a triangle's centre is the texture sampled at its interpolated UV.
  const float centre[3] = {1.0f / 3, 1.0f / 3, 1.0f / 3};
  for (int t = 0; t < sk.numTriangles(); t += 37) {
    const Eigen::Vector4f expected = sk.textures[0].sample(sk.uvAt(t, centre));
    EXPECT_TRUE(sk.surfaceColorAt(t, centre).isApprox(expected, 1e-6f)) << "triangle " << t;
  }
  EXPECT_TRUE(sk.vertexColor.empty());  // the Fox has no COLOR_0
}

TEST(GltfAppearance, CesiumManTextureIsItsJpegWithItsSampler) {
  PELAGE_REQUIRE_SHARED_MODELS();
  const test::GltfParts g = test::GltfParts::read(sharedModel("CesiumMan/CesiumMan.glb"));
  ASSERT_EQ(g.json["images"][0]["mimeType"], "image/jpeg");
  const GltfCreature man = importGltf(sharedModel("CesiumMan/CesiumMan.glb"));
  ASSERT_EQ(man.skin.textures.size(), 1u);
  expectTextureIs(man.skin.textures[0], embeddedImage(g, 0));
  EXPECT_EQ(man.skin.textures[0].wrapS, skin::Wrap::Repeat);  // 10497
  EXPECT_EQ(man.skin.textures[0].wrapT, skin::Wrap::Repeat);
  ASSERT_EQ(man.skin.materials.size(), 1u);
  EXPECT_EQ(man.skin.materials[0].texture, 0);
}

// The Husky: five untextured materials; every triangle's material is its primitive's, whose base
// colour is the file's factor.
TEST(GltfAppearance, HuskyMaterialsAreItsBaseColourFactors) {
  PELAGE_REQUIRE_SHARED_MODELS();
  const test::GltfParts g = test::GltfParts::read(sharedModel("Husky/Husky.gltf"));
  const GltfCreature husky = importGltf(sharedModel("Husky/Husky.gltf"));
  const skin::SkinMesh& sk = husky.skin;
  const auto& materials = g.json["materials"];
  ASSERT_EQ(sk.materials.size(), materials.size());  // every primitive has a material
  for (std::size_t m = 0; m < materials.size(); ++m) {
    SCOPED_TRACE(m);
    EXPECT_EQ(sk.materials[m].name, materials[m]["name"].get<std::string>());
    const auto& f = materials[m]["pbrMetallicRoughness"]["baseColorFactor"];
    for (int k = 0; k < 4; ++k)
      EXPECT_FLOAT_EQ(sk.materials[m].baseColor[k], f[static_cast<std::size_t>(k)].get<float>());
    EXPECT_EQ(sk.materials[m].texture, -1);
  }
  EXPECT_TRUE(sk.textures.empty());
  EXPECT_FALSE(sk.hasUv());
  ASSERT_EQ(sk.triangleMaterial.size(), static_cast<std::size_t>(sk.numTriangles()));
  std::vector<int> used(materials.size(), 0);
  for (const std::int32_t m : sk.triangleMaterial) {
    ASSERT_GE(m, 0);
    ASSERT_LT(m, static_cast<std::int32_t>(materials.size()));
    ++used[static_cast<std::size_t>(m)];
  }
  for (std::size_t m = 0; m < used.size(); ++m) EXPECT_GT(used[m], 0) << "material " << m;
}

// The Fox's PNG moved out of its buffer view: into a data URI, then into a file beside the model
// (a name with a space, percent-encoded in the uri). Both load to the same texture.
TEST(GltfAppearance, ImageFromDataUriOrFileBesideTheModel) {
  PELAGE_REQUIRE_SHARED_MODELS();
  test::TempDir dir;
  const test::GltfParts fox = test::GltfParts::read(sharedModel("Fox/Fox.glb"));
  const std::vector<unsigned char> png = embeddedImage(fox, 0);

  test::GltfParts dataUri = fox;
  dataUri.json["images"][0].erase("bufferView");
  dataUri.json["images"][0]["uri"] = "data:image/png;base64," + test::base64Encode(png);
  dataUri.write(dir.file("data_uri.glb"));
  std::vector<std::string> warnings;
  const GltfCreature a = importCollecting(dir.file("data_uri.glb"), warnings);
  ASSERT_EQ(a.skin.textures.size(), 1u);
  expectTextureIs(a.skin.textures[0], png);
  EXPECT_TRUE(warnings.empty()) << warnings.front();

  test::GltfParts beside = fox;
  beside.json["images"][0].erase("bufferView");
  beside.json["images"][0].erase("mimeType");
  beside.json["images"][0]["uri"] = "fox%20skin.png";
  test::writeBytes(dir.file("fox skin.png"), png);
  beside.write(dir.file("beside.glb"));
  const GltfCreature b = importCollecting(dir.file("beside.glb"), warnings);
  ASSERT_EQ(b.skin.textures.size(), 1u);
  expectTextureIs(b.skin.textures[0], png);
  EXPECT_TRUE(warnings.empty()) << warnings.front();
}

// Every bad image: the model loads, the material keeps its base colour (no texture), and one
// warning names the image (or the missing TEXCOORD_0) and the problem.
TEST(GltfAppearance, BadImagesWarnAndKeepTheBaseColour) {
  PELAGE_REQUIRE_SHARED_MODELS();
  test::TempDir dir;
  const test::GltfParts fox = test::GltfParts::read(sharedModel("Fox/Fox.glb"));
  const std::vector<unsigned char> png = embeddedImage(fox, 0);
  test::writeBytes(dir.file("outside.png"), png);
  const std::vector<unsigned char> half(png.begin(),
                                        png.begin() + static_cast<long>(png.size() / 2));
  std::vector<unsigned char> corrupt = png;
  for (std::size_t i = 64; i < corrupt.size(); i += 7) corrupt[i] ^= 0x5A;

  struct Case {
    std::string name;
    std::function<void(test::GltfParts&)> edit;
    std::string expected;  // in the warning, with the file's name
  };
  auto uri = [](const std::string& u) {
    return [u](test::GltfParts& g) {
      g.json["images"][0].erase("bufferView");
      g.json["images"][0]["uri"] = u;
    };
  };
  auto dataUri = [&](const std::vector<unsigned char>& bytes) {
    return uri("data:image/png;base64," + test::base64Encode(bytes));
  };
  const std::vector<Case> cases = {
      {"truncated", dataUri(half), "image 0"},
      {"corrupt", dataUri(corrupt), "image 0"},
      {"not an image", dataUri(std::vector<unsigned char>(300, 'x')), "image 0"},
      {"missing file", uri("nothere.png"), "does not exist"},
      {"parent folder", uri("../outside.png"), "not a relative path inside"},
      {"absolute path", uri(dir.file("outside.png")), "not a relative path inside"},
      {"a scheme", uri("file:///etc/hostname"), "not a relative path inside"},
      {"no such texture",
       [](test::GltfParts& g) {
         g.json["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["index"] = 7;
       },
       "texture 7 does not exist"},
      {"no TEXCOORD_0",
       [](test::GltfParts& g) {
         for (auto& mesh : g.json["meshes"])
           for (auto& prim : mesh["primitives"]) prim["attributes"].erase("TEXCOORD_0");
       },
       "no TEXCOORD_0"},
  };
  const GltfCreature original = importGltf(sharedModel("Fox/Fox.glb"));
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    test::GltfParts g = fox;
    c.edit(g);
    const std::string path = dir.file("sub/fox.glb");
    std::filesystem::create_directories(dir.file("sub"));
    g.write(path);
    std::vector<std::string> warnings;
    GltfCreature loaded;
    ASSERT_NO_THROW(loaded = importCollecting(path, warnings));
    EXPECT_EQ(loaded.skin.numTriangles(), original.skin.numTriangles());
    EXPECT_TRUE(loaded.skin.textures.empty());
    ASSERT_EQ(loaded.skin.materials.size(), 1u);
    EXPECT_EQ(loaded.skin.materials[0].texture, -1);
    EXPECT_TRUE(loaded.skin.materials[0].baseColor.isApprox(Eigen::Vector4f::Ones()));
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].find("fox.glb"), std::string::npos) << warnings[0];
    EXPECT_NE(warnings[0].find(c.expected), std::string::npos) << warnings[0];
  }
}

}  // namespace
}  // namespace pelage::animation
