// pelage analyze: how the fur responds to gravity as the body moves (issue 7). Per frame of a clip:
// the body's orientation and the hairs' droop (Van Gelder & Wilhelms 1997, sec. 3.5), for the
// paper's quasi-static model and, with --dynamics on, the damped dynamic ends; a CSV with units in
// its header, a plot, and sweeps over stiffness or the dynamic spring.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "commands.h"
#include "options.h"
#include "pelage/animation/clip_file.h"
#include "pelage/scene/analyze.h"
#include "pelage/scene/frame_range.h"
#include "pelage/scene/plot.h"
#include "pelage/util/atomic_file.h"
#include "pelage/util/error.h"

namespace pelage::app {
namespace {

std::vector<double> column(const scene::AnalysisResult& r,
                           double (*get)(const scene::FrameAnalysis&)) {
  std::vector<double> v;
  for (const scene::FrameAnalysis& f : r.frames) v.push_back(get(f));
  return v;
}

scene::PlotPanel orientationPanel(const scene::AnalysisResult& r, const std::vector<double>& t) {
  scene::PlotPanel p;
  p.yLabel = "body orientation (deg): up vector of segment '" + r.orientationSegment + "'";
  p.series.push_back({"pitch (about world Y)", t,
                      column(r, [](const scene::FrameAnalysis& f) { return f.pitchDeg; }),
                      scene::plotColor(7), false});
  p.series.push_back({"tilt from vertical", t,
                      column(r, [](const scene::FrameAnalysis& f) { return f.tiltDeg; }),
                      scene::plotColor(4), false});
  return p;
}

scene::PlotSpec analysisPlot(const scene::AnalysisResult& r, const std::string& title) {
  scene::PlotSpec spec;
  spec.title = title;
  spec.xLabel = "time (s)";
  spec.width = 1200;
  spec.height = 1100;
  const std::vector<double> t = column(r, [](const scene::FrameAnalysis& f) { return f.seconds; });
  spec.panels.push_back(orientationPanel(r, t));
  const auto qsColor = scene::plotColor(0), dynColor = scene::plotColor(1);
  scene::PlotPanel droop{"mean droop angle (deg): end direction vs weightless direction", {}};
  droop.series.push_back(
      {"quasi-static (paper)", t,
       column(r, [](const scene::FrameAnalysis& f) { return f.quasiStatic.all.droopMeanDeg; }),
       qsColor, r.dynamics});
  scene::PlotPanel height{"mean tip height above the root (mm)", {}};
  height.series.push_back(
      {"quasi-static (paper)", t,
       column(r, [](const scene::FrameAnalysis& f) { return f.quasiStatic.tipHeightMm; }), qsColor,
       r.dynamics});
  scene::PlotPanel bodyUp{"mean droop along the body's up axis (mm): < 0 toward its belly", {}};
  bodyUp.series.push_back(
      {"quasi-static (paper)", t,
       column(r, [](const scene::FrameAnalysis& f) { return f.quasiStatic.droopBodyUpMm; }),
       qsColor, r.dynamics});
  if (r.dynamics) {
    droop.series.push_back(
        {"dynamic", t,
         column(r, [](const scene::FrameAnalysis& f) { return f.dynamic.all.droopMeanDeg; }),
         dynColor, false});
    droop.series.push_back({"dynamic - quasi-static lag", t,
                            column(r, [](const scene::FrameAnalysis& f) { return f.lagDeg; }),
                            scene::plotColor(2), false});
    height.series.push_back(
        {"dynamic", t,
         column(r, [](const scene::FrameAnalysis& f) { return f.dynamic.tipHeightMm; }), dynColor,
         false});
    bodyUp.series.push_back(
        {"dynamic", t,
         column(r, [](const scene::FrameAnalysis& f) { return f.dynamic.droopBodyUpMm; }), dynColor,
         false});
  }
  spec.panels.push_back(droop);
  spec.panels.push_back(height);
  spec.panels.push_back(bodyUp);
  if (r.dynamics) {
    scene::PlotPanel offset{"dynamic ends' distance from the quasi-static ends (mm)", {}};
    offset.series.push_back({"mean distance", t,
                             column(r, [](const scene::FrameAnalysis& f) { return f.offsetMm; }),
                             scene::plotColor(3), false});
    if (r.settling.measured)
      offset.series.push_back(
          {"along its direction at the stop", t,
           column(r, [](const scene::FrameAnalysis& f) { return f.stopResponseMm; }),
           scene::plotColor(9), false});
    spec.panels.push_back(offset);
    spec.height = 1350;
  }
  if (r.settling.measured) {
    spec.markerX = r.settling.stopSeconds;
    spec.markerLabel = "body stops";
  }
  return spec;
}

scene::PlotSpec sweepPlot(const scene::SweepResult& s, const std::string& title) {
  scene::PlotSpec spec;
  spec.title = title;
  spec.xLabel = "time (s)";
  spec.width = 1200;
  spec.height = 900;
  const scene::AnalysisResult& first = s.runs.front();
  const std::vector<double> t =
      column(first, [](const scene::FrameAnalysis& f) { return f.seconds; });
  spec.panels.push_back(orientationPanel(first, t));
  const bool dyn = first.dynamics;
  scene::PlotPanel droop{
      std::string("mean droop angle (deg)") + (dyn ? ", dynamic" : ", quasi-static"), {}};
  scene::PlotPanel height{
      std::string("mean tip height above the root (mm)") + (dyn ? ", dynamic" : ", quasi-static"),
      {}};
  const std::vector<double>& values = s.values;
  for (std::size_t i = 0; i < s.runs.size(); ++i) {
    char label[64];
    std::snprintf(label, sizeof label, "%s = %g", s.spec.parameter.c_str(), values[i]);
    const auto color = scene::plotColor(static_cast<int>(i));
    droop.series.push_back(
        {label, t,
         column(
             s.runs[i],
             dyn ? +[](const scene::FrameAnalysis& f) { return f.dynamic.all.droopMeanDeg; }
                 : +[](const scene::FrameAnalysis& f) { return f.quasiStatic.all.droopMeanDeg; }),
         color, false});
    height.series.push_back(
        {label, t,
         column(
             s.runs[i],
             dyn ? +[](const scene::FrameAnalysis& f) { return f.dynamic.tipHeightMm; }
                 : +[](const scene::FrameAnalysis& f) { return f.quasiStatic.tipHeightMm; }),
         color, false});
  }
  spec.panels.push_back(droop);
  spec.panels.push_back(height);
  if (first.settling.measured) {
    spec.markerX = first.settling.stopSeconds;
    spec.markerLabel = "body stops";
  }
  return spec;
}

void printSummary(const scene::AnalysisResult& r) {
  if (r.frames.empty()) return;
  const scene::FrameAnalysis* upright = &r.frames.front();
  const scene::FrameAnalysis* inverted = &r.frames.front();
  for (const scene::FrameAnalysis& f : r.frames) {
    if (f.tiltDeg < upright->tiltDeg) upright = &f;
    if (f.tiltDeg > inverted->tiltDeg) inverted = &f;
  }
  auto line = [&](const char* what, const scene::FrameAnalysis& f) {
    std::printf(
        "%s (frame %d, tilt %.1f deg): quasi-static droop %.2f deg, tip height %+.2f mm, droop "
        "along body up %+.2f mm",
        what, f.frame, f.tiltDeg, f.quasiStatic.all.droopMeanDeg, f.quasiStatic.tipHeightMm,
        f.quasiStatic.droopBodyUpMm);
    if (r.dynamics)
      std::printf("; dynamic %.2f deg, %+.2f mm, %+.2f mm, lag %.2f deg",
                  f.dynamic.all.droopMeanDeg, f.dynamic.tipHeightMm, f.dynamic.droopBodyUpMm,
                  f.lagDeg);
    std::printf("\n");
  };
  line("most upright", *upright);
  line("most inverted", *inverted);
  if (r.settling.measured) {
    const scene::SettlingAnalysis& s = r.settling;
    std::printf(
        "after the body stops at %.3f s: largest swing %+.2f mm at +%.3f s, overshoot %.1f %% "
        "(spring alone: %.1f %%), ",
        s.stopSeconds, s.swingMm, s.swingSeconds, s.overshootPercent, s.springOvershootPercent);
    if (std::isnan(s.settlingSeconds))
      std::printf("not settled by the end of the hold");
    else
      std::printf("settled in %.3f s", s.settlingSeconds);
    std::printf(" (spring alone, a %.1f mm hair at %.2f Hz: %.3f s)\n", s.meanLengthMm,
                s.springFrequencyHz, s.springSettlingSeconds);
  }
}

}  // namespace

void addAnalyzeCommand(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "analyze",
      "Measure the fur's response to gravity over a clip (body orientation, droop, tip height and "
      "speed; with --dynamics on, lag, overshoot and settling) into a CSV, with an optional plot");
  auto model = std::make_shared<ModelOptions>();
  auto pose = std::make_shared<PoseOptions>();
  auto furArgs = std::make_shared<FurOptions>();
  auto dyn = std::make_shared<DynamicsOptions>();
  auto range = std::make_shared<FrameOptions>();
  auto common = std::make_shared<CommonOptions>();
  struct Options {
    std::string out, plot, sweep, groups = "region";
    double hold = 0.0;
    int sweepIndex = -1;
    std::vector<std::string> merge;
  };
  auto o = std::make_shared<Options>();
  model->add(*cmd);
  pose->add(*cmd);
  range->add(*cmd);
  furArgs->add(*cmd);
  dyn->add(*cmd, true);
  cmd->add_option("--hold", o->hold,
                  "Seconds the last frame's pose is held still afterwards [0, 1000] (default 0); "
                  "with --dynamics on, overshoot and settling are measured there");
  cmd->add_option("--groups", o->groups,
                  "Per-group columns: region (skin regions) or segment (body segments) (default "
                  "region)")
      ->check(CLI::IsMember({"region", "segment"}));
  cmd->add_option("--sweep", o->sweep,
                  "Sweep one parameter: stiffness=A:B:N (the paper's, [0, 1]), frequency=A:B:N "
                  "(Hz) or damping=A:B:N (these two with --dynamics on); one CSV with a column per "
                  "value");
  auto* indexOption = cmd->add_option(
      "--sweep-index", o->sweepIndex,
      "With --sweep: run only value I of the sweep [0, N-1] (one task of a sweep split across "
      "processes or a job array; join the parts with --merge)");
  auto* mergeOption = cmd->add_option(
      "--merge", o->merge,
      "Join the CSVs of a split sweep's parts, given in value order, into the CSV one run writes "
      "(no model is loaded; only --out applies)");
  cmd->add_option("--out", o->out, "Output .csv file")->required();
  cmd->add_option("--plot", o->plot, "Also draw the main curves against time into this .png file");
  common->add(*cmd, true);
  cmd->callback([=] {
    if (!o->merge.empty()) {
      for (const CLI::Option* opt : cmd->get_options())
        if (opt->count() > 0 && opt != mergeOption && opt->get_name() != "--out" &&
            opt->get_name() != "--quiet" && opt->get_name() != "--threads")
          inputError("--merge takes only --out (and --quiet, --threads), not ", opt->get_name());
      std::vector<std::string> texts;
      for (const std::string& f : o->merge) {
        if (std::error_code ec; !std::filesystem::is_regular_file(f, ec))
          inputError(f, ": no such file to merge");
        texts.push_back(readTextFile(f));
      }
      writeFileAtomically(o->out, scene::mergeSweepCsv(texts, o->merge));
      if (!common->quiet)
        std::printf("%s: merged %zu sweep parts\n", o->out.c_str(), o->merge.size());
      return;
    }
    if (indexOption->count() > 0 && o->sweep.empty()) inputError("--sweep-index needs --sweep");
    // Options first: bad values fail before the model is built.
    const fur::FurParams params = furArgs->resolve();
    scene::AnalysisOptions opt;
    opt.dynamics = dyn->enabled();
    opt.dynamicsParams = dyn->resolve();
    range->validateFps();
    opt.clock.fps = range->fps;
    opt.clock.preRollFrames = dyn->preRoll;
    opt.holdSeconds = o->hold;
    opt.groups = scene::parseAnalysisGroups(o->groups);
    if (!(o->hold >= 0.0 && o->hold <= 1000.0))
      inputError("--hold ", o->hold, " is out of range [0, 1000] seconds");
    if (!o->plot.empty() && std::filesystem::path(o->plot).extension() != ".png")
      inputError("--plot '", o->plot, "' must name a .png file");
    scene::SweepSpec sweep;
    if (!o->sweep.empty()) {
      sweep = scene::parseSweep(o->sweep);
      if (sweep.parameter != "stiffness" && !opt.dynamics)
        inputError("--sweep ", o->sweep, ": ", sweep.parameter,
                   " is a parameter of the dynamic springs; it needs --dynamics on");
    }
    if (!range->frames.empty()) scene::parseFrameRange(range->frames);
    const bool quiet = common->quiet;
    scene::Model m = model->load();
    scene::PlaybackOptions po;
    pose->sequence(m, po);
    opt.clip = po.clip;
    opt.stillPose = po.stillPose;
    opt.clock.startSeconds = po.startSeconds;
    const scene::FrameRange frames = range->range(m, opt.clip, po.startSeconds, quiet);
    opt.frames = frames;
    const std::string clipName =
        opt.clip >= 0 ? m.clips[static_cast<std::size_t>(opt.clip)].name : "still pose";
    const scene::Fur fur =
        scene::growFur(m, params, "fur '" + params.name + "' with the command-line options");
    std::string title = "pelage analyze: " + m.name + ", clip " + clipName + ", fur " +
                        params.name + ", " + std::to_string(fur.roots.total()) + " hairs";
    if (opt.dynamics) {
      char buf[160];
      const fur::CoatDynamics& cd = opt.dynamicsParams.coats[0];
      std::snprintf(buf, sizeof buf, ", dynamics f0 %g Hz, zeta %g",
                    static_cast<double>(cd.frequencyHz), static_cast<double>(cd.dampingRatio));
      title += buf;
    }
    if (!o->sweep.empty()) {
      const scene::SweepResult s = scene::sweepClip(m, fur, opt, sweep, o->sweepIndex);
      writeFileAtomically(o->out, scene::sweepCsv(s));
      if (!o->plot.empty())
        scene::writePlotPng(o->plot, sweepPlot(s, title + ", sweep " + o->sweep));
      if (quiet) return;
      std::printf("%s: %zu frames x %zu values of %s (%s)\n", o->out.c_str(),
                  s.runs.front().frames.size(), s.values.size(), sweep.parameter.c_str(),
                  opt.dynamics ? "dynamic" : "quasi-static");
      if (!o->plot.empty()) std::printf("%s: plot\n", o->plot.c_str());
      return;
    }
    const scene::AnalysisResult r = scene::analyzeClip(m, fur, opt);
    writeFileAtomically(o->out, scene::analysisCsv(r));
    if (!o->plot.empty()) scene::writePlotPng(o->plot, analysisPlot(r, title));
    if (quiet) return;
    std::printf(
        "%s: %zu frames of clip %s at %g fps, %lld hairs (%s); body orientation from segment "
        "'%s'\n",
        o->out.c_str(), r.frames.size(), clipName.c_str(), opt.clock.fps,
        static_cast<long long>(fur.roots.total()),
        opt.dynamics ? "quasi-static and dynamic" : "quasi-static", r.orientationSegment.c_str());
    printSummary(r);
    if (!o->plot.empty()) std::printf("%s: plot\n", o->plot.c_str());
  });
}

}  // namespace pelage::app
