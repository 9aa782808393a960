#include "pelage/scene/draw_list.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>

#include "pelage/fur/hair_math.h"
#include "pelage/scene/frame.h"
#include "pelage/util/error.h"

namespace pelage::scene {
namespace {

constexpr float kPi = 3.14159265358979f;
float radians(float deg) {
  return deg * kPi / 180.0f;
}

// Whether `text` contains the lower-case `word`, ignoring case (no allocation: runs per frame).
bool containsNoCase(std::string_view text, std::string_view word) {
  if (word.size() > text.size()) return false;
  for (std::size_t i = 0; i + word.size() <= text.size(); ++i) {
    std::size_t k = 0;
    while (k < word.size() && std::tolower(static_cast<unsigned char>(text[i + k])) == word[k]) ++k;
    if (k == word.size()) return true;
  }
  return false;
}

// Index of the first segment whose name contains "head" (case-insensitive), or -1.
int headSegment(const anatomy::Body& body) {
  for (int i = 0; i < body.size(); ++i)
    if (containsNoCase(body.segments[static_cast<std::size_t>(i)].name, "head")) return i;
  return -1;
}

// Centre and radius of the bounding sphere (about the box centre) of the selected vertices.
template <typename Select>
bool sphereOf(const std::vector<Eigen::Vector3f>& p, Select select, Eigen::Vector3f& center,
              float& radius) {
  Eigen::AlignedBox3f box;
  for (std::size_t v = 0; v < p.size(); ++v)
    if (select(v)) box.extend(p[v]);
  if (box.isEmpty()) return false;
  center = box.center();
  float r2 = 0.0f;
  for (std::size_t v = 0; v < p.size(); ++v)
    if (select(v)) r2 = std::max(r2, (p[v] - center).squaredNorm());
  radius = std::sqrt(r2);
  return true;
}

// Distance at which a sphere of radius r fits the narrower field of view, with a 10% margin.
float fitDistance(float radius, float fovYDegrees, float aspect) {
  const float halfY = radians(fovYDegrees) * 0.5f;
  const float halfX = std::atan(std::tan(halfY) * aspect);
  const float half = std::min(halfX, halfY);
  return 1.1f * radius / std::sin(half);
}

Eigen::Vector3f direction(const Eigen::Vector3f& forward, float azimuthFromForwardDeg,
                          float elevationDeg) {
  const Eigen::Vector3f left = Eigen::Vector3f::UnitZ().cross(forward).normalized();
  const float az = radians(azimuthFromForwardDeg), el = radians(elevationDeg);
  return (std::cos(el) * (std::cos(az) * forward + std::sin(az) * left) +
          std::sin(el) * Eigen::Vector3f::UnitZ())
      .normalized();
}

// Places `cam` (looking along -dir) as close as it can be with every corner of `box` inside the
// view with a 10% margin, the box centred on screen: for a corner at lateral offsets (x, y) from
// the view axis and height z above the box centre along dir, the eye distance D must satisfy |x -
// cx| <= tan(halfX) (D - z) / 1.1 (and the same for y), where (cx, cy) centres the corners' lateral
// extent. Tighter than the bounding sphere for long, thin creatures (a monkey with its tail up), so
// the creature fills the view. Also sets the clip planes around the corners.
void fitBox(Camera& cam, const Eigen::AlignedBox3f& box, const Eigen::Vector3f& dir) {
  const Eigen::Vector3f f = -dir;
  Eigen::Vector3f s = f.cross(cam.up);
  if (s.squaredNorm() < 1e-12f) s = f.cross(Eigen::Vector3f::UnitY());
  s.normalize();
  const Eigen::Vector3f u = s.cross(f);
  const Eigen::Vector3f c = box.center();
  float minX = 0, maxX = 0, minY = 0, maxY = 0;
  std::array<Eigen::Vector3f, 8> corners;
  for (int i = 0; i < 8; ++i) {
    corners[static_cast<std::size_t>(i)] =
        box.corner(static_cast<Eigen::AlignedBox3f::CornerType>(i)) - c;
    const float x = corners[static_cast<std::size_t>(i)].dot(s),
                y = corners[static_cast<std::size_t>(i)].dot(u);
    minX = i ? std::min(minX, x) : x;
    maxX = i ? std::max(maxX, x) : x;
    minY = i ? std::min(minY, y) : y;
    maxY = i ? std::max(maxY, y) : y;
  }
  const float cx = 0.5f * (minX + maxX), cy = 0.5f * (minY + maxY);
  const float tanY = std::tan(radians(cam.fovYDegrees) * 0.5f), tanX = tanY * cam.aspect();
  float D = 0.0f;
  for (const Eigen::Vector3f& r : corners) {
    const float z = r.dot(dir);
    D = std::max(D, z + 1.1f * std::abs(r.dot(s) - cx) / tanX);
    D = std::max(D, z + 1.1f * std::abs(r.dot(u) - cy) / tanY);
  }
  float nearest = 0.0f, farthest = 0.0f;
  for (std::size_t i = 0; i < corners.size(); ++i) {
    const float depth = D - corners[i].dot(dir);
    nearest = i ? std::min(nearest, depth) : depth;
    farthest = i ? std::max(farthest, depth) : depth;
  }
  cam.target = c + cx * s + cy * u;
  cam.eye = cam.target + dir * D;
  const float size = std::max(box.diagonal().norm(), 1e-4f);
  cam.nearMeters = std::max(nearest * 0.8f, size * 0.01f);
  cam.farMeters = farthest * 1.25f + size * 0.01f;
}

void setClipPlanes(Camera& cam, const Eigen::Vector3f& center, float radius) {
  const float d = (cam.eye - center).norm();
  const float r = std::max(radius, 1e-4f);
  cam.nearMeters = std::max((d - r) * 0.8f, r * 0.01f);
  cam.farMeters = (d + r) * 1.25f;
}

}  // namespace

Eigen::Matrix4f Camera::view() const {
  const Eigen::Vector3f f = (target - eye).normalized();
  Eigen::Vector3f s = f.cross(up);
  if (s.squaredNorm() < 1e-12f) s = f.cross(Eigen::Vector3f::UnitY());  // looking straight up/down
  s.normalize();
  const Eigen::Vector3f u = s.cross(f);
  Eigen::Matrix4f m = Eigen::Matrix4f::Identity();
  m.block<1, 3>(0, 0) = s.transpose();
  m.block<1, 3>(1, 0) = u.transpose();
  m.block<1, 3>(2, 0) = -f.transpose();
  m(0, 3) = -s.dot(eye);
  m(1, 3) = -u.dot(eye);
  m(2, 3) = f.dot(eye);
  return m;
}

Eigen::Matrix4f Camera::projection() const {
  const float t = 1.0f / std::tan(radians(fovYDegrees) * 0.5f);
  const float n = nearMeters, f = farMeters;
  Eigen::Matrix4f m = Eigen::Matrix4f::Zero();
  m(0, 0) = t / aspect();
  m(1, 1) = t;
  m(2, 2) = (f + n) / (n - f);
  m(2, 3) = 2.0f * f * n / (n - f);
  m(3, 2) = -1.0f;
  return m;
}

std::string_view cameraPresetName(CameraPreset preset) {
  switch (preset) {
    case CameraPreset::Front:
      return "front";
    case CameraPreset::Side:
      return "side";
    case CameraPreset::ThreeQuarter:
      return "three-quarter";
    case CameraPreset::Face:
      return "face";
    case CameraPreset::Follow:
      return "follow";
  }
  return "?";
}

CameraPreset parseCameraPreset(std::string_view name) {
  for (CameraPreset p : {CameraPreset::Front, CameraPreset::Side, CameraPreset::ThreeQuarter,
                         CameraPreset::Face, CameraPreset::Follow})
    if (name == cameraPresetName(p)) return p;
  inputError("unknown camera preset '", name,
             "' (accepted: front, side, three-quarter, face, follow)");
}

std::string_view hairShadingName(HairShading shading) {
  return shading == HairShading::Paper ? "paper" : "kajiya-kay";
}

HairShading parseHairShading(std::string_view name) {
  if (name == "paper") return HairShading::Paper;
  if (name == "kajiya-kay") return HairShading::KajiyaKay;
  inputError("unknown hair shading '", name, "' (accepted: paper, kajiya-kay)");
}

Framing framingOf(const Model& model, const FrameState& frame, float maxHairLengthMeters) {
  PELAGE_CHECK(!frame.skin.positions.empty(), "framingOf before evaluateFrame");
  const std::vector<Eigen::Vector3f>& p = frame.skin.positions;
  const float margin = std::max(maxHairLengthMeters, 0.0f);
  Framing f;
  f.bounds = frame.skinBounds;
  f.bounds.extend(frame.skinBounds.min() - Eigen::Vector3f::Constant(margin));
  f.bounds.extend(frame.skinBounds.max() + Eigen::Vector3f::Constant(margin));
  sphereOf(
      p, [](std::size_t) { return true; }, f.center, f.radius);
  f.radius += margin;
  f.rootPosition =
      frame.body.world.empty() ? f.center : Eigen::Vector3f(frame.body.world[0].translation());

  const int head = headSegment(model.body);
  if (head >= 0) {
    Eigen::Vector3f d = frame.body.world[static_cast<std::size_t>(head)].translation() - f.center;
    d.z() = 0.0f;
    if (d.norm() > 1e-3f * std::max(f.radius, 1e-3f)) f.forward = d.normalized();
  }

  int faceRegion = -1;
  for (std::size_t r = 0; r < model.skin.regionNames.size(); ++r)
    if (model.skin.regionNames[r].size() == 4 && containsNoCase(model.skin.regionNames[r], "face"))
      faceRegion = static_cast<int>(r);
  const std::int32_t* regions = model.skin.regions();
  const skin::Binding* bind = model.skin.bindings();
  bool found = false;
  if (faceRegion >= 0)
    found = sphereOf(
        p, [&](std::size_t v) { return regions[v] == faceRegion; }, f.faceCenter, f.faceRadius);
  if (!found && head >= 0)
    found = sphereOf(
        p, [&](std::size_t v) { return bind[v].segment[0] == head; }, f.faceCenter, f.faceRadius);
  if (!found) {
    f.faceCenter = f.center;
    f.faceRadius = f.radius;
  } else {
    f.faceRadius += margin;
  }
  return f;
}

Camera presetCamera(const Framing& framing, CameraPreset preset, int width, int height,
                    float fovYDegrees) {
  PELAGE_CHECK(width > 0 && height > 0);
  Camera cam;
  cam.width = width;
  cam.height = height;
  cam.fovYDegrees = fovYDegrees;
  Eigen::Vector3f target = framing.center;
  float radius = framing.radius;
  Eigen::Vector3f dir = Eigen::Vector3f::UnitX();
  switch (preset) {
    case CameraPreset::Front:
      dir = direction(framing.forward, 0.0f, 10.0f);
      break;
    case CameraPreset::Side:
      dir = direction(framing.forward, 90.0f, 5.0f);
      break;
    case CameraPreset::ThreeQuarter:
      dir = direction(framing.forward, 45.0f, 20.0f);
      break;
    case CameraPreset::Face:
      dir = direction(framing.forward, 30.0f, 10.0f);
      target = framing.faceCenter;
      radius = framing.faceRadius * 1.15f;
      break;
    case CameraPreset::Follow:
      // From behind and above the root segment; the sphere about the root covers the body.
      dir = direction(framing.forward, 150.0f, 25.0f);
      target = framing.rootPosition;
      radius = framing.radius + (framing.center - framing.rootPosition).norm();
      break;
  }
  const bool wholeBody = preset == CameraPreset::Front || preset == CameraPreset::Side ||
                         preset == CameraPreset::ThreeQuarter;
  if (wholeBody && !framing.bounds.isEmpty()) {
    fitBox(cam, framing.bounds, dir);
    return cam;
  }
  cam.target = target;
  cam.eye = target + dir * fitDistance(radius, fovYDegrees, cam.aspect());
  setClipPlanes(cam, framing.center, framing.radius);
  if (preset == CameraPreset::Face)
    cam.nearMeters = std::min(cam.nearMeters, (cam.eye - target).norm() * 0.5f);
  return cam;
}

Camera orbitCamera(const Orbit& orbit, int width, int height, float fovYDegrees) {
  Camera cam;
  cam.width = width;
  cam.height = height;
  cam.fovYDegrees = fovYDegrees;
  cam.target = orbit.target;
  const float az = radians(orbit.azimuthDegrees), el = radians(orbit.elevationDegrees);
  cam.eye = orbit.target + orbit.distanceMeters * Eigen::Vector3f(std::cos(el) * std::cos(az),
                                                                  std::cos(el) * std::sin(az),
                                                                  std::sin(el));
  cam.nearMeters = orbit.distanceMeters * 0.02f;
  cam.farMeters = orbit.distanceMeters * 20.0f;
  return cam;
}

Orbit orbitOf(const Camera& camera) {
  Orbit o;
  o.target = camera.target;
  const Eigen::Vector3f d = camera.eye - camera.target;
  o.distanceMeters = d.norm();
  if (o.distanceMeters > 0.0f) {
    o.elevationDegrees =
        std::asin(std::clamp(d.z() / o.distanceMeters, -1.0f, 1.0f)) * 180.0f / kPi;
    o.azimuthDegrees = std::atan2(d.y(), d.x()) * 180.0f / kPi;
  }
  return o;
}

Eigen::Vector3f lightDirection(float azimuthDegrees, float elevationDegrees) {
  const float az = radians(azimuthDegrees), el = radians(elevationDegrees);
  return {std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el)};
}

