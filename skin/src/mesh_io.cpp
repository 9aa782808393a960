#include "pelage/skin/mesh_io.h"

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

namespace pelage::skin {
namespace {

std::string lowerExtension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

// Appends a float in shortest round-trip form.
void appendFloat(std::string& out, float v) {
  char buf[32];
  auto r = std::to_chars(buf, buf + sizeof(buf), v);
  out.append(buf, r.ptr);
}

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

// PLY (ascii, binary_little_endian, binary_big_endian 1.0), read here rather than by OpenMesh,
// whose reader trusts what the file claims: it loops forever on a header with no end_header, on an
// end_header prefix or a garbage format version, reads forever past an ASCII face list count, and
// asked for 4 GiB on a binary body it parsed differently from its header (all found by fuzz_mesh).
// The header grammar is checked line by line (known keywords and PLY types, counts the file size
// can hold); the body is read value by value, every list count must fit the rest of the file, and
// only then is anything added to the mesh. Reads x, y, z of element "vertex" and the list
// "vertex_indices" (or "vertex_index") of element "face"; other elements and properties are
// skipped.
enum class PlyType { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };
int plySize(PlyType t) {
  static constexpr int kSizes[] = {1, 1, 2, 2, 4, 4, 4, 8};
  return kSizes[static_cast<int>(t)];
}
bool plyIsInteger(PlyType t) {
  return t != PlyType::Float32 && t != PlyType::Float64;
}

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::Float32;  // scalar type, or a list's item type
  bool list = false;
  PlyType countType = PlyType::UInt8;
};
struct PlyElement {
  std::string name;
  long long count = 0;
  std::vector<PlyProperty> props;
};

class PlyBody {
 public:
  PlyBody(const std::string& path, const std::string& bytes, std::size_t pos, bool ascii,
          bool bigEndian)
      : path_(path), bytes_(bytes), pos_(pos), ascii_(ascii), bigEndian_(bigEndian) {}

  // Reads one value of type `t` of element `e`, instance `i` (for messages).
  double value(PlyType t, std::size_t e, long long i) {
    return ascii_ ? asciiValue(t, e, i) : binaryValue(t, e, i);
  }

  // Reads a list count that must be an integer the rest of the file can hold.
  std::size_t listCount(const PlyProperty& p, std::size_t e, long long i) {
    if (ascii_) {
      const std::string_view t = token(e, i);
      long long k = -1;
      const auto r = std::from_chars(t.data(), t.data() + t.size(), k);
      if (r.ec != std::errc() || r.ptr != t.data() + t.size() || k < 0 ||
          static_cast<std::size_t>(k) > (bytes_.size() - pos_) / 2 + 1)
        inputError(path_, ": PLY element ", e, " instance ", i, ": list count '",
                   std::string(t.substr(0, 40)), "' does not fit the rest of the file");
      return static_cast<std::size_t>(k);
    }
    const double k = binaryValue(p.countType, e, i);
    if (!(k >= 0.0) || k != std::floor(k) ||
        k > static_cast<double>((bytes_.size() - pos_) / static_cast<std::size_t>(plySize(p.type))))
      inputError(path_, ": PLY element ", e, " instance ", i, ": list count ", k,
                 " does not fit the rest of the file");
    return static_cast<std::size_t>(k);
  }

