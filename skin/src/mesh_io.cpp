#include "pelage/skin/mesh_io.h"

#include "mesh_read.h"

#include <OpenMesh/Core/System/omstream.hh>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <string_view>

#include "pelage/util/atomic_file.h"
#include "pelage/util/error.h"
#include "pelage/util/log.h"
#include "pelage/util/path.h"

namespace pelage::skin {

namespace detail {

// Reads the whole file.
std::string readAll(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) inputError(path, ": cannot open the mesh file for reading");
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// A count from a header must be a plain non-negative integer that the file can hold: each element
// needs at least `minBytes` bytes of the file, so a header claiming billions of elements in a small
// file is refused before anything is allocated for them.
long long headerCount(const std::string& path, const std::string& what, const std::string& token,
                      std::uintmax_t fileSize, double minBytes) {
  long long n = -1;
  const auto r = std::from_chars(token.data(), token.data() + token.size(), n);
  if (r.ec != std::errc() || r.ptr != token.data() + token.size() || n < 0)
    inputError(path, ": ", what, " '", token, "' is not a non-negative integer");
  if (static_cast<double>(n) * minBytes > static_cast<double>(fileSize))
    inputError(path, ": ", what, " ", n, " needs at least ", static_cast<double>(n) * minBytes,
               " bytes but the file has ", fileSize, " (truncated or malformed)");
  return n;
}

// Adds a polygon as a triangle fan; triangles with a repeated vertex or that would make the mesh
// non-manifold are counted in `skipped` instead.
void addPolygon(TriMesh& mesh, const std::vector<TriMesh::VertexHandle>& face, long long& skipped) {
  for (std::size_t k = 1; k + 1 < face.size(); ++k) {
    if (face[0] == face[k] || face[k] == face[k + 1] || face[0] == face[k + 1] ||
        !mesh.add_face(face[0], face[k], face[k + 1]).is_valid())
      ++skipped;
  }
}

void warnSkipped(const std::string& path, long long skipped) {
  if (skipped)
    warn(str(path, ": skipped ", skipped, " triangles (repeated vertices or non-manifold edges)"));
}

// Reads the next three words of line `lineNo` as the coordinates of a vertex (OBJ, OFF, ASCII STL).
void readCoordinates(const std::string& path, long long lineNo, std::istringstream& words,
                     float* xyz) {
  for (int k = 0; k < 3; ++k) {
    std::string t;
    words >> t;
    const auto r = std::from_chars(t.data(), t.data() + t.size(), xyz[k]);
    if (t.empty() || r.ec != std::errc() || r.ptr != t.data() + t.size())
      inputError(path, ":", lineNo, ": vertex coordinate '", t.substr(0, 40), "' is not a number");
  }
}
}  // namespace detail

namespace {

using detail::addPolygon;
using detail::headerCount;
using detail::readAll;
using detail::readCoordinates;
using detail::readPly;
using detail::warnSkipped;

// Appends a float in shortest round-trip form.
void appendFloat(std::string& out, float v) {
  char buf[32];
  auto r = std::to_chars(buf, buf + sizeof(buf), v);
  out.append(buf, r.ptr);
}

// STL, read here rather than by OpenMesh so that every format is read by code that checks what it
// reads. A file whose size is exactly 84 + 50 n for the triangle count n at byte 80 is binary;
// otherwise it must be ASCII ("solid ...", "vertex x y z" lines, each "endloop" closing a polygon).
// Corners at bit-identical positions are welded into one vertex (STL stores none shared).
void readStl(const std::string& path, TriMesh& mesh) {
  const std::string bytes = readAll(path);
  std::map<std::array<float, 3>, TriMesh::VertexHandle> welded;
  std::vector<TriMesh::VertexHandle> face;
  long long skipped = 0;
  auto corner = [&](const std::array<float, 3>& p, const std::string& where) {
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
      inputError(path, where, ": vertex has a non-finite coordinate");
    auto [it, inserted] = welded.try_emplace(p);
    if (inserted) it->second = mesh.add_vertex(TriMesh::Point(p[0], p[1], p[2]));
    face.push_back(it->second);
  };
  std::uint32_t n = 0;
  if (bytes.size() >= 84) std::memcpy(&n, bytes.data() + 80, 4);
  const std::uintmax_t expected = 84 + 50 * static_cast<std::uintmax_t>(n);
  if (bytes.size() >= 84 && expected == bytes.size()) {
    for (std::uint32_t t = 0; t < n; ++t) {
      face.clear();
      for (int c = 0; c < 3; ++c) {
        std::array<float, 3> p;
        std::memcpy(p.data(),
                    bytes.data() + 84 + 50 * static_cast<std::size_t>(t) + 12 +
                        12 * static_cast<std::size_t>(c),
                    12);
        corner(p, str(" triangle ", t));
      }
      addPolygon(mesh, face, skipped);
    }
    warnSkipped(path, skipped);
    return;
  }
  if (bytes.rfind("solid", 0) != 0) {
    if (bytes.size() < 84) inputError(path, ": binary STL shorter than its 84-byte header");
    inputError(path, ": binary STL declares ", n, " triangles (", expected,
               " bytes) but the file has ", bytes.size(), " bytes");
  }
  std::istringstream in(bytes);
  std::string line;
  long long lineNo = 0;
  while (std::getline(in, line)) {
    ++lineNo;
    std::istringstream words(line);
    std::string key;
    words >> key;
    if (key == "vertex") {
      std::array<float, 3> p;
      readCoordinates(path, lineNo, words, p.data());
      corner(p, str(":", lineNo));
    } else if (key == "endloop") {
      if (face.size() < 3)
        inputError(path, ":", lineNo, ": a facet needs at least 3 vertices, it has ", face.size());
      addPolygon(mesh, face, skipped);
      face.clear();
    } else if (key == "outer" || key == "facet") {
      face.clear();
    } else if (!key.empty() && key != "solid" && key != "endfacet" && key != "endsolid") {
      inputError(path, ":", lineNo, ": unknown ASCII STL keyword '", key.substr(0, 40),
                 "' (expected solid, facet, outer loop, vertex, endloop, endfacet, endsolid)");
    }
  }
  warnSkipped(path, skipped);
}

// Wavefront OBJ, read here rather than by OpenMesh, whose OBJ reader aborts on an assertion for a
// face with no valid vertex ("f /3", found by fuzz_mesh). Reads "v x y z" and "f" lines (indices
// i, i/t, i//n, i/t/n, negative = relative to the end); polygons become triangle fans; faces that
// would make the mesh non-manifold are skipped with a warning. Other statements are ignored.
void readObj(const std::string& path, TriMesh& mesh) {
  std::ifstream in(path, std::ios::binary);
  if (!in) inputError(path, ": cannot open the mesh file for reading");
  std::vector<TriMesh::VertexHandle> vertices;
  std::vector<TriMesh::VertexHandle> face;
  std::string line;
  long long lineNo = 0, skipped = 0;
  while (std::getline(in, line)) {
    ++lineNo;
    std::istringstream words(line);
    std::string key;
    words >> key;
    if (key == "v") {
      TriMesh::Point p;
      readCoordinates(path, lineNo, words, p.data());
      vertices.push_back(mesh.add_vertex(p));
    } else if (key == "f") {
      face.clear();
      std::string corner;
      while (words >> corner) {
        const std::string first = corner.substr(0, corner.find('/'));
        long long idx = 0;
        const auto r = std::from_chars(first.data(), first.data() + first.size(), idx);
        if (first.empty() || r.ec != std::errc() || r.ptr != first.data() + first.size() ||
            idx == 0)
          inputError(path, ":", lineNo, ": face corner '", corner.substr(0, 40),
                     "' has no valid vertex index");
        const long long n = static_cast<long long>(vertices.size());
        const long long i = idx > 0 ? idx - 1 : n + idx;
        if (i < 0 || i >= n)
          inputError(path, ":", lineNo, ": face vertex ", idx, " is out of range [1, ", n,
                     "] (or [-", n, ", -1])");
        face.push_back(vertices[static_cast<std::size_t>(i)]);
      }
      if (face.size() < 3) inputError(path, ":", lineNo, ": a face needs at least 3 vertices");
      addPolygon(mesh, face, skipped);
    }
  }
  warnSkipped(path, skipped);
}

// OFF (and NOFF/COFF/CNOFF/STOFF), read here rather than by OpenMesh, which reserves whatever
// vertex count a face claims (found by fuzz_mesh: 685,308,834 in an 82-byte file; 2^30 after a
// split vertex line). Line based: after the counts, one vertex per line ("x y z" then optional
// normal/colour/ texture values), one face per line ("k i0 .. ik-1" then an optional colour); '#'
// comments and blank lines are skipped. Polygons become triangle fans; non-manifold faces are
// skipped with a warning.
void readOff(const std::string& path, TriMesh& mesh, std::uintmax_t fileSize) {
  std::ifstream in(path, std::ios::binary);
  if (!in) inputError(path, ": cannot open the mesh file for reading");
  std::string line;
  long long lineNo = 0;
  auto nextLine = [&](std::istringstream& words) {
    while (std::getline(in, line)) {
      ++lineNo;
      const std::size_t hash = line.find('#');
      if (hash != std::string::npos) line.resize(hash);
      if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
      words.clear();
      words.str(line);
      return true;
    }
    return false;
  };
  std::istringstream words;
  std::string magic, nv, nf;
  if (!nextLine(words)) inputError(path, ": file is empty");
  words >> magic >> nv;  // counts may follow the magic on its line
  if (magic != "OFF" && magic != "NOFF" && magic != "COFF" && magic != "CNOFF" && magic != "STOFF")
    inputError(path, ": not an OFF file (it must start with OFF, NOFF, COFF, CNOFF or STOFF)");
  if (nv.empty()) {
    if (!nextLine(words)) inputError(path, ": OFF file ends before its counts");
    words >> nv;
  }
  words >> nf;
  const long long nVertices = headerCount(path, "OFF vertex count", nv, fileSize, 6.0);
  const long long nFaces = headerCount(path, "OFF face count", nf, fileSize, 2.0);
  std::vector<TriMesh::VertexHandle> vertices;
  vertices.reserve(static_cast<std::size_t>(nVertices));
  for (long long v = 0; v < nVertices; ++v) {
    if (!nextLine(words))
      inputError(path, ": OFF file ends after ", v, " of its ", nVertices, " vertices");
    TriMesh::Point p;
    readCoordinates(path, lineNo, words, p.data());
    vertices.push_back(mesh.add_vertex(p));
  }
  long long skipped = 0;
  std::vector<TriMesh::VertexHandle> face;
  for (long long f = 0; f < nFaces; ++f) {
    if (!nextLine(words))
      inputError(path, ": OFF file ends after ", f, " of its ", nFaces, " faces");
    long long k = -1;
    if (!(words >> k) || k < 3 || k > nVertices)
      inputError(path, ":", lineNo, ": face vertex count must be in [3, ", nVertices, "]");
    face.clear();
    for (long long c = 0; c < k; ++c) {
      long long i = -1;
      if (!(words >> i) || i < 0 || i >= nVertices)
        inputError(path, ":", lineNo, ": face vertex index must be in [0, ", nVertices - 1, "]");
      face.push_back(vertices[static_cast<std::size_t>(i)]);
    }
    addPolygon(mesh, face, skipped);
  }
  warnSkipped(path, skipped);
}

}  // namespace

SkinMesh readStaticMesh(const std::string& path, float furLengthMeters, float unitScale) {
  namespace fs = std::filesystem;
  std::error_code ec;
  requireExistingFile(path, "mesh file");
  if (!fs::is_regular_file(path, ec)) inputError(path, ": not a regular file");
  const std::string ext = lowerExtension(path);
  if (ext != ".obj" && ext != ".ply" && ext != ".off" && ext != ".stl")
    inputError(path, ": unsupported mesh format '", ext, "' (accepted: .obj .ply .off .stl)");
  const std::uintmax_t fileSize = fs::file_size(path, ec);
  if (ec) inputError(path, ": cannot read the file size (", ec.message(), ")");
  if (fileSize == 0) inputError(path, ": file is empty");

  SkinMesh skin;
  // Our warnings name the file and count the skipped faces; OpenMesh's add_face would print
  // "complex edge" to stderr for each one.
  omerr().disable();
  if (ext == ".obj")
    readObj(path, skin.mesh);
  else if (ext == ".off")
    readOff(path, skin.mesh, fileSize);
  else if (ext == ".ply")
    readPly(path, skin.mesh);
  else
    readStl(path, skin.mesh);
  TriMesh& m = skin.mesh;
  if (m.n_faces() == 0) inputError(path, ": the mesh has no faces");
  for (auto v : m.vertices()) {
    const auto& p = m.point(v);
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
      inputError(path, ": vertex ", v.idx(), " has a non-finite coordinate");
  }
  // Drop vertices no face uses (they carry no fur and would confuse bounds).
  std::size_t isolated = 0;
  for (auto v : m.vertices())
    if (m.is_isolated(v)) {
      m.delete_vertex(v, false);
      ++isolated;
    }
  if (isolated) {
    m.garbage_collection();
    warn(str(path, ": removed ", isolated, " isolated vertices"));
  }
  if (unitScale != 1.0f)
    for (auto v : m.vertices()) m.point(v) *= unitScale;
  addSkinProperties(skin);
  Eigen::Map<const Eigen::Matrix<float, 3, Eigen::Dynamic>> P(
      skin.restPositions(), 3, static_cast<Eigen::Index>(m.n_vertices()));
  const float diag = (P.rowwise().maxCoeff() - P.rowwise().minCoeff()).norm();
  const float len = furLengthMeters > 0.0f ? furLengthMeters : 0.02f * diag;
  for (auto v : m.vertices()) m.property(skin.furLength, v) = len;
  finalizeSkin(skin);
  return skin;
}

void writeSkin(const std::string& path, const SkinMesh& skin,
               const std::vector<Eigen::Vector3f>& positions,
               const std::vector<Eigen::Vector3f>& normals) {
  const std::string ext = lowerExtension(path);
  const std::size_t nV = static_cast<std::size_t>(skin.numVertices());
  const std::size_t nT = static_cast<std::size_t>(skin.numTriangles());
  PELAGE_CHECK(positions.size() == nV && normals.size() == nV);
  if (ext == ".obj") {
    AtomicFileWriter w(path);
    std::string buf;
    buf.reserve(1 << 20);
    buf += "# pelage skin: " + std::to_string(nV) + " vertices, " + std::to_string(nT) +
           " triangles\n";
    auto flush = [&] {
      if (buf.size() > (1u << 20) - 256) {
        w.write(buf);
        buf.clear();
      }
    };
    for (std::size_t i = 0; i < nV; ++i) {
      buf += "v ";
      for (int k = 0; k < 3; ++k) {
        appendFloat(buf, positions[i][k]);
        buf += k < 2 ? ' ' : '\n';
      }
      flush();
    }
    for (std::size_t i = 0; i < nV; ++i) {
      buf += "vn ";
      for (int k = 0; k < 3; ++k) {
        appendFloat(buf, normals[i][k]);
        buf += k < 2 ? ' ' : '\n';
      }
      flush();
    }
    // Texture coordinates per corner (a seam's vertex has one per side), v up as OBJ has it
    // (glTF's v runs down the image): a template to paint groom and colour maps on.
    const bool uv = skin.hasUv();
    if (uv) {
      for (std::size_t c = 0; c < 3 * nT; ++c) {
        buf += "vt ";
        appendFloat(buf, skin.cornerUv[c].x());
        buf += ' ';
        appendFloat(buf, 1.0f - skin.cornerUv[c].y());
        buf += '\n';
        flush();
      }
    }
    for (std::size_t f = 0; f < nT; ++f) {
      buf += 'f';
      for (int k = 0; k < 3; ++k) {
        const std::size_t corner = 3 * f + static_cast<std::size_t>(k);
        const std::string idx = std::to_string(skin.triangles[corner] + 1);
        buf += ' ' + idx + '/' + (uv ? std::to_string(corner + 1) : std::string()) + '/' + idx;
      }
      buf += '\n';
      flush();
    }
    w.write(buf);
    w.commit();
  } else if (ext == ".ply") {
    AtomicFileWriter w(path);
    w.write("ply\nformat binary_little_endian 1.0\ncomment pelage skin\nelement vertex " +
            std::to_string(nV) +
            "\nproperty float x\nproperty float y\nproperty float z\nproperty float nx\n"
            "property float ny\nproperty float nz\nelement face " +
            std::to_string(nT) + "\nproperty list uchar int vertex_indices\nend_header\n");
    std::vector<char> buf;
    buf.reserve(1 << 20);
    auto put = [&](const void* d, std::size_t n) {
      const char* c = static_cast<const char*>(d);
      buf.insert(buf.end(), c, c + n);
      if (buf.size() > (1u << 20)) {
        w.write(buf.data(), buf.size());
        buf.clear();
      }
    };
    for (std::size_t i = 0; i < nV; ++i) {
      put(positions[i].data(), 12);
      put(normals[i].data(), 12);
    }
    for (std::size_t f = 0; f < nT; ++f) {
      const unsigned char three = 3;
      put(&three, 1);
      put(&skin.triangles[3 * f], 12);
    }
    w.write(buf.data(), buf.size());
    w.commit();
  } else {
    inputError(path, ": unsupported output format '", ext, "' (accepted: .obj .ply)");
  }
}

}  // namespace pelage::skin
