#include "pelage/skin/mesh_io.h"

#include <OpenMesh/Core/IO/MeshIO.hh>

#include <algorithm>
#include <cctype>
#include <charconv>
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

namespace pelage::skin {
namespace {

std::string lowerExtension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

// Appends a float in shortest round-trip form.
void appendFloat(std::string& out, float v) {
  char buf[32];
  auto r = std::to_chars(buf, buf + sizeof(buf), v);
  out.append(buf, r.ptr);
}

// Reads at most `limit` bytes from the start of the file.
std::string readPrefix(const std::string& path, std::size_t limit) {
  std::ifstream in(path, std::ios::binary);
  if (!in) inputError(path, ": cannot open the mesh file for reading");
  std::string bytes(limit, '\0');
  in.read(bytes.data(), static_cast<std::streamsize>(limit));
  bytes.resize(static_cast<std::size_t>(in.gcount()));
  return bytes;
}

// A count from a header must be a plain non-negative integer that the file can hold: each element
// needs at least `minBytes` bytes of the file, so a header claiming billions of elements in a small
// file is refused before any reader allocates for them.
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

// Checks what OpenMesh's readers trust before they read: they loop forever on a PLY header with no
// end_header and allocate whatever element counts a header claims (found by fuzz/fuzz_mesh). PLY:
// the "ply" magic, known header keywords, a format, an end_header in the first 64 KB, element counts
// the file can hold; OFF: the magic and vertex/face counts the file can hold; binary STL: the size
// that its triangle count implies. OBJ is read line by line and needs no check.
void checkMeshHeader(const std::string& path, const std::string& ext, std::uintmax_t fileSize) {
  constexpr std::size_t kHeaderLimit = 1 << 16;
  if (ext == ".ply") {
    const std::string head = readPrefix(path, kHeaderLimit);
    if (head.rfind("ply", 0) != 0 || (head.size() > 3 && head[3] != '\n' && head[3] != '\r'))
      inputError(path, ": not a PLY file (it must start with the line 'ply')");
    static const std::map<std::string, int> kTypes = {
        {"char", 1},   {"uchar", 1},  {"int8", 1},   {"uint8", 1},   {"short", 2},   {"ushort", 2},
        {"int16", 2},  {"uint16", 2}, {"int", 4},    {"uint", 4},    {"int32", 4},   {"uint32", 4},
        {"float", 4},  {"float32", 4}, {"double", 8}, {"float64", 8}};
    struct Prop {
      int size = 0;       // scalar size, or the list's item size
      int countSize = 0;  // > 0 for a list: size of its count
    };
    std::vector<std::vector<Prop>> props;  // per element
    bool bigEndian = false;
    std::streamoff bodyStart = 0;
    std::istringstream lines(head);
    std::string line;
    bool format = false, ascii = false, ended = false, hasVertex = false;
    std::getline(lines, line);  // "ply"
    double bytesPerElement = 0.0;  // of the element being declared
    std::vector<std::pair<long long, double>> elements;  // count, minimum bytes per element
    while (!ended && std::getline(lines, line)) {
      if (!line.empty() && line.back() == '\r') line.pop_back();
      std::istringstream words(line);
      std::string key;
      words >> key;
      if (key.empty() || key == "comment" || key == "obj_info") continue;
      if (key == "end_header") {
        std::string rest;
        if (words >> rest) inputError(path, ": PLY end_header line has extra text '", rest.substr(0, 40), "'");
        ended = true;
        bodyStart = lines.tellg();
      } else if (key == "format") {
        std::string kind, version, extra;
        words >> kind >> version;
        if (kind != "ascii" && kind != "binary_little_endian" && kind != "binary_big_endian")
          inputError(path, ": PLY format '", kind.substr(0, 40), "' is not ascii, binary_little_endian or binary_big_endian");
        if (version != "1.0" || (words >> extra))
          inputError(path, ": PLY format line must be 'format ", kind, " 1.0'");
        format = true;
        ascii = kind == "ascii";
        bigEndian = kind == "binary_big_endian";
      } else if (key == "element") {
        std::string name, count, extra;
        words >> name >> count;
        if (words >> extra) inputError(path, ": PLY element line must be 'element NAME COUNT'");
        if (name == "vertex") hasVertex = true;
        if (!elements.empty()) elements.back().second = std::max(bytesPerElement, 1.0);
        elements.push_back({headerCount(path, "PLY element " + name.substr(0, 40) + " count", count, fileSize, 1.0), 1.0});
        bytesPerElement = 0.0;
        props.emplace_back();
      } else if (key == "property") {
        if (elements.empty()) inputError(path, ": PLY property before any element");
        std::string type, name;
        words >> type;
        if (type == "list") {
          std::string countType, itemType;
          words >> countType >> itemType;
          if (!kTypes.count(countType) || !kTypes.count(itemType))
            inputError(path, ": PLY list property types '", countType.substr(0, 40), "', '", itemType.substr(0, 40),
                       "' are not PLY types (char, uchar, short, ushort, int, uint, float, double, ...)");
          props.back().push_back({kTypes.at(itemType), kTypes.at(countType)});
        } else if (!kTypes.count(type)) {
          inputError(path, ": PLY property type '", type.substr(0, 40),
                     "' is not a PLY type (char, uchar, short, ushort, int, uint, float, double, ...)");
        } else {
          props.back().push_back({kTypes.at(type), 0});
        }
        std::string extra;
        if (!(words >> name) || (words >> extra))
          inputError(path, ": PLY property line must be 'property TYPE NAME' or 'property list TYPE TYPE NAME'");
        // Each property takes at least one byte (binary) or one digit and a separator (ascii).
        bytesPerElement += ascii ? 2.0 : 1.0;
      } else {
        inputError(path, ": unknown PLY header keyword '", key.substr(0, 40), "'");
      }
    }
    if (!ended)
      inputError(path, ": PLY header has no end_header line in its first ", kHeaderLimit, " bytes");
    if (!format) inputError(path, ": PLY header has no format line");
    if (!hasVertex) inputError(path, ": PLY header declares no vertex element");
    if (!elements.empty()) elements.back().second = std::max(bytesPerElement, 1.0);
    double needed = 0.0;
    for (const auto& [count, bytes] : elements) needed += static_cast<double>(count) * bytes;
    if (needed > static_cast<double>(fileSize))
      inputError(path, ": PLY header declares elements needing at least ", needed,
                 " bytes but the file has ", fileSize, " (truncated or malformed)");
    // The body: OpenMesh trusts each list's count (found by fuzz_mesh: an ASCII face list count far
    // beyond the file made it read forever), so every list count must fit in what is left of the
    // file, and the file must hold every element it declares.
    std::ifstream in(path, std::ios::binary);
    std::string body((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (bodyStart < 0 || static_cast<std::size_t>(bodyStart) > body.size())
      inputError(path, ": PLY body missing after end_header");
    std::size_t pos = static_cast<std::size_t>(bodyStart);
    auto truncated = [&](std::size_t e, long long i) {
      inputError(path, ": PLY element ", e, " instance ", i, " is cut off: the file ends (truncated or malformed)");
    };
    for (std::size_t e = 0; e < elements.size(); ++e) {
      for (long long i = 0; i < elements[e].first; ++i) {
        for (const Prop& prop : props[e]) {
          if (ascii) {
            auto token = [&]() -> std::string_view {
              while (pos < body.size() && std::isspace(static_cast<unsigned char>(body[pos]))) ++pos;
              const std::size_t b = pos;
              while (pos < body.size() && !std::isspace(static_cast<unsigned char>(body[pos]))) ++pos;
              if (b == pos) truncated(e, i);
              return std::string_view(body).substr(b, pos - b);
            };
            if (prop.countSize == 0) {
              token();
              continue;
            }
            const std::string_view t = token();
            long long k = -1;
            const auto r = std::from_chars(t.data(), t.data() + t.size(), k);
            if (r.ec != std::errc() || r.ptr != t.data() + t.size() || k < 0 ||
                static_cast<std::size_t>(k) > (body.size() - pos) / 2 + 1)
              inputError(path, ": PLY element ", e, " instance ", i, ": list count '",
                         std::string(t.substr(0, 40)), "' does not fit the rest of the file");
            for (long long c = 0; c < k; ++c) token();
          } else if (prop.countSize == 0) {
            if (body.size() - pos < static_cast<std::size_t>(prop.size)) truncated(e, i);
            pos += static_cast<std::size_t>(prop.size);
          } else {
            if (body.size() - pos < static_cast<std::size_t>(prop.countSize)) truncated(e, i);
            unsigned char b[8] = {};
            std::memcpy(b, body.data() + pos, static_cast<std::size_t>(prop.countSize));
            if (bigEndian) std::reverse(b, b + prop.countSize);
            std::uint64_t k = 0;
            for (int c = prop.countSize - 1; c >= 0; --c) k = (k << 8) | b[c];
            pos += static_cast<std::size_t>(prop.countSize);
            if (k > (body.size() - pos) / static_cast<std::size_t>(prop.size))
              inputError(path, ": PLY element ", e, " instance ", i, ": list count ", k,
                         " does not fit the rest of the file");
            pos += static_cast<std::size_t>(k) * static_cast<std::size_t>(prop.size);
          }
        }
      }
    }
  } else if (ext == ".off") {
    std::istringstream words(readPrefix(path, 64));
    std::string magic;
    words >> magic;
    if (magic != "OFF" && magic != "NOFF" && magic != "COFF" && magic != "CNOFF" && magic != "STOFF")
      inputError(path, ": not an OFF file (it must start with OFF, NOFF, COFF, CNOFF or STOFF)");
  } else if (ext == ".stl") {
    const std::string head = readPrefix(path, 84);
    const bool asciiStl = head.rfind("solid", 0) == 0 && head.find('\0') == std::string::npos;
    if (!asciiStl) {
      if (head.size() < 84) inputError(path, ": binary STL shorter than its 84-byte header");
      std::uint32_t n = 0;
      std::memcpy(&n, head.data() + 80, 4);
      const std::uintmax_t expected = 84 + 50 * static_cast<std::uintmax_t>(n);
      if (expected != fileSize)
        inputError(path, ": binary STL declares ", n, " triangles (", expected, " bytes) but the file has ",
                   fileSize, " bytes");
    }
  }
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
      float x = 0, y = 0, z = 0;
      std::string a, b, c;
      words >> a >> b >> c;
      auto parse = [&](const std::string& t, float& out) {
        const auto r = std::from_chars(t.data(), t.data() + t.size(), out);
        if (t.empty() || r.ec != std::errc() || r.ptr != t.data() + t.size())
          inputError(path, ":", lineNo, ": vertex coordinate '", t.substr(0, 40), "' is not a number");
      };
      parse(a, x);
      parse(b, y);
      parse(c, z);
      vertices.push_back(mesh.add_vertex(TriMesh::Point(x, y, z)));
    } else if (key == "f") {
      face.clear();
      std::string corner;
      while (words >> corner) {
        const std::string first = corner.substr(0, corner.find('/'));
        long long idx = 0;
        const auto r = std::from_chars(first.data(), first.data() + first.size(), idx);
        if (first.empty() || r.ec != std::errc() || r.ptr != first.data() + first.size() || idx == 0)
          inputError(path, ":", lineNo, ": face corner '", corner.substr(0, 40), "' has no valid vertex index");
        const long long n = static_cast<long long>(vertices.size());
        const long long i = idx > 0 ? idx - 1 : n + idx;
        if (i < 0 || i >= n)
          inputError(path, ":", lineNo, ": face vertex ", idx, " is out of range [1, ", n, "] (or [-", n, ", -1])");
        face.push_back(vertices[static_cast<std::size_t>(i)]);
      }
      if (face.size() < 3) inputError(path, ":", lineNo, ": a face needs at least 3 vertices");
      for (std::size_t k = 1; k + 1 < face.size(); ++k) {
        if (face[0] == face[k] || face[k] == face[k + 1] || face[0] == face[k + 1] ||
            !mesh.add_face(face[0], face[k], face[k + 1]).is_valid())
          ++skipped;
      }
    }
  }
  if (skipped) warn(str(path, ": skipped ", skipped, " triangles (repeated vertices or non-manifold edges)"));
}

// OFF (and NOFF/COFF/CNOFF/STOFF), read here rather than by OpenMesh, which reserves whatever vertex
// count a face claims (found by fuzz_mesh: 685,308,834 in an 82-byte file; 2^30 after a split vertex
// line). Line based: after the counts, one vertex per line ("x y z" then optional normal/colour/
// texture values), one face per line ("k i0 .. ik-1" then an optional colour); '#' comments and
// blank lines are skipped. Polygons become triangle fans; non-manifold faces are skipped with a
// warning.
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
    if (!nextLine(words)) inputError(path, ": OFF file ends after ", v, " of its ", nVertices, " vertices");
    TriMesh::Point p;
    for (int k = 0; k < 3; ++k) {
      std::string t;
      words >> t;
      const auto r = std::from_chars(t.data(), t.data() + t.size(), p[k]);
      if (t.empty() || r.ec != std::errc() || r.ptr != t.data() + t.size())
        inputError(path, ":", lineNo, ": vertex coordinate '", t.substr(0, 40), "' is not a number");
    }
    vertices.push_back(mesh.add_vertex(p));
  }
  long long skipped = 0;
  std::vector<TriMesh::VertexHandle> face;
  for (long long f = 0; f < nFaces; ++f) {
    if (!nextLine(words)) inputError(path, ": OFF file ends after ", f, " of its ", nFaces, " faces");
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
    for (std::size_t j = 1; j + 1 < face.size(); ++j) {
      if (face[0] == face[j] || face[j] == face[j + 1] || face[0] == face[j + 1] ||
          !mesh.add_face(face[0], face[j], face[j + 1]).is_valid())
        ++skipped;
    }
  }
  if (skipped) warn(str(path, ": skipped ", skipped, " triangles (repeated vertices or non-manifold edges)"));
}

}  // namespace

