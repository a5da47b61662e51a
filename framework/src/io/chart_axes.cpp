#include "io/chart_axes.hpp"

#include <algorithm>
#include <cmath>

namespace topomill {

std::pair<double, double> data_range(std::vector<double> v, bool log) {
  v.erase(std::remove_if(v.begin(), v.end(),
                         [&](double x) { return !std::isfinite(x) || (log && x <= 0); }),
          v.end());
  if (v.empty()) return {log ? 1.0 : 0.0, log ? 10.0 : 1.0};
  auto [mn, mx] = std::minmax_element(v.begin(), v.end());
  double lo = *mn, hi = *mx;
  if (log) {
    if (hi <= lo) lo /= 2, hi *= 2;
    return {lo / 1.25, hi * 1.25};
  }
  if (hi <= lo) lo -= 0.5 * (std::abs(lo) + 1), hi += 0.5 * (std::abs(hi) + 1);
  const double pad = 0.06 * (hi - lo);
  return {lo - pad, hi + pad};
}

void draw_frame(const Canvas& cv, const ChartLabels& lab, const Axis& x, const Axis& y, int w,
                int h) {
  cairo_t* cr = *cv;
  cairo_set_line_width(cr, 1);
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_rectangle(cr, x.a, y.b, x.b - x.a, y.a - y.b);
  cairo_stroke(cr);
  for (double v : ticks(x.lo, x.hi, x.log)) {
    const double px = x.map(v);
    cairo_set_source_rgb(cr, 0.88, 0.88, 0.88);
    cairo_move_to(cr, px, y.a), cairo_line_to(cr, px, y.b), cairo_stroke(cr);
    cairo_set_source_rgb(cr, 0, 0, 0);
    cv.text(px, y.a + 6, number(v), 0.5, 0);
  }
  for (double v : ticks(y.lo, y.hi, y.log)) {
    const double py = y.map(v);
    cairo_set_source_rgb(cr, 0.88, 0.88, 0.88);
    cairo_move_to(cr, x.a, py), cairo_line_to(cr, x.b, py), cairo_stroke(cr);
    cairo_set_source_rgb(cr, 0, 0, 0);
    cv.text(x.a - 6, py, number(v), 1, 0.5);
  }
  cv.text((x.a + x.b) / 2, h - 22, lab.x, 0.5, 0);
  cv.text(16, (y.a + y.b) / 2, lab.y, 0.5, 0, true);
  cairo_set_font_size(cr, 15);
  cv.text(w / 2.0, 10, lab.title, 0.5, 0);
  cairo_set_font_size(cr, 13);
}

}  // namespace topomill
