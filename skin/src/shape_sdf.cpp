// The creature's signed distance field: the smooth union of its body shapes (shape_sdf.h). In its
// own translation unit, every function it calls inlined or local to it (no inline function shared
// with an instrumented unit, whose copy the linker could pick), so that the sanitizer build can
// leave it uninstrumented (skin/CMakeLists.txt): it is pure arithmetic on the shapes' values, and
// ASan + UBSan made it 19 times slower (61 s instead of 3.2 s to build the monkey's skin), which
// made every test process that builds the monkey take about two minutes under the sanitizers.
#include "shape_sdf.h"
#include "pelage/skin/build_from_shapes.h"

#include <algorithm>
#include <cmath>

namespace pelage::skin {
namespace detail {
namespace {

// Ellipsoid: the "k0 (k0 - 1) / k1" approximation (exact on the surface, close near it).
float ellipsoidDistance(const anatomy::Shape& s, const Eigen::Vector3f& p) {
  const Eigen::Vector3f q = s.rotation.conjugate() * (p - s.center);
  const float k0 = (q.array() / s.radii.array()).matrix().norm();
  const float k1 = (q.array() / (s.radii.array() * s.radii.array())).matrix().norm();
  if (k1 < 1e-20f) return -s.radii.minCoeff();
  return k0 * (k0 - 1.0f) / k1;
}

// Round cone: spheres of radius rFrom at `from` and rTo at `to`, joined by their tangent cone.
float capsuleDistance(const anatomy::Shape& s, const Eigen::Vector3f& p) {
  const Eigen::Vector3d a = s.from.cast<double>(), b = s.to.cast<double>(), x = p.cast<double>();
  const double r1 = static_cast<double>(s.rFrom), r2 = static_cast<double>(s.rTo);
  const Eigen::Vector3d ba = b - a;
  const double l2 = ba.squaredNorm();
  if (l2 < 1e-18) return static_cast<float>((x - a).norm() - std::max(r1, r2));
  const double rr = r1 - r2;
  const double a2 = l2 - rr * rr;
  if (a2 <= 0.0) {  // one sphere contains the other
    return static_cast<float>(std::min((x - a).norm() - r1, (x - b).norm() - r2));
  }
  const double il2 = 1.0 / l2;
  const Eigen::Vector3d pa = x - a;
  const double y = pa.dot(ba);
  const double z = y - l2;
  const double x2 = (pa * l2 - ba * y).squaredNorm();
  const double y2 = y * y * l2;
  const double z2 = z * z * l2;
  const double k = (rr > 0 ? 1.0 : (rr < 0 ? -1.0 : 0.0)) * rr * rr * x2;
  const double sz = z > 0 ? 1.0 : (z < 0 ? -1.0 : 0.0);
  const double sy = y > 0 ? 1.0 : (y < 0 ? -1.0 : 0.0);
  if (sz * a2 * z2 > k) return static_cast<float>(std::sqrt(x2 + z2) * il2 - r2);
  if (sy * a2 * y2 < k) return static_cast<float>(std::sqrt(x2 + y2) * il2 - r1);
  return static_cast<float>((std::sqrt(x2 * a2 * il2) + y * rr) * il2 - r1);
}

}  // namespace

float shapeDistance(const anatomy::Shape& s, const Eigen::Vector3f& p) {
  return s.kind == anatomy::Shape::Kind::Ellipsoid ? ellipsoidDistance(s, p)
                                                   : capsuleDistance(s, p);
}

}  // namespace detail

float creatureDistance(const anatomy::Creature& c, const Eigen::Vector3f& p) {
  float acc = detail::shapeDistance(c.shapes[0], p);
  for (std::size_t i = 1; i < c.shapes.size(); ++i)
    acc = detail::smoothMin(acc, detail::shapeDistance(c.shapes[i], p),
                            detail::shapeBlend(c, c.shapes[i]));
  return acc;
}

}  // namespace pelage::skin
