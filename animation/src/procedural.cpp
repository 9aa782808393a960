#include "pelage/animation/procedural.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>

#include "pelage/util/error.h"

namespace pelage::animation {
namespace {

constexpr double kPi = 3.14159265358979323846;

enum Seg {
  Pelvis,
  Spine,
  Chest,
  Neck,
  Head,
  LUpperarm,
  LForearm,
  LHand,
  RUpperarm,
  RForearm,
  RHand,
  LThigh,
  LShin,
  LFoot,
  RThigh,
  RShin,
  RFoot,
  Tail1,
  Tail2,
  Tail3,
  Tail4,
  Tail5,
  kSegCount
};
constexpr const char* kSegNames[kSegCount] = {
    "pelvis",     "spine",     "chest",  "neck",    "head",   "l_upperarm", "l_forearm", "l_hand",
    "r_upperarm", "r_forearm", "r_hand", "l_thigh", "l_shin", "l_foot",     "r_thigh",   "r_shin",
    "r_foot",     "tail1",     "tail2",  "tail3",   "tail4",  "tail5"};

const Eigen::Vector3f kX = Eigen::Vector3f::UnitX();  // the monkey's forward (roll axis)
const Eigen::Vector3f kY = Eigen::Vector3f::UnitY();  // its left (pitch axis; + = nose down)
const Eigen::Vector3f kZ = Eigen::Vector3f::UnitZ();  // up (yaw axis; + = turn left)

double rad(double deg) {
  return deg * kPi / 180.0;
}
double wrapAngle(double a) {
  return std::remainder(a, 2.0 * kPi);
}
// Angle of the (x, z) vector such that a rotation by theta about +Y adds theta to it:
// R_y(theta) (x, z) = (x cos + z sin, -x sin + z cos).
double sagittalAngle(double x, double z) {
  return std::atan2(x, z);
}
double fract(double x) {
  return x - std::floor(x);
}

Eigen::Quaternionf rot(const Eigen::Vector3f& axis, double deg) {
  return Eigen::Quaternionf(Eigen::AngleAxisf(static_cast<float>(rad(deg)), axis));
}

// The monkey's segments resolved once per evaluation.
struct TumbleBall;

struct Rig {
  const anatomy::Body& body;
  const std::vector<anatomy::Shape>& shapes;  // body shapes (bind-pose world), for ground contact
  std::array<int, kSegCount> idx{};
  mutable std::shared_ptr<const TumbleBall> ball;  // tumble's ball, computed on first use

