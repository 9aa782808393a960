// importGltf's last stage (gltf_stages.h): the clips, every animation with its root channels taken
// to pelage's axes and units.
#include <algorithm>
#include <cmath>
#include <set>

#include "gltf_stages.h"
#include "pelage/util/log.h"

namespace pelage::animation::detail {

std::vector<Clip> readClips(const ImportContext& ctx, const Skeleton& skel, const Units& units,
                            const anatomy::Body& body) {
  const tinygltf::Model& model = ctx.model;
  const std::string& path = ctx.path;
  const int N = static_cast<int>(model.nodes.size());
  const std::vector<int>& segmentOf = skel.segmentOf;
  const double s = static_cast<double>(units.scale);
  const Eigen::Matrix3d& C = units.C;
  const Eigen::Quaterniond& qC = units.qC;
  std::vector<Clip> clips;
  std::set<std::string> clipNames;
  bool warnedWeights = false;
  for (std::size_t ai = 0; ai < model.animations.size(); ++ai) {
    const tinygltf::Animation& an = model.animations[ai];
    Clip clip;
    clip.name = an.name.empty() ? str("clip", ai) : an.name;
    if (!clipNames.insert(clip.name).second) {
      const std::string renamed = str(clip.name, "_", ai);
      warn(str(path, ": two animations are called '", clip.name, "'; the second is '", renamed,
               "'"));
      clip.name = renamed;
      clipNames.insert(renamed);
    }
    clip.loop = true;
    float duration = 0.0f;
    for (std::size_t ci = 0; ci < an.channels.size(); ++ci) {
      const tinygltf::AnimationChannel& ch = an.channels[ci];
      const std::string what = str("animation ", ai, " channel ", ci);
      if (ch.sampler < 0 || ch.sampler >= static_cast<int>(an.samplers.size()))
        ctx.fail(what, " uses sampler ", ch.sampler, ", which does not exist (", an.samplers.size(),
                 " samplers)");
      if (ch.target_node >= N)
        ctx.fail(what, " targets node ", ch.target_node, ", which does not exist (", N, " nodes)");
      const tinygltf::AnimationSampler& sm = an.samplers[static_cast<std::size_t>(ch.sampler)];
      Channel chOut;
      if (ch.target_path == "translation")
        chOut.path = ChannelPath::Translation;
      else if (ch.target_path == "rotation")
        chOut.path = ChannelPath::Rotation;
      else if (ch.target_path == "scale")
        chOut.path = ChannelPath::Scale;
      else if (ch.target_path == "weights") {
        if (!warnedWeights)
          warn(str(path, ": morph-target (weights) animation channels are ignored"));
        warnedWeights = true;
        continue;
      } else {
        ctx.fail(what, " has an unknown target path '", ch.target_path, "'");
      }
      if (sm.interpolation.empty() || sm.interpolation == "LINEAR")
        chOut.interpolation = Interpolation::Linear;
      else if (sm.interpolation == "STEP")
        chOut.interpolation = Interpolation::Step;
      else if (sm.interpolation == "CUBICSPLINE")
        chOut.interpolation = Interpolation::CubicSpline;
      else
        ctx.fail(what, " sampler has an unknown interpolation '", sm.interpolation, "'");
      chOut.times = ctx.acc.floats(sm.input, TINYGLTF_TYPE_SCALAR, false, what + " input (times)");
      for (std::size_t k = 0; k < chOut.times.size(); ++k) {
        if (chOut.times[k] < 0.0f)
          ctx.fail(what, " key time ", k, " is negative (", chOut.times[k], " s)");
        if (chOut.times[k] > 1e6f)
          ctx.fail(what, " key time ", k, " is ", chOut.times[k], " s (limit 1e6)");
        if (k > 0 && chOut.times[k] < chOut.times[k - 1])
          ctx.fail(what, " key times decrease at key ", k, " (", chOut.times[k - 1], " then ",
                   chOut.times[k], " s)");
      }
      const bool cubic = chOut.interpolation == Interpolation::CubicSpline;
      const int nc = chOut.components();
      chOut.values = ctx.acc.floats(sm.output, nc == 4 ? TINYGLTF_TYPE_VEC4 : TINYGLTF_TYPE_VEC3,
                                    nc == 4, what + " output (values)");
      const std::size_t expect =
          chOut.times.size() * (cubic ? 3u : 1u) * static_cast<std::size_t>(nc);
      if (chOut.values.size() != expect)
        ctx.fail(what, ": ", chOut.times.size(), " key times need ",
                 expect / static_cast<std::size_t>(nc), " output values, found ",
                 chOut.values.size() / static_cast<std::size_t>(nc));
      duration = std::max(duration, chOut.times.back());
      if (ch.target_node < 0 || segmentOf[static_cast<std::size_t>(ch.target_node)] < 0)
        continue;  // no effect
      chOut.segment = segmentOf[static_cast<std::size_t>(ch.target_node)];
      const std::size_t nK = chOut.times.size();
      if (nc == 4)  // unit quaternions for the values (not the tangents)
        for (std::size_t k = 0; k < nK; ++k) {
          float* q = chOut.values.data() + (cubic ? (3 * k + 1) * 4 : k * 4);
          const float len = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
          if (!(len > 1e-6f)) ctx.fail(what, " key ", k, " is a zero quaternion");
          for (int i = 0; i < 4; ++i) q[i] /= len;
        }
      if (body.segments[static_cast<std::size_t>(chOut.segment)].parent < 0) {
        // A root: apply the change of basis to values and tangents alike (both transform linearly).
        for (std::size_t e = 0; e < chOut.values.size() / static_cast<std::size_t>(nc); ++e) {
          float* v = chOut.values.data() + e * static_cast<std::size_t>(nc);
          if (nc == 4) {
            const Eigen::Quaternionf q =
                qC.cast<float>() * Eigen::Quaternionf(v[3], v[0], v[1], v[2]);
            v[0] = q.x();
            v[1] = q.y();
            v[2] = q.z();
            v[3] = q.w();
          } else if (chOut.path == ChannelPath::Translation) {
            const Eigen::Vector3f t = (s * C * Eigen::Vector3d(v[0], v[1], v[2])).cast<float>();
            v[0] = t.x();
            v[1] = t.y();
            v[2] = t.z();
          } else {
            for (int i = 0; i < 3; ++i) v[i] *= units.scale;
          }
        }
      }
      clip.channels.push_back(std::move(chOut));
    }
    clip.duration = duration;
    checkClip(clip, body);
    clips.push_back(std::move(clip));
  }
  return clips;
}

}  // namespace pelage::animation::detail
