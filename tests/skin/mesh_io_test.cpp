#include "pelage/skin/mesh_io.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <sstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "pelage/skin/deform.h"
#include "pelage/util/error.h"
#include "support/files.h"
#include "support/models.h"

namespace pelage::skin {
namespace {

using ::testing::HasSubstr;

std::string errorOf(const std::string& path) {
  try {
    readStaticMesh(path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(MeshIO, WrittenSkinReadsBackThroughOpenMesh) {
  const SkinMesh& s = test::defaultMonkey().skin;
  DeformedSkin rest;
  restSkin(s, rest);
  test::TempDir dir;
  for (const char* name : {"skin.obj", "skin.ply"}) {
    const std::string path = dir.file(name);
    writeSkin(path, s, rest.positions, rest.normals);
    const SkinMesh back = readStaticMesh(path, 0.01f);
    EXPECT_EQ(back.numVertices(), s.numVertices()) << name;
    ASSERT_EQ(back.numTriangles(), s.numTriangles()) << name;
    EXPECT_EQ(back.triangles, s.triangles) << name;
    for (int v = 0; v < s.numVertices(); v += 97)
      EXPECT_TRUE(Eigen::Map<const Eigen::Vector3f>(back.restPositions() + 3 * v)
                      .isApprox(rest.positions[static_cast<std::size_t>(v)], 1e-6f));
    EXPECT_NEAR(back.restArea, s.restArea, 1e-6 * s.restArea);
    EXPECT_FLOAT_EQ(back.furLengths()[0], 0.01f);
  }
}

TEST(MeshIO, AnObjHoldsTheSkinsTextureCoordinatesPerCorner) {
  SkinMesh s = test::defaultMonkey().skin;
  const std::size_t nT = static_cast<std::size_t>(s.numTriangles());
  s.cornerUv.resize(3 * nT);
  for (std::size_t c = 0; c < 3 * nT; ++c)  // distinct, exactly representable in 7 digits
    s.cornerUv[c] =
        Eigen::Vector2f(static_cast<float>(c % 1000) / 1000.0f, static_cast<float>(c % 7) / 8.0f);
  DeformedSkin rest;
  restSkin(s, rest);
  test::TempDir dir;
  const std::string path = dir.file("template.obj");
  writeSkin(path, s, rest.positions, rest.normals);
  std::istringstream in(test::readText(path));
  std::string line;
  std::size_t vt = 0, faces = 0;
  while (std::getline(in, line)) {
    std::istringstream words(line);
    std::string tag;
    words >> tag;
    if (tag == "vt") {
      float u = 0, v = 0;
      words >> u >> v;
      ASSERT_LT(vt, 3 * nT);
      EXPECT_FLOAT_EQ(u, s.cornerUv[vt].x()) << vt;
      EXPECT_FLOAT_EQ(v, 1.0f - s.cornerUv[vt].y()) << vt;  // OBJ's v runs up
      ++vt;
    } else if (tag == "f") {
      for (std::size_t k = 0; k < 3; ++k) {
        std::string corner;
        words >> corner;
        const std::size_t c = 3 * faces + k;
        const std::string v = std::to_string(s.triangles[c] + 1);
        EXPECT_EQ(corner, v + "/" + std::to_string(c + 1) + "/" + v);
      }
      ++faces;
    }
  }
  EXPECT_EQ(vt, 3 * nT);
  EXPECT_EQ(faces, nT);
  // pelage reads its own template back: the same triangles.
  EXPECT_EQ(readStaticMesh(path, 0.01f).triangles, s.triangles);
}

TEST(MeshIO, BadFilesAreRejectedWithTheirName) {
  test::TempDir dir;
  EXPECT_THAT(errorOf(dir.file("missing.obj")), HasSubstr("missing.obj: mesh file does not exist"));
  test::writeText(dir.file("empty.ply"), "");
  EXPECT_THAT(errorOf(dir.file("empty.ply")), HasSubstr("empty.ply: file is empty"));
  test::writeText(dir.file("garbage.ply"), "this is not a ply file\n\x01\x02");
  EXPECT_THAT(errorOf(dir.file("garbage.ply")), HasSubstr("garbage.ply"));
  test::writeText(dir.file("noface.obj"), "v 0 0 0\nv 1 0 0\n");
  EXPECT_THAT(errorOf(dir.file("noface.obj")), HasSubstr("no faces"));
  {
    // A binary PLY triangle with a NaN coordinate.
    std::string ply =
        "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float "
        "y\n"
        "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float v[9] = {0, 0, nan, 1, 0, 0, 0, 1, 0};
    ply.append(reinterpret_cast<const char*>(v), sizeof(v));
    const unsigned char three = 3;
    const std::int32_t idx[3] = {0, 1, 2};
    ply.append(reinterpret_cast<const char*>(&three), 1);
    ply.append(reinterpret_cast<const char*>(idx), sizeof(idx));
    test::writeText(dir.file("nan.ply"), ply);
    EXPECT_THAT(errorOf(dir.file("nan.ply")),
                HasSubstr("nan.ply: vertex 0 has a non-finite coordinate"));
  }
  test::writeText(dir.file("mesh.xyz"), "1 2 3\n");
  EXPECT_THAT(errorOf(dir.file("mesh.xyz")), HasSubstr("unsupported mesh format '.xyz'"));
}

// Headers that OpenMesh's readers would trust: found by fuzz/fuzz_mesh (a PLY header with no
// end_header made OpenMesh loop forever) or absurd counts that would allocate before reading.
TEST(MeshIO, HeadersAreCheckedBeforeReading) {
  test::TempDir dir;
  const std::string tetPly =
      "element vertex 4\nproperty float x\nproperty float y\nproperty float z\nelement face 4\n"
      "property list uchar int vertex_indices\n";
  const std::string tetBody = "0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
  test::writeText(dir.file("noend.ply"),
                  "ply\nformat ascii 1.0\n" + tetPly + "uuuuuuuuuuend_header\n" + tetBody);
  EXPECT_THAT(errorOf(dir.file("noend.ply")),
              HasSubstr("noend.ply: unknown PLY header keyword 'uuuuuuuuuuend_header'"));
  test::writeText(dir.file("prefix.ply"),
                  "ply\nformat ascii 1.0\nelement vertex 4\nend_headert z\n" + tetPly +
                      "end_header\n" + tetBody);
  EXPECT_THAT(errorOf(dir.file("prefix.ply")),
              HasSubstr("prefix.ply: unknown PLY header keyword 'end_headert'"));
  test::writeText(dir.file("extra.ply"),
                  "ply\nformat ascii 1.0\n" + tetPly + "end_header z\n" + tetBody);
  EXPECT_THAT(errorOf(dir.file("extra.ply")),
              HasSubstr("extra.ply: PLY end_header line has extra text 'z'"));
  test::writeText(
      dir.file("type.ply"),
      "ply\nformat ascii 1.0\nelement vertex 4\nproperty floa x\nend_header\n" + tetBody);
  EXPECT_THAT(errorOf(dir.file("type.ply")),
              HasSubstr("type.ply: PLY property type 'floa' is not a PLY type"));
  test::writeText(dir.file("version.ply"), "ply\nformat ascii EEEE;EEices\nend_header\n0 0 0\n");
  EXPECT_THAT(errorOf(dir.file("version.ply")),
              HasSubstr("version.ply: PLY format line must be 'format ascii 1.0'"));
  test::writeText(
      dir.file("novertex.ply"),
      "ply\nformat ascii 1.0\nelement face 1\nproperty list uchar int v\nend_header\n3 0 1 2\n");
  EXPECT_THAT(errorOf(dir.file("novertex.ply")),
              HasSubstr("novertex.ply: PLY header declares no vertex element"));
  test::writeText(dir.file("keyword.ply"),
                  "ply\nformat ascii 1.0\nbogus 1\n" + tetPly + "end_header\n" + tetBody);
  EXPECT_THAT(errorOf(dir.file("keyword.ply")),
              HasSubstr("keyword.ply: unknown PLY header keyword 'bogus'"));
  test::writeText(dir.file("nohead.ply"), "ply\nformat ascii 1.0\n" + tetPly);
  EXPECT_THAT(errorOf(dir.file("nohead.ply")),
              HasSubstr("nohead.ply: PLY header has no end_header line"));
  test::writeText(dir.file("noformat.ply"), "ply\n" + tetPly + "end_header\n" + tetBody);
  EXPECT_THAT(errorOf(dir.file("noformat.ply")),
              HasSubstr("noformat.ply: PLY header has no format line"));
  test::writeText(dir.file("huge.ply"),
                  "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\n"
                  "property float x\nend_header\n0000");
  EXPECT_THAT(errorOf(dir.file("huge.ply")),
              HasSubstr("huge.ply: PLY element vertex count 4000000000 needs at least"));
  test::writeText(
      dir.file("list.ply"),
      "ply\nformat ascii 1.0\n" + tetPly +
          "end_header\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n99999999 1 2 3\n");
  EXPECT_THAT(errorOf(dir.file("list.ply")),
              HasSubstr("list.ply: PLY element 1 instance 3: list count '99999999' does not fit "
                        "the rest of the file"));
  test::writeText(dir.file("cut.ply"),
                  "ply\nformat ascii 1.0\n" + tetPly +
                      "end_header\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3\n");
  EXPECT_THAT(errorOf(dir.file("cut.ply")),
              HasSubstr("cut.ply: PLY element 1 instance 2 is cut off"));
  test::writeText(dir.file("ok.ply"), "ply\nformat ascii 1.0\ncomment a tetrahedron\n" + tetPly +
                                          "end_header\n" + tetBody);
  EXPECT_EQ(readStaticMesh(dir.file("ok.ply")).numTriangles(), 4);

  test::writeText(dir.file("huge.off"), "OFF\n900000000 1 0\n0 0 0\n");
  EXPECT_THAT(errorOf(dir.file("huge.off")),
              HasSubstr("huge.off: OFF vertex count 900000000 needs at least"));
  test::writeText(dir.file("bad.off"), "OFX\n3 1 0\n");
  EXPECT_THAT(errorOf(dir.file("bad.off")), HasSubstr("bad.off: not an OFF file"));
  test::writeText(dir.file("neg.off"), "OFF\n-3 1 0\n");
  EXPECT_THAT(errorOf(dir.file("neg.off")),
              HasSubstr("neg.off: OFF vertex count '-3' is not a non-negative integer"));
  test::writeText(dir.file("face.off"), "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n685308834 0 1 2\n");
  EXPECT_THAT(errorOf(dir.file("face.off")),
              HasSubstr("face.off:6: face vertex count must be in [3, 3]"));
  test::writeText(dir.file("split.off"), "OFF\n\n4 4 6\n0 0 0\n1  0\n 0\n0 0 0 0\n");
  EXPECT_THAT(errorOf(dir.file("split.off")),
              HasSubstr("split.off:5: vertex coordinate '' is not a number"));
  test::writeText(dir.file("short.off"), "OFF 3 1 0\n0 0 0\n1 0 0\n0 1 0\n");
  EXPECT_THAT(errorOf(dir.file("short.off")),
              HasSubstr("short.off: OFF file ends after 0 of its 1 faces"));
  test::writeText(dir.file("slash.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf /3\n");
  EXPECT_THAT(errorOf(dir.file("slash.obj")),
              HasSubstr("slash.obj:4: face corner '/3' has no valid vertex index"));
  test::writeText(dir.file("range.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n");
  EXPECT_THAT(errorOf(dir.file("range.obj")),
              HasSubstr("range.obj:4: face vertex 4 is out of range [1, 3]"));
  test::writeText(dir.file("coord.obj"), "v 0 0 x\n");
  EXPECT_THAT(errorOf(dir.file("coord.obj")),
              HasSubstr("coord.obj:1: vertex coordinate 'x' is not a number"));
  test::writeText(dir.file("rel.obj"),
                  "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf -3//1 -2//1 -1//1\n");
  EXPECT_EQ(readStaticMesh(dir.file("rel.obj")).numTriangles(), 1);
  test::writeText(dir.file("ok.off"), "OFF\n4 4 6\n" + tetBody);
  EXPECT_EQ(readStaticMesh(dir.file("ok.off")).numTriangles(), 4);

  std::string stl(80, ' ');
  const std::uint32_t claimed = 1000000;
  stl.append(reinterpret_cast<const char*>(&claimed), 4);
  stl.append(50, '\0');
  test::writeText(dir.file("short.stl"), stl);
  EXPECT_THAT(errorOf(dir.file("short.stl")),
              HasSubstr("short.stl: binary STL declares 1000000 triangles (50000084 bytes) but the "
                        "file has 134 bytes"));
}

// The four corners of the tetrahedron used below, and its faces (outward).
constexpr float kTet[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
constexpr int kTetFaces[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};

void expectTetrahedron(const SkinMesh& s, const std::string& what) {
  ASSERT_EQ(s.numVertices(), 4) << what;
  ASSERT_EQ(s.numTriangles(), 4) << what;
  // Volume 1/6 and area 1.5 + sqrt(3)/2 identify the tetrahedron whatever the vertex order.
  EXPECT_NEAR(s.restArea, 1.5 + std::sqrt(3.0) / 2.0, 1e-6) << what;
  double volume = 0.0;
  for (int f = 0; f < 4; ++f) {
    Eigen::Vector3d p[3];
    for (int c = 0; c < 3; ++c)
      p[c] = Eigen::Map<const Eigen::Vector3f>(
                 s.restPositions() +
                 3 * s.triangles[3 * static_cast<std::size_t>(f) + static_cast<std::size_t>(c)])
                 .cast<double>();
    volume += p[0].dot(p[1].cross(p[2])) / 6.0;
  }
  EXPECT_NEAR(volume, 1.0 / 6.0, 1e-7) << what;
}

template <typename T>
void putBig(std::string& out, T v) {  // big-endian bytes of v
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  for (std::size_t k = sizeof(T); k-- > 0;) out.push_back(b[k]);
}

TEST(MeshIO, PlyVariantsReadTheSameTetrahedron) {
  test::TempDir dir;
  // ASCII with extra vertex properties, properties in another order, faces before vertices, a
  // second list on the faces and an unrelated element.
  std::string ascii =
      "ply\r\nformat ascii 1.0\r\nelement face 4\r\nproperty list uchar float texcoord\r\n"
      "property list int uint vertex_index\r\nelement vertex 4\r\nproperty float nx\r\nproperty "
      "double z\r\n"
      "property float y\r\nproperty float x\r\nproperty uchar red\r\nelement edge 1\r\nproperty "
      "int a\r\nend_header\r\n";
  for (const auto& f : kTetFaces) ascii += str("2 0.5 0.25 3 ", f[0], " ", f[1], " ", f[2], "\n");
  for (const auto& v : kTet) ascii += str("1 ", v[2], " ", v[1], " ", v[0], " 255\n");
  ascii += "7\n";
  test::writeText(dir.file("ascii.ply"), ascii);
  expectTetrahedron(readStaticMesh(dir.file("ascii.ply")), "ascii.ply");

  // Big-endian binary with double coordinates, short counts and int16 indices.
  std::string big =
      "ply\nformat binary_big_endian 1.0\nelement vertex 4\nproperty double x\nproperty double y\n"
      "property double z\nelement face 4\nproperty list short int16 vertex_indices\nend_header\n";
  for (const auto& v : kTet)
    for (float c : v) putBig(big, static_cast<double>(c));
  for (const auto& f : kTetFaces) {
    putBig(big, std::int16_t{3});
    for (int i : f) putBig(big, static_cast<std::int16_t>(i));
  }
  test::writeText(dir.file("big.ply"), big);
  expectTetrahedron(readStaticMesh(dir.file("big.ply")), "big.ply");
}

TEST(MeshIO, PlyBodiesAreCheckedValueByValue) {
  test::TempDir dir;
  const std::string head =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float "
      "z\n";
  const std::string tri = "0 0 0\n1 0 0\n0 1 0\n";
  auto ply = [&](const std::string& name, const std::string& rest) {
    test::writeText(dir.file(name), rest);
    return errorOf(dir.file(name));
  };
  EXPECT_THAT(ply("range.ply",
                  head + "element face 1\nproperty list uchar int vertex_indices\nend_header\n" +
                      tri + "3 0 1 3\n"),
              HasSubstr("range.ply: PLY face 0: vertex index 3 is out of range [0, 2]"));
  EXPECT_THAT(
      ply("two.ply", head + "element face 1\nproperty list uchar int vertex_indices\nend_header\n" +
                         tri + "2 0 1\n"),
      HasSubstr("two.ply: PLY face 0 has 2 vertices"));
  EXPECT_THAT(ply("noxyz.ply",
                  "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float "
                  "y\nend_header\n0 0\n"),
              HasSubstr("noxyz.ply: PLY vertex element needs scalar properties x, y and z"));
  EXPECT_THAT(
      ply("nolist.ply", head + "element face 1\nproperty list uchar int corners\nend_header\n" +
                            tri + "3 0 1 2\n"),
      HasSubstr("nolist.ply: PLY face element needs an integer list property vertex_indices"));
  EXPECT_THAT(
      ply("twice.ply", head + "element vertex 1\nproperty float x\nend_header\n" + tri + "0\n"),
      HasSubstr("twice.ply: PLY element 'vertex' is declared twice"));
  EXPECT_THAT(ply("word.ply", head + "end_header\n0 0 0\n1 zero 0\n0 1 0\n"),
              HasSubstr("word.ply: PLY element 0 instance 1: 'zero' is not a number"));
  EXPECT_THAT(ply("float.ply",
                  head + "element face 1\nproperty list uchar int vertex_indices\nend_header\n" +
                      tri + "3 0 1.5 2\n"),
              HasSubstr("float.ply: PLY element 1 instance 0: '1.5' is not an integer"));
  EXPECT_THAT(ply("fcount.ply",
                  head + "element face 1\nproperty list float int vertex_indices\nend_header\n" +
                      tri + "3 0 1 2\n"),
              HasSubstr("fcount.ply: PLY list count type 'float' must be an integer type"));
  // A signed count of -1 (0xff) must not be read as 255 or as 2^32 - 1.
  std::string bin =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list char int vertex_indices\nend_header\n";
  const float v[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  bin.append(reinterpret_cast<const char*>(v), sizeof(v));
  bin.push_back(static_cast<char>(0xff));
  const std::int32_t idx[3] = {0, 1, 2};
  bin.append(reinterpret_cast<const char*>(idx), sizeof(idx));
  EXPECT_THAT(
      ply("neg.ply", bin),
      HasSubstr(
          "neg.ply: PLY element 1 instance 0: list count -1 does not fit the rest of the file"));
}

TEST(MeshIO, StlBinaryAndAsciiWeldCorners) {
  test::TempDir dir;
  // Binary, with a header that starts with "solid" as some exporters write: the size decides.
  std::string bin = "solid but binary";
  bin.resize(80, ' ');
  const std::uint32_t n = 4;
  bin.append(reinterpret_cast<const char*>(&n), 4);
  std::string ascii = "solid tet\n";
  for (const auto& f : kTetFaces) {
    bin.append(12, '\0');  // normal (ignored)
    ascii += "  facet normal 0 0 0\n    outer loop\n";
    for (int i : f) {
      bin.append(reinterpret_cast<const char*>(kTet[i]), 12);
      ascii += str("      vertex ", kTet[i][0], " ", kTet[i][1], " ", kTet[i][2], "\n");
    }
    bin.append(2, '\0');
    ascii += "    endloop\n  endfacet\n";
  }
  ascii += "endsolid tet\n";
  test::writeText(dir.file("bin.stl"), bin);
  expectTetrahedron(readStaticMesh(dir.file("bin.stl")), "bin.stl");
  test::writeText(dir.file("ascii.stl"), ascii);
  expectTetrahedron(readStaticMesh(dir.file("ascii.stl")), "ascii.stl");

  test::writeText(
      dir.file("word.stl"),
      "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertx 0 1 0\n");
  EXPECT_THAT(errorOf(dir.file("word.stl")),
              HasSubstr("word.stl:6: unknown ASCII STL keyword 'vertx'"));
  test::writeText(dir.file("two.stl"),
                  "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\n");
  EXPECT_THAT(errorOf(dir.file("two.stl")),
              HasSubstr("two.stl:6: a facet needs at least 3 vertices, it has 2"));
  test::writeText(dir.file("nan.stl"), "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 nan\n");
  EXPECT_THAT(errorOf(dir.file("nan.stl")),
              HasSubstr("nan.stl:4: vertex has a non-finite coordinate"));
}

TEST(MeshIO, QuadsAreTriangulated) {
  test::TempDir dir;
  test::writeText(dir.file("quad.obj"), "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n");
  const SkinMesh s = readStaticMesh(dir.file("quad.obj"));
  EXPECT_EQ(s.numTriangles(), 2);
  EXPECT_NEAR(s.restArea, 1.0, 1e-6);
}

}  // namespace
}  // namespace pelage::skin
