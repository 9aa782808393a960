#include "pelage/scene/plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "pelage/util/error.h"
#include "pelage/util/image.h"
#include "pelage/util/path.h"

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wsign-conversion"
#pragma GCC diagnostic ignored "-Wdouble-promotion"
#pragma GCC diagnostic ignored "-Wcast-align"
#include <stb_easy_font.h>
#pragma GCC diagnostic pop

namespace pelage::scene {
namespace {

using Color = std::array<std::uint8_t, 3>;

class Canvas {
 public:
  // White and opaque; stored as RGB (Rgba8Image::fileChannels 3).
  Canvas(int w, int h) {
    image_.width = w;
    image_.height = h;
    image_.fileChannels = 3;
    image_.rgba.assign(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 4, 255);
  }

  // Blends `c` over pixel (x, y) with coverage a in [0, 1].
  void blend(int x, int y, const Color& c, double a) {
    if (x < 0 || y < 0 || x >= image_.width || y >= image_.height || a <= 0.0) return;
    a = std::min(a, 1.0);
    std::uint8_t* p = image_.pixel(x, y);
    for (int k = 0; k < 3; ++k)
      p[k] = static_cast<std::uint8_t>(
          std::lround(p[k] * (1.0 - a) + c[static_cast<std::size_t>(k)] * a));
  }

  void fillRect(double x0, double y0, double x1, double y1, const Color& c) {
    // Exact area coverage of each pixel by the rectangle (anti-aliased edges).
    for (int y = static_cast<int>(std::floor(y0)); y < static_cast<int>(std::ceil(y1)); ++y)
      for (int x = static_cast<int>(std::floor(x0)); x < static_cast<int>(std::ceil(x1)); ++x) {
        const double cx = std::min<double>(x + 1, x1) - std::max<double>(x, x0);
        const double cy = std::min<double>(y + 1, y1) - std::max<double>(y, y0);
        if (cx > 0 && cy > 0) blend(x, y, c, cx * cy);
      }
  }

  // An anti-aliased segment of width `width` (pixels): coverage from the distance to the segment.
  void line(double x0, double y0, double x1, double y1, double width, const Color& c) {
    const double r = width / 2.0;
    const int xa = static_cast<int>(std::floor(std::min(x0, x1) - r - 1)),
              xb = static_cast<int>(std::ceil(std::max(x0, x1) + r + 1));
    const int ya = static_cast<int>(std::floor(std::min(y0, y1) - r - 1)),
              yb = static_cast<int>(std::ceil(std::max(y0, y1) + r + 1));
    const double dx = x1 - x0, dy = y1 - y0, len2 = dx * dx + dy * dy;
    for (int y = std::max(ya, 0); y <= std::min(yb, image_.height - 1); ++y)
      for (int x = std::max(xa, 0); x <= std::min(xb, image_.width - 1); ++x) {
        const double px = x + 0.5 - x0, py = y + 0.5 - y0;
        const double t = len2 > 0 ? std::clamp((px * dx + py * dy) / len2, 0.0, 1.0) : 0.0;
        const double ex = px - t * dx, ey = py - t * dy;
        const double d = std::sqrt(ex * ex + ey * ey);
        blend(x, y, c, std::clamp(r + 0.5 - d, 0.0, 1.0));
      }
  }

  // Text at (x, y) (top-left), glyphs `scale` pixels per font unit.
  void text(double x, double y, const std::string& s, double scale, const Color& c) {
    std::vector<char> buf(s.size() * 300 + 1000);
    std::string copy = s;
    const int quads = stb_easy_font_print(0.0f, 0.0f, copy.data(), nullptr, buf.data(),
                                          static_cast<int>(buf.size()));
    for (int q = 0; q < quads; ++q) {
      float v[4][2];
      for (int k = 0; k < 4; ++k)
        std::memcpy(v[k], buf.data() + (q * 4 + k) * 16, 2 * sizeof(float));
      const double qx0 = std::min({v[0][0], v[1][0], v[2][0], v[3][0]}),
                   qx1 = std::max({v[0][0], v[1][0], v[2][0], v[3][0]});
      const double qy0 = std::min({v[0][1], v[1][1], v[2][1], v[3][1]}),
                   qy1 = std::max({v[0][1], v[1][1], v[2][1], v[3][1]});
      fillRect(x + qx0 * scale, y + qy0 * scale, x + qx1 * scale, y + qy1 * scale, c);
    }
  }
  static double textWidth(const std::string& s, double scale) {
    std::string copy = s;
    return stb_easy_font_width(copy.data()) * scale;
  }

  Rgba8Image take() { return std::move(image_); }

