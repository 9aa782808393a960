// The analysis plots (scene/analysis_plot.h): which panels and curves a run and a sweep draw, and
// the title, on results built by hand.
#include "pelage/scene/analysis_plot.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "pelage/util/error.h"

namespace pelage::scene {
namespace {

AnalysisResult threeFrames(bool dynamics, double droopOffset) {
  AnalysisResult r;
  r.dynamics = dynamics;
  r.orientationSegment = "hips";
  for (int f = 0; f < 3; ++f) {
    FrameAnalysis a;
    a.frame = f;
    a.seconds = f / 30.0;
    a.tiltDeg = 10.0 * f;
    a.quasiStatic.all.droopMeanDeg = droopOffset + f;
    a.dynamic.all.droopMeanDeg = droopOffset + 2.0 * f;
    r.frames.push_back(a);
  }
  return r;
}

TEST(AnalysisPlot, OneRunDrawsOrientationDroopHeightAndBodyUpAgainstTime) {
  const PlotSpec spec = analysisPlot(threeFrames(false, 5.0), "title");
  EXPECT_EQ(spec.title, "title");
  EXPECT_EQ(spec.xLabel, "time (s)");
  ASSERT_EQ(spec.panels.size(), 4u);
  EXPECT_NE(spec.panels[0].yLabel.find("segment 'hips'"), std::string::npos);
  const PlotPanel& droop = spec.panels[1];
  ASSERT_EQ(droop.series.size(), 1u);  // quasi-static only
  EXPECT_EQ(droop.series[0].x, (std::vector<double>{0.0, 1.0 / 30.0, 2.0 / 30.0}));
  EXPECT_EQ(droop.series[0].y, (std::vector<double>{5.0, 6.0, 7.0}));
  EXPECT_FALSE(droop.series[0].dashed);
  EXPECT_TRUE(std::isnan(spec.markerX));  // no hold
  EXPECT_NO_THROW(renderPlot(spec));
}

TEST(AnalysisPlot, DynamicsAddTheDynamicCurvesTheLagAndTheOffsetPanel) {
  AnalysisResult r = threeFrames(true, 0.0);
  r.settling.measured = true;
  r.settling.stopSeconds = 0.05;
  const PlotSpec spec = analysisPlot(r, "t");
  ASSERT_EQ(spec.panels.size(), 5u);
  const PlotPanel& droop = spec.panels[1];
  ASSERT_EQ(droop.series.size(), 3u);  // quasi-static (dashed), dynamic, lag
  EXPECT_TRUE(droop.series[0].dashed);
  EXPECT_EQ(droop.series[1].y, (std::vector<double>{0.0, 2.0, 4.0}));
  EXPECT_EQ(spec.panels[4].series.size(), 2u);  // distance, and along the stop direction
  EXPECT_EQ(spec.markerX, 0.05);
  EXPECT_EQ(spec.markerLabel, "body stops");
  EXPECT_GT(spec.height, analysisPlot(threeFrames(false, 0.0), "t").height);
}

TEST(AnalysisPlot, ASweepDrawsOneCurveAValue) {
  SweepResult s;
  s.spec.parameter = "stiffness";
  s.values = {0.2, 0.8};
  s.runs = {threeFrames(false, 1.0), threeFrames(false, 3.0)};
  const PlotSpec spec = sweepPlot(s, "sweep");
  ASSERT_EQ(spec.panels.size(), 3u);  // orientation, droop, tip height
  const PlotPanel& droop = spec.panels[1];
  ASSERT_EQ(droop.series.size(), 2u);
  EXPECT_EQ(droop.series[0].label, "stiffness = 0.2");
  EXPECT_EQ(droop.series[1].label, "stiffness = 0.8");
  EXPECT_EQ(droop.series[1].y, (std::vector<double>{3.0, 4.0, 5.0}));
  EXPECT_NE(droop.series[0].color, droop.series[1].color);
  EXPECT_NE(droop.yLabel.find("quasi-static"), std::string::npos);
}

TEST(AnalysisPlot, APlotFileIsAPng) {
  EXPECT_NO_THROW(validatePlotFile("a/b.png"));
  EXPECT_NO_THROW(validatePlotFile("B.PNG"));
  try {
    validatePlotFile("p.jpg");
    ADD_FAILURE() << "p.jpg accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "plot");
    EXPECT_STREQ(e.what(), "plot 'p.jpg' must name a .png file");
  }
}

}  // namespace
}  // namespace pelage::scene
