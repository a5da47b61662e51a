// What the charts share: an axis mapping data to pixels, a padded data range, and the frame with
// its ticks, grid lines, axis labels and title.
#pragma once

#include <cmath>
#include <utility>
#include <vector>

#include "io/cairo_canvas.hpp"
#include "io/png_chart.hpp"

namespace topomill {

struct Axis {
  double lo, hi;
  bool log;
  double a, b;  // pixel range
  double map(double v) const {
    const double f = log ? (std::log10(v) - std::log10(lo)) / (std::log10(hi) - std::log10(lo))
                         : (v - lo) / (hi - lo);
    return a + f * (b - a);
  }
};

// Data range padded so that points are not drawn on the frame.
std::pair<double, double> data_range(std::vector<double> v, bool log);

// The frame of the plot area (x.a..x.b, y.b..y.a), grid lines at the ticks, tick labels, the
// axis labels and the title, on a w x h canvas.
void draw_frame(const Canvas& cv, const ChartLabels& lab, const Axis& x, const Axis& y, int w,
                int h);

}  // namespace topomill