 private:
  Rgba8Image image_;
};

std::string tickLabel(double v, double step) {
  char buf[32];
  if (std::abs(v) < step * 1e-6) v = 0.0;
  const int decimals = std::max(0, static_cast<int>(std::ceil(-std::log10(step) - 1e-9)));
  std::snprintf(buf, sizeof buf, "%.*f", std::min(decimals, 6), v);
  return buf;
}

const Color kBlack{0, 0, 0}, kGrid{225, 225, 225}, kAxis{60, 60, 60}, kMarker{120, 120, 120};

}  // namespace

std::vector<double> niceTicks(double lo, double hi, int target) {
  std::vector<double> ticks;
  if (!(std::isfinite(lo) && std::isfinite(hi)) || target < 1) return ticks;
  if (hi <= lo) hi = lo + 1.0;
  const double raw = (hi - lo) / target;
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  double step = mag;
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * mag >= raw) {
      step = m * mag;
      break;
    }
  for (double t = std::ceil(lo / step - 1e-9) * step; t <= hi + step * 1e-9; t += step)
    ticks.push_back(t);
  return ticks;
}

std::array<std::uint8_t, 3> plotColor(int index) {
  static const Color palette[10] = {
      {31, 119, 180}, {255, 127, 14},  {44, 160, 44},   {214, 39, 40},  {148, 103, 189},
      {140, 86, 75},  {227, 119, 194}, {127, 127, 127}, {188, 189, 34}, {23, 190, 207}};
  return palette[((index % 10) + 10) % 10];
}

