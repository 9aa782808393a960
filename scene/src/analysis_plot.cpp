#include "pelage/scene/analysis_plot.h"

#include <cstdio>
#include <string>
#include <vector>

#include "pelage/util/error.h"

namespace pelage::scene {

std::string analysisTitle(const Model& model, const Fur& fur, const AnalysisOptions& options) {
  std::string title = "pelage analyze: " + model.name + ", clip " +
                      analysisClipName(model, options.clip) + ", fur " + fur.params.name + ", " +
                      std::to_string(fur.roots.total()) + " hairs";
  if (options.dynamics) {
    char buf[160];
    const fur::CoatDynamics& cd = options.dynamicsParams.coats[0];
    std::snprintf(buf, sizeof buf, ", dynamics f0 %g Hz, zeta %g",
                  static_cast<double>(cd.frequencyHz), static_cast<double>(cd.dampingRatio));
    title += buf;
  }
  return title;
}

namespace {

std::vector<double> column(const AnalysisResult& r, double (*get)(const FrameAnalysis&)) {
  std::vector<double> v;
  for (const FrameAnalysis& f : r.frames) v.push_back(get(f));
  return v;
}

PlotPanel orientationPanel(const AnalysisResult& r, const std::vector<double>& t) {
  PlotPanel p;
  p.yLabel = "body orientation (deg): up vector of segment '" + r.orientationSegment + "'";
  p.series.push_back({"pitch (about world Y)", t,
                      column(r, [](const FrameAnalysis& f) { return f.pitchDeg; }), plotColor(7),
                      false});
  p.series.push_back({"tilt from vertical", t,
                      column(r, [](const FrameAnalysis& f) { return f.tiltDeg; }), plotColor(4),
                      false});
  return p;
}

// A plot against time whose first panel is the body's orientation; `t` gets the frames' times.
PlotSpec timePlot(const AnalysisResult& r, const std::string& title, int height,
                  std::vector<double>& t) {
  PlotSpec spec;
  spec.title = title;
  spec.xLabel = "time (s)";
  spec.width = 1200;
  spec.height = height;
  t = column(r, [](const FrameAnalysis& f) { return f.seconds; });
  spec.panels.push_back(orientationPanel(r, t));
  return spec;
}

}  // namespace

PlotSpec analysisPlot(const AnalysisResult& r, const std::string& title) {
  std::vector<double> t;
  PlotSpec spec = timePlot(r, title, 1100, t);
  const auto qsColor = plotColor(0), dynColor = plotColor(1);
  PlotPanel droop{"mean droop angle (deg): end direction vs weightless direction", {}};
  droop.series.push_back(
      {"quasi-static (paper)", t,
       column(r, [](const FrameAnalysis& f) { return f.quasiStatic.all.droopMeanDeg; }), qsColor,
       r.dynamics});
  PlotPanel height{"mean tip height above the root (mm)", {}};
  height.series.push_back(
      {"quasi-static (paper)", t,
       column(r, [](const FrameAnalysis& f) { return f.quasiStatic.tipHeightMm; }), qsColor,
       r.dynamics});
  PlotPanel bodyUp{"mean droop along the body's up axis (mm): < 0 toward its belly", {}};
  bodyUp.series.push_back(
      {"quasi-static (paper)", t,
       column(r, [](const FrameAnalysis& f) { return f.quasiStatic.droopBodyUpMm; }), qsColor,
       r.dynamics});
  if (r.dynamics) {
    droop.series.push_back(
        {"dynamic", t, column(r, [](const FrameAnalysis& f) { return f.dynamic.all.droopMeanDeg; }),
         dynColor, false});
    droop.series.push_back({"dynamic - quasi-static lag", t,
                            column(r, [](const FrameAnalysis& f) { return f.lagDeg; }),
                            plotColor(2), false});
    height.series.push_back(
        {"dynamic", t, column(r, [](const FrameAnalysis& f) { return f.dynamic.tipHeightMm; }),
         dynColor, false});
    bodyUp.series.push_back(
        {"dynamic", t, column(r, [](const FrameAnalysis& f) { return f.dynamic.droopBodyUpMm; }),
         dynColor, false});
  }
  spec.panels.push_back(droop);
  spec.panels.push_back(height);
  spec.panels.push_back(bodyUp);
  if (r.dynamics) {
    PlotPanel offset{"dynamic ends' distance from the quasi-static ends (mm)", {}};
    offset.series.push_back({"mean distance", t,
                             column(r, [](const FrameAnalysis& f) { return f.offsetMm; }),
                             plotColor(3), false});
    if (r.settling.measured)
      offset.series.push_back({"along its direction at the stop", t,
                               column(r, [](const FrameAnalysis& f) { return f.stopResponseMm; }),
                               plotColor(9), false});
    spec.panels.push_back(offset);
    spec.height = 1350;
  }
  if (r.settling.measured) {
    spec.markerX = r.settling.stopSeconds;
    spec.markerLabel = "body stops";
  }
  return spec;
}

PlotSpec sweepPlot(const SweepResult& s, const std::string& title) {
  PELAGE_CHECK(!s.runs.empty(), "a sweep without runs");
  const AnalysisResult& first = s.runs.front();
  std::vector<double> t;
  PlotSpec spec = timePlot(first, title, 900, t);
  const bool dyn = first.dynamics;
  PlotPanel droop{std::string("mean droop angle (deg)") + (dyn ? ", dynamic" : ", quasi-static"),
                  {}};
  PlotPanel height{
      std::string("mean tip height above the root (mm)") + (dyn ? ", dynamic" : ", quasi-static"),
      {}};
  const std::vector<double>& values = s.values;
  for (std::size_t i = 0; i < s.runs.size(); ++i) {
    char label[64];
    std::snprintf(label, sizeof label, "%s = %g", s.spec.parameter.c_str(), values[i]);
    const auto color = plotColor(static_cast<int>(i));
    droop.series.push_back(
        {label, t,
         column(
             s.runs[i],
             dyn ? +[](const FrameAnalysis& f) { return f.dynamic.all.droopMeanDeg; }
                 : +[](const FrameAnalysis& f) { return f.quasiStatic.all.droopMeanDeg; }),
         color, false});
    height.series.push_back(
        {label, t,
         column(
             s.runs[i], dyn ? +[](const FrameAnalysis& f) { return f.dynamic.tipHeightMm; }
                            : +[](const FrameAnalysis& f) { return f.quasiStatic.tipHeightMm; }),
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

}  // namespace pelage::scene
