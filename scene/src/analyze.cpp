#include "pelage/scene/analyze.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>

#include "pelage/fur/generate.h"
#include "pelage/fur/hair_math.h"
#include "pelage/scene/playback.h"
#include "pelage/util/enum_names.h"
#include "pelage/util/error.h"
#include "pelage/util/parallel.h"

namespace pelage::scene {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = 180.0 / kPi;
constexpr std::int64_t kHairsPerChunk = 8192;

double angleDeg(double cosine) {
  return std::acos(std::clamp(cosine, -1.0, 1.0)) * kDeg;
}

// The constant part of one hair: where its root is and what it is measured with.
struct HairSite {
  std::int32_t coat = 0;
  std::int32_t v[3] = {0, 0, 0};
  float b[3] = {0.0f, 0.0f, 0.0f};
  std::int32_t root = 0;   // index in the coat
  std::int32_t group = 0;  // index into the analysis' groups
};

// Per-chunk sums, laid out as: for each of the two end models (quasi-static, dynamic):
// n, sum droop, sum droop^2, sum gravity angle, sum tip height, sum droop body-up, sum tip speed,
// then per group n, sum, sum^2; then the sums of lag angles, offsets and stop responses.
struct Layout {
  int groups = 0;
  int perModel() const { return 7 + 3 * groups; }
  int size() const { return 2 * perModel() + 3; }
  int model(int m) const { return m * perModel(); }
  int lag() const { return 2 * perModel(); }
  int offset() const { return 2 * perModel() + 1; }
  int response() const { return 2 * perModel() + 2; }
};

DroopStats droopStats(double n, double sum, double sum2) {
  DroopStats s;
  s.hairs = n;
  if (n <= 0) return s;
  s.droopMeanDeg = sum / n;
  s.droopStdDeg = std::sqrt(std::max(0.0, sum2 / n - s.droopMeanDeg * s.droopMeanDeg));
  return s;
}

EndStats endStats(const std::vector<double>& a, int offset, const Layout& layout) {
  const double* s = a.data() + offset;
  EndStats e;
  const double n = s[0];
  e.all = droopStats(n, s[1], s[2]);
  if (n > 0) {
    e.gravityAngleDeg = s[3] / n;
    e.tipHeightMm = s[4] / n * 1e3;
    e.droopBodyUpMm = s[5] / n * 1e3;
    e.tipSpeed = s[6] / n;
  }
  for (int g = 0; g < layout.groups; ++g)
    e.groups.push_back(droopStats(s[7 + 3 * g], s[8 + 3 * g], s[9 + 3 * g]));
  return e;
}

// The hairs' sites and their groups (empty groups dropped).
void makeSites(const Model& model, const Fur& fur, AnalysisGroups groups,
               std::vector<HairSite>& sites, std::vector<std::string>& names) {
  const skin::SkinMesh& skin = model.skin;
  const std::int32_t* regions = skin.regions();
  const skin::Binding* bindings = skin.bindings();
  const std::size_t groupCount = groups == AnalysisGroups::Region
                                     ? skin.regionNames.size()
                                     : static_cast<std::size_t>(model.body.size());
  std::vector<std::int64_t> count(groupCount, 0);
  for (int c = 0; c < fur::kCoatCount; ++c) {
    const fur::CoatRoots& cr = fur.roots.coats[static_cast<std::size_t>(c)];
    for (std::int64_t r = 0; r < cr.size(); ++r) {
      const auto ru = static_cast<std::size_t>(r);
      HairSite h;
      h.coat = c;
      h.root = static_cast<std::int32_t>(r);
      const std::int32_t* tv =
          skin.triangles.data() + 3 * static_cast<std::int64_t>(cr.triangle[ru]);
      const float* b = fur.roots.barycentric.data() + 4 * cr.tableIndex[ru];
      int nearest = 0;
      for (int k = 0; k < 3; ++k) {
        h.v[k] = tv[k];
        h.b[k] = b[k];
        if (b[k] > b[nearest]) nearest = k;
      }
      const std::int32_t v = h.v[nearest];
      h.group = groups == AnalysisGroups::Region ? regions[v] : bindings[v].segment[0];
      h.group = std::clamp<std::int32_t>(h.group, 0, static_cast<std::int32_t>(groupCount) - 1);
      ++count[static_cast<std::size_t>(h.group)];
      sites.push_back(h);
    }
  }
  std::vector<std::int32_t> remap(groupCount, -1);
  for (std::size_t g = 0; g < groupCount; ++g) {
    if (count[g] == 0) continue;
    remap[g] = static_cast<std::int32_t>(names.size());
    names.push_back(groups == AnalysisGroups::Region ? skin.regionNames[g]
                                                     : model.body.segments[g].name);
  }
  for (HairSite& h : sites) h.group = remap[static_cast<std::size_t>(h.group)];
}

double unwrapDeg(double angle, double previous) {
  while (angle - previous > 180.0) angle -= 360.0;
  while (angle - previous < -180.0) angle += 360.0;
  return angle;
}

// Everything kept between frames of one analysis.
struct Run {
  const Model& model;
  const Fur& fur;
  const AnalysisOptions& options;
  Layout layout;
  std::vector<HairSite> sites;
  std::array<fur::CoatShape, fur::kCoatCount> shapes;
  std::vector<float> previousEnds;    // sites x 6: quasi-static and dynamic ending points (m)
  std::vector<float> stopDirections;  // sites x 3: unit E_dyn - E_qs at the stop (0 if none)
  std::vector<std::vector<double>> partial;
  const Playback& playback;  // the frame owner: the posed skin and the dynamic springs
  int orientationSegment = 0;
  bool first = true;
  double pitch = 0.0, roll = 0.0;

