#include "pelage/animation/clip.h"

#include <algorithm>
#include <cmath>

#include <Eigen/SVD>

#include "pelage/util/error.h"

namespace pelage::animation {
namespace {

// Shortest-arc spherical linear interpolation of unit quaternions (x, y, z, w):
// slerp(a, b, s) = sin((1-s) theta)/sin(theta) a + sin(s theta)/sin(theta) b', cos(theta) = |a.b|,
// b' = sign(a.b) b (q and -q are the same rotation; the sign flip takes the short way round).
void slerp4(const float* a, const float* b, double s, float* out) {
  double dot = 0.0;
  for (int i = 0; i < 4; ++i) dot += static_cast<double>(a[i]) * static_cast<double>(b[i]);
  const double sign = dot < 0.0 ? -1.0 : 1.0;
  dot = std::min(1.0, dot * sign);
  double wa = 1.0 - s, wb = s;
  if (dot < 0.9999) {
    const double theta = std::acos(dot);
    const double st = std::sin(theta);
    wa = std::sin((1.0 - s) * theta) / st;
    wb = std::sin(s * theta) / st;
  }
  wb *= sign;
  double q[4], n = 0.0;
  for (int i = 0; i < 4; ++i) {
    q[i] = wa * static_cast<double>(a[i]) + wb * static_cast<double>(b[i]);
    n += q[i] * q[i];
  }
  n = n > 0.0 ? 1.0 / std::sqrt(n) : 0.0;
  for (int i = 0; i < 4; ++i) out[i] = static_cast<float>(q[i] * n);
}

void normalize4(float* q) {
  double n = 0.0;
  for (int i = 0; i < 4; ++i) n += static_cast<double>(q[i]) * static_cast<double>(q[i]);
  n = std::sqrt(n);
  if (n > 0.0)
    for (int i = 0; i < 4; ++i) q[i] = static_cast<float>(static_cast<double>(q[i]) / n);
}

Eigen::Quaternionf quat(const float* v) {
  return Eigen::Quaternionf(v[3], v[0], v[1], v[2]);
}

}  // namespace

ClipTime clipTime(const Clip& clip, double t) {
  ClipTime ct;
  if (!std::isfinite(t)) return ct;
  const double d = static_cast<double>(clip.duration);
  if (!clip.loop || d <= 0.0) {
    ct.local = std::clamp(t, 0.0, std::max(d, 0.0));
    return ct;
  }
  const double c = std::floor(t / d);
  ct.local = std::clamp(t - c * d, 0.0, d);
  ct.cycles = static_cast<std::int64_t>(std::clamp(c, -1e15, 1e15));
  return ct;
}

void sampleChannel(const Channel& ch, double t, float* out) {
  const int C = ch.components();
  const int nK = ch.keys();
  const bool cubic = ch.interpolation == Interpolation::CubicSpline;
  const int stride = cubic ? 3 * C : C;   // floats per key
  const int valueOffset = cubic ? C : 0;  // the value inside a cubic key's (in, value, out)
  const float* v = ch.values.data();
  auto copyKey = [&](int k) {
    for (int i = 0; i < C; ++i) out[i] = v[k * stride + valueOffset + i];
  };
  if (nK == 0) return;
  if (t <= static_cast<double>(ch.times[0]) || nK == 1) {
    copyKey(0);
    return;
  }
  if (t >= static_cast<double>(ch.times[static_cast<std::size_t>(nK - 1)])) {
    copyKey(nK - 1);
    return;
  }
  // k: the last key with times[k] <= t, so times[k] <= t < times[k + 1].
  const auto it = std::upper_bound(ch.times.begin(), ch.times.end(), static_cast<float>(t));
  const int k = std::clamp(static_cast<int>(it - ch.times.begin()) - 1, 0, nK - 2);
  const double t0 = static_cast<double>(ch.times[static_cast<std::size_t>(k)]);
  const double t1 = static_cast<double>(ch.times[static_cast<std::size_t>(k + 1)]);
  const double td = t1 - t0;
  const double s = td > 0.0 ? std::clamp((t - t0) / td, 0.0, 1.0) : 1.0;
  switch (ch.interpolation) {
    case Interpolation::Step:
      copyKey(k);
      return;
    case Interpolation::Linear: {
      const float* a = v + k * stride;
      const float* b = v + (k + 1) * stride;
      if (C == 4) {
        slerp4(a, b, s, out);
      } else {
        for (int i = 0; i < C; ++i)
          out[i] = static_cast<float>((1.0 - s) * static_cast<double>(a[i]) +
                                      s * static_cast<double>(b[i]));
      }
      return;
    }
    case Interpolation::CubicSpline: {
      // glTF 2.0, Appendix C: p(s) = (2s^3 - 3s^2 + 1) v_k + td (s^3 - 2s^2 + s) b_k
      //                              + (-2s^3 + 3s^2) v_k+1 + td (s^3 - s^2) a_k+1,
      // b_k the out-tangent of key k, a_k+1 the in-tangent of key k + 1.
      const double s2 = s * s, s3 = s2 * s;
      const double h00 = 2 * s3 - 3 * s2 + 1, h10 = td * (s3 - 2 * s2 + s);
      const double h01 = -2 * s3 + 3 * s2, h11 = td * (s3 - s2);
      const float* k0 = v + k * stride;
      const float* k1 = v + (k + 1) * stride;
      for (int i = 0; i < C; ++i)
        out[i] = static_cast<float>(
            h00 * static_cast<double>(k0[C + i]) + h10 * static_cast<double>(k0[2 * C + i]) +
            h01 * static_cast<double>(k1[C + i]) + h11 * static_cast<double>(k1[i]));
      if (C == 4) normalize4(out);
      return;
    }
  }
}

void sampleClip(const Clip& clip, const anatomy::Body& body, double t, anatomy::Pose& pose) {
  const std::size_t n = body.segments.size();
  if (pose.local.size() != n) pose.local.resize(n);
  for (std::size_t i = 0; i < n; ++i) pose.local[i] = body.segments[i].rest;
  const ClipTime ct = clipTime(clip, t);
  float v[4] = {0.0f, 0.0f, 0.0f, 1.0f};
  for (const Channel& ch : clip.channels) {
    if (ch.segment < 0 || static_cast<std::size_t>(ch.segment) >= n)
      continue;  // checkClip rejects these
    sampleChannel(ch, ct.local, v);
    anatomy::Transform& tr = pose.local[static_cast<std::size_t>(ch.segment)];
    switch (ch.path) {
      case ChannelPath::Translation:
        tr.translation = Eigen::Vector3f(v[0], v[1], v[2]);
        break;
      case ChannelPath::Rotation:
        tr.rotation = quat(v);
        break;
      case ChannelPath::Scale:
        tr.scale = Eigen::Vector3f(v[0], v[1], v[2]);
        break;
    }
  }
  if (ct.cycles != 0 && clip.rootMotionSegment >= 0 &&
      static_cast<std::size_t>(clip.rootMotionSegment) < n)
    pose.local[static_cast<std::size_t>(clip.rootMotionSegment)].translation +=
        static_cast<float>(ct.cycles) * clip.rootMotion;
}

void blendPoses(const anatomy::Pose& a, const anatomy::Pose& b, float w, anatomy::Pose& out) {
  const std::size_t n = std::min(a.local.size(), b.local.size());
  if (out.local.size() != n) out.local.resize(n);
  const float u = std::clamp(w, 0.0f, 1.0f);
  for (std::size_t i = 0; i < n; ++i) {
    const anatomy::Transform& ta = a.local[i];
    const anatomy::Transform& tb = b.local[i];
    anatomy::Transform r;
    r.translation = (1.0f - u) * ta.translation + u * tb.translation;
    r.scale = (1.0f - u) * ta.scale + u * tb.scale;
    float q[4];
    slerp4(ta.rotation.coeffs().data(), tb.rotation.coeffs().data(), static_cast<double>(u), q);
    r.rotation = quat(q);
    out.local[i] = r;
  }
}

void sampleBlend(const Clip& a, double timeA, const Clip& b, double timeB, float w,
                 const anatomy::Body& body, anatomy::Pose& scratch, anatomy::Pose& out) {
  sampleClip(b, body, timeB, scratch);
  sampleClip(a, body, timeA, out);
  blendPoses(out, scratch, w, out);
}

float crossFadeWeight(double seconds, double fadeSeconds) {
  if (!(fadeSeconds > 0.0)) return 1.0f;
  const double x = std::clamp(seconds / fadeSeconds, 0.0, 1.0);
  return static_cast<float>(x * x * (3.0 - 2.0 * x));
}

double syncedTime(const Clip& from, double t, const Clip& to) {
  const ClipTime ct = clipTime(from, t);
  const double phase = from.duration > 0.0f ? ct.local / static_cast<double>(from.duration) : 0.0;
  return (static_cast<double>(ct.cycles) + phase) * static_cast<double>(to.duration);
}

anatomy::Pose bindPose(const anatomy::Body& body) {
  anatomy::Pose pose;
  pose.local.resize(body.segments.size());
  for (std::size_t i = 0; i < body.segments.size(); ++i) {
    const int parent = body.segments[i].parent;
    const Eigen::Affine3d bind = body.inverseBind[i].cast<double>().inverse();
    const Eigen::Affine3d local =
        parent < 0 ? bind
                   : body.inverseBind[static_cast<std::size_t>(parent)].cast<double>() * bind;
    Eigen::Matrix3d a = local.linear();
    Eigen::Vector3d s(a.col(0).norm(), a.col(1).norm(), a.col(2).norm());
    if (a.determinant() < 0.0) s.x() = -s.x();
    anatomy::Transform& t = pose.local[i];
    t.translation = local.translation().cast<float>();
    t.scale = s.cast<float>();
    if (s.cwiseAbs().minCoeff() > 0.0) {
      const Eigen::Matrix3d r = a * s.cwiseInverse().asDiagonal();
      const Eigen::JacobiSVD<Eigen::Matrix3d> svd(r, Eigen::ComputeFullU | Eigen::ComputeFullV);
      t.rotation = Eigen::Quaternionf(
          Eigen::Quaterniond(svd.matrixU() * svd.matrixV().transpose()).normalized().cast<float>());
    }
  }
  return pose;
}

int findClip(const std::vector<Clip>& clips, std::string_view name) {
  for (std::size_t i = 0; i < clips.size(); ++i)
    if (clips[i].name == name) return static_cast<int>(i);
  return -1;
}

void checkClip(const Clip& clip, const anatomy::Body& body) {
  PELAGE_CHECK(std::isfinite(clip.duration) && clip.duration >= 0.0f, "clip ", clip.name,
               " duration ", clip.duration);
  PELAGE_CHECK(clip.rootMotionSegment >= -1 && clip.rootMotionSegment < body.size(), "clip ",
               clip.name);
  PELAGE_CHECK(clip.rootMotion.allFinite(), "clip ", clip.name);
  for (const Channel& ch : clip.channels) {
    PELAGE_CHECK(ch.segment >= 0 && ch.segment < body.size(), "clip ", clip.name, " segment ",
                 ch.segment);
    const std::size_t perKey = static_cast<std::size_t>(ch.components()) *
                               (ch.interpolation == Interpolation::CubicSpline ? 3u : 1u);
    PELAGE_CHECK(!ch.times.empty() && ch.values.size() == ch.times.size() * perKey, "clip ",
                 clip.name, " channel of segment ", ch.segment, ": ", ch.times.size(), " keys, ",
                 ch.values.size(), " values");
    for (std::size_t k = 0; k < ch.times.size(); ++k) {
      PELAGE_CHECK(std::isfinite(ch.times[k]), "clip ", clip.name);
      PELAGE_CHECK(k == 0 || ch.times[k] >= ch.times[k - 1], "clip ", clip.name,
                   " times not sorted");
    }
    PELAGE_CHECK(ch.times.back() <= clip.duration * (1.0f + 1e-6f) + 1e-6f, "clip ", clip.name,
                 " key after its duration");
    for (float x : ch.values)
      PELAGE_CHECK(std::isfinite(x), "clip ", clip.name, " non-finite value");
  }
}

Channel cubicChannel(int segment, ChannelPath path, std::vector<float> times,
                     const std::vector<float>& values, const std::vector<float>& derivatives) {
  Channel ch;
  ch.segment = segment;
  ch.path = path;
  ch.interpolation = Interpolation::CubicSpline;
  const std::size_t C = static_cast<std::size_t>(ch.components());
  const std::size_t nK = times.size();
  PELAGE_CHECK(values.size() == nK * C && derivatives.size() == nK * C, "cubicChannel sizes");
  ch.times = std::move(times);
  ch.values.resize(nK * 3 * C);
  float sign = 1.0f;
  for (std::size_t k = 0; k < nK; ++k) {
    if (C == 4 && k > 0) {
      double dot = 0.0;
      for (std::size_t i = 0; i < 4; ++i)
        dot +=
            static_cast<double>(values[k * 4 + i]) * static_cast<double>(values[(k - 1) * 4 + i]);
      if (dot < 0.0) sign = -sign;  // relative to the previous key as stored, then flipped
    }
    for (std::size_t i = 0; i < C; ++i) {
      const float d = sign * derivatives[k * C + i];
      ch.values[k * 3 * C + i] = d;
      ch.values[k * 3 * C + C + i] = sign * values[k * C + i];
      ch.values[k * 3 * C + 2 * C + i] = d;
    }
  }
  return ch;
}

}  // namespace pelage::animation
