// Groom files (fur/groom.h): per-vertex groom values keyed to one mesh.
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "pelage/fur/groom.h"
#include "pelage/util/atomic_file.h"
#include "pelage/util/error.h"
#include "pelage/util/json_reader.h"

namespace pelage::fur {
namespace {

constexpr const char* kFormat = "pelage groom";

std::string hex64(std::uint64_t h) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

void mixBytes(std::uint64_t& h, const void* data, std::size_t n) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < n; ++i) {
    h ^= p[i];
    h *= 0x100000001b3ull;
  }
}

// One array of nV values (width 1, or 2 or 3: pairs or [x, y, z] triples), each finite in
// [lo, hi]; `field` names it.
std::vector<float> readValues(const JsonReader& doc, const char* field, std::size_t nV, int width,
                              double lo, double hi) {
  const JsonReader a = doc.at(field);
  if (!a.isArray() || a.size() != nV)
    a.fail(str("expected an array of ", nV,
               width == 1   ? " numbers"
               : width == 2 ? " [overcoat, undercoat] pairs"
                            : " [x, y, z] triples",
               " (one per skin vertex)"));
  std::vector<float> out(nV * static_cast<std::size_t>(width));
  const nlohmann::json& j = a.json();
  for (std::size_t v = 0; v < nV; ++v) {
    const nlohmann::json& e = j[v];
    for (int k = 0; k < width; ++k) {
      const bool tuple = e.is_array() && e.size() == static_cast<std::size_t>(width);
      const nlohmann::json& x = width == 1 ? e : (tuple ? e[static_cast<std::size_t>(k)] : e);
      const double d = x.is_number() ? x.get<double>() : std::nan("");
      if (!(d >= lo && d <= hi) || (width > 1 && !tuple))
        inputError(a.file(), ": ", a.path(), "[", v, "]: expected ",
                   width == 1 ? std::string("a number") : str(width, " numbers"), " in [", lo, ", ",
                   hi, "]");
      out[v * static_cast<std::size_t>(width) + static_cast<std::size_t>(k)] =
          static_cast<float>(d);
    }
  }
  return out;
}

// readValues' rows as vectors of W floats.
template <int W>
std::vector<Eigen::Matrix<float, W, 1>> readRows(const JsonReader& doc, const char* field,
                                                 std::size_t nV, double lo, double hi) {
  const std::vector<float> flat = readValues(doc, field, nV, W, lo, hi);
  std::vector<Eigen::Matrix<float, W, 1>> out(nV);
  for (std::size_t v = 0; v < nV; ++v)
    out[v] = Eigen::Map<const Eigen::Matrix<float, W, 1>>(flat.data() + W * v);
  return out;
}

}  // namespace

std::uint64_t meshHash(const skin::SkinMesh& skin) {
  std::uint64_t h = 0xcbf29ce484222325ull;
  const std::int64_t counts[2] = {skin.numVertices(), skin.numTriangles()};
  mixBytes(h, counts, sizeof counts);
  mixBytes(h, skin.triangles.data(), skin.triangles.size() * sizeof(std::int32_t));
  mixBytes(h, skin.restPositions(),
           static_cast<std::size_t>(skin.numVertices()) * 3 * sizeof(float));
  return h;
}