Material skinMaterial(const Eigen::Vector3f& color) {
  Material m;
  m.ambient = color;
  m.diffuse = color;
  m.specular = Eigen::Vector3f::Constant(0.08f);
  m.shininess = 24.0f;
  return m;
}

std::int64_t DrawList::drawnHairs() const {
  std::int64_t n = 0;
  for (const FurDrawItem& f : fur) n += f.drawnHairs;
  return n;
}

Material furMaterial(const fur::Material& m) {
  Material out;
  out.ambient = m.ambient;
  out.diffuse = m.diffuse;
  out.specular = m.specular;
  out.shininess = m.shininess;
  return out;
}

void buildDrawList(const Model& model, const FrameState& frame, const Fur* fur,
                   const Camera& camera, const Light& light, const DrawOptions& options,
                   DrawList& list) {
  list.camera = camera;
  list.light = light;
  list.hairShading = options.hairShading;
  list.hairWidth = options.hairWidth;
  list.bounds = frame.skinBounds;
  list.skin = SkinDrawItem{};
  if (options.drawSkin) {
    list.skin.material = skinMaterial(model.skin.color);
    list.skin.positions = &frame.skin.positions;
    list.skin.normals = &frame.skin.normals;
    list.skin.triangles = &model.skin.triangles;
    list.skin.vertices = model.skin.numVertices();
    list.skin.triangleCount = model.skin.numTriangles();
  }
  list.fur.clear();
  list.gpuFur = GpuFurInputs{};
  if (!fur || !options.drawFur) return;
  const bool cpu = options.hairSource == HairSource::Cpu;
  PELAGE_CHECK(!cpu || frame.cpuFur, "CPU hair source without evaluateFur(..., cpuHairs = true)");
  if (!cpu)
    list.gpuFur =
        GpuFurInputs{&fur->params, &fur->roots, fur->generation, &model.skin, &frame.skin};
  const float pad = maxHairLength(model, fur->params);
  list.bounds.extend(frame.skinBounds.min() - Eigen::Vector3f::Constant(pad));
  list.bounds.extend(frame.skinBounds.max() + Eigen::Vector3f::Constant(pad));
  for (int c = 0; c < fur::kCoatCount; ++c) {
    const auto ci = static_cast<std::size_t>(c);
    const std::int64_t roots = fur->roots.coats[ci].size();
    if (roots == 0) continue;
    const fur::CoatParams& cp = fur->params.coats[ci];
    FurDrawItem item;
    item.coat = c;
    item.style = cp.style;
    item.material = furMaterial(cp.material);
    switch (cp.style) {
      case fur::HairStyle::Line:
        item.strandPoints = 2;
        break;
      case fur::HairStyle::Polyline:
        item.strandPoints = fur::kPolylinePoints;
        break;
      case fur::HairStyle::Curve:
        item.strandPoints = cp.curvePoints;
        break;
      case fur::HairStyle::Tube:
        item.strandPoints = cp.curvePoints;
        item.strandStride = cp.tubeSides;
        item.triangles = true;
        break;
    }
    item.rootCount = roots;
    item.drawnHairs = frame.drawnHairs[ci];
    item.cullFactor = frame.cullFactor;
    item.source = options.hairSource;
    if (cpu) {
      const fur::HairBuffers& hb = frame.fur.coats[ci];
      PELAGE_CHECK(hb.pointsPerHair == item.pointsPerHair(), "CPU hairs of coat ", c, " have ",
                   hb.pointsPerHair, " points, the parameters ", item.pointsPerHair());
      item.positions = hb.positions.data();
      item.normals = hb.normals.data();
    }
    list.fur.push_back(item);
  }
}

}  // namespace pelage::scene
