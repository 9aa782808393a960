#include "pelage/fur/preset.h"

#include <filesystem>

#include "pelage/models/builtin.h"
#include "pelage/util/atomic_file.h"
#include "pelage/util/error.h"
#include "pelage/util/json_reader.h"

namespace pelage::fur {
namespace {

constexpr const char* kPresetDir = "presets/";

float num(const JsonReader& j, const char* key, float fallback, double lo, double hi) {
  return static_cast<float>(j.number(key, fallback, lo, hi));
}

Eigen::Vector3f color(const JsonReader& j, const char* key, const Eigen::Vector3f& fallback) {
  if (!j.has(key)) return fallback;
  const JsonReader c = j.at(key);
  if (!c.isArray() || c.size() != 3)
    c.fail("expected an array of 3 numbers in [0, 1] (linear RGB)");
  Eigen::Vector3f v;
  for (std::size_t k = 0; k < 3; ++k)
    v[static_cast<int>(k)] = static_cast<float>(c.at(k).asNumber(0.0, 1.0));
  return v;
}

CoatColor parseCoatColor(const JsonReader& j, const CoatColor& defaults) {
  j.rejectUnknown({"source", "tint", "tipLightness", "tipColor", "hueVariation", "valueVariation"});
  CoatColor c = defaults;
  if (j.has("source")) c.source = parseColorSource(j.string("source"), j.at("source").where());
  if (j.has("tint")) {
    const JsonReader t = j.at("tint");
    if (!t.isArray() || t.size() != 3) t.fail("expected an array of 3 numbers in [0, 10]");
    for (std::size_t k = 0; k < 3; ++k)
      c.tint[static_cast<int>(k)] = static_cast<float>(t.at(k).asNumber(0.0, 10.0));
  }
  c.tipLightness = num(j, "tipLightness", c.tipLightness, 0.0, 10.0);
  if (j.has("tipColor")) {
    if (j.at("tipColor").json().is_null()) {
      c.hasTipColor = false;
    } else {
      c.hasTipColor = true;
      c.tipColor = color(j, "tipColor", c.tipColor);
    }
  }
  c.hueVariation = num(j, "hueVariation", c.hueVariation, 0.0, 180.0);
  c.valueVariation = num(j, "valueVariation", c.valueVariation, 0.0, 1.0);
  return c;
}

CoatParams parseCoat(const JsonReader& j, const CoatParams& defaults) {
  j.rejectUnknown({"style", "stiffness", "normalRandomize", "hairEndRandomize",
                   "segmentDirectionWeight", "relativeLength", "ambient", "diffuse", "specular",
                   "shininess", "curvePoints", "tubeSides", "width", "tubeRadius", "curl", "frizz",
                   "clump", "color"});
  CoatParams c = defaults;
  if (j.has("style")) c.style = parseStyle(j.string("style"), j.at("style").where());
  c.stiffness = num(j, "stiffness", c.stiffness, 0.0, 1.0);
  c.normalRandomize = num(j, "normalRandomize", c.normalRandomize, 0.0, 1.0);
  c.hairEndRandomize = num(j, "hairEndRandomize", c.hairEndRandomize, 0.0, 2.0);
  c.segmentDirectionWeight = num(j, "segmentDirectionWeight", c.segmentDirectionWeight, 0.0, 1.0);
  c.lengthFactor = num(j, "relativeLength", c.lengthFactor, 0.0, 10.0);
  c.material.ambient = color(j, "ambient", c.material.ambient);
  c.material.diffuse = color(j, "diffuse", c.material.diffuse);
  c.material.specular = color(j, "specular", c.material.specular);
  c.material.shininess = num(j, "shininess", c.material.shininess, 1.0, 1000.0);
  c.curvePoints = static_cast<int>(j.integer("curvePoints", c.curvePoints, 2, 64));
  c.tubeSides = static_cast<int>(j.integer("tubeSides", c.tubeSides, 3, 32));
  if (auto w = j.find("width")) {
    w->rejectUnknown({"root", "tip"});
    c.width.rootMm = num(*w, "root", c.width.rootMm, 0.001, 20.0);
    c.width.tipMm = num(*w, "tip", c.width.tipMm, 0.0, 20.0);
  }
  if (j.has("tubeRadius")) {
    // The earlier spelling: a tube's root radius in metres, its tip 0.05 of it.
    if (j.has("width"))
      inputError(j.at("tubeRadius").where(), " and width both given: width {root, tip} in mm",
                 " replaces tubeRadius");
    c.width.rootMm = 2000.0f * num(j, "tubeRadius", 0.0002f, 1e-6, 0.01);
    c.width.tipMm = 0.05f * c.width.rootMm;
  }
  if (auto curl = j.find("curl")) {
    curl->rejectUnknown({"radius", "turns"});
    c.curlRadius = num(*curl, "radius", c.curlRadius, 0.0, kMaxCurlRadius);
    c.curlTurns = num(*curl, "turns", c.curlTurns, 0.0, kMaxCurlTurns);
  }
  if (auto frizz = j.find("frizz")) {
    frizz->rejectUnknown({"amplitude", "frequency", "tipWeight"});
    c.frizz.amplitudeMm = num(*frizz, "amplitude", c.frizz.amplitudeMm, 0.0, 100.0);
    c.frizz.frequency = num(*frizz, "frequency", c.frizz.frequency, 0.1, 64.0);
    c.frizz.tipWeight = num(*frizz, "tipWeight", c.frizz.tipWeight, 1.0, 8.0);
  }
  if (auto clump = j.find("clump")) {
    clump->rejectUnknown({"density", "strength", "shape", "radius"});
    c.clump.density = num(*clump, "density", c.clump.density, 0.0, 100.0);
    c.clump.strength = num(*clump, "strength", c.clump.strength, 0.0, 1.0);
    c.clump.shape = num(*clump, "shape", c.clump.shape, 0.1, 10.0);
    c.clump.radiusMm = num(*clump, "radius", c.clump.radiusMm, 0.1, 1000.0);
  }
  if (auto col = j.find("color")) c.color = parseCoatColor(*col, c.color);
  return c;
}

// A groom map path, made absolute: relative ones resolve against the preset file's folder
// (`baseDir`; built-in presets and keyword-made ones: the working directory), so a preset saved
// elsewhere still names the same files.
std::string mapPath(const JsonReader& j, const char* key, const std::string& baseDir) {
  const std::string p = j.string(key);
  if (p.empty()) j.at(key).fail("an image file name, or leave the field out");
  std::error_code ec;
  const std::filesystem::path full =
      std::filesystem::absolute(std::filesystem::path(baseDir) / p, ec);
  return ec ? p : full.lexically_normal().string();
}

LengthRegion parseRegion(const JsonReader& j) {
  j.rejectUnknown({"sphere", "box", "scale"});
  LengthRegion r;
  r.scale = num(j, "scale", 1.0f, 0.0, 10.0);
  if (j.has("sphere") == j.has("box")) j.fail("give exactly one of 'sphere' or 'box'");
  if (auto s = j.find("sphere")) {
    s->rejectUnknown({"center", "radius"});
    r.shape = RegionShape::Sphere;
    r.center = s->vec3("center");
    r.radius = num(*s, "radius", 0.0f, 1e-6, 1e4);
    if (!s->has("radius")) s->fail("missing 'radius' (metres, [1e-06, 10000])");
  } else {
    const JsonReader b = j.at("box");
    b.rejectUnknown({"min", "max"});
    r.shape = RegionShape::Box;
    r.boxMin = b.vec3("min");
    r.boxMax = b.vec3("max");
  }
  return r;
}

// A region's per-coat value in [0, hi]: one number (both coats) or [overcoat, undercoat]; unset
// where the region does not name it.
std::optional<Eigen::Vector2f> coatPair(const JsonReader& j, const char* field, double hi = 1.0) {
  if (!j.has(field)) return std::nullopt;
  const JsonReader s = j.at(field);
  if (!s.isArray()) {
    const auto both = static_cast<float>(s.asNumber(0.0, hi));
    return Eigen::Vector2f(both, both);
  }
  if (s.size() != 2)
    s.fail(str("expected a number in [0, ", hi,
               "] (both coats) or [overcoat, undercoat], each in [0, ", hi, "]"));
  return Eigen::Vector2f(static_cast<float>(s.at(0).asNumber(0.0, hi)),
                         static_cast<float>(s.at(1).asNumber(0.0, hi)));
}

// "regions": [{"match": PATTERN, "lengthScale": s, "lengthMm": mm, "densityScale": d,
// "tint": [r, g, b], "stiffness": s | [overcoat, undercoat], "segmentDirectionWeight": w |
// [overcoat, undercoat], "curl": {"radius": r | [o, u], "turns": t | [o, u]}, "widthScale": s |
// [o, u], "colorSource": NAME | [o, u]}, ...]; the list
// replaces the base preset's.
std::vector<FurRegion> parseFurRegions(const JsonReader& list) {
  if (!list.isArray())
    list.fail("expected an array of regions, e.g. [{\"match\": \"b_Tail*\", \"lengthScale\": 2}]");
  if (list.size() > kMaxFurRegions)
    list.fail(str("has ", list.size(), " regions; accepted: at most ", kMaxFurRegions));
  std::vector<FurRegion> out;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const JsonReader j = list.at(i);
    if (!j.isObject()) j.fail("expected an object {\"match\": PATTERN, ...}");
    // Of the coat fields the stiffness, the segment direction weight, the curl, the width (as a
    // scale) and the colour source are per region.
    j.rejectUnknown({"match", "lengthScale", "lengthMm", "densityScale", "tint", "stiffness",
                     "segmentDirectionWeight", "curl", "widthScale", "colorSource"});
    FurRegion r;
    if (!j.has("match"))
      j.fail("missing 'match' (a region, material or joint name; '*' wildcards)");
    r.match = j.string("match");
    if (r.match.empty()) j.at("match").fail("a region, material or joint name; '*' wildcards");
    r.lengthScale = num(j, "lengthScale", r.lengthScale, 0.0, 10.0);
    r.lengthMm = num(j, "lengthMm", r.lengthMm, 0.0, 10000.0);
    r.densityScale = num(j, "densityScale", r.densityScale, 0.0, 100.0);
    if (j.has("tint")) {
      const JsonReader t = j.at("tint");
      if (!t.isArray() || t.size() != 3) t.fail("expected an array of 3 numbers in [0, 10]");
      for (std::size_t k = 0; k < 3; ++k)
        r.tint[static_cast<int>(k)] = static_cast<float>(t.at(k).asNumber(0.0, 10.0));
    }
    r.stiffness = coatPair(j, "stiffness");
    r.segmentDirectionWeight = coatPair(j, "segmentDirectionWeight");
    if (j.has("curl")) {
      const JsonReader curl = j.at("curl");
      if (!curl.isObject())
        curl.fail(
            "expected {\"radius\": r, \"turns\": t}, each one number or [overcoat, undercoat]");
      curl.rejectUnknown({"radius", "turns"});
      r.curlRadius = coatPair(curl, "radius", kMaxCurlRadius);
      r.curlTurns = coatPair(curl, "turns", kMaxCurlTurns);
    }
    r.widthScale = coatPair(j, "widthScale", kMaxWidthScale);
    if (j.has("colorSource")) {
      const JsonReader s = j.at("colorSource");
      const auto source = [&](const JsonReader& name) {
        return parseColorSource(name.asString(), name.where());
      };
      if (s.isArray()) {
        if (s.size() != 2) s.fail("expected a colour source name or [overcoat, undercoat]");
        r.colorSource = std::array<ColorSource, 2>{source(s.at(0)), source(s.at(1))};
      } else {
        const ColorSource both = source(s);
        r.colorSource = std::array<ColorSource, 2>{both, both};
      }
    }
    out.push_back(std::move(r));
  }
  return out;
}

std::optional<std::string> builtinPresetText(const std::string& name) {
  const auto text = models::builtinFile(std::string(kPresetDir) + name + ".json");
  if (!text) return std::nullopt;
  return std::string(*text);
}

nlohmann::json colorJson(const Eigen::Vector3f& c) {
  return {c.x(), c.y(), c.z()};
}

nlohmann::json coatJson(const CoatParams& c) {
  nlohmann::json j;
  j["style"] = styleName(c.style);
  j["stiffness"] = c.stiffness;
  j["normalRandomize"] = c.normalRandomize;
  j["hairEndRandomize"] = c.hairEndRandomize;
  j["segmentDirectionWeight"] = c.segmentDirectionWeight;
  j["relativeLength"] = c.lengthFactor;
  j["ambient"] = colorJson(c.material.ambient);
  j["diffuse"] = colorJson(c.material.diffuse);
  j["specular"] = colorJson(c.material.specular);
  j["shininess"] = c.material.shininess;
  j["curvePoints"] = c.curvePoints;
  j["tubeSides"] = c.tubeSides;
  j["width"] = {{"root", c.width.rootMm}, {"tip", c.width.tipMm}};
  j["curl"] = {{"radius", c.curlRadius}, {"turns", c.curlTurns}};
  j["frizz"] = {{"amplitude", c.frizz.amplitudeMm},
                {"frequency", c.frizz.frequency},
                {"tipWeight", c.frizz.tipWeight}};
  j["clump"] = {{"density", c.clump.density},
                {"strength", c.clump.strength},
                {"shape", c.clump.shape},
                {"radius", c.clump.radiusMm}};
  const CoatColor& k = c.color;
  j["color"] = {{"source", colorSourceName(k.source)},
                {"tint", colorJson(k.tint)},
                {"tipLightness", k.tipLightness},
                {"tipColor", k.hasTipColor ? colorJson(k.tipColor) : nlohmann::json(nullptr)},
                {"hueVariation", k.hueVariation},
                {"valueVariation", k.valueVariation}};
  return j;
}

}  // namespace

