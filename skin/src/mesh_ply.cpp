// The PLY reader of readStaticMesh (mesh_io.h).
#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>
#include <string_view>

#include "mesh_read.h"
#include "pelage/util/error.h"

namespace pelage::skin::detail {
namespace {

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

}  // namespace

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

}  // namespace pelage::skin::detail
