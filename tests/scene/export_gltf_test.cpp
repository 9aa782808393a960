// glTF binary export re-read with tinygltf: the posed skin mesh and one LINES primitive per coat,
// with the frame's exact positions, consecutive index pairs, bounds and coat colours.
#include "pelage/scene/export_gltf.h"

#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <cstring>
#include <filesystem>

#include "pelage/fur/colors.h"
#include "pelage/util/error.h"
#include "support/exports.h"
#include "support/files.h"

namespace pelage::test {
namespace {

tinygltf::Model load(const std::string& path) {
  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string err, warn;
  const bool ok = loader.LoadBinaryFromFile(&model, &err, &warn, path);
  EXPECT_TRUE(ok) << err;
  EXPECT_EQ(err, "");
  return model;
}

// The accessor's data as `T`s (tightly packed views only, as pelage writes them).
template <class T>
std::vector<T> read(const tinygltf::Model& m, int accessor) {
  const tinygltf::Accessor& a = m.accessors[static_cast<std::size_t>(accessor)];
  const tinygltf::BufferView& v = m.bufferViews[static_cast<std::size_t>(a.bufferView)];
  const std::size_t comps = a.type == TINYGLTF_TYPE_VEC3 ? 3 : 1;
  std::vector<T> out(a.count * comps);
  EXPECT_EQ(v.byteLength, out.size() * sizeof(T));
  std::memcpy(
      out.data(),
      m.buffers[static_cast<std::size_t>(v.buffer)].data.data() + v.byteOffset + a.byteOffset,
      out.size() * sizeof(T));
  return out;
}

const tinygltf::Mesh* meshNamed(const tinygltf::Model& m, const std::string& name) {
  for (const tinygltf::Mesh& mesh : m.meshes)
    if (mesh.name == name) return &mesh;
  return nullptr;
}

void checkFrame(fur::HairStyle style) {
  const scene::Fur fur = exportFur(style, 1500.0);
  scene::FrameState state;
  exportFrame(fur, 2, state);
  TempDir dir;
  const std::string path = dir.file("frame.glb");
  const scene::GlbCounts n = scene::writeFrameGlb(path, sceneCritter(), fur, state, "pelage test");
  EXPECT_EQ(n.bytes, std::filesystem::file_size(path));
  const tinygltf::Model g = load(path);
  EXPECT_EQ(g.asset.version, "2.0");
  EXPECT_EQ(g.asset.generator, "pelage test");
  ASSERT_EQ(g.scenes.size(), 1u);
  EXPECT_EQ(g.scenes[0].nodes.size(), 3u);

  const scene::Model& m = sceneCritter();
  const tinygltf::Mesh* skin = meshNamed(g, "skin");
  ASSERT_NE(skin, nullptr);
  ASSERT_EQ(skin->primitives.size(), 1u);
  const tinygltf::Primitive& sp = skin->primitives[0];
  EXPECT_EQ(sp.mode, TINYGLTF_MODE_TRIANGLES);
  const std::vector<float> pos = read<float>(g, sp.attributes.at("POSITION"));
  ASSERT_EQ(pos.size(), static_cast<std::size_t>(m.skin.numVertices()) * 3);
  // glTF axes: +Y up; pelage's (x, y, z) is (y, z, x) there, exactly.
  for (std::size_t v = 0; v < pos.size() / 3; ++v) {
    ASSERT_EQ(pos[3 * v], state.skin.positions[v].y());
    ASSERT_EQ(pos[3 * v + 1], state.skin.positions[v].z());
    ASSERT_EQ(pos[3 * v + 2], state.skin.positions[v].x());
  }
  EXPECT_EQ(read<float>(g, sp.attributes.at("NORMAL")).size(), pos.size());
  const std::vector<std::uint32_t> tri = read<std::uint32_t>(g, sp.indices);
  ASSERT_EQ(tri.size(), m.skin.triangles.size());
  for (std::size_t i = 0; i < tri.size(); ++i)
    ASSERT_EQ(tri[i], static_cast<std::uint32_t>(m.skin.triangles[i]));

  for (int c = 0; c < 2; ++c) {
    const tinygltf::Mesh* coat = meshNamed(g, c == 0 ? "overcoat" : "undercoat");
    ASSERT_NE(coat, nullptr);
    ASSERT_EQ(coat->primitives.size(), 1u);
    const tinygltf::Primitive& p = coat->primitives[0];
    EXPECT_EQ(p.mode, TINYGLTF_MODE_LINE);
    const fur::HairBuffers& b = state.fur.coats[static_cast<std::size_t>(c)];
    const fur::CoatParams& cp = fur.params.coats[static_cast<std::size_t>(c)];
    const int K = style == fur::HairStyle::Tube ? cp.curvePoints : b.layout.pointsPerHair();
    const int M = style == fur::HairStyle::Tube ? cp.tubeSides : 1;
    const std::vector<float> hp = read<float>(g, p.attributes.at("POSITION"));
    ASSERT_EQ(static_cast<std::int64_t>(hp.size()), b.drawn * K * 3);
    EXPECT_EQ(n.hairs[static_cast<std::size_t>(c)], b.drawn);
    // Positions: the hair points (tubes: the mean of each ring).
    for (std::int64_t h = 0; h < b.drawn; h += 7)
      for (int k = 0; k < K; ++k)
        for (int a = 0; a < 3; ++a) {
          float expect = 0.0f;
          for (int j = 0; j < M; ++j) expect += b.positions.data()[((h * K + k) * M + j) * 3 + a];
          expect /= static_cast<float>(M);
          // Written in glTF axes: component a of pelage lands at (a + 2) % 3.
          ASSERT_NEAR(hp[static_cast<std::size_t>((h * K + k) * 3 + (a + 2) % 3)], expect, 1e-7f);
        }
    // Bounds contain every point.
    const tinygltf::Accessor& acc =
        g.accessors[static_cast<std::size_t>(p.attributes.at("POSITION"))];
    ASSERT_EQ(acc.minValues.size(), 3u);
    for (std::size_t i = 0; i < hp.size(); ++i) {
      ASSERT_GE(hp[i], acc.minValues[i % 3]);
      ASSERT_LE(hp[i], acc.maxValues[i % 3]);
    }
    // Segments join consecutive points of one hair.
    const std::vector<std::uint32_t> idx = read<std::uint32_t>(g, p.indices);
    ASSERT_EQ(static_cast<std::int64_t>(idx.size()), b.drawn * (K - 1) * 2);
    for (std::size_t s = 0; s < idx.size(); s += 2) {
      ASSERT_EQ(idx[s + 1], idx[s] + 1);
      ASSERT_NE(idx[s + 1] % static_cast<std::uint32_t>(K), 0u);
    }
    // Colours: COLOR_0, normalized RGBA8, linear: each hair's root colour at its first point and
    // tip colour at its last; the material is white so they show unchanged.
    const tinygltf::Material& mat = g.materials[static_cast<std::size_t>(p.material)];
    EXPECT_EQ(mat.pbrMetallicRoughness.baseColorFactor, (std::vector<double>{1.0, 1.0, 1.0, 1.0}));
    const tinygltf::Accessor& ca =
        g.accessors[static_cast<std::size_t>(p.attributes.at("COLOR_0"))];
    ASSERT_EQ(ca.componentType, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE);
    ASSERT_EQ(ca.type, TINYGLTF_TYPE_VEC4);
    ASSERT_TRUE(ca.normalized);
    ASSERT_EQ(static_cast<std::int64_t>(ca.count), b.drawn * K);
    const tinygltf::BufferView& cv = g.bufferViews[static_cast<std::size_t>(ca.bufferView)];
    const unsigned char* rgba = g.buffers[0].data.data() + cv.byteOffset + ca.byteOffset;
    const fur::CoatColors& cc = fur.colors.coats[static_cast<std::size_t>(c)];
    for (std::int64_t h = 0; h < b.drawn; h += 5)
      for (const int k : {0, K - 1}) {
        const Eigen::Vector3f want =
            cc.perHair ? fur::unpackSrgb8(b.colors[static_cast<std::size_t>(2 * h + (k > 0))])
                       : cc.diffuse;
        for (int j = 0; j < 3; ++j)
          ASSERT_EQ(rgba[(h * K + k) * 4 + j], std::lround(want[j] * 255.0f)) << h << " " << k;
        ASSERT_EQ(rgba[(h * K + k) * 4 + 3], 255);
      }
    // Widths: _WIDTH, one float per point, the coat's width tapering linearly from the root's to
    // the tip's (tubes: the diameter), in metres.
    const std::vector<float> widths = read<float>(g, p.attributes.at("_WIDTH"));
    ASSERT_EQ(static_cast<std::int64_t>(widths.size()), b.drawn * K);
    for (std::int64_t h = 0; h < b.drawn; ++h)
      for (int k = 0; k < K; ++k)
        ASSERT_NEAR(
            widths[static_cast<std::size_t>(h * K + k)],
            1e-3f * (cp.width.rootMm + (cp.width.tipMm - cp.width.rootMm) * static_cast<float>(k) /
                                           static_cast<float>(K - 1)),
            1e-9f);  // a nanometre: float rounding of the interpolation
  }
}

TEST(ExportGltf, PolylineFrameReadsBackWithTinygltf) {
  checkFrame(fur::HairStyle::Polyline);
}
TEST(ExportGltf, LineFrameReadsBack) {
  checkFrame(fur::HairStyle::Line);
}
TEST(ExportGltf, CurveFrameReadsBack) {
  checkFrame(fur::HairStyle::Curve);
}
TEST(ExportGltf, TubeFrameIsRingCentreLines) {
  checkFrame(fur::HairStyle::Tube);
}

TEST(ExportGltf, UnwritableDirectoryNamesTheFile) {
  const scene::Fur fur = exportFur(fur::HairStyle::Line, 200.0);
  scene::FrameState state;
  exportFrame(fur, 0, state);
  try {
    scene::writeFrameGlb("/nonexistent-dir/f.glb", sceneCritter(), fur, state);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent-dir/f.glb"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace pelage::test