  Run(const Model& m, const Fur& f, const AnalysisOptions& o, std::vector<std::string>& names,
      const Playback& p)
      : model(m), fur(f), options(o), playback(p) {
    makeSites(model, fur, options.groups, sites, names);
    // Segment 0 (the root) when hairs are bound to it, else the segment carrying the most hairs
    // (a glTF armature's root node often carries no skin).
    std::vector<std::int64_t> perSegment(static_cast<std::size_t>(model.body.size()), 0);
    const skin::Binding* bindings = model.skin.bindings();
    for (const HairSite& h : sites) {
      int nearest = 0;
      for (int k = 1; k < 3; ++k)
        if (h.b[k] > h.b[nearest]) nearest = k;
      const std::int32_t s = bindings[h.v[nearest]].segment[0];
      if (s >= 0 && s < model.body.size()) ++perSegment[static_cast<std::size_t>(s)];
    }
    if (!perSegment.empty() && perSegment[0] == 0)
      orientationSegment = static_cast<int>(std::max_element(perSegment.begin(), perSegment.end()) -
                                            perSegment.begin());
    layout.groups = static_cast<int>(names.size());
    for (int c = 0; c < fur::kCoatCount; ++c)
      shapes[static_cast<std::size_t>(c)] = fur::makeCoatShape(fur.params, fur.roots, c);
    previousEnds.assign(sites.size() * 6, 0.0f);
    stopDirections.assign(sites.size() * 3, 0.0f);
    const auto chunks = static_cast<std::size_t>(
        (static_cast<std::int64_t>(sites.size()) + kHairsPerChunk - 1) / kHairsPerChunk);
    partial.assign(chunks, std::vector<double>(static_cast<std::size_t>(layout.size()), 0.0));
  }

  // The overcoat's mean rest hair length (m): interpolated vertex lengths times the length scales.
  double meanOvercoatLength() const {
    const float* lengths = fur.roots.lengths(model.skin);
    const double mul =
        static_cast<double>(fur.params.lengthScale * fur.params.coats[fur::kOvercoat].lengthFactor);
    double sum = 0.0, n = 0.0;
    for (const HairSite& h : sites) {
      if (h.coat != fur::kOvercoat) continue;
      sum += mul * static_cast<double>(h.b[0] * lengths[h.v[0]] + h.b[1] * lengths[h.v[1]] +
                                       h.b[2] * lengths[h.v[2]]);
      n += 1.0;
    }
    return n > 0 ? sum / n : 0.0;
  }

