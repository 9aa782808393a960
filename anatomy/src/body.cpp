#include "pelage/anatomy/body.h"

#include <cmath>
#include <unordered_map>

#include "pelage/util/error.h"

namespace pelage::anatomy {
namespace {
bool finite(const Transform& t) {
  return t.rotation.coeffs().allFinite() && t.translation.allFinite() && t.scale.allFinite();
}
}  // namespace

int Body::find(std::string_view name) const {
  for (int i = 0; i < size(); ++i)
    if (segments[static_cast<std::size_t>(i)].name == name) return i;
  return -1;
}

Body makeBody(const std::vector<SegmentSpec>& specs, const std::string& source) {
  if (specs.empty()) inputError(source, ": the body has no segments");
  std::unordered_map<std::string, std::size_t> byName;
  for (std::size_t i = 0; i < specs.size(); ++i) {
    const SegmentSpec& s = specs[i];
    if (s.name.empty()) inputError(source, ": segment #", i, " has an empty name");
    if (!byName.emplace(s.name, i).second)
      inputError(source, ": duplicate segment name '", s.name, "'");
    if (!finite(s.rest) || !s.direction.allFinite())
      inputError(source, ": segment '", s.name, "' has a non-finite (NaN or infinite) value");
    if (std::abs(s.rest.rotation.norm() - 1.0f) > 1e-3f)
      inputError(source, ": segment '", s.name, "' rotation is not a unit quaternion");
    if ((s.rest.scale.array() <= 0.0f).any())
      inputError(source, ": segment '", s.name, "' scale must be positive");
  }
  for (const SegmentSpec& s : specs) {
    if (!s.parent.empty() && !byName.count(s.parent))
      inputError(source, ": segment '", s.name, "' has unknown parent '", s.parent, "'");
    if (s.parent == s.name) inputError(source, ": segment '", s.name, "' is its own parent");
  }
  // Topological order: repeatedly emit segments whose parent is already placed.
  Body body;
  std::unordered_map<std::string, int> placed;
  std::vector<bool> done(specs.size(), false);
  for (std::size_t round = 0; placed.size() < specs.size(); ++round) {
    bool progress = false;
    for (std::size_t i = 0; i < specs.size(); ++i) {
      if (done[i]) continue;
      const SegmentSpec& s = specs[i];
      int parent = -1;
      if (!s.parent.empty()) {
        auto it = placed.find(s.parent);
        if (it == placed.end()) continue;
        parent = it->second;
      }
      Segment seg;
      seg.name = s.name;
      seg.parent = parent;
      seg.rest = s.rest;
      seg.rest.rotation.normalize();
      seg.direction = s.direction;
      placed[s.name] = body.size();
      body.segments.push_back(std::move(seg));
      done[i] = true;
      progress = true;
    }
    if (!progress) {
      std::string cycle;
      for (std::size_t i = 0; i < specs.size(); ++i)
        if (!done[i]) cycle += (cycle.empty() ? "" : ", ") + specs[i].name;
      inputError(source, ": the segment hierarchy has a cycle (segments: ", cycle, ")");
    }
  }
  const std::vector<Eigen::Affine3f> world = restWorldTransforms(body);
  body.inverseBind.resize(world.size());
  for (std::size_t i = 0; i < world.size(); ++i) body.inverseBind[i] = world[i].inverse();
  return body;
}

std::vector<Eigen::Affine3f> restWorldTransforms(const Body& body) {
  std::vector<Eigen::Affine3f> world(body.segments.size());
  for (std::size_t i = 0; i < body.segments.size(); ++i) {
    const Segment& s = body.segments[i];
    world[i] = s.parent < 0 ? s.rest.matrix()
                            : world[static_cast<std::size_t>(s.parent)] * s.rest.matrix();
  }
  return world;
}

void checkBody(const Body& body) {
  PELAGE_CHECK(body.inverseBind.size() == body.segments.size(), "inverseBind size ",
               body.inverseBind.size(), " vs ", body.segments.size());
  for (int i = 0; i < body.size(); ++i) {
    const Segment& s = body.segments[static_cast<std::size_t>(i)];
    PELAGE_CHECK(s.parent < i, "segment ", s.name, " parent ", s.parent, " not before ", i);
    PELAGE_CHECK(s.parent >= -1);
    PELAGE_CHECK(finite(s.rest), "segment ", s.name);
  }
}

}  // namespace pelage::anatomy