std::vector<std::string> builtinPresetNames() {
  std::vector<std::string> names;
  for (const std::string& f : models::builtinFileNames()) {
    if (f.rfind(kPresetDir, 0) != 0 || f.size() < 5 || f.substr(f.size() - 5) != ".json") continue;
    names.push_back(
        f.substr(std::string(kPresetDir).size(), f.size() - std::string(kPresetDir).size() - 5));
  }
  return names;
}

namespace {

// The maximum depth of a chain of "base" presets (a file based on a file based on ...).
constexpr int kMaxBaseDepth = 16;

bool looksLikePresetPath(const std::string& nameOrPath) {
  return nameOrPath.find('/') != std::string::npos ||
         std::filesystem::path(nameOrPath).extension() == ".json";
}

// Where a preset's text comes from and what it stands on.
//  source: names it in messages; baseDir: the folder its relative paths (maps, "base") resolve
//    against ("" = the working directory); defaultName: its name when it gives none;
//  over: the parameters it starts from when it names no "base" (nullptr: a self-contained built-in
//    preset, starting from FurParams' own values, its undercoat from its overcoat);
//  chain: the presets being read, outermost first (a base chain that loops is an error).
struct PresetSource {
  std::string source, baseDir, defaultName;
  const FurParams* over = nullptr;
};

FurParams parsePreset(const nlohmann::json& doc, const PresetSource& src,
                      std::vector<std::string>& chain);
FurParams loadPresetIn(const std::string& nameOrPath, const std::string& baseDir,
                       std::vector<std::string>& chain, const std::string& where);

// The built-in default preset, parsed once.
const FurParams& builtinDefault() {
  static const FurParams params = [] {
    std::vector<std::string> chain;
    return loadPresetIn(kDefaultPreset, "", chain, "");
  }();
  return params;
}

// A preset's fields over the parameters it starts from: each field given replaces the one below
// it, coat and group fields one by one (Van Gelder & Wilhelms 1997, sec. 3.1's two coats and the
// Figure 2 parameters, each validated).
FurParams parsePreset(const nlohmann::json& doc, const PresetSource& src,
                      std::vector<std::string>& chain) {
  const JsonReader j(doc, src.source);
  if (!j.isObject()) j.fail("expected a JSON object with the fur parameters");
  j.rejectUnknown({"name", "description", "base", "hairs", "density", "coverage", "undercoatShare",
                   "seed", "lengthScale", "lengthRegion", "regions", "up", "culling", "overcoat",
                   "undercoat", "maps", "groom"});
  FurParams p;
  bool selfContained = true;
  if (j.has("base")) {
    const std::string base = j.string("base");
    if (base.empty()) j.at("base").fail("a built-in preset name or a preset file");
    p = loadPresetIn(base, src.baseDir, chain, j.at("base").where());
    selfContained = false;
  } else if (src.over) {
    p = *src.over;
    selfContained = false;
  }
  p.name = j.string("name", src.defaultName);
  if (j.has("description")) (void)j.string("description");
  // One way to count the hairs: a total, a density or a coverage; each replaces the base's.
  if (int(j.has("hairs")) + int(j.has("density")) + int(j.has("coverage")) > 1)
    j.fail(
        "give one of 'hairs' (a total), 'density' (hairs per square metre) or 'coverage' (the "
        "share of skin hidden), not several");
  p.hairs = j.number("hairs", p.hairs, 0.0, kMaxHairs);
  if (j.has("hairs")) p.densityPerM2 = p.coverage = 0.0;
  p.densityPerM2 = j.number("density", p.densityPerM2, 0.0, 1e10);
  if (j.has("density")) p.coverage = 0.0;
  p.coverage = j.number("coverage", p.coverage, 0.0, kMaxCoverage);
  if (j.has("coverage")) p.densityPerM2 = 0.0;
  p.undercoatShare = num(j, "undercoatShare", p.undercoatShare, 0.0, 1.0);
  p.seed = static_cast<std::uint64_t>(
      j.integer("seed", static_cast<std::int64_t>(p.seed), 0, std::int64_t(1) << 53));
  p.lengthScale = num(j, "lengthScale", p.lengthScale, 0.0, 10.0);
  if (auto r = j.find("lengthRegion")) p.lengthRegion = parseRegion(*r);
  if (auto r = j.find("regions")) p.regions = parseFurRegions(*r);
  p.up = j.vec3("up", p.up);
  if (auto c = j.find("culling")) {
    c->rejectUnknown({"enabled", "referenceDistance", "fovDegrees", "referenceHeight"});
    p.culling.enabled = c->boolean("enabled", p.culling.enabled);
    p.culling.referenceDistance =
        num(*c, "referenceDistance", p.culling.referenceDistance, 0.0, 1e4);
    p.culling.fovYDegrees = num(*c, "fovDegrees", p.culling.fovYDegrees, 1.0, 179.0);
    p.culling.referenceHeight =
        static_cast<int>(c->integer("referenceHeight", p.culling.referenceHeight, 16, 16384));
  }
  if (auto m = j.find("maps")) {
    m->rejectUnknown({"density", "length", "color"});
    if (m->has("density")) p.maps.density = mapPath(*m, "density", src.baseDir);
    if (m->has("length")) p.maps.length = mapPath(*m, "length", src.baseDir);
    if (m->has("color")) p.maps.color = mapPath(*m, "color", src.baseDir);
  }
  if (j.has("groom"))
    p.groom = j.at("groom").json().is_null() ? "" : mapPath(j, "groom", src.baseDir);
  if (auto c = j.find("overcoat")) p.coats[kOvercoat] = parseCoat(*c, p.coats[kOvercoat]);
  CoatParams under = p.coats[kUndercoat];
  if (selfContained) {
    // A self-contained preset states only what its undercoat changes from its overcoat.
    under = p.coats[kOvercoat];
    under.lengthFactor = 0.3f;  // the paper's favourite relative length (sec. 4)
  }
  p.coats[kUndercoat] = j.has("undercoat") ? parseCoat(j.at("undercoat"), under) : under;
  validateFurParams(p, src.source);
  return p;
}

// Loads a preset by built-in name or path (relative paths against `baseDir`), as the base of
// another (`where` names the referring field; "" for the outermost).
FurParams loadPresetIn(const std::string& nameOrPath, const std::string& baseDir,
                       std::vector<std::string>& chain, const std::string& where) {
  const std::string in = where.empty() ? "" : where + ": ";
  if (static_cast<int>(chain.size()) >= kMaxBaseDepth)
    inputError(in, "more than ", kMaxBaseDepth, " presets deep in 'base' (", excerpt(chain[0]),
               " ...)");
  if (!looksLikePresetPath(nameOrPath)) {
    if (auto text = builtinPresetText(nameOrPath)) {
      PresetSource src{"built-in preset " + nameOrPath, "", nameOrPath, nullptr};
      // Built-in presets are self-contained, except where one names a base.
      return parsePreset(JsonReader::parseText(*text, src.source), src, chain);
    }
    if (std::error_code ec; !std::filesystem::exists(nameOrPath, ec)) {
      std::string list;
      for (const std::string& n : builtinPresetNames()) list += (list.empty() ? "" : ", ") + n;
      inputError(in, "unknown fur preset '", excerpt(nameOrPath), "' (built-in: ", list,
                 "; or give a .json file)");
    }
  }
  std::filesystem::path path(nameOrPath);
  if (path.is_relative() && !baseDir.empty()) path = std::filesystem::path(baseDir) / path;
  std::error_code ec;
  const std::filesystem::path canonical = std::filesystem::weakly_canonical(path, ec);
  const std::string key = ec ? path.lexically_normal().string() : canonical.string();
  for (const std::string& c : chain)
    if (c == key) inputError(in, "preset '", excerpt(path.string()), "' is its own base");
  chain.push_back(key);
  const std::string file = path.string();
  PresetSource src{file, path.parent_path().string(), path.stem().string(), &builtinDefault()};
  FurParams p = parsePreset(JsonReader::parseFile(file), src, chain);
  p.file = file;
  chain.pop_back();
  return p;
}

}  // namespace

