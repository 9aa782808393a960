// Segment directions, unit scale and region patterns for glTF creatures (see gltf_import.h).
#include <algorithm>
#include <cctype>
#include <cmath>
#include <deque>
#include <limits>

#include "pelage/animation/gltf_import.h"
#include "pelage/util/error.h"
#include "pelage/util/json_reader.h"
#include "pelage/util/path.h"

namespace pelage::animation {
namespace {

constexpr float kMinBone = 1e-6f;  // relative to the skeleton's size

}  // namespace

const std::vector<std::string>& defaultNoFurRegions() {
  static const std::vector<std::string> patterns = {"Eye*",    "*Eyes*",   "Eye_*",  "Hooves",
                                                    "*Hoof*",  "Nose",     "*Horn*", "*Antler*",
                                                    "*Teeth*", "*Tongue*", "*Claw*"};
  return patterns;
}

float detectUnitScale(float longest, std::string* reason) {
  auto say = [&](const std::string& r) {
    if (reason) *reason = r;
  };
  if (!(longest > 0.0f) || !std::isfinite(longest)) {
    say("empty bounds: metres assumed");
    return 1.0f;
  }
  if (longest > 3000.0f) {
    say(str("longest side ", longest, " units > 3000: millimetres assumed (x 0.001)"));
    return 0.001f;
  }
  if (longest > 30.0f) {
    say(str("longest side ", longest, " units > 30: centimetres assumed (x 0.01)"));
    return 0.01f;
  }
  say(str("longest side ", longest, " units <= 30: metres (glTF's unit)"));
  return 1.0f;
}

// Van Gelder & Wilhelms 1997, sec. 3.4: "Animal hairs typically are oriented from head to tail."
// The tree distance d from the head orients every bone away from the head; spine segments follow
// the head-to-tail path, the others average their oriented bones (see gltf_import.h).
std::vector<Eigen::Vector3f> headToTailDirections(const anatomy::Body& body,
                                                  const std::vector<Eigen::Vector3f>& bindJoints,
                                                  const std::vector<bool>& bound) {
  const int n = body.size();
  PELAGE_CHECK(static_cast<int>(bindJoints.size()) == n && static_cast<int>(bound.size()) == n);
  std::vector<Eigen::Vector3f> dir(static_cast<std::size_t>(n), Eigen::Vector3f::Zero());
  auto joint = [&](int i) { return static_cast<bool>(bound[static_cast<std::size_t>(i)]); };
  auto pos = [&](int i) -> const Eigen::Vector3f& {
    return bindJoints[static_cast<std::size_t>(i)];
  };
  auto parentOf = [&](int i) { return body.segments[static_cast<std::size_t>(i)].parent; };
  std::vector<std::vector<int>> children(static_cast<std::size_t>(n));
  std::vector<int> depth(static_cast<std::size_t>(n), 0);
  Eigen::AlignedBox3f box;
  for (int i = 0; i < n; ++i) {
    const int p = parentOf(i);
    if (p >= 0) {
      children[static_cast<std::size_t>(p)].push_back(i);
      depth[static_cast<std::size_t>(i)] = depth[static_cast<std::size_t>(p)] + 1;
    }
    if (joint(i)) box.extend(pos(i));
  }
  if (box.isEmpty()) return dir;
  const float minBone = kMinBone * std::max(box.diagonal().norm(), 1e-12f);

  // 1. The head.
  int head = -1;
  for (int i = 0; i < n; ++i)
    if (joint(i) &&
        lowerCase(body.segments[static_cast<std::size_t>(i)].name).find("head") !=
            std::string::npos &&
        (head < 0 || depth[static_cast<std::size_t>(i)] < depth[static_cast<std::size_t>(head)]))
      head = i;
  if (head < 0) {
    const Eigen::Vector3f ext = box.sizes();
    const int axis = std::max(ext.x(), ext.y()) >= ext.z() ? 0 : 2;
    float best = -std::numeric_limits<float>::infinity();
    for (int i = 0; i < n; ++i)
      if (joint(i) && pos(i)[axis] > best) {
        best = pos(i)[axis];
        head = i;
      }
  }

  // 2. From the head through the tree (breadth-first over parent and child links): d, the number
  // of edges; along, the summed bone lengths; via, the neighbour one step nearer the head.
  std::vector<int> d(static_cast<std::size_t>(n), -1), via(static_cast<std::size_t>(n), -1);
  std::vector<double> along(static_cast<std::size_t>(n), 0.0);
  std::deque<int> queue{head};
  d[static_cast<std::size_t>(head)] = 0;
  while (!queue.empty()) {
    const int s = queue.front();
    queue.pop_front();
    std::vector<int> next = children[static_cast<std::size_t>(s)];
    if (parentOf(s) >= 0) next.push_back(parentOf(s));
    for (int c : next)
      if (d[static_cast<std::size_t>(c)] < 0) {
        d[static_cast<std::size_t>(c)] = d[static_cast<std::size_t>(s)] + 1;
        along[static_cast<std::size_t>(c)] =
            along[static_cast<std::size_t>(s)] + static_cast<double>((pos(c) - pos(s)).norm());
        via[static_cast<std::size_t>(c)] = s;
        queue.push_back(c);
      }
  }
  // The bone between a and b oriented away from the head (zero if too short).
  auto oriented = [&](int a, int b) -> Eigen::Vector3f {
    Eigen::Vector3f v = pos(b) - pos(a);
    const float len = v.norm();
    if (len < minBone) return Eigen::Vector3f::Zero();
    v /= len;
    return d[static_cast<std::size_t>(b)] > d[static_cast<std::size_t>(a)] ? v
                                                                           : Eigen::Vector3f(-v);
  };

  // 3. The spine: the tree path from the head to the joint farthest from it along the bones (the
  // tail tip of an animal). Its segments follow the path only, so that the limbs branching off the
  // chest and hips do not bend the back's direction.
  int tip = head;
  for (int i = 0; i < n; ++i)
    if (joint(i) && along[static_cast<std::size_t>(i)] > along[static_cast<std::size_t>(tip)])
      tip = i;
  std::vector<bool> onPath(static_cast<std::size_t>(n), false);
  std::vector<int> nextOnPath(static_cast<std::size_t>(n), -1);
  for (int s = tip; s >= 0; s = via[static_cast<std::size_t>(s)]) {
    onPath[static_cast<std::size_t>(s)] = true;
    if (via[static_cast<std::size_t>(s)] >= 0)
      nextOnPath[static_cast<std::size_t>(via[static_cast<std::size_t>(s)])] = s;
  }

  // 4. Per joint segment: the normalised mean of its oriented bones (path bones on the spine).
  for (int s = 0; s < n; ++s) {
    if (!joint(s)) continue;
    Eigen::Vector3f sum = Eigen::Vector3f::Zero();
    if (onPath[static_cast<std::size_t>(s)]) {
      if (via[static_cast<std::size_t>(s)] >= 0)
        sum += oriented(via[static_cast<std::size_t>(s)], s);
      if (nextOnPath[static_cast<std::size_t>(s)] >= 0)
        sum += oriented(s, nextOnPath[static_cast<std::size_t>(s)]);
    } else {
      for (int c : children[static_cast<std::size_t>(s)])
        if (joint(c)) sum += oriented(s, c);
      if (parentOf(s) >= 0 && joint(parentOf(s))) sum += oriented(parentOf(s), s);
    }
    if (sum.norm() < 1e-6f) {
      // A leaf (or only zero-length bones): the bone from the nearest distinct ancestor.
      for (int p = parentOf(s); p >= 0 && sum.norm() < 1e-6f; p = parentOf(p)) sum = oriented(p, s);
    }
    const float len = sum.norm();
    dir[static_cast<std::size_t>(s)] =
        len > 1e-6f ? Eigen::Vector3f(sum / len) : Eigen::Vector3f::Zero();
  }
  return dir;
}

void applyDirectionFile(anatomy::Body& body, const std::string& path) {
  const nlohmann::json doc = JsonReader::parseFile(path);
  const JsonReader root(doc, path);
  if (!root.isObject()) root.fail("a segment direction file must be a JSON object");
  root.rejectUnknown({"directions", "description"});
  const JsonReader dirs = root.at("directions");
  for (const std::string& name : dirs.keys()) {
    const JsonReader e = dirs.at(name);
    const int s = body.find(name);
    if (s < 0) e.fail("unknown segment '" + name + "'");
    const Eigen::Vector3f v = e.asVec3();
    if ((v.array().abs() > 1e6f).any()) e.fail("direction components must lie within [-1e6, 1e6]");
    const float len = v.norm();
    body.segments[static_cast<std::size_t>(s)].direction =
        len > 1e-12f ? Eigen::Vector3f(v / len) : Eigen::Vector3f::Zero();
  }
}

}  // namespace pelage::animation
