#include "pelage/anatomy/creature.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "pelage/util/error.h"
#include "pelage/util/json_reader.h"

namespace pelage::anatomy {
namespace {

constexpr double kMaxCoord = 1e4;  // metres; anything larger is certainly a unit mistake

Eigen::Vector3f point(const JsonReader& r) {
  const Eigen::Vector3f v = r.asVec3();
  if ((v.array().abs() > kMaxCoord).any())
    r.fail(str("coordinates must lie within [-", kMaxCoord, ", ", kMaxCoord, "] metres"));
  return v;
}

Eigen::Quaternionf rotationOf(const JsonReader& r) {
  r.rejectUnknown({"axis", "degrees"});
  Eigen::Vector3f axis = r.at("axis").asVec3();
  if (axis.norm() < 1e-6f) r.at("axis").fail("rotation axis must be non-zero");
  const double deg = r.number("degrees", -360.0, 360.0);
  return Eigen::Quaternionf(
      Eigen::AngleAxisf(static_cast<float>(deg * M_PI / 180.0), axis.normalized()));
}

int segmentIndex(const Body& body, const JsonReader& r) {
  const std::string name = r.asString();
  const int i = body.find(name);
  if (i < 0) r.fail("unknown segment '" + name + "'");
  return i;
}

}  // namespace

namespace {

// An sRGB colour field: three numbers in [0, 1].
Eigen::Vector3f colorField(const JsonReader& parent, const char* key) {
  const Eigen::Vector3f c = parent.vec3(key);
  if (!(c.array() >= 0.0f).all() || !(c.array() <= 1.0f).all())
    parent.at(key).fail("colour components must lie in [0, 1]");
  return c;
}

}  // namespace

Creature parseCreature(const std::string& jsonText, const std::string& source) {
  const nlohmann::json doc = JsonReader::parseText(jsonText, source);
  const JsonReader root(doc, source);
  if (!root.isObject()) root.fail("a creature file must be a JSON object");
  root.rejectUnknown({"name", "description", "units", "furLength", "furColor", "skin", "segments",
                      "shapes", "regions"});
  Creature c;
  c.source = source;
  c.name = root.string("name", "creature");
  if (root.has("units") && root.string("units") != "meters")
    root.at("units").fail("only \"meters\" is supported");
  c.furLengthMeters = static_cast<float>(root.number("furLength", 0.02, 0.0, 10.0));

  if (auto skin = root.find("skin")) {
    skin->rejectUnknown({"triangles", "blendRadius", "color"});
    c.defaultTriangles = static_cast<int>(skin->integer("triangles", 130000, 2000, 2000000));
    c.blendRadiusMeters = static_cast<float>(skin->number("blendRadius", 0.02, 0.0, 10.0));
    if (skin->has("color")) c.skinColor = colorField(*skin, "color");
  }
  if (auto fc = root.find("furColor")) {
    fc->rejectUnknown({"back", "belly", "spread"});
    CreatureFurColor f;
    f.back = colorField(*fc, "back");
    f.belly = colorField(*fc, "belly");
    f.spread = static_cast<float>(fc->number("spread", 0.4, 0.01, 1.0));
    c.furColor = f;
  }

  // Segments: joints in bind-pose world coordinates; the rest local transform is the offset from
  // the parent's joint (rest rotations are identity: segment frames are aligned with the world).
  const JsonReader segs = root.at("segments");
  if (segs.size() == 0) segs.fail("the body needs at least one segment");
  if (segs.size() > 4096) segs.fail("at most 4096 segments are supported");
  std::vector<SegmentSpec> specs;
  std::vector<Eigen::Vector3f> joints;
  for (std::size_t i = 0; i < segs.size(); ++i) {
    const JsonReader s = segs.at(i);
    s.rejectUnknown({"name", "parent", "joint", "direction"});
    SegmentSpec spec;
    spec.name = s.string("name");
    if (s.has("parent") && !s.at("parent").json().is_null()) spec.parent = s.string("parent");
    joints.push_back(point(s.at("joint")));
    if (s.has("direction")) {
      const Eigen::Vector3f d = s.vec3("direction");
      if (d.norm() > 1e-6f) spec.direction = d.normalized();
    }
    specs.push_back(std::move(spec));
  }
  // Local translations need the parent's joint: resolve names first.
  for (std::size_t i = 0; i < specs.size(); ++i) {
    Eigen::Vector3f parentJoint = Eigen::Vector3f::Zero();
    if (!specs[i].parent.empty()) {
      for (std::size_t j = 0; j < specs.size(); ++j)
        if (specs[j].name == specs[i].parent) parentJoint = joints[j];
    }
    specs[i].rest.translation = joints[i] - parentJoint;
  }
  c.body = makeBody(specs, source);

  const JsonReader shapes = root.at("shapes");
  if (shapes.size() == 0) shapes.fail("at least one body shape is needed to build a skin");
  for (std::size_t i = 0; i < shapes.size(); ++i) {
    const JsonReader s = shapes.at(i);
    Shape sh;
    sh.segment = segmentIndex(c.body, s.at("segment"));
    const std::string type = s.string("type");
    if (type == "ellipsoid") {
      s.rejectUnknown({"segment", "type", "center", "radii", "rotation", "blend"});
      sh.kind = Shape::Kind::Ellipsoid;
      sh.center = point(s.at("center"));
      sh.radii = s.vec3("radii");
      if ((sh.radii.array() <= 1e-5f).any() || (sh.radii.array() > 1e3f).any())
        s.at("radii").fail(
            "ellipsoid radii must lie in (0.00001, 1000] metres (a zero-size shape)");
      if (auto rot = s.find("rotation")) sh.rotation = rotationOf(*rot);
    } else if (type == "capsule") {
      s.rejectUnknown({"segment", "type", "from", "to", "radius", "radiusTo", "blend"});
      sh.kind = Shape::Kind::Capsule;
      sh.from = point(s.at("from"));
      sh.to = point(s.at("to"));
      sh.rFrom = static_cast<float>(s.number("radius", 1e-5, 1e3));
      sh.rTo = static_cast<float>(s.number("radiusTo", sh.rFrom, 1e-5, 1e3));
      if ((sh.to - sh.from).norm() < 1e-6f && std::abs(sh.rFrom - sh.rTo) > 0.0f)
        s.fail("a capsule with from == to must have equal radii");
    } else {
      s.at("type").fail("unknown shape type '" + type + "' (accepted: ellipsoid, capsule)");
    }
    sh.blend = static_cast<float>(s.number("blend", -1.0, -1.0, 10.0));
    c.shapes.push_back(sh);
  }

  if (auto regions = root.find("regions")) {
    for (std::size_t i = 0; i < regions->size(); ++i) {
      const JsonReader r = regions->at(i);
      r.rejectUnknown({"name", "lengthScale", "segments", "sphere", "spheres", "box", "boxes",
                       "blend", "furColor"});
      FurRegion reg;
      reg.name = r.string("name");
      if (reg.name.empty() || reg.name == "body")
        r.at("name").fail("region name must be non-empty and not \"body\"");
      reg.lengthScale = static_cast<float>(r.number("lengthScale", 0.0, 100.0));
      if (r.has("furColor")) reg.furColor = colorField(r, "furColor");
      if (auto segsSel = r.find("segments"))
        for (std::size_t k = 0; k < segsSel->size(); ++k)
          reg.segments.push_back(segmentIndex(c.body, segsSel->at(k)));
      auto readSphere = [&](const JsonReader& sphere) {
        sphere.rejectUnknown({"center", "radius"});
        const Eigen::Vector3f ctr = point(sphere.at("center"));
        const float rad = static_cast<float>(sphere.number("radius", 1e-6, 1e3));
        reg.spheres.emplace_back(ctr.x(), ctr.y(), ctr.z(), rad);
      };
      auto readBox = [&](const JsonReader& box) {
        box.rejectUnknown({"min", "max"});
        const Eigen::Vector3f lo = point(box.at("min")), hi = point(box.at("max"));
        if ((lo.array() > hi.array()).any()) box.fail("box min must not exceed max");
        reg.boxes.emplace_back(lo, hi);
      };
      if (auto sphere = r.find("sphere")) readSphere(*sphere);
      if (auto list = r.find("spheres"))
        for (std::size_t k = 0; k < list->size(); ++k) readSphere(list->at(k));
      if (auto box = r.find("box")) readBox(*box);
      if (auto list = r.find("boxes"))
        for (std::size_t k = 0; k < list->size(); ++k) readBox(list->at(k));
      if (reg.segments.empty() && reg.spheres.empty() && reg.boxes.empty())
        r.fail("a region needs at least one of: segments, sphere(s), box(es)");
      reg.blend = static_cast<float>(r.number("blend", 0.0, 0.0, 10.0));
      c.regions.push_back(std::move(reg));
    }
  }
  return c;
}

Creature loadCreature(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec))
    throw MissingFileError(path + ": cannot open creature file (missing or unreadable)");
  std::ifstream in(path, std::ios::binary);
  if (!in) inputError(path, ": cannot open creature file (missing or unreadable)");
  std::ostringstream ss;
  ss << in.rdbuf();
  return parseCreature(ss.str(), path);
}

}  // namespace pelage::anatomy