 private:
  [[noreturn]] void truncated(std::size_t e, long long i) const {
    inputError(path_, ": PLY element ", e, " instance ", i,
               " is cut off: the file ends (truncated or malformed)");
  }
  std::string_view token(std::size_t e, long long i) {
    while (pos_ < bytes_.size() && std::isspace(static_cast<unsigned char>(bytes_[pos_]))) ++pos_;
    const std::size_t b = pos_;
    while (pos_ < bytes_.size() && !std::isspace(static_cast<unsigned char>(bytes_[pos_]))) ++pos_;
    if (b == pos_) truncated(e, i);
    return std::string_view(bytes_).substr(b, pos_ - b);
  }
  double asciiValue(PlyType t, std::size_t e, long long i) {
    const std::string_view s = token(e, i);
    double v = 0.0;
    std::from_chars_result r{};
    if (plyIsInteger(t)) {
      long long n = 0;
      r = std::from_chars(s.data(), s.data() + s.size(), n);
      v = static_cast<double>(n);
    } else {
      r = std::from_chars(s.data(), s.data() + s.size(), v);
    }
    if (r.ec != std::errc() || r.ptr != s.data() + s.size())
      inputError(path_, ": PLY element ", e, " instance ", i, ": '", std::string(s.substr(0, 40)),
                 "' is not ", plyIsInteger(t) ? "an integer" : "a number");
    return v;
  }
  double binaryValue(PlyType t, std::size_t e, long long i) {
    unsigned char b[8] = {};
    // (plySize is at most 8; the bound also tells GCC's -Wstringop-overflow so on aarch64.)
    const std::size_t n = std::min(static_cast<std::size_t>(plySize(t)), sizeof b);
    if (bytes_.size() - pos_ < n) truncated(e, i);
    std::memcpy(b, bytes_.data() + pos_, n);
    pos_ += n;
    if (bigEndian_) std::reverse(b, b + n);
    switch (t) {
      case PlyType::Int8:
        return static_cast<double>(static_cast<std::int8_t>(b[0]));
      case PlyType::UInt8:
        return static_cast<double>(b[0]);
      case PlyType::Int16: {
        std::int16_t x;
        std::memcpy(&x, b, 2);
        return x;
      }
      case PlyType::UInt16: {
        std::uint16_t x;
        std::memcpy(&x, b, 2);
        return x;
      }
      case PlyType::Int32: {
        std::int32_t x;
        std::memcpy(&x, b, 4);
        return x;
      }
      case PlyType::UInt32: {
        std::uint32_t x;
        std::memcpy(&x, b, 4);
        return x;
      }
      case PlyType::Float32: {
        float x;
        std::memcpy(&x, b, 4);
        return x;
      }
      case PlyType::Float64: {
        double x;
        std::memcpy(&x, b, 8);
        return x;
      }
    }
    return 0.0;
  }