  // Measures the hairs of the skin in `frame` (dynamics already stepped when enabled).
  // stop: 0 before the stop, 1 at the last moving frame (records the directions), 2 after it.
  FrameAnalysis measure(int frameNumber, bool held, int stop = 0) {
    FrameAnalysis out;
    out.frame = frameNumber;
    out.seconds = frameNumber / options.clock.fps;
    out.held = held;
    // Body orientation: the orientation segment's rotation relative to its bind pose.
    const FrameState& frame = playback.state();
    const fur::FurDynamicsState& state = playback.dynamicsState();
    const auto seg = static_cast<std::size_t>(orientationSegment);
    const Eigen::Matrix3f rel =
        frame.body.world[seg].linear() * model.body.inverseBind[seg].linear();
    const Eigen::Vector3d up = (rel * Eigen::Vector3f::UnitZ()).cast<double>().normalized();
    const Eigen::Vector3d U = fur.params.up.cast<double>().normalized();
    out.bodyUp = up;
    const double pitch0 = std::atan2(up.x(), up.z()) * kDeg,
                 roll0 = std::atan2(-up.y(), up.z()) * kDeg;
    pitch = first ? pitch0 : unwrapDeg(pitch0, pitch);
    roll = first ? roll0 : unwrapDeg(roll0, roll);
    out.pitchDeg = pitch;
    out.rollDeg = roll;
    out.tiltDeg = angleDeg(up.dot(U));

    const skin::DeformedSkin& d = frame.skin;
    const bool dynamic = options.dynamics;
    const bool hasPrevious = !first;
    const double invDt = options.clock.fps;
    const Eigen::Vector3f upF = up.cast<float>(), Uf = U.cast<float>();
    const Layout L = layout;
    parallelForChunks(
        static_cast<std::int64_t>(sites.size()), kHairsPerChunk,
        [&](std::int64_t b, std::int64_t e) {
          std::vector<double>& acc = partial[static_cast<std::size_t>(b / kHairsPerChunk)];
          std::fill(acc.begin(), acc.end(), 0.0);
          for (std::int64_t i = b; i < e; ++i) {
            const HairSite& h = sites[static_cast<std::size_t>(i)];
            const fur::CoatShape& shape = shapes[static_cast<std::size_t>(h.coat)];
            // Sec. 3.2: the hair's inputs interpolated at its root, then sec. 3.4-3.5
            // (hair_math.h).
            const fur::HairInput<float> in =
                fur::rootInput(model.skin, fur.roots, d, h.coat, h.root);
            fur::HairFrame<float> f;
            fur::hairFrame(shape, in, f);
            if (!(f.length > 0.0f)) continue;
            const Eigen::Vector3f R(f.root.x, f.root.y, f.root.z);
            const Eigen::Vector3f dT(f.dTilde.x, f.dTilde.y, f.dTilde.z);
            const Eigen::Vector3f eQs(f.e.x, f.e.y, f.e.z);
            Eigen::Vector3f ends[2] = {eQs, eQs};
            if (dynamic) {
              const std::int64_t n = state.roots(h.coat);
              const auto at = [&](const float* field) {
                return Eigen::Vector3f(fur::planar(field, n, h.root, 0),
                                       fur::planar(field, n, h.root, 1),
                                       fur::planar(field, n, h.root, 2));
              };
              const Eigen::Vector3f u = at(state.offset(h.coat));
              const Eigen::Vector3f T = at(state.lastEnd(h.coat));
              const Eigen::Vector3f y = (T - R) + u;
              if (y.squaredNorm() > 1e-20f) ends[1] = y.normalized();
            }
            const double len = f.length;
            float* prev = previousEnds.data() + 6 * i;
            for (int m = 0; m < (dynamic ? 2 : 1); ++m) {
              double* a = acc.data() + L.model(m);
              const Eigen::Vector3f& ev = ends[m];
              const double droop = angleDeg(static_cast<double>(ev.dot(dT)));
              const Eigen::Vector3f E = R + ev * f.length;
              a[0] += 1.0;
              a[1] += droop;
              a[2] += droop * droop;
              a[3] += angleDeg(-static_cast<double>(ev.dot(Uf)));
              a[4] += len * static_cast<double>(ev.dot(Uf));
              a[5] += len * static_cast<double>((ev - dT).dot(upF));
              if (hasPrevious)
                a[6] += static_cast<double>(
                            (E - Eigen::Map<const Eigen::Vector3f>(prev + 3 * m)).norm()) *
                        invDt;
              Eigen::Map<Eigen::Vector3f>(prev + 3 * m) = E;
              if (h.group >= 0) {
                a[7 + 3 * h.group] += 1.0;
                a[8 + 3 * h.group] += droop;
                a[9 + 3 * h.group] += droop * droop;
              }
            }
            if (dynamic) {
              acc[static_cast<std::size_t>(L.lag())] +=
                  angleDeg(static_cast<double>(ends[1].dot(eQs)));
              const Eigen::Vector3f deviation = (ends[1] - eQs) * f.length;
              acc[static_cast<std::size_t>(L.offset())] += static_cast<double>(deviation.norm());
              float* sd = stopDirections.data() + 3 * i;
              if (stop == 1) {
                const float n = deviation.norm();
                const Eigen::Vector3f unit =
                    n > 0.0f ? Eigen::Vector3f(deviation / n) : Eigen::Vector3f::Zero();
                sd[0] = unit.x();
                sd[1] = unit.y();
                sd[2] = unit.z();
              }
              if (stop > 0)
                acc[static_cast<std::size_t>(L.response())] +=
                    static_cast<double>(deviation.dot(Eigen::Map<const Eigen::Vector3f>(sd)));
            }
          }
        });
    std::vector<double> total(static_cast<std::size_t>(layout.size()), 0.0);
    for (const std::vector<double>& p : partial)  // in chunk order: deterministic
      for (std::size_t k = 0; k < total.size(); ++k) total[k] += p[k];
    out.quasiStatic = endStats(total, layout.model(0), layout);
    if (dynamic) {
      out.dynamic = endStats(total, layout.model(1), layout);
      const double n = total[static_cast<std::size_t>(layout.model(1))];
      out.lagDeg = n > 0 ? total[static_cast<std::size_t>(layout.lag())] / n : 0.0;
      out.offsetMm = n > 0 ? total[static_cast<std::size_t>(layout.offset())] / n * 1e3 : 0.0;
      out.stopResponseMm =
          n > 0 ? total[static_cast<std::size_t>(layout.response())] / n * 1e3 : 0.0;
    }
    first = false;
    return out;
  }
};

SettlingAnalysis settle(const AnalysisResult& r, const AnalysisOptions& o, double meanLength) {
  SettlingAnalysis s;
  std::size_t stop = r.frames.size();
  for (std::size_t i = 0; i < r.frames.size(); ++i)
    if (r.frames[i].held) {
      stop = i;
      break;
    }
  if (!r.dynamics || stop == r.frames.size() || r.frames.size() - stop < 2) return s;
  const std::size_t begin = stop > 0 ? stop - 1 : stop;  // the last moving frame is t = 0
  s.measured = true;
  s.stopSeconds = r.frames[begin].seconds;
  auto response = [&](std::size_t i) { return r.frames[i].stopResponseMm; };
  std::size_t peak = begin;
  for (std::size_t i = begin; i < r.frames.size(); ++i)
    if (std::abs(response(i)) > std::abs(response(peak))) peak = i;
  s.swingMm = response(peak);
  s.swingSeconds = r.frames[peak].seconds - s.stopSeconds;
  const double swing = std::abs(s.swingMm);
  double beyond = 0.0;
  for (std::size_t i = peak; i < r.frames.size(); ++i)
    beyond = std::max(beyond, -response(i) * (s.swingMm < 0 ? -1.0 : 1.0));
  s.overshootPercent = swing > 0.0 ? 100.0 * beyond / swing : 0.0;
  s.settlingSeconds = 0.0;
  for (std::size_t i = begin; i < r.frames.size(); ++i)
    if (std::abs(response(i)) > o.settleTolerance * swing)
      s.settlingSeconds = i + 1 < r.frames.size() ? r.frames[i + 1].seconds - s.stopSeconds
                                                  : std::numeric_limits<double>::quiet_NaN();
  const fur::CoatDynamics& cd = o.dynamicsParams.coats[fur::kOvercoat];
  s.meanLengthMm = meanLength * 1e3;
  s.springFrequencyHz = meanLength > 0.0 ? fur::hairFrequencyHz(cd, meanLength) : 0.0;
  s.springOvershootPercent = 100.0 * fur::overshootFraction(static_cast<double>(cd.dampingRatio));
  if (s.springFrequencyHz > 0.0)
    s.springSettlingSeconds = fur::settlingTime(
        s.springFrequencyHz, static_cast<double>(cd.dampingRatio), o.settleTolerance);
  return s;
}

void checkOptions(const Model& model, const AnalysisOptions& o) {
  PELAGE_CHECK(o.clip >= -1 && o.clip < static_cast<int>(model.clips.size()), "clip ", o.clip);
  if (o.dynamics && o.clip < 0)
    fieldError("dynamics", "on needs a clip: the rest pose does not move");
  validateClock(o.clock);
  validateFrameRange(o.frames);
  validateHoldSeconds(o.holdSeconds);
  if (!(o.settleTolerance > 0.0 && o.settleTolerance < 1.0))
    inputError("settle tolerance ", o.settleTolerance, " is out of range (0, 1)");
  if (o.dynamics) fur::validateDynamicsParams(o.dynamicsParams, "dynamics");
}

double parseNumber(const std::string& text, const std::string& field, const std::string& spec) {
  double v = 0.0;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, v);
  if (text.empty() || ec != std::errc() || ptr != end || !std::isfinite(v))
    fieldError(field, "'", excerpt(spec), "': '", excerpt(text),
               "' is not a number (expected NAME=A:B:N, e.g. stiffness=0.2:1.0:5)");
  return v;
}

}  // namespace

