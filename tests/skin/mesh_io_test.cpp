#include "pelage/skin/mesh_io.h"

#include <limits>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "monkey_fixture.h"
#include "pelage/skin/deform.h"
#include "pelage/util/error.h"
#include "test_support.h"

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
        "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
        "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float v[9] = {0, 0, nan, 1, 0, 0, 0, 1, 0};
    ply.append(reinterpret_cast<const char*>(v), sizeof(v));
    const unsigned char three = 3;
    const std::int32_t idx[3] = {0, 1, 2};
    ply.append(reinterpret_cast<const char*>(&three), 1);
    ply.append(reinterpret_cast<const char*>(idx), sizeof(idx));
    test::writeText(dir.file("nan.ply"), ply);
    EXPECT_THAT(errorOf(dir.file("nan.ply")), HasSubstr("nan.ply: vertex 0 has a non-finite coordinate"));
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
  test::writeText(dir.file("noend.ply"), "ply\nformat ascii 1.0\n" + tetPly + "uuuuuuuuuuend_header\n" + tetBody);
  EXPECT_THAT(errorOf(dir.file("noend.ply")), HasSubstr("noend.ply: unknown PLY header keyword 'uuuuuuuuuuend_header'"));
  test::writeText(dir.file("prefix.ply"), "ply\nformat ascii 1.0\nelement vertex 4\nend_headert z\n" + tetPly + "end_header\n" + tetBody);
  EXPECT_THAT(errorOf(dir.file("prefix.ply")), HasSubstr("prefix.ply: unknown PLY header keyword 'end_headert'"));
  test::writeText(dir.file("extra.ply"), "ply\nformat ascii 1.0\n" + tetPly + "end_header z\n" + tetBody);
  EXPECT_THAT(errorOf(dir.file("extra.ply")), HasSubstr("extra.ply: PLY end_header line has extra text 'z'"));
  test::writeText(dir.file("type.ply"), "ply\nformat ascii 1.0\nelement vertex 4\nproperty floa x\nend_header\n" + tetBody);
  EXPECT_THAT(errorOf(dir.file("type.ply")), HasSubstr("type.ply: PLY property type 'floa' is not a PLY type"));
  test::writeText(dir.file("version.ply"), "ply\nformat ascii EEEE;EEices\nend_header\n0 0 0\n");
  EXPECT_THAT(errorOf(dir.file("version.ply")), HasSubstr("version.ply: PLY format line must be 'format ascii 1.0'"));
  test::writeText(dir.file("novertex.ply"), "ply\nformat ascii 1.0\nelement face 1\nproperty list uchar int v\nend_header\n3 0 1 2\n");
  EXPECT_THAT(errorOf(dir.file("novertex.ply")), HasSubstr("novertex.ply: PLY header declares no vertex element"));
  test::writeText(dir.file("keyword.ply"), "ply\nformat ascii 1.0\nbogus 1\n" + tetPly + "end_header\n" + tetBody);
  EXPECT_THAT(errorOf(dir.file("keyword.ply")), HasSubstr("keyword.ply: unknown PLY header keyword 'bogus'"));
  test::writeText(dir.file("nohead.ply"), "ply\nformat ascii 1.0\n" + tetPly);
  EXPECT_THAT(errorOf(dir.file("nohead.ply")), HasSubstr("nohead.ply: PLY header has no end_header line"));
  test::writeText(dir.file("noformat.ply"), "ply\n" + tetPly + "end_header\n" + tetBody);
  EXPECT_THAT(errorOf(dir.file("noformat.ply")), HasSubstr("noformat.ply: PLY header has no format line"));
  test::writeText(dir.file("huge.ply"), "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\n"
                                        "property float x\nend_header\n0000");
  EXPECT_THAT(errorOf(dir.file("huge.ply")), HasSubstr("huge.ply: PLY element vertex count 4000000000 needs at least"));
  test::writeText(dir.file("list.ply"), "ply\nformat ascii 1.0\n" + tetPly + "end_header\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n99999999 1 2 3\n");
  EXPECT_THAT(errorOf(dir.file("list.ply")), HasSubstr("list.ply: PLY element 1 instance 3: list count '99999999' does not fit the rest of the file"));
  test::writeText(dir.file("cut.ply"), "ply\nformat ascii 1.0\n" + tetPly + "end_header\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3\n");
  EXPECT_THAT(errorOf(dir.file("cut.ply")), HasSubstr("cut.ply: PLY element 1 instance 2 is cut off"));
  test::writeText(dir.file("ok.ply"), "ply\nformat ascii 1.0\ncomment a tetrahedron\n" + tetPly + "end_header\n" + tetBody);
  EXPECT_EQ(readStaticMesh(dir.file("ok.ply")).numTriangles(), 4);

  test::writeText(dir.file("huge.off"), "OFF\n900000000 1 0\n0 0 0\n");
  EXPECT_THAT(errorOf(dir.file("huge.off")), HasSubstr("huge.off: OFF vertex count 900000000 needs at least"));
  test::writeText(dir.file("bad.off"), "OFX\n3 1 0\n");
  EXPECT_THAT(errorOf(dir.file("bad.off")), HasSubstr("bad.off: not an OFF file"));
  test::writeText(dir.file("neg.off"), "OFF\n-3 1 0\n");
  EXPECT_THAT(errorOf(dir.file("neg.off")), HasSubstr("neg.off: OFF vertex count '-3' is not a non-negative integer"));
  test::writeText(dir.file("face.off"), "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n685308834 0 1 2\n");
  EXPECT_THAT(errorOf(dir.file("face.off")), HasSubstr("face.off:6: face vertex count must be in [3, 3]"));
  test::writeText(dir.file("split.off"), "OFF\n\n4 4 6\n0 0 0\n1  0\n 0\n0 0 0 0\n");
  EXPECT_THAT(errorOf(dir.file("split.off")), HasSubstr("split.off:5: vertex coordinate '' is not a number"));
  test::writeText(dir.file("short.off"), "OFF 3 1 0\n0 0 0\n1 0 0\n0 1 0\n");
  EXPECT_THAT(errorOf(dir.file("short.off")), HasSubstr("short.off: OFF file ends after 0 of its 1 faces"));
  test::writeText(dir.file("slash.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf /3\n");
  EXPECT_THAT(errorOf(dir.file("slash.obj")), HasSubstr("slash.obj:4: face corner '/3' has no valid vertex index"));
  test::writeText(dir.file("range.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n");
  EXPECT_THAT(errorOf(dir.file("range.obj")), HasSubstr("range.obj:4: face vertex 4 is out of range [1, 3]"));
  test::writeText(dir.file("coord.obj"), "v 0 0 x\n");
  EXPECT_THAT(errorOf(dir.file("coord.obj")), HasSubstr("coord.obj:1: vertex coordinate 'x' is not a number"));
  test::writeText(dir.file("rel.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf -3//1 -2//1 -1//1\n");
  EXPECT_EQ(readStaticMesh(dir.file("rel.obj")).numTriangles(), 1);
  test::writeText(dir.file("ok.off"), "OFF\n4 4 6\n" + tetBody);
  EXPECT_EQ(readStaticMesh(dir.file("ok.off")).numTriangles(), 4);

  std::string stl(80, ' ');
  const std::uint32_t claimed = 1000000;
  stl.append(reinterpret_cast<const char*>(&claimed), 4);
  stl.append(50, '\0');
  test::writeText(dir.file("short.stl"), stl);
  EXPECT_THAT(errorOf(dir.file("short.stl")), HasSubstr("short.stl: binary STL declares 1000000 triangles (50000084 bytes) but the file has 134 bytes"));
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