FurParams parseFurPreset(const std::string& jsonText, const std::string& source) {
  std::vector<std::string> chain;
  const PresetSource src{source, "", std::filesystem::path(source).stem().string(),
                         &builtinDefault()};
  return parsePreset(JsonReader::parseText(jsonText, source), src, chain);
}

FurParams applyFurPresetFields(const FurParams& base, const std::string& jsonText,
                               const std::string& source) {
  std::vector<std::string> chain;
  const PresetSource src{source, "", base.name, &base};
  return parsePreset(JsonReader::parseText(jsonText, source), src, chain);
}

FurParams loadFurPreset(const std::string& nameOrPath) {
  std::vector<std::string> chain;
  return loadPresetIn(nameOrPath, "", chain, "");
}

std::string furPresetJson(const FurParams& p) {
  nlohmann::json j;
  j["name"] = p.name;
  if (p.coverage > 0.0)
    j["coverage"] = p.coverage;
  else if (p.densityPerM2 > 0.0)
    j["density"] = p.densityPerM2;
  else
    j["hairs"] = p.hairs;
  j["undercoatShare"] = p.undercoatShare;
  j["seed"] = p.seed;
  j["lengthScale"] = p.lengthScale;
  const LengthRegion& r = p.lengthRegion;
  if (r.shape == RegionShape::Sphere)
    j["lengthRegion"] = {{"sphere", {{"center", colorJson(r.center)}, {"radius", r.radius}}},
                         {"scale", r.scale}};
  if (r.shape == RegionShape::Box)
    j["lengthRegion"] = {{"box", {{"min", colorJson(r.boxMin)}, {"max", colorJson(r.boxMax)}}},
                         {"scale", r.scale}};
  if (!p.regions.empty()) {
    nlohmann::json list = nlohmann::json::array();
    for (const FurRegion& g : p.regions) {
      nlohmann::json region = {{"match", g.match},
                               {"lengthScale", g.lengthScale},
                               {"lengthMm", g.lengthMm},
                               {"densityScale", g.densityScale},
                               {"tint", colorJson(g.tint)}};
      if (g.stiffness) region["stiffness"] = {g.stiffness->x(), g.stiffness->y()};
      if (g.segmentDirectionWeight)
        region["segmentDirectionWeight"] = {g.segmentDirectionWeight->x(),
                                            g.segmentDirectionWeight->y()};
      if (g.curlRadius) region["curl"]["radius"] = {g.curlRadius->x(), g.curlRadius->y()};
      if (g.curlTurns) region["curl"]["turns"] = {g.curlTurns->x(), g.curlTurns->y()};
      if (g.widthScale) region["widthScale"] = {g.widthScale->x(), g.widthScale->y()};
      if (g.colorSource)
        region["colorSource"] = {colorSourceName((*g.colorSource)[0]),
                                 colorSourceName((*g.colorSource)[1])};
      list.push_back(std::move(region));
    }
    j["regions"] = list;
  }
  j["up"] = colorJson(p.up);
  j["culling"] = {{"enabled", p.culling.enabled},
                  {"referenceDistance", p.culling.referenceDistance},
                  {"fovDegrees", p.culling.fovYDegrees},
                  {"referenceHeight", p.culling.referenceHeight}};
  if (p.maps.any()) {
    nlohmann::json m = nlohmann::json::object();
    if (!p.maps.density.empty()) m["density"] = p.maps.density;
    if (!p.maps.length.empty()) m["length"] = p.maps.length;
    if (!p.maps.color.empty()) m["color"] = p.maps.color;
    j["maps"] = m;
  }
  if (!p.groom.empty()) j["groom"] = p.groom;
  j["overcoat"] = coatJson(p.coats[kOvercoat]);
  j["undercoat"] = coatJson(p.coats[kUndercoat]);
  return j.dump(2) + "\n";
}

void saveFurPreset(const std::string& path, const FurParams& params) {
  writeFileAtomically(path, furPresetJson(params));
}

}  // namespace pelage::fur