std::string groomFileJson(const skin::SkinMesh& skin, const VertexGroom& g) {
  const auto nV = static_cast<std::size_t>(skin.numVertices());
  PELAGE_CHECK((g.length.empty() || g.length.size() == nV) &&
                   (g.density.empty() || g.density.size() == nV) &&
                   (g.tint.empty() || g.tint.size() == nV) &&
                   (g.comb.empty() || g.comb.size() == nV) &&
                   (g.clump.empty() || g.clump.size() == nV) &&
                   (g.stiffness.empty() || g.stiffness.size() == nV) &&
                   (g.segmentDirectionWeight.empty() || g.segmentDirectionWeight.size() == nV) &&
                   (g.curlRadius.empty() || g.curlRadius.size() == nV) &&
                   (g.curlTurns.empty() || g.curlTurns.size() == nV) &&
                   (g.widthScale.empty() || g.widthScale.size() == nV) &&
                   std::all_of(g.colorSourceWeight.begin(), g.colorSourceWeight.end(),
                               [&](const auto& w) {
                                 return w.size() == g.colorSourceWeight[0].size() &&
                                        (w.empty() || w.size() == nV);
                               }),
               "groom arrays sized for another mesh");
  nlohmann::json j;
  j["format"] = kFormat;
  j["version"] = kGroomFileVersion;
  j["mesh"] = {{"vertices", skin.numVertices()},
               {"triangles", skin.numTriangles()},
               {"hash", hex64(meshHash(skin))}};
  // Each value as its shortest decimal: it reads back as the same float.
  const auto singles = [](const std::vector<float>& values) {
    nlohmann::json t = nlohmann::json::array();
    for (const float v : values) t.push_back(shortestDecimal(v));
    return t;
  };
  if (!g.length.empty()) j["length"] = singles(g.length);
  if (!g.density.empty()) j["density"] = singles(g.density);
  // Rows ([x, y, z] triples, [overcoat, undercoat] pairs) the same way.
  const auto rows = [](const auto& values) {
    nlohmann::json t = nlohmann::json::array();
    for (const auto& row : values) {
      nlohmann::json r = nlohmann::json::array();
      for (Eigen::Index k = 0; k < row.size(); ++k) r.push_back(shortestDecimal(row[k]));
      t.push_back(std::move(r));
    }
    return t;
  };
  if (!g.tint.empty()) j["tint"] = rows(g.tint);
  if (!g.comb.empty()) j["comb"] = rows(g.comb);
  if (!g.clump.empty()) j["clump"] = singles(g.clump);
  if (!g.stiffness.empty()) j["stiffness"] = rows(g.stiffness);
  if (!g.segmentDirectionWeight.empty())
    j["segmentDirectionWeight"] = rows(g.segmentDirectionWeight);
  if (!g.curlRadius.empty()) j["curlRadius"] = rows(g.curlRadius);
  if (!g.curlTurns.empty()) j["curlTurns"] = rows(g.curlTurns);
  if (!g.widthScale.empty()) j["widthScale"] = rows(g.widthScale);
  if (g.hasColorSourceWeights())
    for (int s = 0; s < kColorSourceCount; ++s)
      j["colorSourceWeight"][std::string(colorSourceName(static_cast<ColorSource>(s)))] =
          rows(g.colorSourceWeight[static_cast<std::size_t>(s)]);
  return j.dump() + "\n";
}

void writeGroomFile(const std::string& path, const skin::SkinMesh& skin, const VertexGroom& g) {
  writeFileAtomically(path, groomFileJson(skin, g));
}

