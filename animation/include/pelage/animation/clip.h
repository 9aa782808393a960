// Animation clips: per-segment keyframed channels (glTF 2.0 animation semantics) sampled into a
// Pose, and pose blending. A Clip is constant during playback; sampling writes into a caller-owned
// Pose and neither allocates (after the Pose is sized once) nor throws.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "pelage/anatomy/body.h"
#include "pelage/anatomy/pose.h"

namespace pelage::animation {

// glTF's three keyframe interpolations.
enum class Interpolation { Step, Linear, CubicSpline };
// The local transform component a channel drives.
enum class ChannelPath { Translation, Rotation, Scale };

// One animated component of one segment.
struct Channel {
  int segment = 0;
  ChannelPath path = ChannelPath::Rotation;
  Interpolation interpolation = Interpolation::Linear;
  std::vector<float> times;  // nK key times (s), non-decreasing
  // Step/Linear: nK x C values; CubicSpline: nK x 3 x C (in-tangent, value, out-tangent per key,
  // glTF order; tangents in units per second). C = 4 for rotation (quaternion x, y, z, w), else 3.
  std::vector<float> values;

  int components() const { return path == ChannelPath::Rotation ? 4 : 3; }
  int keys() const { return static_cast<int>(times.size()); }
};

// A named clip. Time wraps over [0, duration] when looping and clamps otherwise.
struct Clip {
  std::string name;
  float duration = 0.0f;  // seconds (the last key time unless set longer)
  bool loop = true;
  std::vector<Channel> channels;
  // Root motion: a looping clip that travels (walk, tumble) moves `rootMotion` (in the parent frame
  // of `rootMotionSegment`, metres) per cycle; sampling adds completed cycles x rootMotion to that
  // segment's translation so that playback continues seamlessly past the loop point.
  int rootMotionSegment = -1;
  Eigen::Vector3f rootMotion = Eigen::Vector3f::Zero();
};

// Where time `t` falls in a clip: the local time in [0, duration] and the completed loop cycles
// (0 for clamped clips).
struct ClipTime {
  double local = 0.0;
  std::int64_t cycles = 0;
};
ClipTime clipTime(const Clip& clip, double t);

// Value of one channel at local time `t` (s): `out` receives components() floats. Before the first
// key: the first value; after the last: the last. Rotations are unit quaternions (x, y, z, w):
// LINEAR uses shortest-arc slerp, CUBICSPLINE normalises the Hermite result (glTF 2.0 spec, App.
// C).
void sampleChannel(const Channel& channel, double t, float* out);

// Samples `clip` at time `t` (s) into `pose`: every segment starts at its rest transform, then each
// channel overrides its component, then root motion is added. `pose` is resized only when its size
// differs from the body's.
void sampleClip(const Clip& clip, const anatomy::Body& body, double t, anatomy::Pose& pose);

// Per-segment blend out = (1 - w) a + w b: translations and scales interpolate linearly, rotations
// by shortest-arc slerp. w in [0, 1]. `out` may alias `a` or `b`.
void blendPoses(const anatomy::Pose& a, const anatomy::Pose& b, float w, anatomy::Pose& out);

// Samples two clips and blends them (walk-to-run with a weight, or a cross-fade when switching).
// `scratch` holds clip b's pose between calls.
void sampleBlend(const Clip& a, double timeA, const Clip& b, double timeB, float w,
                 const anatomy::Body& body, anatomy::Pose& scratch, anatomy::Pose& out);

// Cross-fade weight `seconds` after a switch that takes `fadeSeconds`: smoothstep from 0 to 1 (1 at
// once when fadeSeconds <= 0).
float crossFadeWeight(double seconds, double fadeSeconds);

// The time in clip `to` at the same phase (fraction of its duration) as time `t` in clip `from`, so
// that two gaits blend foot-in-step.
double syncedTime(const Clip& from, double t, const Clip& to);

// The bind pose: every segment at its bind transform (the inverse of Body::inverseBind), so that
// all skinning matrices are the identity and the skin is exactly its stored bind-space mesh. (A
// glTF file's node rest transforms may differ from its skin's bind pose.) Each local transform is
// decomposed into TRS (rotation from the polar decomposition, scale = column norms).
anatomy::Pose bindPose(const anatomy::Body& body);

// Index of the clip called `name`, or -1.
int findClip(const std::vector<Clip>& clips, std::string_view name);

// Checks a clip against the body it drives (segment indices, value counts, finite values, sorted
// times, duration); PELAGE_CHECK on failure. Loaders validate user input before this.
void checkClip(const Clip& clip, const anatomy::Body& body);

// Builds a CUBICSPLINE channel from key values and their time derivatives (per second), both
// nK x C. Rotation keys are sign-aligned (q and -q are the same rotation) so that consecutive keys
// take the short way.
Channel cubicChannel(int segment, ChannelPath path, std::vector<float> times,
                     const std::vector<float>& values, const std::vector<float>& derivatives);

}  // namespace pelage::animation