std::string analysisClipName(const Model& model, int clip) {
  return clip >= 0 ? model.clips[static_cast<std::size_t>(clip)].name : "still pose";
}

void validateHoldSeconds(double seconds, const std::string& field) {
  if (!(seconds >= 0.0 && seconds <= kMaxHoldSeconds))
    fieldError(field, seconds, " is out of range [0, ", kMaxHoldSeconds, "] seconds");
}

AnalysisGroups parseAnalysisGroups(const std::string& name, const std::string& field) {
  constexpr auto kNames = makeEnumNames<AnalysisGroups>(
      {{AnalysisGroups::Region, "region"}, {AnalysisGroups::Segment, "segment"}});
  if (const auto g = kNames.find(name)) return *g;
  fieldError(field, "'", excerpt(name), "' (accepted: ", kNames.list(), ")");
}

AnalysisResult analyzeClip(const Model& model, const Fur& fur, const AnalysisOptions& options) {
  checkOptions(model, options);
  AnalysisResult result;
  result.clipName = analysisClipName(model, options.clip);
  result.fps = options.clock.fps;
  result.dynamics = options.dynamics;
  PlaybackOptions po;
  po.clip = options.clip;
  po.stillPose = options.stillPose;
  po.clock = options.clock;
  po.dynamics = options.dynamics;
  po.dynamicsParams = options.dynamicsParams;
  po.hairSource = HairSource::Cpu;
  Playback playback(model, fur, po);
  Run run(model, fur, options, result.groupNames, playback);
  result.orientationSegment =
      model.body.segments[static_cast<std::size_t>(run.orientationSegment)].name;
  const auto holdFrames = static_cast<int>(std::lround(options.holdSeconds * options.clock.fps));
  const FrameRange& range = options.frames;
  for (int f = range.first; f <= range.last; ++f) {
    playback.poseFrame(f);
    if (options.dynamics) playback.stepDynamics();
    FrameAnalysis a = run.measure(f, false, f == range.last && holdFrames > 0 ? 1 : 0);
    if (range.contains(f)) result.frames.push_back(std::move(a));
  }
  for (int k = 1; k <= holdFrames; ++k) {  // the last pose, still: the springs go on
    playback.holdFrame();
    if (options.dynamics) playback.stepDynamics();
    result.frames.push_back(run.measure(range.last + k, true, 2));
  }
  result.settling = settle(result, options, run.meanOvercoatLength());
  return result;
}

