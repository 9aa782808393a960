// The gravity-response analysis (analyze.h) and dynamic fur over clips (dynamic_fur.h) on a
// hand-made model with known answers: a furred ball (one segment, 1 cm hairs) held still, turned
// upside down, turned suddenly; sweeps, CSV columns and units, determinism and pre-roll.
#include "pelage/scene/analyze.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "pelage/animation/clip.h"
#include "pelage/util/error.h"
#include "pelage/util/parallel.h"
#include "support/skins.h"

namespace pelage::scene {
namespace {

constexpr double kPi = 3.14159265358979323846;

// A clip turning the root about +X: `degrees[k]` at `times[k]`, step or linear interpolation.
animation::Clip turnClip(const std::string& name, std::vector<float> times,
                         const std::vector<double>& degrees, animation::Interpolation interpolation,
                         float duration) {
  animation::Clip clip;
  clip.name = name;
  clip.loop = false;
  clip.duration = duration;
  animation::Channel ch;
  ch.segment = 0;
  ch.path = animation::ChannelPath::Rotation;
  ch.interpolation = interpolation;
  ch.times = std::move(times);
  for (double d : degrees) {
    const Eigen::Quaternionf q(
        Eigen::AngleAxisf(static_cast<float>(d * kPi / 180.0), Eigen::Vector3f::UnitX()));
    ch.values.insert(ch.values.end(), {q.x(), q.y(), q.z(), q.w()});
  }
  clip.channels.push_back(ch);
  return clip;
}

// A ball of radius 2 cm on one segment, every hair 1 cm long (so every hair springs at f0), with
// clips: still (1 s at rest), flip (upside down: 180 degrees about X over 1 s), jolt (a 10 degree
// turn within one frame at 0.5 s, then still).
const Model& ball() {
  static const Model m = [] {
    Model b;
    b.name = "ball";
    b.source = "analyze_test";
    anatomy::SegmentSpec root;
    root.name = "root";
    b.body = anatomy::makeBody({root}, "analyze_test");
    b.skin = test::makeSphere(0.02f, 16, 32);
    for (auto v : b.skin.mesh.vertices()) b.skin.mesh.property(b.skin.furLength, v) = 0.01f;
    b.clips.push_back(turnClip("still", {0.0f}, {0.0}, animation::Interpolation::Linear, 1.0f));
    b.clips.push_back(
        turnClip("flip", {0.0f, 1.0f}, {0.0, 179.9}, animation::Interpolation::Linear, 1.0f));
    b.clips.push_back(
        turnClip("jolt", {0.0f, 0.5f}, {0.0, 10.0}, animation::Interpolation::Step, 0.5f));
    return b;
  }();
  return m;
}

const Fur& ballFur() {
  static const Fur f = [] {
    fur::FurParams p = test::simpleParams(fur::HairStyle::Polyline, 6000);
    return growFur(ball(), p, "analyze_test");
  }();
  return f;
}

AnalysisOptions options(int clip, int last, bool dynamics) {
  AnalysisOptions o;
  o.clip = clip;
  o.frames = {0, last};
  o.dynamics = dynamics;
  o.dynamicsParams.coats = {fur::CoatDynamics{3.0f, 0.3f}, fur::CoatDynamics{3.0f, 0.3f}};
  return o;
}

TEST(Analyze, AStillBodyStartsAndStaysOnTheQuasiStaticHairs) {
  AnalysisOptions o = options(0, 30, true);
  o.holdSeconds = 1.0;
  const AnalysisResult r = analyzeClip(ball(), ballFur(), o);
  ASSERT_EQ(r.frames.size(), 61u);
  for (const FrameAnalysis& f : r.frames) {
    EXPECT_NEAR(f.dynamic.all.droopMeanDeg, f.quasiStatic.all.droopMeanDeg, 1e-3);
    EXPECT_NEAR(f.dynamic.tipHeightMm, f.quasiStatic.tipHeightMm, 1e-4);
    EXPECT_LT(f.lagDeg, 1e-2);
    EXPECT_NEAR(f.tiltDeg, 0.0, 1e-6);
    EXPECT_LT(f.quasiStatic.tipSpeed, 1e-6);
  }
  // Gravity pulls every hair down: the ends fall below the weightless ends (droop > 0) and the mean
  // droop of the ball's hairs is the same in every frame.
  EXPECT_GT(r.frames[0].quasiStatic.all.droopMeanDeg, 5.0);
  EXPECT_EQ(r.frames[0].quasiStatic.all.droopMeanDeg, r.frames.back().quasiStatic.all.droopMeanDeg);
  EXPECT_EQ(r.groupNames, std::vector<std::string>{"body"});
  EXPECT_EQ(r.frames[0].quasiStatic.groups[0].hairs, r.frames[0].quasiStatic.all.hairs);
}

TEST(Analyze, UpsideDownFlipsTheMeanDroopDirectionRelativeToTheBody) {
  const AnalysisResult r = analyzeClip(ball(), ballFur(), options(1, 30, false));
  const FrameAnalysis& up = r.frames.front();
  const FrameAnalysis& down = r.frames.back();
  EXPECT_NEAR(up.tiltDeg, 0.0, 1e-4);
  EXPECT_NEAR(down.tiltDeg, 179.9, 1e-2);
  EXPECT_NEAR(down.rollDeg, 179.9, 1e-2);  // the up vector turned about +X towards -Y
  EXPECT_NEAR(down.bodyUp.z(), -1.0, 1e-4);
  // Upright the ends fall toward the body's underside, upside down toward its top: opposite signs
  // and (a symmetric ball) the same size.
  EXPECT_LT(up.quasiStatic.droopBodyUpMm, -0.5);
  EXPECT_GT(down.quasiStatic.droopBodyUpMm, 0.5);
  EXPECT_NEAR(down.quasiStatic.droopBodyUpMm, -up.quasiStatic.droopBodyUpMm,
              0.05 * std::abs(up.quasiStatic.droopBodyUpMm));
  // Relative to the world nothing changes: the tips hang below their roots by the same amount.
  EXPECT_NEAR(down.quasiStatic.tipHeightMm, up.quasiStatic.tipHeightMm,
              0.05 * std::abs(up.quasiStatic.tipHeightMm));
}

TEST(Analyze, StifferCoatsDroopLessMonotonically) {
  const SweepSpec spec = parseSweep("stiffness=0.1:0.9:5");
  const SweepResult s = sweepClip(ball(), ballFur(), options(1, 10, false), spec);
  ASSERT_EQ(s.runs.size(), 5u);
  for (std::size_t f = 0; f < s.runs[0].frames.size(); ++f)
    for (std::size_t i = 1; i < s.runs.size(); ++i) {
      EXPECT_LT(s.runs[i].frames[f].quasiStatic.all.droopMeanDeg,
                s.runs[i - 1].frames[f].quasiStatic.all.droopMeanDeg);
      EXPECT_GT(s.runs[i].frames[f].quasiStatic.tipHeightMm,
                s.runs[i - 1].frames[f].quasiStatic.tipHeightMm);
    }
  // Its CSV: a column per value, named as the unswept columns are (qs_: quasi-static).
  const std::string csv = sweepCsv(s);
  EXPECT_EQ(csv.substr(0, csv.find('\n')),
            "frame,time_s,held,pitch_deg,tilt_deg,qs_droop_mean_deg[stiffness=0.1],"
            "qs_droop_mean_deg[stiffness=0.3],qs_droop_mean_deg[stiffness=0.5],"
            "qs_droop_mean_deg[stiffness=0.7],qs_droop_mean_deg[stiffness=0.9],"
            "qs_tip_height_mm[stiffness=0.1],qs_tip_height_mm[stiffness=0.3],"
            "qs_tip_height_mm[stiffness=0.5],qs_tip_height_mm[stiffness=0.7],"
            "qs_tip_height_mm[stiffness=0.9]");
  // The table holds the values themselves; the CSV writes each as the shortest decimal that reads
  // back as the same double (not 6 digits).
  const AnalysisTable t = sweepTable(s);
  ASSERT_EQ(t.names.size(), 15u);
  EXPECT_EQ(t.rows(), s.runs[0].frames.size());
  EXPECT_EQ(t.columns[7][2], s.runs[2].frames[2].quasiStatic.all.droopMeanDeg);
  const std::string row =
      csv.substr(csv.find('\n') + 1, csv.find('\n', csv.find('\n') + 1) - csv.find('\n') - 1);
  std::vector<std::string> cells;
  for (std::size_t at = 0, comma; at <= row.size(); at = comma + 1) {
    comma = row.find(',', at);
    if (comma == std::string::npos) comma = row.size();
    cells.push_back(row.substr(at, comma - at));
  }
  ASSERT_EQ(cells.size(), 15u);
  for (std::size_t c = 3; c < cells.size(); ++c)
    EXPECT_EQ(std::stod(cells[c]), t.columns[c][0]) << t.names[c] << " = " << cells[c];
  // An explicit list of values, in the given order; bad ones name the field.
  const SweepSpec listed = sweepValues("stiffness", {0.8, 0.2});
  EXPECT_EQ(listed.values(), (std::vector<double>{0.8, 0.2}));
  EXPECT_THROW(sweepValues("stiffness", {}), InputError);
  EXPECT_THROW(sweepValues("stiffness", {0.5, 1.5}), InputError);
  EXPECT_THROW(sweepRange("damping", 0.0, 1.0, 0), InputError);
  EXPECT_EQ(sweepRange("damping", 0.0, 1.0, 3).values(), (std::vector<double>{0.0, 0.5, 1.0}));
}

TEST(Analyze, AFrameStepReportsTheFramesOfAWholeRun) {
  const AnalysisResult whole = analyzeClip(ball(), ballFur(), options(1, 12, true));
  AnalysisOptions stepped = options(1, 12, true);
  stepped.frames.step = 4;
  const AnalysisResult every4 = analyzeClip(ball(), ballFur(), stepped);
  ASSERT_EQ(every4.frames.size(), 4u);
  for (std::size_t i = 0; i < every4.frames.size(); ++i) {
    const FrameAnalysis& a = every4.frames[i];
    const FrameAnalysis& b = whole.frames[4 * i];
    EXPECT_EQ(a.frame, b.frame);
    EXPECT_EQ(a.dynamic.all.droopMeanDeg, b.dynamic.all.droopMeanDeg);
    EXPECT_EQ(a.dynamic.tipSpeed, b.dynamic.tipSpeed);
  }
}

// The jolt's answer from the spring alone: the target jumps by dT within one frame (moving at
// V = dT / dt), from rest: after that frame u = -uv V, E' = V + vv (-V); from then on the target is
// still and u(t) = uu(t) u0 + uv(t) E'0, normalised here by |dT|. Returns u at the frames k / fps.
std::vector<double> joltResponse(double f, double zeta, double fps, int frames) {
  const double dt = 1.0 / fps, v = 1.0 / dt;
  const fur::SpringStep jump = fur::springStep(f, zeta, dt);
  const double u0 = -jump.uv * v, e0 = v - jump.vv * v;
  std::vector<double> u;
  for (int k = 0; k <= frames; ++k) {
    const fur::SpringStep m = fur::springStep(f, zeta, k * dt);
    u.push_back(m.uu * u0 + m.uv * e0);
  }
  return u;
}

class Jolt : public testing::TestWithParam<float> {};
TEST_P(Jolt, TheEndsLagASuddenTurnThenSwingAndSettleAsTheSpringPredicts) {
  const float zeta = GetParam();
  AnalysisOptions o = options(2, 15, true);  // the turn happens between frames 14 and 15
  for (auto& c : o.dynamicsParams.coats) c.dampingRatio = zeta;
  o.holdSeconds = 2.0;
  const AnalysisResult r = analyzeClip(ball(), ballFur(), o);
  EXPECT_LT(r.frames[14].lagDeg, 1e-2);
  EXPECT_GT(r.frames[15].lagDeg, 5.0) << "the ends lag the turn";
  const SettlingAnalysis& s = r.settling;
  ASSERT_TRUE(s.measured);
  EXPECT_NEAR(s.stopSeconds, 0.5, 1e-9);
  EXPECT_NEAR(s.meanLengthMm, 10.0, 1e-3);
  EXPECT_NEAR(s.springFrequencyHz, 3.0, 1e-5);
  // The spring released from rest: 2 % envelope time ln(1 / (0.02 sqrt(1 - zeta^2))) / (zeta w).
  if (zeta < 1.0f) {
    const double z = zeta;
    EXPECT_NEAR(s.springSettlingSeconds,
                std::log(1.0 / (0.02 * std::sqrt(1 - z * z))) / (z * 2 * kPi * 3.0), 1e-5);
    EXPECT_NEAR(s.springOvershootPercent, 100 * std::exp(-kPi * z / std::sqrt(1 - z * z)), 1e-3);
  }
  // The measured response against the jolt's analytic answer (all hairs 1 cm: one frequency),
  // sampled at the same frames: swing, overshoot past the rest shape, 2 % settling time.
  const std::vector<double> u = joltResponse(3.0, zeta, 30.0, 60);
  std::size_t peak = 0;
  for (std::size_t k = 0; k < u.size(); ++k)
    if (std::abs(u[k]) > std::abs(u[peak])) peak = k;
  double beyond = 0.0, settled = 0.0;
  for (std::size_t k = peak; k < u.size(); ++k)
    beyond = std::max(beyond, -u[k] * (u[peak] < 0 ? -1.0 : 1.0));
  for (std::size_t k = 0; k < u.size(); ++k)
    if (std::abs(u[k]) > 0.02 * std::abs(u[peak])) settled = (k + 1) / 30.0;
  EXPECT_NEAR(s.swingSeconds, peak / 30.0, 1.5 / 30.0);
  EXPECT_NEAR(s.overshootPercent, 100.0 * beyond / std::abs(u[peak]), 6.0);
  ASSERT_FALSE(std::isnan(s.settlingSeconds)) << "settles within the 2 s hold";
  EXPECT_NEAR(s.settlingSeconds, settled, 2.5 / 30.0);
  // And it does settle: the last frames are back on the quasi-static hairs.
  EXPECT_LT(r.frames.back().lagDeg, 0.05);
}
INSTANTIATE_TEST_SUITE_P(DampingRatios, Jolt, testing::Values(0.2f, 0.3f, 1.5f));

// The CSV's rows, split.
std::vector<std::vector<std::string>> parseCsv(const std::string& text) {
  std::vector<std::vector<std::string>> rows;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::istringstream l(line);
    std::string cell;
    while (std::getline(l, cell, ',')) cells.push_back(cell);
    rows.push_back(cells);
  }
  return rows;
}

TEST(AnalysisCsv, HeaderNamesEveryColumnWithItsUnitAndRowsMatchIt) {
  AnalysisOptions o = options(1, 6, true);
  o.holdSeconds = 0.1;
  const AnalysisResult r = analyzeClip(ball(), ballFur(), o);
  const auto rows = parseCsv(analysisCsv(r));
  ASSERT_EQ(rows.size(), r.frames.size() + 1);
  const std::vector<std::string> expected = {"frame",
                                             "time_s",
                                             "held",
                                             "body_up_x",
                                             "body_up_y",
                                             "body_up_z",
                                             "pitch_deg",
                                             "roll_deg",
                                             "tilt_deg",
                                             "qs_droop_mean_deg",
                                             "qs_droop_std_deg",
                                             "qs_gravity_angle_deg",
                                             "qs_tip_height_mm",
                                             "qs_droop_body_up_mm",
                                             "qs_tip_speed_m_per_s",
                                             "qs_droop_mean_deg[body]",
                                             "qs_droop_std_deg[body]",
                                             "dyn_droop_mean_deg",
                                             "dyn_droop_std_deg",
                                             "dyn_gravity_angle_deg",
                                             "dyn_tip_height_mm",
                                             "dyn_droop_body_up_mm",
                                             "dyn_tip_speed_m_per_s",
                                             "dyn_droop_mean_deg[body]",
                                             "dyn_droop_std_deg[body]",
                                             "lag_deg",
                                             "dyn_offset_mm",
                                             "dyn_stop_response_mm"};
  EXPECT_EQ(rows[0], expected);
  for (std::size_t i = 1; i < rows.size(); ++i) {
    ASSERT_EQ(rows[i].size(), expected.size()) << i;
    for (const std::string& cell : rows[i]) EXPECT_NO_THROW((void)std::stod(cell)) << cell;
  }
  // Units: time in seconds, heights in millimetres, angles in degrees.
  const FrameAnalysis& f = r.frames[3];
  EXPECT_DOUBLE_EQ(std::stod(rows[4][1]), 3.0 / 30.0);
  EXPECT_NEAR(std::stod(rows[4][8]), f.tiltDeg, 1e-4);
  EXPECT_NEAR(std::stod(rows[4][12]), f.quasiStatic.tipHeightMm, 1e-4);
  EXPECT_LT(std::abs(f.quasiStatic.tipHeightMm), 10.0);  // 1 cm hairs: within +-10 mm
  EXPECT_GT(std::abs(f.quasiStatic.tipHeightMm), 0.5);
  EXPECT_EQ(rows.back()[2], "1");  // the held frames are marked
  // Quasi-static only: no dynamic columns.
  const auto qs = parseCsv(analysisCsv(analyzeClip(ball(), ballFur(), options(1, 2, false))));
  EXPECT_EQ(qs[0].size(), 17u);
}

// Several chunks of hairs (20,000 > 8,192 a chunk), the CSV at full precision: one thread sums
// the same per-chunk partials in the same order as three.
TEST(Analyze, BitIdenticalWhateverTheThreadCount) {
  const Fur many = growFur(ball(), test::simpleParams(fur::HairStyle::Polyline, 20000), "threads");
  AnalysisOptions o = options(1, 12, true);
  setThreadCount(1);
  const std::string one = analysisCsv(analyzeClip(ball(), many, o));
  setThreadCount(3);
  const std::string three = analysisCsv(analyzeClip(ball(), many, o));
  setThreadCount(2);
  const std::string two = analysisCsv(analyzeClip(ball(), many, o));
  setThreadCount(0);
  EXPECT_EQ(one, three);
  EXPECT_EQ(one, two);
}

TEST(Analyze, AFrameRangePreRollsFromTheClipStartAndMatchesTheWholeRun) {
  const AnalysisResult whole = analyzeClip(ball(), ballFur(), options(1, 20, true));
  AnalysisOptions part = options(1, 20, true);
  part.frames.first = 12;
  const AnalysisResult shard = analyzeClip(ball(), ballFur(), part);
  ASSERT_EQ(shard.frames.size(), 9u);
  for (std::size_t i = 0; i < shard.frames.size(); ++i) {
    const FrameAnalysis& a = shard.frames[i];
    const FrameAnalysis& b = whole.frames[i + 12];
    EXPECT_EQ(a.frame, b.frame);
    EXPECT_EQ(a.dynamic.all.droopMeanDeg, b.dynamic.all.droopMeanDeg);
    EXPECT_EQ(a.dynamic.tipHeightMm, b.dynamic.tipHeightMm);
    EXPECT_EQ(a.lagDeg, b.lagDeg);
    if (i > 0) {
      EXPECT_EQ(a.dynamic.tipSpeed, b.dynamic.tipSpeed);
    }
  }
  // A short pre-roll starts the hairs on the quasi-static shape mid-motion: close, not identical.
  part.clock.preRollFrames = 2;
  const AnalysisResult quick = analyzeClip(ball(), ballFur(), part);
  EXPECT_NE(quick.frames[0].dynamic.all.droopMeanDeg, whole.frames[12].dynamic.all.droopMeanDeg);
  EXPECT_EQ(preRollStart(12, part.clock), 10);
  EXPECT_EQ(preRollStart(1, part.clock), 0);
  EXPECT_EQ(preRollStart(12, Clock{}), 0);
}

TEST(Analyze, BadRangesAndSweepsAreInputErrors) {
  AnalysisOptions o = options(0, 5, false);
  o.frames.first = 6;
  EXPECT_THROW(analyzeClip(ball(), ballFur(), o), InputError);
  o = options(0, 5, false);
  o.holdSeconds = -1.0;
  EXPECT_THROW(analyzeClip(ball(), ballFur(), o), InputError);
  o = options(0, 5, true);
  o.dynamicsParams.coats[0].frequencyHz = 0.0f;
  EXPECT_THROW(analyzeClip(ball(), ballFur(), o), InputError);
  for (const char* bad :
       {"stiffness", "stiffness=0.2:1.0", "stiffness=0.2:1.0:0", "stiffness=0.2:1.5:3",
        "stiffness=a:1:3", "stiffness=0.2:1:2.5", "length=0.2:1:3", "frequency=0:4:3",
        "damping=-1:1:3", "stiffness=0.2:1:3:4"}) {
    try {
      parseSweep(bad, "--sweep");
      ADD_FAILURE() << bad;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("--sweep"), std::string::npos) << e.what();
    }
  }
  const SweepSpec s = parseSweep("frequency=2:8:4");
  EXPECT_EQ(s.values(), (std::vector<double>{2, 4, 6, 8}));
  EXPECT_EQ(parseSweep("damping=0.5:0.5:1").values(), std::vector<double>{0.5});
}

}  // namespace
}  // namespace pelage::scene
