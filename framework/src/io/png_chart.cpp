#include "io/png_chart.hpp"

#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <stdexcept>

#include "io/atomic_file.hpp"

namespace topomill {

namespace {

using Surface = std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)>;
using Context = std::unique_ptr<cairo_t, decltype(&cairo_destroy)>;

struct Canvas {
  Surface surface;
  Context cr;
  Canvas(int w, int h)
      : surface(cairo_image_surface_create(CAIRO_FORMAT_RGB24, w, h), cairo_surface_destroy),
        cr(cairo_create(surface.get()), cairo_destroy) {
    cairo_set_source_rgb(cr.get(), 1, 1, 1);
    cairo_paint(cr.get());
    cairo_select_font_face(cr.get(), "DejaVu Sans", CAIRO_FONT_SLANT_NORMAL,
                           CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr.get(), 13);
    cairo_set_source_rgb(cr.get(), 0, 0, 0);
  }
  cairo_t* operator*() const { return cr.get(); }

  // Text anchored at (x, y): ax, ay in [0, 1] pick which point of its box sits there.
  void text(double x, double y, const std::string& s, double ax = 0, double ay = 0,
            bool vertical = false) const {
    cairo_text_extents_t e;
    cairo_text_extents(cr.get(), s.c_str(), &e);
    cairo_save(cr.get());
    cairo_translate(cr.get(), x, y);
    if (vertical) cairo_rotate(cr.get(), -M_PI / 2);
    cairo_move_to(cr.get(), -e.x_advance * ax, e.height * (1 - ay));
    cairo_show_text(cr.get(), s.c_str());
    cairo_restore(cr.get());
  }

  void write(const std::string& path) const {
    cairo_surface_flush(surface.get());
    write_atomically_to(path, [&](const std::string& tmp) {
      if (cairo_surface_write_to_png(surface.get(), tmp.c_str()) != CAIRO_STATUS_SUCCESS)
        throw std::runtime_error("cannot write PNG '" + path + "'");
    });
  }
};

// Qualitative palette (Okabe-Ito), readable by colour-blind viewers.
void palette(cairo_t* cr, std::size_t i) {
  static const double c[][3] = {{0.00, 0.45, 0.70}, {0.84, 0.37, 0.00}, {0.00, 0.62, 0.45},
                                {0.80, 0.47, 0.65}, {0.90, 0.62, 0.00}, {0.34, 0.71, 0.91},
                                {0.94, 0.89, 0.26}, {0.0, 0.0, 0.0}};
  const auto& k = c[i % 8];
  cairo_set_source_rgb(cr, k[0], k[1], k[2]);
}

// Viridis control points, as in the single heat map.
void viridis(double t, double rgb[3]) {
  static const double stops[][3] = {
      {68, 1, 84}, {59, 82, 139}, {33, 145, 140}, {94, 201, 98}, {253, 231, 37}};
  t = std::clamp(t, 0.0, 1.0) * 4.0;
  const int k = std::min(3, static_cast<int>(t));
  const double w = t - k;
  for (int i = 0; i < 3; ++i) rgb[i] = ((1 - w) * stops[k][i] + w * stops[k + 1][i]) / 255.0;
}

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", v);
  return buf;
}

