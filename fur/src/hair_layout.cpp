#include "pelage/fur/hair_layout.h"

#include "pelage/fur/fur_params.h"
#include "pelage/fur/hair_math.h"
#include "pelage/util/enum_names.h"
#include "pelage/util/error.h"

namespace pelage::fur {

namespace {

constexpr auto kStyleNames = makeEnumNames<HairStyle>({{HairStyle::Line, "line"},
                                                       {HairStyle::Polyline, "polyline"},
                                                       {HairStyle::Curve, "curve"},
                                                       {HairStyle::Tube, "tube"}});

}  // namespace

const char* styleName(HairStyle style) {
  return kStyleNames.name(style).data();
}

std::string styleNames() {
  return kStyleNames.list();
}

HairStyle parseStyle(std::string_view name, const std::string& where) {
  if (const auto s = kStyleNames.find(name)) return *s;
  inputError(where, ": unknown hair style '", excerpt(name), "' (accepted: ", styleNames(), ")");
}

HairLayout hairLayout(const CoatParams& coat) {
  HairLayout l;
  l.style = coat.style;
  switch (coat.style) {
    case HairStyle::Line:  // sec. 3.6: root and ending point
      l.strandPoints = 2;
      break;
    case HairStyle::Polyline:  // sec. 3.7: "eight control points"
      l.strandPoints = kPolylinePoints;
      break;
    case HairStyle::Curve:  // sec. 3.8 nurbs curve, tessellated at K points
      l.strandPoints = coat.curvePoints;
      l.basis = CurveBasis::Bezier;
      l.curl = coat.curlRadius > 0.0f;
      break;
    case HairStyle::Tube:  // sec. 3.8 nurbs surface: M-point rings around the K curve points
      l.strandPoints = coat.curvePoints;
      l.ringSides = coat.tubeSides;
      l.topology = HairTopology::Rings;
      l.basis = CurveBasis::Bezier;
      l.curl = coat.curlRadius > 0.0f;
      break;
  }
  return l;
}

int pointsPerHair(const CoatParams& coat) {
  return hairLayout(coat).pointsPerHair();
}

int HairLayout::segmentsPerHair() const {
  switch (topology) {
    case HairTopology::Strand:
      return pointsPerHair() - 1;
    case HairTopology::Rings:
      return 0;
  }
  return 0;
}

int HairLayout::trianglesPerHair() const {
  switch (topology) {
    case HairTopology::Strand:
      return 0;
    case HairTopology::Rings:
      return (strandPoints - 1) * ringSides * 2;
  }
  return 0;
}

int HairLayout::indicesPerHair() const {
  switch (topology) {
    case HairTopology::Strand:
      return pointsPerHair() + 1;
    case HairTopology::Rings:
      return 3 * trianglesPerHair();
  }
  return 0;
}

double HairLayout::frameBytesPerHair() const {
  return static_cast<double>(pointsPerHair()) * 6.0 * sizeof(float) + sizeof(std::int32_t);
}

int HairLayout::curveVertices() const {
  switch (basis) {
    case CurveBasis::Linear:
      return strandPoints;
    case CurveBasis::Bezier:
      return curl ? 3 * (strandPoints - 1) + 1 : 4;
  }
  return 0;
}

bool usesCurveParams(HairStyle style) {
  switch (style) {
    case HairStyle::Line:
    case HairStyle::Polyline:
      return false;
    case HairStyle::Curve:
    case HairStyle::Tube:
      return true;
  }
  return false;
}

bool usesTubeParams(HairStyle style) {
  switch (style) {
    case HairStyle::Line:
    case HairStyle::Polyline:
    case HairStyle::Curve:
      return false;
    case HairStyle::Tube:
      return true;
  }
  return false;
}

std::vector<std::int32_t> tubeTriangles(int curvePoints, int tubeSides) {
  std::vector<std::int32_t> tri;
  const int K = curvePoints, M = tubeSides;
  PELAGE_CHECK(K >= 2 && M >= 3, "tube of ", K, " x ", M, " points");
  tri.reserve(static_cast<std::size_t>((K - 1) * M * 6));
  for (int k = 0; k + 1 < K; ++k)
    for (int j = 0; j < M; ++j) {
      const int a = k * M + j, b = k * M + (j + 1) % M;
      const int c = (k + 1) * M + j, d = (k + 1) * M + (j + 1) % M;
      tri.insert(tri.end(), {a, c, d, a, d, b});
    }
  return tri;
}

std::vector<std::int32_t> hairTriangles(const HairLayout& layout) {
  switch (layout.topology) {
    case HairTopology::Strand:
      return {};
    case HairTopology::Rings:
      return tubeTriangles(layout.strandPoints, layout.ringSides);
  }
  return {};
}

std::vector<std::uint32_t> hairIndexPattern(const HairLayout& layout, std::uint32_t restart) {
  std::vector<std::uint32_t> pattern;
  pattern.reserve(static_cast<std::size_t>(layout.indicesPerHair()));
  switch (layout.topology) {
    case HairTopology::Strand:
      for (int i = 0; i < layout.pointsPerHair(); ++i)
        pattern.push_back(static_cast<std::uint32_t>(i));
      pattern.push_back(restart);
      break;
    case HairTopology::Rings:
      for (std::int32_t i : hairTriangles(layout)) pattern.push_back(static_cast<std::uint32_t>(i));
      break;
  }
  return pattern;
}

}  // namespace pelage::fur