namespace {

// The accepted range of each sweep parameter.
struct SweepParameter {
  const char* name;
  double lo, hi;
  bool openLow;
};
constexpr SweepParameter kSweepParameters[] = {
    {"stiffness", 0.0, 1.0, false}, {"frequency", 0.0, 100.0, true}, {"damping", 0.0, 10.0, false}};
constexpr const char* kSweepForm =
    " (expected NAME=A:B:N with NAME stiffness [0, 1], frequency (0, 100] Hz or damping [0, 10], "
    "N in [1, 100])";

// `count` values from `first` to `last`, evenly spaced.
std::vector<double> evenly(double first, double last, int count) {
  std::vector<double> v;
  for (int i = 0; i < count; ++i)
    v.push_back(count == 1 ? first : first + (last - first) * i / (count - 1));
  return v;
}

SweepSpec checkedSweep(SweepSpec s, const std::string& field, const std::string& text) {
  const SweepParameter* p = nullptr;
  for (const SweepParameter& q : kSweepParameters)
    if (s.parameter == q.name) p = &q;
  if (!p)
    fieldError(field, "'", excerpt(text), "': unknown parameter '", s.parameter, "'", kSweepForm);
  if (s.list.empty() || s.count() > kMaxSweepValues)
    fieldError(field, "'", excerpt(text), "': ", s.count(), " values (accepted: 1 to ",
               kMaxSweepValues, ")");
  for (double v : s.list)
    if (!std::isfinite(v) || v > p->hi || (p->openLow ? v <= p->lo : v < p->lo))
      fieldError(field, "'", excerpt(text), "': ", s.parameter, " ", v, " is out of range ",
                 p->openLow ? "(" : "[", p->lo, ", ", p->hi, "]");
  return s;
}

}  // namespace

