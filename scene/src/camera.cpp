#include "pelage/scene/camera.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>

#include "pelage/scene/frame.h"
#include "pelage/scene/frame_range.h"
#include "pelage/util/enum_names.h"
#include "pelage/util/error.h"
#include "pelage/util/json_reader.h"

namespace pelage::scene {

void validateImageSize(int width, int height, std::string_view field) {
  if (width < kMinImageSide || width > kMaxImageSide || height < kMinImageSide ||
      height > kMaxImageSide)
    fieldError(std::string(field), width, "x", height, " is out of range [", kMinImageSide, ", ",
               kMaxImageSide, "] per side");
}

void validateSamples(int samples, std::string_view field) {
  if (samples < -1 || samples > kMaxSamples)
    fieldError(std::string(field), samples, " is out of range [-1, ", kMaxSamples, "]");
}

void validateFov(double degrees, std::string_view field) {
  if (!(degrees > kMinFovYDegrees && degrees < kMaxFovYDegrees))
    fieldError(std::string(field), degrees, " is out of range (", kMinFovYDegrees, ", ",
               kMaxFovYDegrees, ") degrees");
}

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
// the creature fills the view.
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
  cam.target = c + cx * s + cy * u;
  cam.eye = cam.target + dir * D;
}

}  // namespace

fur::ViewCamera viewCamera(const Camera& camera) {
  fur::ViewCamera v;
  v.eye = camera.eye;
  v.fovYDegrees = camera.fovYDegrees;
  v.imageHeight = camera.height;
  return v;
}

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

namespace {

constexpr auto kCameraPresetNames =
    makeEnumNames<CameraPreset>({{CameraPreset::Front, "front"},
                                 {CameraPreset::Side, "side"},
                                 {CameraPreset::ThreeQuarter, "three-quarter"},
                                 {CameraPreset::Face, "face"},
                                 {CameraPreset::Follow, "follow"}});

}  // namespace

std::string_view cameraPresetName(CameraPreset preset) {
  return kCameraPresetNames.name(preset);
}

std::string cameraPresetNames() {
  return kCameraPresetNames.list();
}

CameraPreset parseCameraPreset(std::string_view name, std::string_view field) {
  if (const auto p = kCameraPresetNames.find(name)) return *p;
  fieldError(std::string(field), ": unknown camera preset '", excerpt(name),
             "' (accepted: ", cameraPresetNames(), ")");
}

void fitClipPlanes(Camera& camera, const Framing& framing) {
  const float d = (camera.eye - framing.center).norm();
  camera.nearMeters = std::max((d - framing.radius) * 0.5f, framing.radius * 0.002f);
  camera.farMeters = d + framing.radius * 2.0f;
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
  } else {
    cam.target = target;
    cam.eye = target + dir * fitDistance(radius, fovYDegrees, cam.aspect());
  }
  fitClipPlanes(cam, framing);
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

namespace {

CameraPath parseCameraJson(const nlohmann::json& doc, const std::string& source) {
  const JsonReader root(doc, source);
  if (!root.isObject()) root.fail("a camera file is a JSON object");
  CameraPath out;
  auto readKey = [](const JsonReader& j, CameraKey& k) {
    k.eye = j.vec3("eye");
    k.target = j.vec3("target");
    k.up = j.vec3("up", Eigen::Vector3f::UnitZ());
    k.fovYDegrees = static_cast<float>(
        j.number("fovYDegrees", kDefaultFovYDegrees, kMinFovYDegrees, kMaxFovYDegrees));
    if ((k.eye - k.target).norm() < 1e-6f) j.fail("eye and target must differ");
    if (k.up.norm() < 1e-6f ||
        (k.eye - k.target).normalized().cross(k.up.normalized()).norm() < 1e-4f)
      j.fail("up must be non-zero and not parallel to the view direction");
  };
  if (root.has("keys")) {
    root.rejectUnknown({"keys", "track"});
    const JsonReader keys = root.at("keys");
    if (!keys.isArray() || keys.size() == 0) keys.fail("needs at least one key");
    for (std::size_t i = 0; i < keys.size(); ++i) {
      const JsonReader k = keys.at(i);
      k.rejectUnknown({"frame", "eye", "target", "up", "fovYDegrees"});
      CameraKey key;
      key.frame = static_cast<int>(k.integer("frame", 0, kMaxFrameNumber));
      readKey(k, key);
      if (!out.keys.empty() && key.frame <= out.keys.back().frame)
        k.fail("key frames must increase (" + std::to_string(key.frame) + " after " +
               std::to_string(out.keys.back().frame) + ")");
      out.keys.push_back(key);
    }
  } else {
    root.rejectUnknown({"eye", "target", "up", "fovYDegrees", "track"});
    CameraKey key;
    readKey(root, key);
    out.keys.push_back(key);
  }
  out.track = root.boolean("track", false);
  return out;
}

}  // namespace

CameraPath loadCameraFile(const std::string& path) {
  const nlohmann::json doc = JsonReader::parseFile(path);
  return parseCameraJson(doc, path);
}

CameraPath parseCameraFile(const std::string& text, const std::string& source) {
  return parseCameraJson(JsonReader::parseText(text, source), source);
}

Camera cameraOnPath(const CameraPath& path, int frame, int width, int height) {
  PELAGE_CHECK(!path.keys.empty());
  Camera cam;
  cam.width = width;
  cam.height = height;
  const std::vector<CameraKey>& k = path.keys;
  std::size_t i = 0;
  while (i + 1 < k.size() && k[i + 1].frame <= frame) ++i;
  const CameraKey& a = k[i];
  if (frame <= a.frame || i + 1 == k.size()) {
    cam.eye = a.eye;
    cam.target = a.target;
    cam.up = a.up;
    cam.fovYDegrees = a.fovYDegrees;
    return cam;
  }
  const CameraKey& b = k[i + 1];
  const float s = static_cast<float>(frame - a.frame) / static_cast<float>(b.frame - a.frame);
  cam.eye = a.eye + s * (b.eye - a.eye);
  cam.target = a.target + s * (b.target - a.target);
  cam.up = (a.up + s * (b.up - a.up)).normalized();
  cam.fovYDegrees = a.fovYDegrees + s * (b.fovYDegrees - a.fovYDegrees);
  return cam;
}

Camera rigCamera(const CameraRig& rig, const Framing& first, const Framing& current, int frame,
                 int width, int height) {
  Camera cam;
  bool track = rig.track;
  if (rig.path) {
    cam = cameraOnPath(*rig.path, frame, width, height);
    track = track || rig.path->track;
  } else {
    cam = presetCamera(first, rig.preset, width, height, rig.fovYDegrees);
    track = track || rig.preset == CameraPreset::Follow;
  }
  if (track) {
    Eigen::Vector3f d = current.rootPosition - first.rootPosition;
    d.z() = 0.0f;
    cam.eye += d;
    cam.target += d;
  }
  fitClipPlanes(cam, current);
  return cam;
}

}  // namespace pelage::scene
