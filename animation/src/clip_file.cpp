#include "pelage/animation/clip_file.h"

#include <cmath>
#include <filesystem>
#include <set>
#include <utility>

#include "pelage/util/error.h"
#include "pelage/util/json_reader.h"

namespace pelage::animation {
namespace {

constexpr double kMaxTime = 1e5;  // seconds

Interpolation interpolationOf(const JsonReader& r) {
  const std::string s = r.asString();
  if (s == "step") return Interpolation::Step;
  if (s == "linear") return Interpolation::Linear;
  if (s == "cubic") return Interpolation::CubicSpline;
  r.fail("unknown interpolation '" + s + "' (accepted: step, linear, cubic)");
}

// Catmull-Rom tangents m_k = (v_k+1 - v_k-1) / (t_k+1 - t_k-1), one-sided at the ends. A periodic
// channel (looping clip, keys at 0 and at the duration) wraps around at its ends: the neighbour of
// key 0 is key n-2 one period earlier, mapped into key 0's frame (`sign` for quaternions, whose
// last key may be -q of the first; `cycleOffset` for a root-motion translation).
std::vector<float> catmullRomTangents(const std::vector<float>& t, const std::vector<float>& v,
                                      std::size_t C, bool periodic, float duration, float sign,
                                      const Eigen::Vector3f& cycleOffset) {
  const std::size_t n = t.size();
  std::vector<float> m(n * C, 0.0f);
  if (n < 2) return m;
  auto at = [&](std::size_t k, std::size_t i) { return static_cast<double>(v[k * C + i]); };
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t a = k == 0 ? 0 : k - 1, b = k + 1 < n ? k + 1 : n - 1;
    for (std::size_t i = 0; i < C; ++i) {
      double dv = at(b, i) - at(a, i);
      double dt = static_cast<double>(t[b]) - static_cast<double>(t[a]);
      if (periodic && n >= 3 && (k == 0 || k == n - 1)) {
        // Both ends: (v_1 - v_n-2 one period earlier) / (t_1 + duration - t_n-2), in the end's
        // frame.
        const double off =
            C == 3 ? static_cast<double>(cycleOffset[static_cast<Eigen::Index>(i)]) : 0.0;
        const double s = C == 4 ? static_cast<double>(sign) : 1.0;
        dv = at(1, i) - (s * at(n - 2, i) - off);
        if (k == n - 1) dv *= s;
        dt = static_cast<double>(t[1]) + static_cast<double>(duration) -
             static_cast<double>(t[n - 2]);
      }
      m[k * C + i] = dt > 0.0 ? static_cast<float>(dv / dt) : 0.0f;
    }
  }
  return m;
}

struct ParsedChannel {
  Channel channel;
  std::vector<float> keyValues;  // nK x C (before tangents)
};

}  // namespace

