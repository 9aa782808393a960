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
#include "pelage/scene/analysis_plot.h"
#include "pelage/scene/analyze.h"
#include "pelage/scene/frame_range.h"
#include "pelage/scene/plot.h"
#include "pelage/util/atomic_file.h"
#include "pelage/util/error.h"

namespace pelage::app {
namespace {

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
    scene::validateHoldSeconds(o->hold);
    if (!o->plot.empty()) scene::validatePlotFile(o->plot);
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
    opt.clock.startSeconds = po.clock.startSeconds;
    const scene::FrameRange frames = range->range(m, opt.clip, po.clock.startSeconds, quiet);
    opt.frames = frames;
    const std::string clipName = scene::analysisClipName(m, opt.clip);
    const scene::Fur fur =
        scene::growFur(m, params, "fur '" + params.name + "' with the command-line options");
    const std::string title = scene::analysisTitle(m, fur, opt);
    if (!o->sweep.empty()) {
      const scene::SweepResult s = scene::sweepClip(m, fur, opt, sweep, o->sweepIndex);
      writeFileAtomically(o->out, scene::sweepCsv(s));
      if (!o->plot.empty())
        scene::writePlotPng(o->plot, scene::sweepPlot(s, title + ", sweep " + o->sweep));
      if (quiet) return;
      std::printf("%s: %zu frames x %zu values of %s (%s)\n", o->out.c_str(),
                  s.runs.front().frames.size(), s.values.size(), sweep.parameter.c_str(),
                  opt.dynamics ? "dynamic" : "quasi-static");
      if (!o->plot.empty()) std::printf("%s: plot\n", o->plot.c_str());
      return;
    }
    const scene::AnalysisResult r = scene::analyzeClip(m, fur, opt);
    writeFileAtomically(o->out, scene::analysisCsv(r));
    if (!o->plot.empty()) scene::writePlotPng(o->plot, scene::analysisPlot(r, title));
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
