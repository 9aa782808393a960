// A malformed-file corpus generated from the real models in a temp dir (truncations, wrong magic,
// edited JSON, patched buffers, random byte flips): every file is rejected with an InputError that
// names it and says what is wrong, or (for harmless random flips) loads into a finite skin; never a
// crash, another exception, or (under the sanitizers) an out-of-bounds read.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <functional>
#include <limits>
#include <random>

#include "pelage/animation/gltf_import.h"
#include "pelage/util/error.h"
#include "pelage/util/log.h"
#include "support/files.h"
#include "support/gltf.h"

namespace pelage::animation {
namespace {

using test::GltfParts;
using test::sharedModel;
using ::testing::HasSubstr;

// Silences import warnings for the corpus (many files are odd on purpose).
struct QuietWarnings {
  WarningSink old = setWarningSink([](const std::string&) {});
  ~QuietWarnings() { setWarningSink(old); }
};

void expectRejected(const std::string& path, const std::string& expect) {
  try {
    importGltf(path);
    ADD_FAILURE() << path << ": accepted, expected an error mentioning '" << expect << "'";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr(path));
    EXPECT_THAT(e.what(), HasSubstr(expect));
  }
}

struct Corpus : ::testing::Test {
  void SetUp() override {
    if (!test::haveSharedModels())
      GTEST_SKIP() << "shared glTF models not found at " << PELAGE_SHARED_MODELS_DIR;
    fox = test::readBytes(sharedModel("Fox/Fox.glb"));
  }
  std::string put(const std::string& name, const std::vector<unsigned char>& bytes) {
    const std::string p = dir.file(name);
    test::writeBytes(p, bytes);
    return p;
  }
  // SimpleSkin (a .gltf with data-URI buffers) edited by `edit`.
  std::string simple(const std::string& name, const std::function<void(GltfParts&)>& edit) {
    GltfParts g = GltfParts::read(sharedModel("SimpleSkin/SimpleSkin.gltf"));
    edit(g);
    const std::string p = dir.file(name);
    g.write(p);
    return p;
  }
  // The Fox (a .glb) edited by `edit`.
  std::string foxEdit(const std::string& name, const std::function<void(GltfParts&)>& edit) {
    GltfParts g = GltfParts::read(sharedModel("Fox/Fox.glb"));
    edit(g);
    const std::string p = dir.file(name);
    g.write(p);
    return p;
  }
  test::TempDir dir;
  std::vector<unsigned char> fox;
  QuietWarnings quiet;
};

TEST_F(Corpus, RewrittenCopiesStillLoad) {
  // The corpus tools themselves are faithful: an unedited rewrite loads like the original.
  const GltfCreature a = importGltf(foxEdit("fox_copy.glb", [](GltfParts&) {}));
  const GltfCreature b = importGltf(simple("simple_copy.gltf", [](GltfParts&) {}));
  EXPECT_EQ(a.skin.numTriangles(), 576);
  EXPECT_EQ(b.skin.numTriangles(), 8);
}

TEST_F(Corpus, TruncatedAndEmptyFiles) {
  expectRejected(put("empty.glb", {}), "empty");
  expectRejected(put("ten.glb", std::vector<unsigned char>(fox.begin(), fox.begin() + 10)),
                 "truncated");
  for (std::size_t keep : {std::size_t{20}, std::size_t{1000}, fox.size() / 2, fox.size() - 4})
    expectRejected(
        put("cut" + std::to_string(keep) + ".glb",
            std::vector<unsigned char>(fox.begin(), fox.begin() + static_cast<long>(keep))),
        "truncated");
  const std::string text = test::readText(sharedModel("SimpleSkin/SimpleSkin.gltf"));
  test::writeText(dir.file("cut.gltf"), text.substr(0, text.size() / 2));
  expectRejected(dir.file("cut.gltf"), "malformed glTF");
}

TEST_F(Corpus, BrokenGlbContainers) {
  std::vector<unsigned char> b = fox;
  b[0] = 'x';
  expectRejected(put("magic.glb", b), "wrong magic");
  b = fox;
  b[4] = 1;
  expectRejected(put("version.glb", b), "GLB version 1");
  b = fox;
  b[12] = 0xFF, b[13] = 0xFF, b[14] = 0xFF;  // JSON chunk length beyond the file
  expectRejected(put("chunk.glb", b), "runs past the end");
  b = fox;
  b[16] = 'X';  // JSON chunk type
  expectRejected(put("chunktype.glb", b), "first GLB chunk must be JSON");
  b = fox;
  b.insert(b.end(), {0, 0, 0, 0});
  expectRejected(put("trailing.glb", b), "trailing data");
}

TEST_F(Corpus, BrokenJson) {
  std::vector<unsigned char> b = fox;  // the JSON chunk replaced by "[1, 2]" and spaces
  const std::uint32_t jsonLen = test::le32(b, 12);
  std::fill(b.begin() + 20, b.begin() + 20 + jsonLen, ' ');
  const std::string arr = "[1, 2]";
  std::copy(arr.begin(), arr.end(), b.begin() + 20);
  expectRejected(put("badjson.glb", b), "malformed glTF");
  test::writeText(dir.file("garbage.gltf"),
                  "{ \"asset\": { \"version\": \"2.0\" }, \"nodes\": [ { \"children\": [7] ");
  expectRejected(dir.file("garbage.gltf"), "malformed glTF");
}

TEST_F(Corpus, AccessorsAndViewsOutOfRange) {
  expectRejected(foxEdit("count.glb",
                         [](GltfParts& g) {
                           const int pos =
                               g.json["meshes"][0]["primitives"][0]["attributes"]["POSITION"];
                           g.json["accessors"][static_cast<std::size_t>(pos)]["count"] = 100000;
                         }),
                 "out of range");
  expectRejected(
      foxEdit("offset.glb",
              [](GltfParts& g) {
                const int pos = g.json["meshes"][0]["primitives"][0]["attributes"]["POSITION"];
                g.json["accessors"][static_cast<std::size_t>(pos)]["byteOffset"] = 4000000000u;
              }),
      "POSITION");
  expectRejected(
      foxEdit("view.glb", [](GltfParts& g) { g.json["bufferViews"][0]["byteLength"] = 99999999; }),
      "bufferView");
  expectRejected(foxEdit("noaccessor.glb",
                         [](GltfParts& g) {
                           g.json["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 999;
                         }),
                 "no such accessor");
  expectRejected(simple("type.gltf",
                        [](GltfParts& g) {
                          const int pos =
                              g.json["meshes"][0]["primitives"][0]["attributes"]["POSITION"];
                          g.json["accessors"][static_cast<std::size_t>(pos)]["type"] = "VEC2";
                        }),
                 "must be VEC3");
  expectRejected(simple("sparse.gltf",
                        [](GltfParts& g) {
                          const int pos =
                              g.json["meshes"][0]["primitives"][0]["attributes"]["POSITION"];
                          g.json["accessors"][static_cast<std::size_t>(pos)]["sparse"] = {
                              {"count", 1},
                              {"indices", {{"bufferView", 0}, {"componentType", 5123}}},
                              {"values", {{"bufferView", 0}}}};
                        }),
                 "sparse");
}

// Fewer vertices than the indices use: indices beyond the vertex count.
TEST_F(Corpus, IndicesBeyondTheVertexCount) {
  expectRejected(simple("indices.gltf",
                        [](GltfParts& g) {
                          for (const char* a : {"POSITION", "JOINTS_0", "WEIGHTS_0"}) {
                            const int i = g.json["meshes"][0]["primitives"][0]["attributes"][a];
                            g.json["accessors"][static_cast<std::size_t>(i)]["count"] = 5;
                          }
                        }),
                 "beyond the primitive's 5 vertices");
}

TEST_F(Corpus, NaNsInTheData) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  expectRejected(simple("nan.gltf",
                        [&](GltfParts& g) {
                          const int pos =
                              g.json["meshes"][0]["primitives"][0]["attributes"]["POSITION"];
                          const auto [off, buf] = g.accessorBytes(pos);
                          std::memcpy(g.buffers[buf].data() + off + 16, &nan, 4);  // element 1, y
                        }),
                 "element 1 has a NaN");
  expectRejected(foxEdit("nan_ibm.glb",
                         [&](GltfParts& g) {
                           const int ibm = g.json["skins"][0]["inverseBindMatrices"];
                           const auto [off, buf] = g.accessorBytes(ibm);
                           std::memcpy(g.buffers[buf].data() + off, &nan, 4);
                         }),
                 "inverseBindMatrices");
  expectRejected(foxEdit("nan_anim.glb",
                         [&](GltfParts& g) {
                           const int out = g.json["animations"][0]["samplers"][0]["output"];
                           const auto [off, buf] = g.accessorBytes(out);
                           std::memcpy(g.buffers[buf].data() + off + 4, &nan, 4);
                         }),
                 "NaN");
}

TEST_F(Corpus, MissingBuffers) {
  expectRejected(
      simple("missing.gltf", [](GltfParts& g) { g.json["buffers"][0]["uri"] = "missing.bin"; }),
      "missing.bin");
  expectRejected(foxEdit("nobin.glb", [](GltfParts& g) { g.buffers.clear(); }), "malformed glTF");
  expectRejected(
      simple("badview.gltf", [](GltfParts& g) { g.json["bufferViews"][0]["buffer"] = 9; }),
      "buffer");
}

// A data-URI buffer cut short: the message names the file and quotes a few dozen characters of
// the URI, not the whole buffer (it was 2 MB for the Horse).
TEST_F(Corpus, AShortenedBase64BufferGivesAShortMessage) {
  const std::string path = simple("short.gltf", [](GltfParts& g) {
    g.buffers[0].resize(g.buffers[0].size() + 300000, 0);
    g.json["buffers"][0]["byteLength"] = g.buffers[0].size();
  });
  std::string text = test::readText(path);
  const std::size_t at = text.find("base64,");
  ASSERT_NE(at, std::string::npos);
  const std::size_t end = text.find('"', at);
  text.erase(end - 1000, 1000);
  test::writeText(path, text);
  try {
    importGltf(path);
    ADD_FAILURE() << "a shortened buffer was accepted";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_THAT(m, HasSubstr(path));
    EXPECT_THAT(m, HasSubstr("bytes)"));
    EXPECT_LT(m.size(), path.size() + 300) << m.substr(0, 500);
  }
}

TEST_F(Corpus, UnsupportedRequiredExtensions) {
  expectRejected(simple("draco.gltf",
                        [](GltfParts& g) {
                          g.json["extensionsUsed"] = {"KHR_draco_mesh_compression"};
                          g.json["extensionsRequired"] = {"KHR_draco_mesh_compression"};
                        }),
                 "KHR_draco_mesh_compression");
  // Appearance-only extensions are fine.
  EXPECT_NO_THROW(importGltf(simple("unlit.gltf", [](GltfParts& g) {
    g.json["extensionsUsed"] = {"KHR_materials_unlit"};
    g.json["extensionsRequired"] = {"KHR_materials_unlit"};
  })));
}

TEST_F(Corpus, SkinsNodesAndAnimationsThatDoNotAddUp) {
  expectRejected(simple("joints.gltf", [](GltfParts& g) { g.json["skins"][0]["joints"] = {1}; }),
                 "but the skin has 1 joints");
  expectRejected(simple("jointnode.gltf",
                        [](GltfParts& g) {
                          g.json["skins"][0]["joints"] = {1, 99};
                        }),
                 "joint node 99");
  expectRejected(simple("cycle.gltf", [](GltfParts& g) { g.json["nodes"][2]["children"] = {1}; }),
                 "cycle");
  expectRejected(
      simple("twoparents.gltf", [](GltfParts& g) { g.json["nodes"][0]["children"] = {2}; }),
      "two parents");
  expectRejected(simple("child.gltf",
                        [](GltfParts& g) {
                          g.json["nodes"][1]["children"] = {2, 40};
                        }),
                 "child 40");
  expectRejected(simple("shear.gltf",
                        [](GltfParts& g) {
                          g.json["nodes"][1]["matrix"] = {1, 0, 0, 0, 0.5, 1, 0, 0,
                                                          0, 0, 1, 0, 0,   0, 0, 1};
                        }),
                 "shear");
  expectRejected(
      simple("sampler.gltf",
             [](GltfParts& g) { g.json["animations"][0]["channels"][0]["sampler"] = 5; }),
      "sampler 5");
  expectRejected(simple("keys.gltf",
                        [](GltfParts& g) {
                          const int in = g.json["animations"][0]["samplers"][0]["input"];
                          g.json["accessors"][static_cast<std::size_t>(in)]["count"] = 3;
                        }),
                 "output values");
  expectRejected(simple("interp.gltf",
                        [](GltfParts& g) {
                          g.json["animations"][0]["samplers"][0]["interpolation"] = "BEZIER";
                        }),
                 "BEZIER");
  expectRejected(simple("path.gltf",
                        [](GltfParts& g) {
                          g.json["animations"][0]["channels"][0]["target"]["path"] = "shear";
                        }),
                 "shear");
  expectRejected(simple("nomesh.gltf", [](GltfParts& g) { g.json["nodes"][0].erase("mesh"); }),
                 "no mesh");
  expectRejected(simple("weights.gltf",
                        [](GltfParts& g) {
                          g.json["meshes"][0]["primitives"][0]["attributes"].erase("WEIGHTS_0");
                        }),
                 "lacks WEIGHTS_0");
}

// Random corruption: byte flips anywhere in the Fox's GLB and in SimpleSkin's text, and random
// truncations. Each file loads (then its skin is finite) or is an InputError naming the file.
TEST_F(Corpus, RandomCorruptionNeverCrashes) {
  std::mt19937 rng(2024);
  const std::string text = test::readText(sharedModel("SimpleSkin/SimpleSkin.gltf"));
  int loaded = 0, rejected = 0;
  for (int i = 0; i < 400; ++i) {
    std::vector<unsigned char> b;
    std::string name;
    if (i % 2 == 0) {
      b = fox;
      name = "fuzz" + std::to_string(i) + ".glb";
    } else {
      b.assign(text.begin(), text.end());
      name = "fuzz" + std::to_string(i) + ".gltf";
    }
    const int kind = i % 5;
    if (kind == 4) {
      b.resize(std::uniform_int_distribution<std::size_t>(0, b.size() - 1)(rng));
    } else {
      const int flips = 1 + kind * 3;
      // Half of the Fox's flips land in the JSON chunk (the first ~4 KB), where structure lives.
      const std::size_t span = (i % 4 == 0) ? std::min<std::size_t>(b.size(), 4096) : b.size();
      for (int f = 0; f < flips; ++f) {
        const std::size_t at = std::uniform_int_distribution<std::size_t>(0, span - 1)(rng);
        b[at] = static_cast<unsigned char>(std::uniform_int_distribution<int>(0, 255)(rng));
      }
    }
    const std::string path = put(name, b);
    try {
      const GltfCreature c = importGltf(path);
      ++loaded;
      for (int v = 0; v < c.skin.numVertices(); ++v)
        ASSERT_TRUE(std::isfinite(c.skin.restPositions()[3 * v])) << path;
    } catch (const InputError& e) {
      ++rejected;
      ASSERT_THAT(e.what(), HasSubstr(path));
    } catch (const std::exception& e) {
      FAIL() << path << ": unexpected exception " << e.what();
    }
  }
  EXPECT_GT(rejected, 100);
  std::printf("random corruption: %d loaded, %d rejected\n", loaded, rejected);
}

// The same from every shared model (GLB and embedded-base64 .gltf, Khronos and Quaternius
// exporters): truncations at several points are rejected as truncated (GLB) or malformed JSON
// (.gltf); random corruption of the binary data (GLB BIN chunk bytes, or characters of the base64
// data URI, which keeps the JSON valid) loads into a finite skin or is rejected naming the file;
// an accessor count past its buffer view and an index past the vertex count are named.
TEST_F(Corpus, EveryModelTruncatedOrCorruptedIsHandled) {
  const char* files[] = {"Fox/Fox.glb",
                         "CesiumMan/CesiumMan.glb",
                         "RiggedFigure/RiggedFigure.glb",
                         "RiggedSimple/RiggedSimple.glb",
                         "SimpleSkin/SimpleSkin.gltf",
                         "Wolf/Wolf.gltf",
                         "Husky/Husky.gltf",
                         "Horse/Horse.gltf",
                         "Stag/Stag.gltf",
                         "Alpaca/Alpaca.gltf"};
  std::mt19937 rng(77);
  int loaded = 0, rejected = 0;
  for (const char* file : files) {
    SCOPED_TRACE(file);
    const std::vector<unsigned char> bytes = test::readBytes(sharedModel(file));
    ASSERT_GT(bytes.size(), 1000u);
    const bool glb = std::memcmp(bytes.data(), "glTF", 4) == 0;
    const std::string ext = glb ? ".glb" : ".gltf";
    const std::string stem = std::filesystem::path(file).stem().string();
    for (double frac : {0.01, 0.3, 0.7, 0.999}) {
      const std::size_t keep = static_cast<std::size_t>(frac * static_cast<double>(bytes.size()));
      const std::string p =
          put(stem + "_cut" + std::to_string(keep) + ext,
              std::vector<unsigned char>(bytes.begin(), bytes.begin() + static_cast<long>(keep)));
      expectRejected(p, glb ? "truncated" : "malformed glTF");
    }
    // Where the binary data lies: the BIN chunk, or the first data URI's base64 text.
    std::size_t from = 0, to = 0;
    if (glb) {
      from = 20 + test::le32(bytes, 12) + 8;
      to = bytes.size();
    } else {
      const std::string text(bytes.begin(), bytes.end());
      from = text.find("base64,") + 7;
      to = text.find('"', from);
    }
    ASSERT_LT(from + 100, to);
    static const char* b64 = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    for (int k = 0; k < 3; ++k) {
      std::vector<unsigned char> b = bytes;
      const int flips = 1 + 20 * k;
      for (int f = 0; f < flips; ++f) {
        const std::size_t at = std::uniform_int_distribution<std::size_t>(from, to - 1)(rng);
        b[at] =
            glb ? static_cast<unsigned char>(std::uniform_int_distribution<int>(0, 255)(rng))
                : static_cast<unsigned char>(b64[std::uniform_int_distribution<int>(0, 63)(rng)]);
      }
      const std::string p = put(stem + "_flip" + std::to_string(k) + ext, b);
      try {
        const GltfCreature c = importGltf(p);
        ++loaded;
        for (int v = 0; v < 3 * c.skin.numVertices(); ++v)
          ASSERT_TRUE(std::isfinite(c.skin.restPositions()[v])) << p;
      } catch (const InputError& e) {
        ++rejected;
        ASSERT_THAT(e.what(), HasSubstr(p));
      } catch (const std::exception& e) {
        FAIL() << p << ": unexpected exception " << e.what();
      }
    }
    // Structured edits of the first primitive, written back through the independent reader.
    const GltfParts original = GltfParts::read(sharedModel(file));
    const auto& prim = original.json["meshes"][0]["primitives"][0];
    GltfParts g = original;
    g.json["accessors"][prim["attributes"]["POSITION"].get<std::size_t>()]["count"] = 50000000;
    g.write(dir.file(stem + "_count" + ext));
    expectRejected(dir.file(stem + "_count" + ext), "out of range");
    if (prim.contains("indices")) {
      g = original;
      const auto [off, buf] = g.accessorBytes(prim["indices"].get<int>());
      const int type = g.json["accessors"][prim["indices"].get<std::size_t>()]["componentType"];
      const int size = type == 5121 ? 1 : type == 5123 ? 2 : 4;
      std::memset(g.buffers[buf].data() + off + static_cast<std::size_t>(size), 0xFF,
                  static_cast<std::size_t>(size));
      g.write(dir.file(stem + "_index" + ext));
      expectRejected(dir.file(stem + "_index" + ext), "beyond the primitive's");
    }
  }
  std::printf("every model corrupted: %d loaded, %d rejected\n", loaded, rejected);
}

TEST_F(Corpus, CommandLineReportsAndExits) {
  const std::string bad =
      put("cut.glb", std::vector<unsigned char>(fox.begin(), fox.begin() + 5000));
  const auto r = test::runPelage("info " + bad);
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("pelage: error: " + bad));
  EXPECT_THAT(r.output, HasSubstr("truncated"));
}

}  // namespace
}  // namespace pelage::animation