  explicit Rig(const anatomy::Creature& c) : body(c.body), shapes(c.shapes) {
    const anatomy::Body& b = c.body;
    for (int s = 0; s < kSegCount; ++s) {
      idx[static_cast<std::size_t>(s)] = b.find(kSegNames[s]);
      if (idx[static_cast<std::size_t>(s)] < 0)
        inputError("the procedural monkey clips need a segment named '", kSegNames[s], "'");
    }
    PELAGE_CHECK(b.segments[static_cast<std::size_t>(idx[Pelvis])].parent < 0,
                 "pelvis must be the root");
  }
  int operator[](Seg s) const { return idx[static_cast<std::size_t>(s)]; }
  const anatomy::Segment& seg(Seg s) const {
    return body.segments[static_cast<std::size_t>((*this)[s])];
  }
  anatomy::Transform& local(anatomy::Pose& p, Seg s) const {
    return p.local[static_cast<std::size_t>((*this)[s])];
  }
  // Turns segment s by `deg` about `axis` in its own frame, on top of its current rotation.
  void turn(anatomy::Pose& p, Seg s, const Eigen::Vector3f& axis, double deg) const {
    anatomy::Transform& t = local(p, s);
    t.rotation = (t.rotation * rot(axis, deg)).normalized();
  }
  // World transform of segment index i in pose p (a walk up its parent chain).
  Eigen::Affine3f world(const anatomy::Pose& p, int i) const {
    Eigen::Affine3f m = Eigen::Affine3f::Identity();
    for (; i >= 0; i = body.segments[static_cast<std::size_t>(i)].parent)
      m = p.local[static_cast<std::size_t>(i)].matrix() * m;
    return m;
  }
  Eigen::Affine3f world(const anatomy::Pose& p, Seg s) const { return world(p, (*this)[s]); }
  // Bind-pose world position of a segment's joint.
  Eigen::Vector3f restJoint(Seg s) const {
    return (body.inverseBind[static_cast<std::size_t>((*this)[s])].inverse()).translation();
  }
};

// Two-bone inverse kinematics: the end segment's joint reaches `target` (world). In the upper
// segment's parent frame, the upper segment first swings sideways about its local X by alpha so
// that the target lies in the limb's plane: with the chain's constant lateral offset y0 and the
// target's (ty, tz) relative to the upper joint, R_x(alpha) (y0, z) = (ty, tz) gives
// z = -sqrt(ty^2 + tz^2 - y0^2). Then, in that plane (rotations about local Y), the law of cosines
// r^2 = |a|^2 + |b|^2 + 2 |a||b| cos(phi), phi the angle between the bones, keeps the rest bend
// direction (knees forward, elbows back). Finally the end segment (foot, hand) turns to the world
// orientation "level, heading with the parent, pitched by endPitchDeg".
void solveLimb(const Rig& rig, anatomy::Pose& p, Seg upper, Seg lower, Seg end,
               const Eigen::Vector3f& target, double endPitchDeg) {
  const int parent = rig.seg(upper).parent;
  const Eigen::Affine3f W = rig.world(p, parent);
  const Eigen::Vector3f P = W.inverse() * target;
  const Eigen::Vector3f J = rig.seg(upper).rest.translation;
  const Eigen::Vector3f a = rig.seg(lower).rest.translation;
  const Eigen::Vector3f b = rig.seg(end).rest.translation;
  // Abduction.
  const double y0 = static_cast<double>(a.y() + b.y());
  const double ty = static_cast<double>(P.y() - J.y()), tz = static_cast<double>(P.z() - J.z());
  const double zPlane = -std::sqrt(std::max(ty * ty + tz * tz - y0 * y0, 1e-8));
  const double alpha = wrapAngle(std::atan2(tz, ty) - std::atan2(zPlane, y0));
  // In the plane.
  const double ax = a.x(), az = a.z(), bx = b.x(), bz = b.z();
  const double la = std::hypot(ax, az), lb = std::hypot(bx, bz);
  const double dx = static_cast<double>(P.x() - J.x()), dz = zPlane;
  const double r = std::clamp(std::hypot(dx, dz), std::abs(la - lb) + 1e-4, 0.999 * (la + lb));
  const double phi0 = wrapAngle(sagittalAngle(bx, bz) - sagittalAngle(ax, az));
  const double c = std::clamp((r * r - la * la - lb * lb) / (2.0 * la * lb), -1.0, 1.0);
  const double phi = (phi0 >= 0.0 ? 1.0 : -1.0) * std::acos(c);
  const double th2 = phi - phi0;
  const double ex = ax + bx * std::cos(th2) + bz * std::sin(th2);
  const double ez = az - bx * std::sin(th2) + bz * std::cos(th2);
  const double th1 = wrapAngle(sagittalAngle(dx, dz) - sagittalAngle(ex, ez));
  rig.local(p, upper).rotation =
      (rig.seg(upper).rest.rotation * rot(kX, alpha * 180.0 / kPi) * rot(kY, th1 * 180.0 / kPi))
          .normalized();
  rig.local(p, lower).rotation =
      (rig.seg(lower).rest.rotation * rot(kY, th2 * 180.0 / kPi)).normalized();
  // The end segment: world rotation = R_z(heading of the parent) R_y(endPitch) R_rest-world.
  const Eigen::Vector3f fwd = W.linear() * kX;
  const double heading = std::atan2(static_cast<double>(fwd.y()), static_cast<double>(fwd.x()));
  const Eigen::Quaternionf restWorld(
      rig.body.inverseBind[static_cast<std::size_t>(rig[end])].inverse().linear());
  const Eigen::Quaternionf want = rot(kZ, heading * 180.0 / kPi) * rot(kY, endPitchDeg) * restWorld;
  const Eigen::Quaternionf lowerWorld(rig.world(p, lower).linear());
  rig.local(p, end).rotation = (lowerWorld.conjugate() * want).normalized();
}

// ---------------------------------------------------------------------------------------------
// walk: a lateral-sequence quadrupedal walk (hind left, fore left, hind right, fore right, a
// quarter cycle apart). Each foot is planted for a duty factor beta of the cycle, moving backward
// relative to the body at exactly the body's speed (so it stays still on the ground), then swings
// forward on a C1 Hermite path lifted by H sin^2(pi w).
constexpr double kWalkDuration = 1.0;  // s
constexpr double kWalkSpeed = 0.22;    // m/s
constexpr double kWalkDuty = 0.62;
constexpr double kWalkCrouch = 0.018;  // m the body lowers while walking
constexpr double kWalkLift = 0.03;     // m

// Foot offset along +X from its rest position relative to the body, at leg phase u in [0, 1).
double footStride(double u, double stride) {
  if (u < kWalkDuty) return stride / 2.0 - stride * u / kWalkDuty;
  const double w = (u - kWalkDuty) / (1.0 - kWalkDuty);
  const double m = -stride * (1.0 - kWalkDuty) / kWalkDuty;  // stance velocity in swing time units
  const double w2 = w * w, w3 = w2 * w;
  return (2 * w3 - 3 * w2 + 1) * (-stride / 2.0) + (w3 - 2 * w2 + w) * m +
         (-2 * w3 + 3 * w2) * (stride / 2.0) + (w3 - w2) * m;
}
double footLift(double u) {
  if (u < kWalkDuty) return 0.0;
  const double s = std::sin(kPi * (u - kWalkDuty) / (1.0 - kWalkDuty));
  return s * s;
}

void walk(const Rig& rig, double t, anatomy::Pose& p) {
  const double ph = 2.0 * kPi * t / kWalkDuration;
  const double stride = kWalkSpeed * kWalkDuty * kWalkDuration;
  anatomy::Transform& root = rig.local(p, Pelvis);
  root.translation +=
      Eigen::Vector3f(static_cast<float>(kWalkSpeed * t), 0.0f,
                      static_cast<float>(-kWalkCrouch + 0.004 * std::cos(2.0 * ph)));
  rig.turn(p, Pelvis, kZ, 2.0 * std::sin(ph));
  rig.turn(p, Pelvis, kX, 2.0 * std::cos(ph));
  rig.turn(p, Pelvis, kY, 1.2 * std::sin(2.0 * ph));
  rig.turn(p, Spine, kZ, -1.5 * std::sin(ph));
  rig.turn(p, Chest, kZ, -1.5 * std::sin(ph));
  rig.turn(p, Chest, kX, -1.5 * std::cos(ph));
  rig.turn(p, Neck, kY, -1.2 * std::sin(2.0 * ph));
  rig.turn(p, Head, kY, 3.0 * std::sin(2.0 * ph + 1.0));
  rig.turn(p, Head, kZ, 2.0 * std::sin(ph));
  const Seg tails[5] = {Tail1, Tail2, Tail3, Tail4, Tail5};
  for (int i = 0; i < 5; ++i) {
    rig.turn(p, tails[i], kZ, (6.0 + 2.0 * i) * std::sin(ph - 0.6 * i));
    rig.turn(p, tails[i], kY, 3.0 * std::sin(2.0 * ph - 0.5 * i));
  }
  struct Leg {
    Seg upper, lower, end;
    double phase, endFlex;
  };
  const Leg legs[4] = {{LThigh, LShin, LFoot, 0.0, 25.0},
                       {LUpperarm, LForearm, LHand, 0.25, 30.0},
                       {RThigh, RShin, RFoot, 0.5, 25.0},
                       {RUpperarm, RForearm, RHand, 0.75, 30.0}};
  for (const Leg& leg : legs) {
    const double u = fract(t / kWalkDuration + leg.phase);
    const Eigen::Vector3f rest = rig.restJoint(leg.end);
    const Eigen::Vector3f target =
        rest + Eigen::Vector3f(static_cast<float>(kWalkSpeed * t + footStride(u, stride)), 0.0f,
                               static_cast<float>(kWalkLift * footLift(u)));
    solveLimb(rig, p, leg.upper, leg.lower, leg.end, target, leg.endFlex * footLift(u));
  }
}

// ---------------------------------------------------------------------------------------------
// tumble: a slow forward roll. The body curls into a ball (spine, neck and head flexed, knees to
// the chest, arms hugging them, the tail wrapped round the flank) and the root pitches a full turn
// about +Y, theta = 2 pi t / T. The ball's centre c (mean of the body shapes' centres, pelvis
// frame) moves forward uniformly, x = r theta, r its mean height; the root's height keeps the
// body's lowest point on the ground: root z = smax_i(depth_i(theta)) over the body shapes (see
// Contact), smax the log-sum-exp soft maximum (smooth, so the motion stays C1). Upside down at
// theta = pi.
constexpr double kTumbleDuration = 3.0;

void tumbleCurl(const Rig& rig, anatomy::Pose& p) {
  rig.turn(p, Spine, kY, 20.0);
  rig.turn(p, Chest, kY, 25.0);
  rig.turn(p, Neck, kY, 30.0);
  rig.turn(p, Head, kY, 35.0);
  for (Seg s : {LThigh, RThigh}) rig.turn(p, s, kY, -55.0);
  for (Seg s : {LShin, RShin}) rig.turn(p, s, kY, 115.0);
  for (Seg s : {LFoot, RFoot}) rig.turn(p, s, kY, -30.0);
  for (Seg s : {LUpperarm, RUpperarm}) rig.turn(p, s, kY, -10.0);
  for (Seg s : {LForearm, RForearm}) rig.turn(p, s, kY, 100.0);
  for (Seg s : {LHand, RHand}) rig.turn(p, s, kY, 20.0);
  // The tail: flattened (its rest curl over the back undone) and wrapped round the left flank.
  const double yaw[5] = {70.0, 35.0, 35.0, 30.0, 30.0};
  const double pitch[5] = {-15.0, -35.0, -35.0, -25.0, -15.0};
  const Seg tails[5] = {Tail1, Tail2, Tail3, Tail4, Tail5};
  for (int i = 0; i < 5; ++i) {
    rig.turn(p, tails[i], kZ, yaw[i]);
    rig.turn(p, tails[i], kY, pitch[i]);
  }
}

// The body's lowest point below the pelvis joint when the pelvis frame is pitched by theta, as
// a list of "depths" (one per shape): for an ellipsoid with centre C, axes Q and radii r (in the
// pelvis frame of the curled pose), depth = -(R C).z + |diag(r) (R Q)^T z|, its exact support in
// -z; for a round cone, the deeper of its two end spheres. Without shapes: the joints with 5 cm of
// flesh.
struct Contact {
  std::vector<Eigen::Vector3d> centre;  // per shape (or joint)
  std::vector<Eigen::Matrix3d> axes;    // columns scaled by the radii (ellipsoids)
  std::vector<double> radius;           // sphere radius (capsule ends, joints); 0 for ellipsoids
  void depths(double theta, std::vector<double>& out) const {
    const Eigen::Matrix3d R = Eigen::AngleAxisd(theta, Eigen::Vector3d::UnitY()).toRotationMatrix();
    out.resize(centre.size());
    for (std::size_t i = 0; i < centre.size(); ++i) {
      const double z = (R * centre[i]).z();
      out[i] = radius[i] > 0.0 ? radius[i] - z : (R * axes[i]).row(2).norm() - z;
    }
  }
};

Contact curledContact(const Rig& rig, const anatomy::Pose& curled) {
  Contact c;
  anatomy::Pose ref = curled;
  rig.local(ref, Pelvis) = anatomy::Transform{};
  auto skinning = [&](int seg) {
    return (rig.world(ref, seg) * rig.body.inverseBind[static_cast<std::size_t>(seg)])
        .cast<double>();
  };
  for (const anatomy::Shape& sh : rig.shapes) {
    const Eigen::Affine3d S = skinning(sh.segment);
    if (sh.kind == anatomy::Shape::Kind::Ellipsoid) {
      c.centre.push_back(S * sh.center.cast<double>());
      c.axes.push_back(S.linear() * sh.rotation.cast<double>().toRotationMatrix() *
                       sh.radii.cast<double>().asDiagonal());
      c.radius.push_back(0.0);
    } else {
      for (const auto& [p, r] : {std::pair{sh.from, sh.rFrom}, std::pair{sh.to, sh.rTo}}) {
        c.centre.push_back(S * p.cast<double>());
        c.axes.push_back(Eigen::Matrix3d::Zero());
        c.radius.push_back(std::max(static_cast<double>(r), 1e-4));
      }
    }
  }
  if (c.centre.empty())
    for (int i = 0; i < rig.body.size(); ++i) {
      c.centre.push_back(rig.world(ref, i).translation().cast<double>());
      c.axes.push_back(Eigen::Matrix3d::Zero());
      c.radius.push_back(0.05);
    }
  return c;
}

// Soft maximum (log-sum-exp, sharpness k per metre): smooth, at most log(n)/k above the maximum.
double softMax(const std::vector<double>& x, double k) {
  double top = -1e300;
  for (double v : x) top = std::max(top, v);
  double sum = 0.0;
  for (double v : x) sum += std::exp(k * (v - top));
  return top + std::log(sum) / k;
}

// The curled ball, computed once per Rig (it depends only on the body and its shapes).
struct TumbleBall {
  Contact contact;
  Eigen::Vector3d centre;  // c, pelvis frame
  double radius = 0.0;     // r, the centre's mean height over a turn
  double rootHeight(double theta, std::vector<double>& scratch) const {
    contact.depths(theta, scratch);
    return softMax(scratch, 400.0);
  }
};

const TumbleBall& tumbleBall(const Rig& rig, const anatomy::Pose& curled) {
  if (!rig.ball) {
    auto ball = std::make_shared<TumbleBall>();
    ball->contact = curledContact(rig, curled);
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (const auto& x : ball->contact.centre) c += x;
    c /= static_cast<double>(ball->contact.centre.size());
    c.y() = 0.0;
    ball->centre = c;
    std::vector<double> scratch;
    const int samples = 72;
    for (int i = 0; i < samples; ++i) {
      const double th = 2.0 * kPi * i / samples;
      ball->radius +=
          ball->rootHeight(th, scratch) + (Eigen::AngleAxisd(th, Eigen::Vector3d::UnitY()) * c).z();
    }
    ball->radius /= samples;
    rig.ball = std::move(ball);
  }
  return *rig.ball;
}

void tumble(const Rig& rig, double t, anatomy::Pose& p) {
  tumbleCurl(rig, p);
  const TumbleBall& ball = tumbleBall(rig, p);
  std::vector<double> scratch;
  const double theta = 2.0 * kPi * t / kTumbleDuration;
  const Eigen::Vector3d Rc = Eigen::AngleAxisd(theta, Eigen::Vector3d::UnitY()) * ball.centre;
  anatomy::Transform& root = rig.local(p, Pelvis);
  root.rotation = (rot(kY, theta * 180.0 / kPi) * rig.seg(Pelvis).rest.rotation).normalized();
  root.translation = Eigen::Vector3f(static_cast<float>(ball.radius * theta - Rc.x()), 0.0f,
                                     static_cast<float>(ball.rootHeight(theta, scratch)));
}

// ---------------------------------------------------------------------------------------------
// hang: hanging from the left hand, which stays fixed at a point P above the ground. The arm
// reaches overhead, the rest of the body dangles; the whole body is rotated so that its centre (the
// mean of its joints) hangs straight below the grip, then swings about P like a pendulum, phi(t) =
// A sin(2 pi t / T); legs, free arm and tail swing behind it with a phase lag.
constexpr double kHangDuration = 1.4;
constexpr double kHangSwingDeg = 16.0;

void hangLimbs(const Rig& rig, anatomy::Pose& p, double ph, double motion) {
  rig.turn(p, LUpperarm, kY, -95.0);
  rig.turn(p, LForearm, kY, -8.0);
  rig.turn(p, LHand, kY, -25.0);
  rig.turn(p, RUpperarm, kY, 75.0 + motion * 14.0 * std::sin(ph - 1.0));
  rig.turn(p, RForearm, kY, -25.0 - motion * 8.0 * std::sin(ph - 1.4));
  rig.turn(p, Spine, kY, -6.0);
  rig.turn(p, Head, kY, -12.0);
  rig.turn(p, Head, kZ, motion * 10.0 * std::sin(ph + 0.5));
  for (Seg s : {LThigh, RThigh}) rig.turn(p, s, kY, 55.0 + motion * 12.0 * std::sin(ph - 0.8));
  for (Seg s : {LShin, RShin}) rig.turn(p, s, kY, -25.0 - motion * 8.0 * std::sin(ph - 1.2));
  for (Seg s : {LFoot, RFoot}) rig.turn(p, s, kY, 25.0);
  const double straighten[5] = {-15.0, -35.0, -35.0, -25.0, -15.0};
  const Seg tails[5] = {Tail1, Tail2, Tail3, Tail4, Tail5};
  for (int i = 0; i < 5; ++i) {
    rig.turn(p, tails[i], kY, straighten[i] + motion * 6.0 * std::sin(ph - 0.9 - 0.4 * i));
    rig.turn(p, tails[i], kZ, motion * (4.0 + 2.0 * i) * std::sin(ph - 0.5 * i));
  }
}

// The grip: a point in the left palm, below the wrist joint in the hand's frame.
Eigen::Vector3f gripPoint(const Rig& rig, const anatomy::Pose& p) {
  return rig.world(p, LHand) * Eigen::Vector3f(0.012f, 0.0f, -0.03f);
}

void hang(const Rig& rig, double t, anatomy::Pose& p) {
  const double ph = 2.0 * kPi * t / kHangDuration;
  // Reference orientation from the pose without secondary motion, so that it is constant.
  anatomy::Pose ref = p;
  hangLimbs(rig, ref, 0.0, 0.0);
  rig.local(ref, Pelvis) = anatomy::Transform{};
  Eigen::Vector3f centre = Eigen::Vector3f::Zero();
  for (int i = 0; i < rig.body.size(); ++i) centre += rig.world(ref, i).translation();
  centre /= static_cast<float>(rig.body.size());
  const Eigen::Vector3f g0 = gripPoint(rig, ref);
  const Eigen::Quaternionf hangRot = Eigen::Quaternionf::FromTwoVectors(g0 - centre, kZ);
  // The grip height: the lowest joint 12 cm above the ground when hanging still.
  float drop = 0.0f;
  for (int i = 0; i < rig.body.size(); ++i)
    drop = std::max(drop, (hangRot * (g0 - rig.world(ref, i).translation())).z());
  const Eigen::Vector3f P(0.0f, 0.0f, drop + 0.12f);

  hangLimbs(rig, p, ph, 1.0);
  rig.local(p, Pelvis) = anatomy::Transform{};
  const Eigen::Vector3f g = gripPoint(rig, p);  // in the pelvis frame (root at identity)
  anatomy::Transform& root = rig.local(p, Pelvis);
  root.rotation = (rot(kY, kHangSwingDeg * std::sin(ph)) * hangRot).normalized();
  root.translation = P - root.rotation * g;
  root.scale = rig.seg(Pelvis).rest.scale;
}

// ---------------------------------------------------------------------------------------------
// shake: a wet-dog shake. The trunk rolls about the body axis at 5 Hz, each segment lagging the one
// behind it, under the envelope sin^2(pi t / T) (zero with zero slope at the loop point). The legs
// counter-roll to stay under the body.
constexpr double kShakeDuration = 1.5;

void shake(const Rig& rig, double t, anatomy::Pose& p) {
  const double s = std::sin(kPi * t / kShakeDuration);
  const double env = s * s;
  const double w = 2.0 * kPi * 5.0 * t;
  const double rollPelvis = env * 5.0 * std::sin(w);
  const double rollSpine = env * 10.0 * std::sin(w - 0.4);
  const double rollChest = env * 16.0 * std::sin(w - 0.8);
  rig.local(p, Pelvis).translation.z() += static_cast<float>(0.006 * env);
  rig.turn(p, Pelvis, kX, rollPelvis);
  rig.turn(p, Spine, kX, rollSpine);
  rig.turn(p, Chest, kX, rollChest);
  rig.turn(p, Neck, kX, env * 14.0 * std::sin(w - 1.2));
  rig.turn(p, Head, kX, env * 22.0 * std::sin(w - 1.6));
  rig.turn(p, Head, kY, env * 6.0);
  for (Seg leg : {LThigh, RThigh}) rig.turn(p, leg, kX, -rollPelvis);
  for (Seg arm : {LUpperarm, RUpperarm})
    rig.turn(p, arm, kX, -(rollPelvis + rollSpine + rollChest));
  const Seg tails[5] = {Tail1, Tail2, Tail3, Tail4, Tail5};
  for (int i = 0; i < 5; ++i)
    rig.turn(p, tails[i], kZ, env * (10.0 + 4.0 * i) * std::sin(w - 2.0 - 0.5 * i));
}

// ---------------------------------------------------------------------------------------------
// idle: breathing (2 s), looking around and a lazy tail (4 s). Every period divides the clip.
constexpr double kIdleDuration = 4.0;

void idle(const Rig& rig, double t, anatomy::Pose& p) {
  const double slow = 2.0 * kPi * t / kIdleDuration;
  const double breath = 2.0 * slow;
  rig.local(p, Pelvis).translation.z() += static_cast<float>(0.0015 * std::sin(breath));
  rig.turn(p, Spine, kY, 0.6 * std::sin(breath));
  rig.turn(p, Chest, kY, -1.2 * std::sin(breath));
  rig.turn(p, Neck, kY, 3.0 * std::sin(slow + 0.3));
  rig.turn(p, Head, kZ, 20.0 * std::sin(slow));
  rig.turn(p, Head, kY, 4.0 * std::sin(breath));
  const Seg tails[5] = {Tail1, Tail2, Tail3, Tail4, Tail5};
  for (int i = 0; i < 5; ++i) {
    rig.turn(p, tails[i], kZ, (5.0 + 3.0 * i) * std::sin(slow - 0.5 * i));
    rig.turn(p, tails[i], kY, 4.0 * std::sin(breath - 0.4 * i));
  }
}

struct ClipDef {
  const char* name;
  double duration;
  void (*fn)(const Rig&, double, anatomy::Pose&);
};
const ClipDef kClips[] = {{"walk", kWalkDuration, walk},
                          {"tumble", kTumbleDuration, tumble},
                          {"hang", kHangDuration, hang},
                          {"shake", kShakeDuration, shake},
                          {"idle", kIdleDuration, idle}};

const ClipDef& clipDef(const std::string& name) {
  for (const ClipDef& c : kClips)
    if (name == c.name) return c;
  inputError("unknown procedural clip '", excerpt(name),
             "' (known: walk, tumble, hang, shake, idle)");
}

}  // namespace

const std::vector<std::string>& monkeyClipNames() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for (const ClipDef& c : kClips) n.emplace_back(c.name);
    return n;
  }();
  return names;
}

