#include "pelage/anatomy/pose_file.h"

#include <cmath>

#include "pelage/util/error.h"
#include "pelage/util/json_reader.h"

namespace pelage::anatomy {

Pose parsePose(const Body& body, const std::string& jsonText, const std::string& source) {
  const nlohmann::json doc = JsonReader::parseText(jsonText, source);
  const JsonReader root(doc, source);
  if (!root.isObject()) root.fail("a pose file must be a JSON object");
  root.rejectUnknown({"pose", "description"});
  Pose pose = restPose(body);
  const JsonReader entries = root.at("pose");
  for (const std::string& name : entries.keys()) {
    const int s = body.find(name);
    const JsonReader e = entries.at(name);
    if (s < 0) e.fail("unknown segment '" + name + "'");
    e.rejectUnknown({"rotate", "translate"});
    Transform& t = pose.local[static_cast<std::size_t>(s)];
    if (auto rot = e.find("rotate")) {
      rot->rejectUnknown({"axis", "degrees"});
      const Eigen::Vector3f axis = rot->vec3("axis");
      if (axis.norm() < 1e-6f) rot->at("axis").fail("rotation axis must be non-zero");
      const double deg = rot->number("degrees", -3600.0, 3600.0);
      t.rotation = (t.rotation * Eigen::Quaternionf(Eigen::AngleAxisf(
                                     static_cast<float>(deg * M_PI / 180.0), axis.normalized())))
                       .normalized();
    }
    if (auto tr = e.find("translate")) {
      const Eigen::Vector3f d = tr->asVec3();
      if ((d.array().abs() > 1e4f).any())
        tr->fail("translation must lie within [-10000, 10000] metres");
      t.translation += d;
    }
  }
  return pose;
}

Pose loadPose(const Body& body, const std::string& path) {
  const nlohmann::json doc = JsonReader::parseFile(path);
  return parsePose(body, doc.dump(), path);
}

}  // namespace pelage::anatomy