SweepSpec sweepRange(const std::string& parameter, double first, double last, int count,
                     const std::string& field) {
  const std::string text = str(parameter, "=", first, ":", last, ":", count);
  if (count < 1 || count > kMaxSweepValues)
    fieldError(field, "'", excerpt(text), "': N = ", count, " is not a whole number in [1, ",
               kMaxSweepValues, "]");
  SweepSpec s;
  s.parameter = parameter;
  s.list = evenly(first, last, count);
  return checkedSweep(std::move(s), field, text);
}

SweepSpec sweepValues(const std::string& parameter, std::vector<double> values,
                      const std::string& field) {
  std::string text = parameter + "=[";
  for (std::size_t i = 0; i < values.size() && i < 8; ++i) text += (i ? ", " : "") + str(values[i]);
  text += values.size() > 8 ? ", ...]" : "]";
  SweepSpec s;
  s.parameter = parameter;
  s.list = std::move(values);
  return checkedSweep(std::move(s), field, text);
}

SweepSpec parseSweep(const std::string& text, const std::string& field) {
  const std::size_t eq = text.find('=');
  if (eq == std::string::npos) fieldError(field, "'", excerpt(text), "' has no '='", kSweepForm);
  const std::string parameter = text.substr(0, eq);
  const std::string rest = text.substr(eq + 1);
  const std::size_t c1 = rest.find(':');
  const std::size_t c2 = c1 == std::string::npos ? std::string::npos : rest.find(':', c1 + 1);
  if (c2 == std::string::npos || rest.find(':', c2 + 1) != std::string::npos)
    fieldError(field, "'", excerpt(text), "' is not of the form NAME=A:B:N", kSweepForm);
  const double from = parseNumber(rest.substr(0, c1), field, text);
  const double to = parseNumber(rest.substr(c1 + 1, c2 - c1 - 1), field, text);
  const double n = parseNumber(rest.substr(c2 + 1), field, text);
  if (!(n >= 1 && n <= kMaxSweepValues && n == std::floor(n)))
    fieldError(field, "'", excerpt(text), "': N = ", n, " is not a whole number in [1, ",
               kMaxSweepValues, "]");
  SweepSpec s;
  s.parameter = parameter;
  s.list = evenly(from, to, static_cast<int>(n));
  return checkedSweep(std::move(s), field, text);
}

SweepResult sweepClip(const Model& model, const Fur& fur, const AnalysisOptions& options,
                      const SweepSpec& spec, int index) {
  if (index < -1 || index >= spec.count())
    fieldError("sweep index", index, " is out of range [0, ", spec.count() - 1, "] (", spec.count(),
               " values)");
  SweepResult out;
  out.spec = spec;
  const std::vector<double> all = spec.values();
  if (index >= 0)
    out.values = {all[static_cast<std::size_t>(index)]};
  else
    out.values = all;
  for (double v : out.values) {
    Fur varied = fur;
    AnalysisOptions o = options;
    for (int c = 0; c < fur::kCoatCount; ++c) {
      const auto ci = static_cast<std::size_t>(c);
      if (spec.parameter == "stiffness") varied.params.coats[ci].stiffness = static_cast<float>(v);
      if (spec.parameter == "frequency")
        o.dynamicsParams.coats[ci].frequencyHz = static_cast<float>(v);
      if (spec.parameter == "damping")
        o.dynamicsParams.coats[ci].dampingRatio = static_cast<float>(v);
    }
    fur::validateFurParams(varied.params, "sweep " + spec.parameter);
    out.runs.push_back(analyzeClip(model, varied, o));
  }
  return out;
}

}  // namespace pelage::scene
