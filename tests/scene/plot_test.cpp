// The plot renderer (plot.h): tick choice, and image statistics of a rendered plot (every series
// drawn in its colour, the text and axes dark, mostly white background), and the PNG file.
#include "pelage/scene/plot.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "pelage/util/error.h"
#include "support/files.h"

namespace pelage::scene {
namespace {

TEST(NiceTicks, AreRoundStepsCoveringTheRange) {
  EXPECT_EQ(niceTicks(0.0, 10.0, 5), (std::vector<double>{0, 2, 4, 6, 8, 10}));
  EXPECT_EQ(niceTicks(0.0, 3.0, 8), (std::vector<double>{0, 0.5, 1, 1.5, 2, 2.5, 3}));
  const std::vector<double> t = niceTicks(-7.3, 42.1, 5);
  ASSERT_GE(t.size(), 3u);
  EXPECT_EQ(t.front(), 0.0);  // steps of 10: the first multiple >= -7.3
  EXPECT_EQ(t[1] - t[0], 10.0);
  EXPECT_TRUE(niceTicks(NAN, 1.0, 5).empty());
}

PlotSpec samplePlot() {
  PlotSpec spec;
  spec.title = "test plot";
  spec.xLabel = "time (s)";
  spec.width = 800;
  spec.height = 600;
  PlotPanel a{"first (deg)", {}}, b{"second (mm)", {}};
  PlotSeries sine{"sine", {}, {}, {255, 0, 0}, false};
  PlotSeries ramp{"ramp", {}, {}, {0, 0, 255}, true};
  PlotSeries flat{"flat", {}, {}, {0, 160, 0}, false};
  for (int i = 0; i <= 100; ++i) {
    const double t = i / 20.0;
    sine.x.push_back(t);
    sine.y.push_back(std::sin(t));
    ramp.x.push_back(t);
    ramp.y.push_back(t * 3.0);
    flat.x.push_back(t);
    flat.y.push_back(2.0);
  }
  a.series = {sine, ramp};
  b.series = {flat};
  spec.panels = {a, b};
  spec.markerX = 2.5;
  spec.markerLabel = "stop";
  return spec;
}

// Pixels of `img` for which `is(r, g, b)` holds.
template <class Pred>
int count(const Rgba8Image& img, Pred is) {
  int n = 0;
  for (std::size_t i = 0; i + 3 < img.rgba.size(); i += 4)
    n += is(img.rgba[i], img.rgba[i + 1], img.rgba[i + 2]);
  return n;
}
bool reddish(int r, int g, int b) {
  return r > 200 && g < 140 && b < 140;
}
bool greenish(int r, int g, int b) {
  return g > r + 50 && g > b + 50;
}
bool bluish(int r, int g, int b) {
  return b > r + 80 && b > g + 80;
}
bool dark(int r, int g, int b) {
  return r < 110 && g < 110 && b < 110;
}
bool white(int r, int g, int b) {
  return r == 255 && g == 255 && b == 255;
}

TEST(RenderPlot, DrawsEverySeriesAxesAndTextOnWhite) {
  const Rgba8Image img = renderPlot(samplePlot());
  ASSERT_EQ(img.width, 800);
  ASSERT_EQ(img.height, 600);
  ASSERT_EQ(img.rgba.size(), 800u * 600u * 4u);
  EXPECT_EQ(img.fileChannels, 3);  // written as RGB
  for (std::size_t i = 3; i < img.rgba.size(); i += 4) ASSERT_EQ(img.rgba[i], 255);  // opaque
  const int total = 800 * 600;
  const int background = count(img, white);
  EXPECT_GT(background, total * 6 / 10);  // mostly background
  EXPECT_LT(background, total * 97 / 100);
  // Each series in its colour, in proportion to its length: the sine and the flat line span the
  // plot width (about 600 px), each pixel column crossed by a line about 1.5 px wide.
  const int red = count(img, reddish), green = count(img, greenish), blue = count(img, bluish);
  EXPECT_GT(red, 600) << red;
  EXPECT_GT(green, 600) << green;
  EXPECT_GT(blue, 300) << blue;
  EXPECT_LT(blue, 1.2 * red) << "dashes leave gaps (the ramp is also steeper: longer)";
  EXPECT_GT(count(img, dark), 1500) << "text and axes";
  // The left margin holds tick labels, the right one the legend: dark pixels in both.
  int leftDark = 0, rightDark = 0;
  for (int y = 0; y < 600; ++y)
    for (int x = 0; x < 800; ++x) {
      const std::uint8_t* p = img.pixel(x, y);
      const bool isDark = dark(p[0], p[1], p[2]);
      if (isDark && x < 60) ++leftDark;
      if (isDark && x > 700) ++rightDark;
    }
  EXPECT_GT(leftDark, 50);
  EXPECT_GT(rightDark, 50);
}

TEST(WritePlotPng, WritesAReadablePngAndNamesUnwritableFiles) {
  test::TempDir dir;
  const std::string path = dir.file("plot.png");
  writePlotPng(path, samplePlot());
  const std::string bytes = test::readText(path);
  ASSERT_GT(bytes.size(), 2000u);
  EXPECT_EQ(bytes.substr(1, 3), "PNG");
  EXPECT_THROW(writePlotPng(dir.file("missing/dir/plot.png"), samplePlot()), InputError);
  PlotSpec none = samplePlot();
  none.panels.clear();
  EXPECT_THROW(renderPlot(none), InternalError);
}

}  // namespace
}  // namespace pelage::scene