// Ticks: 1-2-5 steps on a linear axis, powers of ten (with 2 and 5 if few) on a log axis.
std::vector<double> ticks(double lo, double hi, bool log) {
  std::vector<double> out;
  if (log) {
    for (double p = std::floor(std::log10(lo)); p <= std::ceil(std::log10(hi)); ++p)
      for (double m : {1.0, 2.0, 5.0}) {
        const double v = m * std::pow(10.0, p);
        if (v >= lo * (1 - 1e-9) && v <= hi * (1 + 1e-9)) out.push_back(v);
      }
    if (out.size() > 9) {  // many decades: powers of ten only
      std::vector<double> decades;
      for (double v : out)
        if (std::abs(std::log10(v) - std::round(std::log10(v))) < 1e-9) decades.push_back(v);
      out = decades;
    }
    return out;
  }
  const double raw = (hi - lo) / 5;
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  double step = 10 * p;
  for (double m : {1.0, 2.0, 5.0})
    if (m * p >= raw) {
      step = m * p;
      break;
    }
  for (double v = std::ceil(lo / step) * step; v <= hi + step * 1e-9; v += step)
    out.push_back(std::abs(v) < step * 1e-9 ? 0.0 : v);
  return out;
}

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
std::pair<double, double> range(std::vector<double> v, bool log) {
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

void frame(const Canvas& cv, const ChartLabels& lab, const Axis& x, const Axis& y, int w, int h) {
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

}  // namespace

void write_line_chart(const std::string& path, const ChartLabels& lab,
                      const std::vector<Series>& series) {
  const int w = 980, h = 480;
  Canvas cv(w, h);
  cairo_t* cr = *cv;
  // The ranges cover the points drawn: a failed case (NaN) does not stretch the x axis.
  std::vector<double> xs, ys;
  for (const auto& s : series)
    for (std::size_t i = 0; i < s.x.size() && i < s.y.size(); ++i)
      if (std::isfinite(s.x[i]) && std::isfinite(s.y[i]))
        xs.push_back(s.x[i]), ys.push_back(s.y[i]);
  const auto [xl, xh] = range(xs, lab.log_x);
  const auto [yl, yh] = range(ys, lab.log_y);
  const bool legend = series.size() > 1;
  const Axis x{xl, xh, lab.log_x, 80, legend ? w - 390.0 : w - 30.0};
  const Axis y{yl, yh, lab.log_y, h - 60.0, 40};
  frame(cv, lab, x, y, w, h);
  cairo_rectangle(cr, x.a, y.b, x.b - x.a, y.a - y.b);
  cairo_clip(cr);
  auto usable = [&](double vx, double vy) {
    return std::isfinite(vx) && std::isfinite(vy) && (!lab.log_x || vx > 0) &&
           (!lab.log_y || vy > 0);
  };
  for (std::size_t k = 0; k < series.size(); ++k) {
    const Series& s = series[k];
    palette(cr, k);
    cairo_set_line_width(cr, 2);
    bool open = false;
    for (std::size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
      if (!usable(s.x[i], s.y[i])) {
        open = false;
        continue;
      }
      if (open)
        cairo_line_to(cr, x.map(s.x[i]), y.map(s.y[i]));
      else
        cairo_move_to(cr, x.map(s.x[i]), y.map(s.y[i]));
      open = true;
    }
    cairo_stroke(cr);
    for (std::size_t i = 0; i < s.x.size() && i < s.y.size(); ++i)
      if (usable(s.x[i], s.y[i])) {
        cairo_arc(cr, x.map(s.x[i]), y.map(s.y[i]), 4, 0, 2 * M_PI);
        cairo_fill(cr);
      }
  }
  cairo_reset_clip(cr);
  if (legend)
    for (std::size_t k = 0; k < series.size(); ++k) {
      const double ly = 50 + 22.0 * k;
      palette(cr, k);
      cairo_rectangle(cr, w - 380, ly, 14, 14);
      cairo_fill(cr);
      cairo_set_source_rgb(cr, 0, 0, 0);
      cv.text(w - 360, ly + 7, series[k].name, 0, 0.5);
    }
  cv.write(path);
}

void write_bar_chart(const std::string& path, const ChartLabels& lab,
                     const std::vector<std::pair<std::string, double>>& bars) {
  const int w = std::max(480, 90 + 110 * static_cast<int>(bars.size())), h = 480;
  Canvas cv(w, h);
  cairo_t* cr = *cv;
  double top = 0;
  for (const auto& b : bars)
    if (std::isfinite(b.second)) top = std::max(top, b.second);
  const Axis y{0, top > 0 ? top * 1.15 : 1, false, h - 90.0, 40};
  const Axis x{0, 1, false, 80, w - 20.0};
  // Frame and y ticks only: the x axis carries the bar labels.
  cairo_set_line_width(cr, 1);
  cairo_rectangle(cr, x.a, y.b, x.b - x.a, y.a - y.b);
  cairo_stroke(cr);
  for (double v : ticks(y.lo, y.hi, false)) {
    cairo_set_source_rgb(cr, 0.88, 0.88, 0.88);
    cairo_move_to(cr, x.a, y.map(v)), cairo_line_to(cr, x.b, y.map(v)), cairo_stroke(cr);
    cairo_set_source_rgb(cr, 0, 0, 0);
    cv.text(x.a - 6, y.map(v), number(v), 1, 0.5);
  }
  cv.text(16, (y.a + y.b) / 2, lab.y, 0.5, 0, true);
  cairo_set_font_size(cr, 15);
  cv.text(w / 2.0, 10, lab.title, 0.5, 0);
  cairo_set_font_size(cr, 13);
  const double slot = (x.b - x.a) / std::max<std::size_t>(1, bars.size());
  for (std::size_t k = 0; k < bars.size(); ++k) {
    const double cx = x.a + slot * (k + 0.5);
    cairo_set_source_rgb(cr, 0, 0, 0);
    // A long label shrinks to its slot.
    cairo_text_extents_t e;
    cairo_text_extents(cr, bars[k].first.c_str(), &e);
    cairo_set_font_size(cr, std::min(13.0, 13.0 * slot * 0.95 / std::max(1.0, e.x_advance)));
    cv.text(cx, y.a + 8, bars[k].first, 0.5, 0);
    cairo_set_font_size(cr, 13);
    if (!std::isfinite(bars[k].second)) {
      cv.text(cx, y.a - 20, "failed", 0.5, 0.5);
      continue;
    }
    palette(cr, k);
    const double top_px = y.map(bars[k].second);
    cairo_rectangle(cr, cx - slot * 0.35, top_px, slot * 0.7, y.a - top_px);
    cairo_fill(cr);
    cairo_set_source_rgb(cr, 0, 0, 0);
    cv.text(cx, top_px - 4, number(bars[k].second), 0.5, 1);
  }
  cv.write(path);
}

void write_heatmap_panels(const std::string& path,
                          const std::vector<std::pair<std::string, HeightMap>>& panels) {
  if (panels.empty()) throw std::invalid_argument("no heat maps to draw");
  // Each map about its own mean: the variants' textures compare on one scale even when an
  // effect lifts the whole surface (springback).
  std::vector<double> mean(panels.size(), 0.0);
  double lo = INFINITY, hi = -INFINITY;
  for (std::size_t k = 0; k < panels.size(); ++k) {
    std::size_t n = 0;
    for (double z : panels[k].second.z)
      if (std::isfinite(z)) mean[k] += z, ++n;
    mean[k] /= std::max<std::size_t>(1, n);
    for (double z : panels[k].second.z)
      if (std::isfinite(z))
        lo = std::min(lo, (z - mean[k]) * 1e3), hi = std::max(hi, (z - mean[k]) * 1e3);
  }
  if (!(hi > lo)) hi = lo + 1;
  const int side = 220, gap = 20, top = 40, bar = 130;
  const int w = gap + static_cast<int>(panels.size()) * (side + gap) + bar, h = top + side + 40;
  Canvas cv(w, h);
  cairo_t* cr = *cv;
  for (std::size_t k = 0; k < panels.size(); ++k) {
    const HeightMap& m = panels[k].second;
    const int x0 = gap + static_cast<int>(k) * (side + gap);
    const double cell_w = static_cast<double>(side) / m.grid.nx,
                 cell_h = static_cast<double>(side) / m.grid.ny;
    for (std::size_t j = 0; j < m.grid.ny; ++j)
      for (std::size_t i = 0; i < m.grid.nx; ++i) {
        double rgb[3];
        viridis(((m.at(i, j) - mean[k]) * 1e3 - lo) / (hi - lo), rgb);
        cairo_set_source_rgb(cr, rgb[0], rgb[1], rgb[2]);
        // s grows upwards, as on the single heat map.
        cairo_rectangle(cr, x0 + i * cell_w, top + side - (j + 1) * cell_h, cell_w + 0.5,
                        cell_h + 0.5);
        cairo_fill(cr);
      }
    cairo_set_source_rgb(cr, 0, 0, 0);
    cv.text(x0 + side / 2.0, top - 22, panels[k].first, 0.5, 0);
  }
  const int bx = w - bar + 10;
  for (int py = 0; py < side; ++py) {
    double rgb[3];
    viridis(1.0 - py / double(side - 1), rgb);
    cairo_set_source_rgb(cr, rgb[0], rgb[1], rgb[2]);
    cairo_rectangle(cr, bx, top + py, 16, 1);
    cairo_fill(cr);
  }
  cairo_set_source_rgb(cr, 0, 0, 0);
  cv.text(bx + 20, top, number(hi), 0, 0.5);
  cv.text(bx + 20, top + side, number(lo), 0, 0.5);
  cv.text(bx, top + side + 14, "h - mean (um)", 0, 0);
  cv.write(path);
}

}  // namespace topomill