Clip parseClip(const anatomy::Body& body, const std::string& jsonText, const std::string& source) {
  const nlohmann::json doc = JsonReader::parseText(jsonText, source);
  const JsonReader root(doc, source);
  if (!root.isObject()) root.fail("a clip file must be a JSON object");
  root.rejectUnknown({"name", "description", "loop", "duration", "rootMotion", "channels"});
  Clip clip;
  clip.name = root.string("name", std::filesystem::path(source).stem().string());
  if (clip.name.empty()) root.at("name").fail("the clip name must not be empty");
  clip.loop = root.boolean("loop", true);

  const JsonReader channels = root.at("channels");
  if (channels.size() == 0) channels.fail("a clip needs at least one channel");
  std::set<std::pair<int, int>> seen;
  std::vector<ParsedChannel> parsed;
  float lastKey = 0.0f;
  for (std::size_t c = 0; c < channels.size(); ++c) {
    const JsonReader e = channels.at(c);
    e.rejectUnknown({"segment", "path", "interpolation", "keys"});
    const std::string segName = e.string("segment");
    const int seg = body.find(segName);
    if (seg < 0) e.at("segment").fail("unknown segment '" + segName + "'");
    const std::string pathName = e.string("path");
    ParsedChannel pc;
    Channel& ch = pc.channel;
    ch.segment = seg;
    if (pathName == "rotate")
      ch.path = ChannelPath::Rotation;
    else if (pathName == "translate")
      ch.path = ChannelPath::Translation;
    else if (pathName == "scale")
      ch.path = ChannelPath::Scale;
    else
      e.at("path").fail("unknown path '" + pathName + "' (accepted: rotate, translate, scale)");
    if (!seen.emplace(seg, static_cast<int>(ch.path)).second)
      e.fail("segment '" + segName + "' already has a '" + pathName + "' channel");
    ch.interpolation =
        e.has("interpolation") ? interpolationOf(e.at("interpolation")) : Interpolation::Linear;
    const JsonReader keys = e.at("keys");
    if (keys.size() == 0) keys.fail("a channel needs at least one key");
    const anatomy::Transform& rest = body.segments[static_cast<std::size_t>(seg)].rest;
    for (std::size_t k = 0; k < keys.size(); ++k) {
      const JsonReader key = keys.at(k);
      const float time = static_cast<float>(key.number("time", 0.0, kMaxTime));
      if (k > 0 && !(time > ch.times.back()))
        key.at("time").fail(
            str("key times must increase (", time, " after ", ch.times.back(), ")"));
      ch.times.push_back(time);
      if (ch.path == ChannelPath::Rotation) {
        key.rejectUnknown({"time", "axis", "degrees"});
        const Eigen::Vector3f axis = key.vec3("axis");
        if (!(axis.norm() > 1e-6f)) key.at("axis").fail("rotation axis must be non-zero");
        const double deg = key.number("degrees", -36000.0, 36000.0);
        const Eigen::Quaternionf q =
            (rest.rotation * Eigen::Quaternionf(Eigen::AngleAxisf(
                                 static_cast<float>(deg * M_PI / 180.0), axis.normalized())))
                .normalized();
        pc.keyValues.insert(pc.keyValues.end(), {q.x(), q.y(), q.z(), q.w()});
      } else {
        key.rejectUnknown({"time", "value"});
        const Eigen::Vector3f v = key.vec3("value");
        Eigen::Vector3f out;
        if (ch.path == ChannelPath::Translation) {
          if ((v.array().abs() > 1e4f).any())
            key.at("value").fail("translation must lie within [-10000, 10000] metres");
          out = rest.translation + v;
        } else {
          if ((v.array() <= 0.0f).any() || (v.array() > 1000.0f).any())
            key.at("value").fail("scale factors must lie in (0, 1000]");
          out = rest.scale.cwiseProduct(v);
        }
        pc.keyValues.insert(pc.keyValues.end(), {out.x(), out.y(), out.z()});
      }
    }
    lastKey = std::max(lastKey, ch.times.back());
    parsed.push_back(std::move(pc));
  }

  clip.duration = lastKey;
  if (root.has("duration")) {
    const JsonReader d = root.at("duration");
    clip.duration = static_cast<float>(d.asNumber(0.0, kMaxTime));
    if (clip.duration < lastKey)
      d.fail(
          str("duration ", clip.duration, " s is shorter than the last key time ", lastKey, " s"));
  }

  if (auto rm = root.find("rootMotion")) {
    rm->rejectUnknown({"segment", "translate"});
    const std::string segName = rm->string("segment");
    clip.rootMotionSegment = body.find(segName);
    if (clip.rootMotionSegment < 0) rm->at("segment").fail("unknown segment '" + segName + "'");
    clip.rootMotion = rm->vec3("translate");
    if ((clip.rootMotion.array().abs() > 1e4f).any())
      rm->at("translate").fail("root motion must lie within [-10000, 10000] metres per cycle");
  }
  for (ParsedChannel& pc : parsed) {
    Channel& ch = pc.channel;
    if (ch.interpolation == Interpolation::CubicSpline) {
      const std::size_t C = static_cast<std::size_t>(ch.components());
      if (C == 4)  // sign-align so that differences between keys are short-arc
        for (std::size_t k = 1; k < ch.times.size(); ++k) {
          float dot = 0.0f;
          for (std::size_t i = 0; i < 4; ++i)
            dot += pc.keyValues[k * 4 + i] * pc.keyValues[(k - 1) * 4 + i];
          if (dot < 0.0f)
            for (std::size_t i = 0; i < 4; ++i) pc.keyValues[k * 4 + i] = -pc.keyValues[k * 4 + i];
        }
      const std::size_t n = ch.times.size();
      const bool periodic =
          clip.loop && ch.times.front() == 0.0f && ch.times.back() == clip.duration;
      float sign = 1.0f;
      if (C == 4 && n >= 2) {
        float dot = 0.0f;
        for (std::size_t i = 0; i < 4; ++i) dot += pc.keyValues[(n - 1) * 4 + i] * pc.keyValues[i];
        sign = dot < 0.0f ? -1.0f : 1.0f;
      }
      const bool rootTranslation =
          ch.path == ChannelPath::Translation && ch.segment == clip.rootMotionSegment;
      const Eigen::Vector3f offset = rootTranslation ? clip.rootMotion : Eigen::Vector3f::Zero();
      const std::vector<float> m =
          catmullRomTangents(ch.times, pc.keyValues, C, periodic, clip.duration, sign, offset);
      ch = cubicChannel(ch.segment, ch.path, ch.times, pc.keyValues, m);
    } else {
      ch.values = std::move(pc.keyValues);
    }
    clip.channels.push_back(std::move(ch));
  }

  checkClip(clip, body);
  return clip;
}

Clip loadClip(const anatomy::Body& body, const std::string& path) {
  const nlohmann::json doc = JsonReader::parseFile(path);
  return parseClip(body, doc.dump(), path);
}

}  // namespace pelage::animation
