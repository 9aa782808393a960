// A small line-plot renderer for `pelage analyze --plot`: stacked panels sharing the x axis, each
// with axes, ticks, grid, a y label and a legend; text from stb_easy_font, anti-aliased lines,
// PNG through stb_image_write. Own code rather than a plotting library: Debian's C++ options
// (PLplot, MathGL) bring large dependency trees (cairo, Qt, ...) for what is four hundred lines
// here.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "pelage/util/image.h"

namespace pelage::scene {

struct PlotSeries {
  std::string label;
  std::vector<double> x, y;  // same length; NaN y values break the line
  std::array<std::uint8_t, 3> color{31, 119, 180};
  bool dashed = false;
};

struct PlotPanel {
  std::string yLabel;  // e.g. "mean droop angle (deg)"
  std::vector<PlotSeries> series;
};

struct PlotSpec {
  std::string title;
  std::string xLabel;  // shared by the panels, e.g. "time (s)"
  std::vector<PlotPanel> panels;
  int width = 1200;  // pixels, [200, 8000]
  int height = 900;  // pixels, [150, 8000]
  // A dashed vertical line across every panel (e.g. where the motion stops), NaN for none.
  double markerX = std::numeric_limits<double>::quiet_NaN();
  std::string markerLabel;
};

// Tick values covering [lo, hi]: multiples of 1, 2 or 5 x 10^k, about `target` of them.
std::vector<double> niceTicks(double lo, double hi, int target);

// The 10-colour palette used for successive series (matplotlib's "tab10").
std::array<std::uint8_t, 3> plotColor(int index);

// Draws the plot: opaque, stored as RGB (fileChannels 3). PELAGE_CHECK on sizes out of range or a
// spec without panels.
Rgba8Image renderPlot(const PlotSpec& spec);

// A plot's file names a .png; InputError naming `field` otherwise.
void validatePlotFile(const std::string& path, const std::string& field = "plot");

// Writes the plot as a PNG atomically (validatePlotFile first); InputError naming the file when it
// cannot be written.
void writePlotPng(const std::string& path, const PlotSpec& spec);

}  // namespace pelage::scene