VertexGroom parseGroomFile(const std::string& text, const std::string& source,
                           const skin::SkinMesh& skin, const std::string& modelName) {
  const nlohmann::json doc = JsonReader::parseText(text, source);
  const JsonReader j(doc, source);
  if (!j.isObject()) j.fail("expected a pelage groom file (a JSON object)");
  if (!j.has("format") || !j.at("format").json().is_string() || j.string("format") != kFormat)
    j.fail(str("not a groom file: expected \"format\": \"", kFormat,
               "\" (groom files come from pelage's groom output or Python's write_groom)"));
  j.rejectUnknown({"format", "version", "mesh", "length", "density", "tint", "comb", "clump",
                   "stiffness", "segmentDirectionWeight", "curlRadius", "curlTurns", "widthScale",
                   "colorSourceWeight"});
  j.integer("version", kGroomFileVersion, kGroomFileVersion);
  const JsonReader mesh = j.at("mesh");
  mesh.rejectUnknown({"vertices", "triangles", "hash"});
  const std::int64_t nV = mesh.integer("vertices", 0, std::int64_t(1) << 31);
  const std::int64_t nT = mesh.integer("triangles", 0, std::int64_t(1) << 31);
  const std::string hash = mesh.string("hash");
  const std::string ours = hex64(meshHash(skin));
  if (nV != skin.numVertices() || nT != skin.numTriangles() || hash != ours)
    inputError(source, ": the groom belongs to another mesh (", nV, " vertices, ", nT,
               " triangles, hash ", excerpt(hash), "); model '", excerpt(modelName), "' has ",
               skin.numVertices(), " vertices, ", skin.numTriangles(), " triangles, hash ", ours,
               " (a groom is keyed to the skin it was made on, as loaded with the same options)");
  const auto n = static_cast<std::size_t>(nV);
  VertexGroom g;
  if (j.has("length"))
    g.length = readValues(j, "length", n, 1, 0.0, static_cast<double>(kMaxGroomLengthMeters));
  if (j.has("density"))
    g.density = readValues(j, "density", n, 1, 0.0, static_cast<double>(kMaxGroomDensity));
  if (j.has("clump")) g.clump = readValues(j, "clump", n, 1, 0.0, 1.0);
  if (j.has("stiffness")) g.stiffness = readRows<2>(j, "stiffness", n, 0.0, 1.0);
  if (j.has("segmentDirectionWeight"))
    g.segmentDirectionWeight = readRows<2>(j, "segmentDirectionWeight", n, 0.0, 1.0);
  if (j.has("curlRadius"))
    g.curlRadius = readRows<2>(j, "curlRadius", n, 0.0, static_cast<double>(kMaxCurlRadius));
  if (j.has("curlTurns"))
    g.curlTurns = readRows<2>(j, "curlTurns", n, 0.0, static_cast<double>(kMaxCurlTurns));
  if (j.has("widthScale"))
    g.widthScale = readRows<2>(j, "widthScale", n, 0.0, static_cast<double>(kMaxWidthScale));
  if (j.has("colorSourceWeight")) {
    const JsonReader w = j.at("colorSourceWeight");
    if (!w.isObject())
      w.fail("expected an object of the colour sources (" + colorSourceNames() +
             "), each nV x [overcoat, undercoat] weights");
    for (const std::string& key : w.keys())
      if (!findColorSource(key))
        w.fail("unknown colour source '" + key + "' (accepted: " + colorSourceNames() + ")");
    for (int s = 0; s < kColorSourceCount; ++s) {
      const std::string name(colorSourceName(static_cast<ColorSource>(s)));
      if (!w.has(name)) w.fail("missing '" + name + "': give the weights of all five sources");
      g.colorSourceWeight[static_cast<std::size_t>(s)] = readRows<2>(w, name.c_str(), n, 0.0, 1.0);
    }
    for (std::size_t v = 0; v < n; ++v)
      for (int c = 0; c < kCoatCount; ++c) {
        float sum = 0.0f;
        for (const auto& weights : g.colorSourceWeight) sum += weights[v][c];
        if (!(std::abs(sum - 1.0f) <= 1e-3f))
          w.fail(str("the ", c == kOvercoat ? "overcoat" : "undercoat", " weights of vertex ", v,
                     " sum to ", sum, "; accepted: 1 (a blend of the sources)"));
      }
  }
  if (j.has("tint")) g.tint = readRows<3>(j, "tint", n, 0.0, static_cast<double>(kMaxGroomTint));
  if (j.has("comb")) {
    g.comb = readRows<3>(j, "comb", n, -1.0, 1.0);
    for (std::size_t v = 0; v < n; ++v)
      if (!(g.comb[v].squaredNorm() <= kMaxCombLength2))
        j.at("comb").fail(str("comb[", v, "] has length ", g.comb[v].norm(),
                              "; accepted: at most 1 (the direction times the comb amount)"));
  }
  return g;
}

VertexGroom readGroomFile(const std::string& path, const skin::SkinMesh& skin,
                          const std::string& modelName) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec))
    throw MissingFileError("groom", ": " + path + ": cannot open file (missing or unreadable)");
  try {
    return parseGroomFile(readTextFile(path), path, skin, modelName);
  } catch (const InputError& e) {
    fieldError("groom", ": ", e.what());
  }
}

}  // namespace pelage::fur