std::string missingMonkeySegment(const anatomy::Body& body) {
  for (const char* name : kSegNames)
    if (body.find(name) < 0) return name;
  return "";
}

double monkeyClipDuration(const std::string& name) {
  return clipDef(name).duration;
}

void evaluateMonkeyClip(const anatomy::Creature& creature, const std::string& name, double t,
                        anatomy::Pose& pose) {
  const ClipDef& def = clipDef(name);
  const Rig rig(creature);
  pose = anatomy::restPose(creature.body);
  def.fn(rig, t, pose);
}

Clip bakeMonkeyClip(const anatomy::Creature& creature, const std::string& name, int keysPerSecond) {
  if (keysPerSecond < 4 || keysPerSecond > 240)
    inputError("keys per second ", keysPerSecond, " is out of range [4, 240]");
  const ClipDef& def = clipDef(name);
  const Rig rig(creature);
  const anatomy::Body& body = creature.body;
  const int intervals = std::max(2, static_cast<int>(std::lround(def.duration * keysPerSecond)));
  const double h = 1e-3;  // s, central-difference step for the tangents
  const std::size_t nK = static_cast<std::size_t>(intervals) + 1;
  const std::size_t nS = body.segments.size();
  std::vector<float> times(nK);
  // Per key: the pose at t and at t -+ h.
  std::vector<anatomy::Pose> at(nK), before(nK), after(nK);
  for (std::size_t k = 0; k < nK; ++k) {
    const double t = def.duration * static_cast<double>(k) / intervals;
    times[k] = static_cast<float>(t);
    for (auto [poses, dt] : {std::pair{&at, 0.0}, std::pair{&before, -h}, std::pair{&after, h}}) {
      anatomy::Pose& p = (*poses)[k];
      p = anatomy::restPose(body);
      def.fn(rig, t + dt, p);
    }
  }
  Clip clip;
  clip.name = def.name;
  clip.duration = static_cast<float>(def.duration);
  clip.loop = true;
  for (std::size_t s = 0; s < nS; ++s) {
    std::vector<float> q(nK * 4), dq(nK * 4);
    bool moves = false;
    for (std::size_t k = 0; k < nK; ++k) {
      const Eigen::Vector4f c = at[k].local[s].rotation.coeffs();
      Eigen::Vector4f b = before[k].local[s].rotation.coeffs(),
                      a = after[k].local[s].rotation.coeffs();
      if (b.dot(c) < 0.0f) b = -b;
      if (a.dot(c) < 0.0f) a = -a;
      const Eigen::Vector4f d = (a - b) / static_cast<float>(2.0 * h);
      for (int i = 0; i < 4; ++i) {
        q[k * 4 + static_cast<std::size_t>(i)] = c[i];
        dq[k * 4 + static_cast<std::size_t>(i)] = d[i];
      }
      moves = moves || !at[k].local[s].rotation.isApprox(body.segments[s].rest.rotation, 1e-6f);
    }
    if (moves)
      clip.channels.push_back(
          cubicChannel(static_cast<int>(s), ChannelPath::Rotation, times, q, dq));
  }
  // The root's translation (the only translated segment).
  const std::size_t root = static_cast<std::size_t>(rig[Pelvis]);
  std::vector<float> x(nK * 3), dx(nK * 3);
  for (std::size_t k = 0; k < nK; ++k) {
    const Eigen::Vector3f v = at[k].local[root].translation;
    const Eigen::Vector3f d =
        (after[k].local[root].translation - before[k].local[root].translation) /
        static_cast<float>(2.0 * h);
    for (int i = 0; i < 3; ++i) {
      x[k * 3 + static_cast<std::size_t>(i)] = v[i];
      dx[k * 3 + static_cast<std::size_t>(i)] = d[i];
    }
  }
  clip.channels.push_back(
      cubicChannel(static_cast<int>(root), ChannelPath::Translation, times, x, dx));
  clip.rootMotionSegment = static_cast<int>(root);
  clip.rootMotion = at[nK - 1].local[root].translation - at[0].local[root].translation;
  if (clip.rootMotion.norm() < 1e-6f) clip.rootMotion.setZero();
  checkClip(clip, body);
  return clip;
}

std::vector<Clip> monkeyClips(const anatomy::Creature& creature) {
  std::vector<Clip> clips;
  for (const std::string& name : monkeyClipNames()) clips.push_back(bakeMonkeyClip(creature, name));
  return clips;
}

}  // namespace pelage::animation
