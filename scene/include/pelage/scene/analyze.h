// Measuring the fur's response to gravity as a body moves (`pelage analyze`): per frame of a clip,
// the body's orientation and statistics of every hair's droop (Van Gelder & Wilhelms 1997,
// sec. 3.5: the ending point falls from the weightless ending point along -U), for the paper's
// quasi-static model and, optionally, the damped dynamic ends of fur/dynamics.h; after the motion
// stops (a held pose), the dynamic ends' overshoot and settling time. GL-free.
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <string>
#include <vector>

#include "pelage/fur/dynamics.h"
#include "pelage/scene/dynamic_fur.h"
#include "pelage/scene/frame.h"
#include "pelage/scene/frame_range.h"
#include "pelage/scene/model.h"

namespace pelage::scene {

// How hairs are grouped for the per-group columns: by skin region (the root's nearest vertex's
// region: body, face, ears, ...) or by body segment (that vertex's closest segment).
enum class AnalysisGroups { Region, Segment };
// "region" or "segment"; InputError naming `field` and the accepted names otherwise.
AnalysisGroups parseAnalysisGroups(const std::string& name, const std::string& field = "groups");

struct AnalysisOptions {
  int clip = 0;             // index into model.clips; -1: the still pose in every frame
  anatomy::Pose stillPose;  // the pose without a clip (empty: the rest pose)
  // Frame f shows clip time clock.startSeconds + f / fps. With a step, every frame from first to
  // last is played (the springs and speeds need them) and the frames on the step are reported.
  FrameRange frames;
  double holdSeconds = 0.0;  // after frames.last, the last pose held still this long (see below)
  bool dynamics = false;     // also the damped dynamic ends (fur/dynamics.h)
  fur::DynamicsParams dynamicsParams;
  Clock clock;  // fps, start time and pre-roll
  AnalysisGroups groups = AnalysisGroups::Region;
  double settleTolerance = 0.02;  // settled: within this fraction of the largest swing, (0, 1)
};

// The hold after the last frame: [0, kMaxHoldSeconds]; InputError naming `field` otherwise.
inline constexpr double kMaxHoldSeconds = 1000.0;
void validateHoldSeconds(double seconds, const std::string& field = "hold");

// Droop statistics of one set of hairs. Droop angle: between the hair's end direction e (root to
// ending point) and its weightless direction d~ (root to weightless ending point, sec. 3.4-3.5).
struct DroopStats {
  double hairs = 0;           // hairs counted (length > 0)
  double droopMeanDeg = 0.0;  // mean droop angle (degrees)
  double droopStdDeg = 0.0;   // its standard deviation over the hairs (degrees)
};

// One frame's measurements for one model of the ends (quasi-static or dynamic).
struct EndStats {
  DroopStats all;
  std::vector<DroopStats> groups;  // per AnalysisResult::groupNames
  double gravityAngleDeg = 0.0;    // mean angle between e and gravity -U (0: hanging straight down)
  double tipHeightMm = 0.0;        // mean (E - R) . U (mm): ending point above (+) / below the root
  double droopBodyUpMm = 0.0;      // mean (E - W) . up_body (mm): < 0 when the ends fall toward the
                                   // body's underside, > 0 when it is upside down
  double tipSpeed = 0.0;  // mean |E(t) - E(t - dt)| / dt (m/s, world); 0 on the first frame
};

struct FrameAnalysis {
  int frame = 0;
  double seconds = 0.0;  // frame / fps
  bool held = false;     // in the hold after the clip range (body still)
  // The orientation segment's (AnalysisResult::orientationSegment) rotation R relative to its bind
  // pose: up = R * (0, 0, 1) in world
  // coordinates, pitch = atan2(up.x, up.z) (its tilt towards +X, about world +Y), roll =
  // atan2(-up.y, up.z) (towards -Y, about world +X), tilt = angle(up, U) in [0, 180] (180 upside
  // down). Pitch and roll are unwrapped over the frames (continuous past +-180).
  Eigen::Vector3d bodyUp = Eigen::Vector3d::UnitZ();
  double pitchDeg = 0.0, rollDeg = 0.0, tiltDeg = 0.0;
  EndStats quasiStatic;   // the paper's model
  EndStats dynamic;       // the dynamic ends (when AnalysisOptions::dynamics)
  double lagDeg = 0.0;    // mean angle between the dynamic and the quasi-static end directions
  double offsetMm = 0.0;  // mean |E_dyn - E_qs| (mm), the dynamic ends' distance from the paper's
  // After the body stops (held frames, and the last moving frame): the mean of each hair's
  // deviation E_dyn - E_qs along its direction at the stop (mm). Linear in the springs' state, so
  // with one frequency it is one damped oscillation; 0 elsewhere.
  double stopResponseMm = 0.0;
};

// The dynamic ends after the motion stops (the hold), from the stop response r(t)
// (FrameAnalysis::stopResponseMm), which decays to 0: the swing P is its largest |r| after the
// stop; overshoot = the largest excursion of r past 0 on the other side after that swing, as a
// percentage of |P|; settling time = from the stop to the last time |r| exceeds
// settleTolerance |P|. The spring's own figures for comparison: overshootFraction(zeta) and
// settlingTime(f, zeta, tolerance) of an overcoat hair of the coat's mean length (f =
// hairFrequencyHz).
struct SettlingAnalysis {
  bool measured = false;      // dynamic mode with a hold of at least two frames
  double stopSeconds = 0.0;   // when the body stopped
  double swingMm = 0.0;       // P
  double swingSeconds = 0.0;  // when P was reached, after the stop
  double overshootPercent = 0.0;
  double settlingSeconds = 0.0;    // NaN when still outside the band at the end of the hold
  double meanLengthMm = 0.0;       // the overcoat's mean hair length (rest pose)
  double springFrequencyHz = 0.0;  // of a hair of that length
  double springOvershootPercent = 0.0;
  double springSettlingSeconds = 0.0;
};

struct AnalysisResult {
  std::string clipName;
  double fps = 30.0;
  bool dynamics = false;
  std::vector<std::string> groupNames;
  // The segment whose orientation is reported: segment 0 (the root) when hairs are bound to it,
  // else the segment carrying the most hairs.
  std::string orientationSegment;
  std::vector<FrameAnalysis> frames;
  SettlingAnalysis settling;
};

// The name an analysis gives its clip: the clip's, or "still pose" for clip -1.
std::string analysisClipName(const Model& model, int clip);

// Runs the clip's frames (and the hold) and measures every hair of both coats (hairs of length 0
// are skipped). Parallel over hairs; bit-identical whatever the thread count. Throws InputError
// for a frame range or hold out of range.
AnalysisResult analyzeClip(const Model& model, const Fur& fur, const AnalysisOptions& options);

// Measurements as named columns, one value per frame (row), in the order the CSV writes them: the
// one owner of the column names and of what each holds (the CSV and the Python package read it).
struct AnalysisTable {
  std::vector<std::string> names;
  std::vector<std::vector<double>> columns;  // columns[c][row]
  std::size_t rows() const { return columns.empty() ? 0 : columns.front().size(); }
};

// The table of one analysis: every column named with its unit (frame, time_s, held, pitch_deg,
// droop_mean_deg, tip_height_mm, tip_speed_m_per_s, ...). Quasi-static columns are prefixed "qs_",
// dynamic ones "dyn_" (present in dynamic mode); group columns are "qs_droop_mean_deg[face]" etc.
AnalysisTable analysisTable(const AnalysisResult& result);

// A table as CSV text: the header, then one row per frame; "frame" and "held" as integers, every
// other value as the shortest decimal that reads back as the same double ("nan" where undefined).
std::string tableCsv(const AnalysisTable& table);

// tableCsv(analysisTable(result)).
std::string analysisCsv(const AnalysisResult& result);

// A sweep over one parameter: "stiffness" (the paper's, both coats, [0, 1]), "frequency" (dynamic
// spring, Hz, both coats) or "damping" (dynamic damping ratio, both coats).
struct SweepSpec {
  std::string parameter;
  std::vector<double> list;  // the values, in the order run; 1 to kMaxSweepValues of them
  std::vector<double> values() const { return list; }
  int count() const { return static_cast<int>(list.size()); }
};
inline constexpr int kMaxSweepValues = 100;

// A sweep of `parameter` over `count` values evenly spaced from `first` to `last` (both included).
SweepSpec sweepRange(const std::string& parameter, double first, double last, int count,
                     const std::string& field = "sweep");
// A sweep of `parameter` over the values given.
SweepSpec sweepValues(const std::string& parameter, std::vector<double> values,
                      const std::string& field = "sweep");
// Parses "NAME=A:B:N" (sweepRange); InputError naming `field` and the accepted form and ranges
// otherwise. Every constructor checks the parameter's name and range, and the count.
SweepSpec parseSweep(const std::string& text, const std::string& field = "sweep");

struct SweepResult {
  SweepSpec spec;
  std::vector<double> values;        // the values run (all of spec.values(), or one of them)
  std::vector<AnalysisResult> runs;  // one per value
};
// Runs analyzeClip once per value (fur parameters changed per run; the roots stay); with `index`
// in [0, spec.count), only value `index` (one task of a sweep split across processes, whose CSVs
// mergeSweepCsv joins). InputError naming field "sweep index" for an index out of range.
SweepResult sweepClip(const Model& model, const Fur& fur, const AnalysisOptions& options,
                      const SweepSpec& spec, int index = -1);

// The sweep's table: frame, time_s, held, pitch_deg, tilt_deg, then per value v the mean droop and
// tip height of the model in use, named as analysisTable names them ("qs_" quasi-static, "dyn_"
// dynamic): "qs_droop_mean_deg[stiffness=0.2]", ..., "qs_tip_height_mm[stiffness=0.2]", ...
AnalysisTable sweepTable(const SweepResult& sweep);
// tableCsv(sweepTable(sweep)).
std::string sweepCsv(const SweepResult& sweep);

// Joins the CSVs of one sweep's parts (sweepCsv of runs of single values, in value order) into the
// CSV one run of the whole sweep writes: the shared columns (frame, time, held, pitch, tilt) must
// agree row for row, then every part's droop columns, then every part's tip-height columns.
// InputError naming `sources[i]` for a part that is not a sweep CSV or does not fit the others.
std::string mergeSweepCsv(const std::vector<std::string>& texts,
                          const std::vector<std::string>& sources);

}  // namespace pelage::scene
