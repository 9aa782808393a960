// Frames with CPU hairs for the export tests: the test critter in its rest pose and bent poses,
// every hair drawn (no culling), and a tiny reader for the structure of USD ASCII layers.
#pragma once

#include <gtest/gtest.h>

#include <cstdlib>
#include <string>
#include <utility>
#include <vector>

#include "pelage/fur/preset.h"
#include "pelage/scene/frame.h"
#include "support/models.h"

namespace pelage::test {

// Fur on the critter with `hairs` hairs, both coats in `style`, culling off (export writes every
// hair).
inline scene::Fur exportFur(fur::HairStyle style, double hairs = 2000.0, float curlRadius = 0.0f) {
  fur::FurParams p = fur::loadFurPreset("default");
  p.setHairCount(hairs);
  p.undercoatShare = 0.25f;
  p.culling.enabled = false;
  for (fur::CoatParams& c : p.coats) {
    c.style = style;
    c.curlRadius = curlRadius;
    c.curlTurns = curlRadius > 0.0f ? 2.0f : 0.0f;
  }
  return scene::growFur(sceneCritter(), p, "export test");
}

// Frame i: the tail and head bent by i * 12 degrees, with CPU hairs.
inline void exportFrame(const scene::Fur& fur, int i, scene::FrameState& state) {
  const scene::Model& m = sceneCritter();
  anatomy::Pose pose = anatomy::restPose(m.body);
  for (std::size_t s = 1; s < pose.local.size(); ++s)
    pose.local[s].rotation =
        pose.local[s].rotation * Eigen::Quaternionf(Eigen::AngleAxisf(0.21f * static_cast<float>(i),
                                                                      Eigen::Vector3f::UnitY()));
  scene::evaluateFrame(m, pose, state);
  scene::evaluateFur(m, fur, fur::FurView{}, true, state);
}

// The text of the block that starts at the line containing `header` ("def Mesh \"skin\""), up to
// its matching closing brace.
inline std::string usdBlock(const std::string& text, const std::string& header) {
  const std::size_t at = text.find(header);
  if (at == std::string::npos) return "";
  const std::size_t open = text.find('{', at);
  int depth = 0;
  for (std::size_t i = open; i < text.size(); ++i) {
    if (text[i] == '{') ++depth;
    if (text[i] == '}' && --depth == 0) return text.substr(at, i + 1 - at);
  }
  return "";
}

// The numbers of the bracketed array starting at `pos` ('[' expected): tuples flattened.
inline std::vector<double> usdNumbers(const std::string& text, std::size_t& pos) {
  std::vector<double> out;
  EXPECT_EQ(text[pos], '[');
  const std::size_t end = text.find(']', pos);
  std::string body = text.substr(pos + 1, end - pos - 1);
  for (char& c : body)
    if (c == '(' || c == ')' || c == ',') c = ' ';
  const char* p = body.c_str();
  char* q = nullptr;
  for (;;) {
    const double v = std::strtod(p, &q);
    if (q == p) break;
    out.push_back(v);
    p = q;
  }
  pos = end + 1;
  return out;
}

// The value of `attr = [...]` in `block` (e.g. "int[] curveVertexCounts").
inline std::vector<double> usdArray(const std::string& block, const std::string& attr) {
  std::size_t at = block.find(attr + " = [");
  if (at == std::string::npos) return {};
  at += attr.size() + 3;  // the value's '[' (not the type's "[]")
  return usdNumbers(block, at);
}

// The time samples of `attr` ("point3f[] points") in `block`: (time code, numbers) pairs.
inline std::vector<std::pair<int, std::vector<double>>> usdTimeSamples(const std::string& block,
                                                                       const std::string& attr) {
  std::vector<std::pair<int, std::vector<double>>> out;
  std::size_t at = block.find(attr + ".timeSamples = {");
  if (at == std::string::npos) return out;
  at = block.find('{', at) + 1;
  for (;;) {
    const std::size_t next = block.find_first_not_of(" \n", at);
    if (next == std::string::npos || block[next] == '}') break;
    char* q = nullptr;
    const long key = std::strtol(block.c_str() + next, &q, 10);
    std::size_t pos = block.find('[', next);
    std::vector<double> numbers = usdNumbers(block, pos);
    out.emplace_back(static_cast<int>(key), std::move(numbers));
    at = block.find(',', pos) + 1;
  }
  return out;
}

}  // namespace pelage::test