  const std::string& path_;
  const std::string& bytes_;
  std::size_t pos_;
  bool ascii_, bigEndian_;
};

void readPly(const std::string& path, TriMesh& mesh) {
  constexpr std::size_t kHeaderLimit = 1 << 16;
  const std::string bytes = readAll(path);
  const std::uintmax_t fileSize = bytes.size();
  if (bytes.rfind("ply", 0) != 0 || (bytes.size() > 3 && bytes[3] != '\n' && bytes[3] != '\r'))
    inputError(path, ": not a PLY file (it must start with the line 'ply')");
  static const std::map<std::string, PlyType> kTypes = {
      {"char", PlyType::Int8},      {"int8", PlyType::Int8},       {"uchar", PlyType::UInt8},
      {"uint8", PlyType::UInt8},    {"short", PlyType::Int16},     {"int16", PlyType::Int16},
      {"ushort", PlyType::UInt16},  {"uint16", PlyType::UInt16},   {"int", PlyType::Int32},
      {"int32", PlyType::Int32},    {"uint", PlyType::UInt32},     {"uint32", PlyType::UInt32},
      {"float", PlyType::Float32},  {"float32", PlyType::Float32}, {"double", PlyType::Float64},
      {"float64", PlyType::Float64}};
  auto type = [&](const std::string& name) {
    const auto it = kTypes.find(name);
    if (it == kTypes.end())
      inputError(path, ": PLY property type '", name.substr(0, 40),
                 "' is not a PLY type (char, uchar, short, ushort, int, uint, float, double, ...)");
    return it->second;
  };
  std::vector<PlyElement> elements;
  std::istringstream lines(bytes.substr(0, kHeaderLimit));
  std::string line;
  bool format = false, ascii = false, bigEndian = false, ended = false;
  std::streamoff bodyStart = 0;
  std::getline(lines, line);  // "ply"
  while (!ended && std::getline(lines, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream words(line);
    std::string key;
    words >> key;
    if (key.empty() || key == "comment" || key == "obj_info") continue;
    if (key == "end_header") {
      std::string rest;
      if (words >> rest)
        inputError(path, ": PLY end_header line has extra text '", rest.substr(0, 40), "'");
      ended = true;
      bodyStart = lines.tellg();
    } else if (key == "format") {
      std::string kind, version, extra;
      words >> kind >> version;
      if (kind != "ascii" && kind != "binary_little_endian" && kind != "binary_big_endian")
        inputError(path, ": PLY format '", kind.substr(0, 40),
                   "' is not ascii, binary_little_endian or binary_big_endian");
      if (version != "1.0" || (words >> extra))
        inputError(path, ": PLY format line must be 'format ", kind, " 1.0'");
      format = true;
      ascii = kind == "ascii";
      bigEndian = kind == "binary_big_endian";
    } else if (key == "element") {
      std::string name, count, extra;
      words >> name >> count;
      if (words >> extra) inputError(path, ": PLY element line must be 'element NAME COUNT'");
      for (const PlyElement& e : elements)
        if (e.name == name)
          inputError(path, ": PLY element '", name.substr(0, 40), "' is declared twice");
      elements.push_back(
          {name,
           headerCount(path, "PLY element " + name.substr(0, 40) + " count", count, fileSize, 1.0),
           {}});
    } else if (key == "property") {
      if (elements.empty()) inputError(path, ": PLY property before any element");
      PlyProperty p;
      std::string first, extra;
      words >> first;
      if (first == "list") {
        std::string countType, itemType;
        words >> countType >> itemType;
        p.list = true;
        p.countType = type(countType);
        p.type = type(itemType);
        if (!plyIsInteger(p.countType))
          inputError(path, ": PLY list count type '", countType, "' must be an integer type");
      } else {
        p.type = type(first);
      }
      if (!(words >> p.name) || (words >> extra))
        inputError(
            path,
            ": PLY property line must be 'property TYPE NAME' or 'property list TYPE TYPE NAME'");
      elements.back().props.push_back(p);
    } else {
      inputError(path, ": unknown PLY header keyword '", key.substr(0, 40), "'");
    }
  }
  if (!ended)
    inputError(path, ": PLY header has no end_header line in its first ", kHeaderLimit, " bytes");
  if (!format) inputError(path, ": PLY header has no format line");
  // Every property of every instance takes at least one byte (binary) or a digit and a separator.
  double needed = 0.0;
  for (const PlyElement& e : elements)
    needed += static_cast<double>(e.count) *
              std::max(1.0, static_cast<double>(e.props.size()) * (ascii ? 2.0 : 1.0));
  if (needed > static_cast<double>(fileSize))
    inputError(path, ": PLY header declares elements needing at least ", needed,
               " bytes but the file has ", fileSize, " (truncated or malformed)");
  const auto vertexIt = std::find_if(elements.begin(), elements.end(),
                                     [](const PlyElement& e) { return e.name == "vertex"; });
  if (vertexIt == elements.end()) inputError(path, ": PLY header declares no vertex element");
  int xyz[3] = {-1, -1, -1};
  for (std::size_t k = 0; k < vertexIt->props.size(); ++k)
    for (int c = 0; c < 3; ++c)
      if (!vertexIt->props[k].list &&
          vertexIt->props[k].name == std::string(1, static_cast<char>('x' + c)))
        xyz[c] = static_cast<int>(k);
  if (xyz[0] < 0 || xyz[1] < 0 || xyz[2] < 0)
    inputError(path, ": PLY vertex element needs scalar properties x, y and z");
  int faceList = -1;
  const auto faceIt = std::find_if(elements.begin(), elements.end(),
                                   [](const PlyElement& e) { return e.name == "face"; });
  if (faceIt != elements.end()) {
    for (std::size_t k = 0; k < faceIt->props.size(); ++k)
      if (faceIt->props[k].list &&
          (faceIt->props[k].name == "vertex_indices" || faceIt->props[k].name == "vertex_index"))
        faceList = static_cast<int>(k);
    if (faceList < 0 || !plyIsInteger(faceIt->props[static_cast<std::size_t>(faceList)].type))
      inputError(path, ": PLY face element needs an integer list property vertex_indices");
  }

  // The body, read completely before anything is added to the mesh.
  if (bodyStart < 0 || static_cast<std::size_t>(bodyStart) > bytes.size())
    inputError(path, ": PLY body missing after end_header");
  PlyBody body(path, bytes, static_cast<std::size_t>(bodyStart), ascii, bigEndian);
  std::vector<float> points;
  std::vector<long long> faceStarts, faceIndices;
  for (std::size_t e = 0; e < elements.size(); ++e) {
    const PlyElement& el = elements[e];
    const bool isVertex = &el == &*vertexIt, isFace = faceIt != elements.end() && &el == &*faceIt;
    if (isVertex) points.reserve(3 * static_cast<std::size_t>(el.count));
    for (long long i = 0; i < el.count; ++i) {
      float p[3] = {0, 0, 0};
      for (std::size_t k = 0; k < el.props.size(); ++k) {
        const PlyProperty& prop = el.props[k];
        if (!prop.list) {
          const double v = body.value(prop.type, e, i);
          for (int c = 0; c < 3; ++c)
            if (isVertex && xyz[c] == static_cast<int>(k)) p[c] = static_cast<float>(v);
          continue;
        }
        const std::size_t n = body.listCount(prop, e, i);
        const bool indices = isFace && faceList == static_cast<int>(k);
        if (indices) faceStarts.push_back(static_cast<long long>(faceIndices.size()));
        for (std::size_t c = 0; c < n; ++c) {
          const double v = body.value(prop.type, e, i);
          if (indices) faceIndices.push_back(static_cast<long long>(v));
        }
      }
      if (isVertex) points.insert(points.end(), p, p + 3);
    }
  }
  const long long nV = vertexIt->count;
  std::vector<TriMesh::VertexHandle> vertices(static_cast<std::size_t>(nV));
  for (long long v = 0; v < nV; ++v) {
    const float* p = &points[3 * static_cast<std::size_t>(v)];
    vertices[static_cast<std::size_t>(v)] = mesh.add_vertex(TriMesh::Point(p[0], p[1], p[2]));
  }
  faceStarts.push_back(static_cast<long long>(faceIndices.size()));
  long long skipped = 0;
  std::vector<TriMesh::VertexHandle> face;
  for (std::size_t f = 0; f + 1 < faceStarts.size(); ++f) {
    face.clear();
    for (long long c = faceStarts[f]; c < faceStarts[f + 1]; ++c) {
      const long long idx = faceIndices[static_cast<std::size_t>(c)];
      if (idx < 0 || idx >= nV)
        inputError(path, ": PLY face ", f, ": vertex index ", idx, " is out of range [0, ", nV - 1,
                   "]");
      face.push_back(vertices[static_cast<std::size_t>(idx)]);
    }
    if (face.size() < 3)
      inputError(path, ": PLY face ", f, " has ", face.size(),
                 " vertices (a face needs at least 3)");
    addPolygon(mesh, face, skipped);
  }
  warnSkipped(path, skipped);
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
    for (std::size_t f = 0; f < nT; ++f) {
      buf += 'f';
      for (int k = 0; k < 3; ++k) {
        const std::string idx =
            std::to_string(skin.triangles[3 * f + static_cast<std::size_t>(k)] + 1);
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