SkinMesh readStaticMesh(const std::string& path, float furLengthMeters) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::exists(path, ec)) inputError(path, ": mesh file does not exist");
  if (!fs::is_regular_file(path, ec)) inputError(path, ": not a regular file");
  const std::string ext = lowerExtension(path);
  if (ext != ".obj" && ext != ".ply" && ext != ".off" && ext != ".stl")
    inputError(path, ": unsupported mesh format '", ext, "' (accepted: .obj .ply .off .stl)");
  const std::uintmax_t fileSize = fs::file_size(path, ec);
  if (ec) inputError(path, ": cannot read the file size (", ec.message(), ")");
  if (fileSize == 0) inputError(path, ": file is empty");
  checkMeshHeader(path, ext, fileSize);

  SkinMesh skin;
  OpenMesh::IO::Options opt;
  // Our messages name the file and the problem; OpenMesh's own stderr chatter would only repeat them.
  omerr().disable();
  omlog().disable();
  if (ext == ".obj") {
    readObj(path, skin.mesh);
  } else if (ext == ".off") {
    readOff(path, skin.mesh, fileSize);
  } else if (!OpenMesh::IO::read_mesh(skin.mesh, path, opt)) {
    inputError(path, ": OpenMesh could not read this ", ext, " file (malformed or truncated)");
  }
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
  addSkinProperties(skin);
  Eigen::Map<const Eigen::Matrix<float, 3, Eigen::Dynamic>> P(skin.restPositions(), 3,
                                                              static_cast<Eigen::Index>(m.n_vertices()));
  const float diag = (P.rowwise().maxCoeff() - P.rowwise().minCoeff()).norm();
  const float len = furLengthMeters > 0.0f ? furLengthMeters : 0.03f * diag;
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
    buf += "# pelage skin: " + std::to_string(nV) + " vertices, " + std::to_string(nT) + " triangles\n";
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
    for (std::size_t f = 0; f < nT; ++f) {
      buf += 'f';
      for (int k = 0; k < 3; ++k) {
        const std::string idx = std::to_string(skin.triangles[3 * f + static_cast<std::size_t>(k)] + 1);
        buf += ' ' + idx + "//" + idx;
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