Rgba8Image renderPlot(const PlotSpec& spec) {
  PELAGE_CHECK(spec.width >= 200 && spec.width <= 8000 && spec.height >= 150 && spec.height <= 8000,
               "plot size ", spec.width, "x", spec.height);
  PELAGE_CHECK(!spec.panels.empty(), "a plot without panels");
  Canvas canvas(spec.width, spec.height);
  const double scale = std::clamp(spec.width / 650.0, 1.0, 4.0);  // font units to pixels
  const double lineHeight = 9.0 * scale;
  // Legend width: the longest label of any panel.
  double legend = 0.0;
  for (const PlotPanel& p : spec.panels)
    for (const PlotSeries& s : p.series)
      legend = std::max(legend, Canvas::textWidth(s.label, scale));
  const double left = 8.0 * scale + Canvas::textWidth("-0000.0", scale),
               right = legend + 40.0 * scale;
  const double top = 4.5 * lineHeight, bottom = 4.0 * lineHeight;
  const double gap = 2.5 * lineHeight;
  const auto n = static_cast<double>(spec.panels.size());
  const double plotW = spec.width - left - right;
  const double panelH = (spec.height - top - bottom - gap * (n - 1)) / n;
  PELAGE_CHECK(plotW > 50 && panelH > 30, "plot too small for its panels and legend");
  // The title, shrunk to fit the width.
  const double titleScale =
      std::min(scale * 1.4, (spec.width - 2.0 * 8.0 * scale) /
                                std::max(1.0, Canvas::textWidth(spec.title, 1.0)));
  canvas.text(std::max(8.0 * scale, (spec.width - Canvas::textWidth(spec.title, titleScale)) / 2),
              0.8 * lineHeight, spec.title, titleScale, kBlack);
  // Shared x range.
  double xlo = INFINITY, xhi = -INFINITY;
  for (const PlotPanel& p : spec.panels)
    for (const PlotSeries& s : p.series)
      for (double x : s.x)
        if (std::isfinite(x)) xlo = std::min(xlo, x), xhi = std::max(xhi, x);
  if (!(xlo < xhi)) xlo = 0.0, xhi = 1.0;
  const std::vector<double> xt = niceTicks(xlo, xhi, 8);
  for (std::size_t pi = 0; pi < spec.panels.size(); ++pi) {
    const PlotPanel& p = spec.panels[pi];
    const double y0 = top + static_cast<double>(pi) * (panelH + gap), y1 = y0 + panelH;
    double ylo = INFINITY, yhi = -INFINITY;
    for (const PlotSeries& s : p.series)
      for (double y : s.y)
        if (std::isfinite(y)) ylo = std::min(ylo, y), yhi = std::max(yhi, y);
    if (!(ylo <= yhi)) ylo = 0.0, yhi = 1.0;
    const double pad = yhi > ylo ? 0.06 * (yhi - ylo) : std::max(1.0, std::abs(ylo) * 0.1);
    std::vector<double> yt = niceTicks(ylo - pad, yhi + pad, 5);
    const double step = yt.size() > 1 ? yt[1] - yt[0] : 1.0;
    ylo = std::min(ylo - pad, yt.empty() ? ylo : yt.front());
    yhi = std::max(yhi + pad, yt.empty() ? yhi : yt.back());
    auto X = [&](double x) { return left + (x - xlo) / (xhi - xlo) * plotW; };
    auto Y = [&](double y) { return y1 - (y - ylo) / (yhi - ylo) * panelH; };
    // Grid, ticks and labels.
    for (double t : yt) {
      canvas.line(left, Y(t), left + plotW, Y(t), 1.0, kGrid);
      const std::string s = tickLabel(t, step);
      canvas.text(left - 6.0 * scale - Canvas::textWidth(s, scale), Y(t) - 3.5 * scale, s, scale,
                  kAxis);
    }
    const double xstep = xt.size() > 1 ? xt[1] - xt[0] : 1.0;
    for (double t : xt) {
      canvas.line(X(t), y0, X(t), y1, 1.0, kGrid);
      if (pi + 1 == spec.panels.size()) {
        const std::string s = tickLabel(t, xstep);
        canvas.text(X(t) - Canvas::textWidth(s, scale) / 2, y1 + 4.0 * scale, s, scale, kAxis);
      }
    }
    canvas.text(left, y0 - 1.2 * lineHeight, p.yLabel, scale, kBlack);
    if (std::isfinite(spec.markerX) && spec.markerX >= xlo && spec.markerX <= xhi) {
      for (double y = y0; y < y1; y += 8.0 * scale)
        canvas.line(X(spec.markerX), y, X(spec.markerX), std::min(y + 4.0 * scale, y1), 1.5,
                    kMarker);
      if (pi == 0 && !spec.markerLabel.empty())
        canvas.text(X(spec.markerX) + 3.0 * scale, y0 + 2.0 * scale, spec.markerLabel, scale,
                    kMarker);
    }
    // Series, clipped to the panel by construction of the ranges.
    for (std::size_t si = 0; si < p.series.size(); ++si) {
      const PlotSeries& s = p.series[si];
      double dash = 0.0;
      for (std::size_t i = 1; i < std::min(s.x.size(), s.y.size()); ++i) {
        if (!(std::isfinite(s.y[i - 1]) && std::isfinite(s.y[i]) && std::isfinite(s.x[i - 1]) &&
              std::isfinite(s.x[i])))
          continue;
        const double ax = X(s.x[i - 1]), ay = Y(s.y[i - 1]), bx = X(s.x[i]), by = Y(s.y[i]);
        const double seg = std::hypot(bx - ax, by - ay);
        if (s.dashed) {  // 10 on, 6 off (pixels per scale unit)
          const double period = 16.0 * scale;
          for (double t = 0.0; t < seg;) {
            const double phase = std::fmod(dash + t, period);
            const double on = 10.0 * scale;
            const double run =
                phase < on ? std::min(on - phase, seg - t) : std::min(period - phase, seg - t);
            if (phase < on && seg > 0) {
              const double ta = t / seg, tb = (t + run) / seg;
              canvas.line(ax + (bx - ax) * ta, ay + (by - ay) * ta, ax + (bx - ax) * tb,
                          ay + (by - ay) * tb, 2.0 * scale * 0.6, s.color);
            }
            t += std::max(run, 1e-3);
          }
          dash += seg;
        } else {
          canvas.line(ax, ay, bx, by, 2.0 * scale * 0.6, s.color);
        }
      }
      // Legend entry.
      const double ly = y0 + 4.0 * scale + static_cast<double>(si) * lineHeight * 1.3;
      const double lx = left + plotW + 10.0 * scale;
      canvas.line(lx, ly + 3.5 * scale, lx + 20.0 * scale, ly + 3.5 * scale, 2.0 * scale * 0.6,
                  s.color);
      canvas.text(lx + 25.0 * scale, ly, s.label, scale, kBlack);
    }
    // Axes box.
    canvas.line(left, y0, left, y1, 1.2, kAxis);
    canvas.line(left, y1, left + plotW, y1, 1.2, kAxis);
    canvas.line(left, y0, left + plotW, y0, 1.0, kAxis);
    canvas.line(left + plotW, y0, left + plotW, y1, 1.0, kAxis);
  }
  canvas.text(left + plotW / 2 - Canvas::textWidth(spec.xLabel, scale) / 2,
              spec.height - bottom + 2.2 * lineHeight, spec.xLabel, scale, kBlack);
  return canvas.take();
}

void validatePlotFile(const std::string& path, const std::string& field) {
  if (lowerExtension(path) != ".png") fieldError(field, "'", path, "' must name a .png file");
}

void writePlotPng(const std::string& path, const PlotSpec& spec) {
  validatePlotFile(path);
  writeImageFile(path, renderPlot(spec));
}

}  // namespace pelage::scene
