#include "pelage/fur/groom_strokes.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include <nlohmann/json.hpp>

#include "pelage/skin/deform.h"
#include "pelage/util/enum_names.h"
#include "pelage/util/error.h"
#include "pelage/util/json_reader.h"
#include "pelage/util/parallel.h"

namespace pelage::fur {
namespace {

using Vec3 = Eigen::Vector3f;

constexpr auto kToolNames = makeEnumNames<BrushTool>({{BrushTool::Length, "length"},
                                                      {BrushTool::Density, "density"},
                                                      {BrushTool::Color, "color"},
                                                      {BrushTool::Comb, "comb"},
                                                      {BrushTool::Cut, "cut"},
                                                      {BrushTool::Clump, "clump"}});
constexpr const char* kAxes[] = {"x", "y", "z"};

// Distance from p to the polyline through `points` (a single point: to it), and the direction
// (not normalised) of the polyline's nearest segment (0 for a single point).
float polylineDistance(const std::vector<Vec3>& points, const Vec3& p, Vec3* direction = nullptr) {
  float best = (p - points[0]).squaredNorm();
  if (direction) direction->setZero();
  for (std::size_t i = 1; i < points.size(); ++i) {
    const Vec3 a = points[i - 1], ab = points[i] - a;
    const float len2 = ab.squaredNorm();
    const float t = len2 > 0.0f ? std::clamp((p - a).dot(ab) / len2, 0.0f, 1.0f) : 0.0f;
    const float d2 = (a + t * ab - p).squaredNorm();
    if (d2 < best || (direction && direction->isZero() && d2 == best)) {
      best = d2;
      if (direction && len2 > 0.0f) *direction = ab;
    }
  }
  return std::sqrt(best);
}

// One pass of `s` with its points as given (`restNormals`: the skin's rest vertex normals, for the
// comb).
void applyStroke(const skin::SkinMesh& skin, const GroomStroke& s, const std::vector<Vec3>& points,
                 const std::vector<Vec3>& restNormals, VertexGroom& g) {
  Eigen::AlignedBox3f box;
  for (const Vec3& p : points) box.extend(p);
  box.min().array() -= s.radius;
  box.max().array() += s.radius;
  const float* rest = skin.restPositions();
  parallelFor(skin.numVertices(), 1024, [&](std::int64_t v) {
    const Vec3 p = Eigen::Map<const Vec3>(rest + 3 * v);
    if (!box.contains(p)) return;
    Vec3 along;
    const float w = brushFalloff(polylineDistance(points, p, &along), s.radius);
    if (w <= 0.0f) return;
    const auto i = static_cast<std::size_t>(v);
    switch (s.tool) {
      case BrushTool::Length:
        g.length[i] =
            std::min(g.length[i] * (1.0f + w * (s.strength - 1.0f)), kMaxGroomLengthMeters);
        break;
      case BrushTool::Density:
        g.density[i] += w * (s.strength - g.density[i]);
        break;
      case BrushTool::Color:
        g.tint[i] += (w * s.strength) * (s.color - g.tint[i]);
        break;
      case BrushTool::Comb: {
        // The stroke's direction in the skin's tangent plane at the vertex; a convex step toward
        // it keeps |comb| <= 1.
        const Vec3& n = restNormals[i];
        const Vec3 t = along - along.dot(n) * n;
        const float len = t.norm();
        if (len > 1e-12f) g.comb[i] += (w * s.strength) * (t / len - g.comb[i]);
        break;
      }
      case BrushTool::Clump:
        g.clump[i] = std::lerp(g.clump[i], s.strength, w);  // exactly `strength` in the core
        break;
      case BrushTool::Cut:
        // std::lerp: exactly the cut length under the brush's core at strength 1, and exactly
        // the length where it is already shorter.
        g.length[i] = std::lerp(g.length[i], std::min(g.length[i], s.cutLength), w * s.strength);
        break;
    }
  });
}

// The strokes of a parsed strokes file.
std::vector<GroomStroke> strokesFrom(const JsonReader& root) {
  if (!root.isObject()) root.fail("expected a strokes file: {\"strokes\": [...]}");
  root.rejectUnknown({"strokes"});
  const JsonReader list = root.at("strokes");
  if (list.size() > kMaxGroomStrokes)
    list.fail(str(list.size(), " strokes; accepted: at most ", kMaxGroomStrokes));
  std::vector<GroomStroke> strokes(list.size());
  for (std::size_t k = 0; k < list.size(); ++k) {
    const JsonReader j = list.at(k);
    if (!j.isObject()) j.fail("expected a stroke object");
    j.rejectUnknown({"tool", "points", "radius", "strength", "color", "length", "mirror"});
    GroomStroke& s = strokes[k];
    const std::string tool = j.string("tool");
    const auto known = kToolNames.find(tool);
    if (!known)
      j.at("tool").fail(str("unknown brush '", tool, "' (accepted: ", kToolNames.list(), ")"));
    s.tool = *known;
    const JsonReader points = j.at("points");
    if (points.size() < 1 || points.size() > kMaxStrokePoints)
      points.fail(str(points.size(), " points; accepted: 1 to ", kMaxStrokePoints));
    for (std::size_t i = 0; i < points.size(); ++i) {
      const Vec3 p = points.at(i).asVec3();
      if (!p.allFinite()) points.at(i).fail("expected finite coordinates (metres)");
      s.points.push_back(p);
    }
    s.radius =
        static_cast<float>(j.number("radius", 1e-6, static_cast<double>(kMaxBrushRadiusMeters)));
    const StrengthRange range = brushStrengthRange(s.tool);
    // Length, density and clump strokes say their strength; the others default to full.
    const bool defaults =
        s.tool == BrushTool::Comb || s.tool == BrushTool::Cut || s.tool == BrushTool::Color;
    s.strength =
        static_cast<float>(defaults ? j.number("strength", 1.0, static_cast<double>(range.lo),
                                               static_cast<double>(range.hi))
                                    : j.number("strength", static_cast<double>(range.lo),
                                               static_cast<double>(range.hi)));
    switch (s.tool) {
      case BrushTool::Comb: {
        bool moves = false;
        for (const Vec3& p : s.points) moves = moves || p != s.points[0];
        if (!moves) points.fail("a comb stroke needs at least two distinct points (its direction)");
        break;
      }
      case BrushTool::Cut:
        s.cutLength =
            static_cast<float>(j.number("length", 0.0, static_cast<double>(kMaxGroomLengthMeters)));
        break;
      case BrushTool::Color: {
        s.color = j.vec3("color");
        for (int c = 0; c < 3; ++c)
          if (!(s.color[c] >= 0.0f && s.color[c] <= kMaxGroomTint))
            j.at("color").fail(str("component ", c, " = ", s.color[c], " is out of range [0, 10]"));
        break;
      }
      default:
        break;
    }
    if (s.tool != BrushTool::Color && j.has("color"))
      j.at("color").fail(str("only the color brush takes a colour (this is ", tool, ")"));
    if (s.tool != BrushTool::Cut && j.has("length"))
      j.at("length").fail(str("only the cut brush takes a length (this is ", tool, ")"));
    if (j.has("mirror")) {
      const std::string axis = j.string("mirror");
      const auto a = std::find(std::begin(kAxes), std::end(kAxes), axis);
      if (a == std::end(kAxes))
        j.at("mirror").fail(str("unknown axis '", axis, "' (accepted: x, y, z)"));
      s.mirrorAxis = static_cast<int>(a - std::begin(kAxes));
    }
  }
  return strokes;
}

}  // namespace

const char* brushToolName(BrushTool tool) {
  return kToolNames.name(tool).data();
}

StrengthRange brushStrengthRange(BrushTool tool) {
  switch (tool) {
    case BrushTool::Length:
      return {1e-6f, 10.0f};
    case BrushTool::Density:
      return {0.0f, kMaxGroomDensity};
    default:
      return {0.0f, 1.0f};
  }
}

void validateGroomStroke(const GroomStroke& s, const std::string& source, bool needPoints) {
  const std::string at = source + ": ";
  if (needPoints && (s.points.empty() || s.points.size() > kMaxStrokePoints))
    inputError(at, "points: ", s.points.size(), " points; accepted: 1 to ", kMaxStrokePoints);
  for (std::size_t i = 0; i < s.points.size(); ++i)
    if (!s.points[i].allFinite())
      inputError(at, "points[", i, "]: expected finite coordinates (metres)");
  if (needPoints && s.tool == BrushTool::Comb &&
      std::all_of(s.points.begin(), s.points.end(),
                  [&](const Vec3& p) { return p == s.points[0]; }))
    inputError(at, "points: a comb stroke needs at least two distinct points (its direction)");
  if (!(s.radius >= 1e-6f && s.radius <= kMaxBrushRadiusMeters))
    inputError(at, "radius = ", s.radius, " m is out of range (0, ", kMaxBrushRadiusMeters, "]");
  const StrengthRange r = brushStrengthRange(s.tool);
  if (!(s.strength >= r.lo && s.strength <= r.hi))
    inputError(at, "strength = ", s.strength, " is out of range [", r.lo, ", ", r.hi, "] for the ",
               brushToolName(s.tool), " brush");
  if (s.tool == BrushTool::Cut && !(s.cutLength >= 0.0f && s.cutLength <= kMaxGroomLengthMeters))
    inputError(at, "length = ", s.cutLength, " m is out of range [0, ", kMaxGroomLengthMeters, "]");
  for (int c = 0; c < 3 && s.tool == BrushTool::Color; ++c)
    if (!(s.color[c] >= 0.0f && s.color[c] <= kMaxGroomTint))
      inputError(at, "color: component ", c, " = ", s.color[c], " is out of range [0, 10]");
  if (s.mirrorAxis < -1 || s.mirrorAxis > 2)
    inputError(at, "mirror: axis ", s.mirrorAxis, " (accepted: x, y, z or none)");
}

float brushFalloff(float distance, float radius) {
  if (!(distance < radius)) return 0.0f;
  const float t = std::clamp(2.0f * (radius - distance) / radius, 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}

std::vector<GroomStroke> parseGroomStrokes(const std::string& text, const std::string& source) {
  const nlohmann::json doc = JsonReader::parseText(text, source);
  return strokesFrom(JsonReader(doc, source));
}

std::vector<GroomStroke> readGroomStrokes(const std::string& path) {
  const nlohmann::json doc = JsonReader::parseFile(path);
  return strokesFrom(JsonReader(doc, path));
}

std::string groomStrokesJson(const std::vector<GroomStroke>& strokes) {
  nlohmann::json list = nlohmann::json::array();
  for (const GroomStroke& s : strokes) {
    nlohmann::json j;
    j["tool"] = brushToolName(s.tool);
    nlohmann::json points = nlohmann::json::array();
    for (const Vec3& p : s.points)
      points.push_back({shortestDecimal(p.x()), shortestDecimal(p.y()), shortestDecimal(p.z())});
    j["points"] = points;
    j["radius"] = shortestDecimal(s.radius);
    j["strength"] = shortestDecimal(s.strength);
    if (s.tool == BrushTool::Color)
      j["color"] = {shortestDecimal(s.color.x()), shortestDecimal(s.color.y()),
                    shortestDecimal(s.color.z())};
    if (s.tool == BrushTool::Cut) j["length"] = shortestDecimal(s.cutLength);
    if (s.mirrorAxis >= 0) j["mirror"] = kAxes[s.mirrorAxis];
    list.push_back(j);
  }
  return nlohmann::json{{"strokes", list}}.dump() + "\n";
}

void applyGroomStrokes(const skin::SkinMesh& skin, const std::vector<GroomStroke>& strokes,
                       VertexGroom& g) {
  const auto n = static_cast<std::size_t>(skin.numVertices());
  std::vector<Vec3> restNormals;
  for (const GroomStroke& s : strokes)
    if (s.tool == BrushTool::Comb && restNormals.empty()) {
      skin::DeformedSkin rest;
      skin::restSkin(skin, rest);
      restNormals = std::move(rest.normals);
    }
  for (const GroomStroke& s : strokes) {
    if ((s.tool == BrushTool::Length || s.tool == BrushTool::Cut) && g.length.empty())
      g.length.assign(skin.furLengths(), skin.furLengths() + n);
    if (s.tool == BrushTool::Density && g.density.empty()) g.density.assign(n, 1.0f);
    if (s.tool == BrushTool::Color && g.tint.empty()) g.tint.assign(n, Vec3::Ones());
    if (s.tool == BrushTool::Comb && g.comb.empty()) g.comb.assign(n, Vec3::Zero());
    if (s.tool == BrushTool::Clump && g.clump.empty()) g.clump.assign(n, 1.0f);
    applyStroke(skin, s, s.points, restNormals, g);
    if (s.mirrorAxis >= 0) {
      std::vector<Vec3> mirrored = s.points;
      for (Vec3& p : mirrored) p[s.mirrorAxis] = -p[s.mirrorAxis];
      applyStroke(skin, s, mirrored, restNormals, g);
    }
  }
}

}  // namespace pelage::fur
