#include "io/png_chart.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <stdexcept>

#include "io/cairo_canvas.hpp"
#include "io/chart_axes.hpp"

namespace topomill {

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
  for (const auto& [name, v] : lab.marks_x)
    if (std::isfinite(v)) xs.push_back(v);
  const auto [xl, xh] = data_range(xs, lab.log_x);
  const auto [yl, yh] = data_range(ys, lab.log_y);
  const bool legend = !series.empty();
  // The legend as wide as its longest name (the plot takes the rest).
  double names = 0;
  for (const auto& s : series) {
    cairo_text_extents_t e;
    cairo_text_extents(cr, s.name.c_str(), &e);
    names = std::max(names, e.x_advance);
  }
  const double key = w - std::min(names + 56.0, w / 2.0);  // where the legend starts
  const Axis x{xl, xh, lab.log_x, 80, legend ? key - 20.0 : w - 30.0};
  const Axis y{yl, yh, lab.log_y, h - 60.0, 40};
  draw_frame(cv, lab, x, y, w, h);
  cairo_rectangle(cr, x.a, y.b, x.b - x.a, y.a - y.b);
  cairo_clip(cr);
  for (const auto& [name, v] : lab.marks_x) {
    if (!std::isfinite(v) || (lab.log_x && v <= 0)) continue;
    const double dash[] = {6, 4};
    cairo_set_source_rgb(cr, 0.3, 0.3, 0.3);
    cairo_set_line_width(cr, 1.2);
    cairo_set_dash(cr, dash, 2, 0);
    cairo_move_to(cr, x.map(v), y.a), cairo_line_to(cr, x.map(v), y.b), cairo_stroke(cr);
    cairo_set_dash(cr, nullptr, 0, 0);
    cv.text(x.map(v) + 4, y.a - 8, name, 0, 1);  // at the foot: the data crowd the top
  }
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
      cairo_rectangle(cr, key, ly, 14, 14);
      cairo_fill(cr);
      cairo_set_source_rgb(cr, 0, 0, 0);
      cv.text(key + 20, ly + 7, series[k].name, 0, 0.5);
    }
  cv.write(path);
}

void write_bar_chart(const std::string& path, const ChartLabels& lab,
                     const std::vector<std::string>& series,
                     const std::vector<std::pair<std::string, std::vector<double>>>& groups) {
  const std::size_t per = std::max<std::size_t>(1, series.size());
  const int w = std::max(560, 230 + static_cast<int>(groups.size() * (40 + 46 * per))), h = 500;
  Canvas cv(w, h);
  cairo_t* cr = *cv;
  double top = 0;
  for (const auto& g : groups)
    for (double v : g.second)
      if (std::isfinite(v)) top = std::max(top, v);
  const Axis y{0, top > 0 ? top * 1.15 : 1, false, h - 90.0, 40};
  const Axis x{0, 1, false, 80, w - 150.0};
  // Frame and y ticks only: the x axis carries the group labels.
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
  const double slot = (x.b - x.a) / std::max<std::size_t>(1, groups.size());
  const double bar = slot * 0.8 / per;
  for (std::size_t k = 0; k < groups.size(); ++k) {
    const double cx = x.a + slot * (k + 0.5);
    cairo_set_source_rgb(cr, 0, 0, 0);
    // A long label shrinks to its slot.
    cairo_text_extents_t e;
    cairo_text_extents(cr, groups[k].first.c_str(), &e);
    cairo_set_font_size(cr, std::min(13.0, 13.0 * slot * 0.95 / std::max(1.0, e.x_advance)));
    cv.text(cx, y.a + 8, groups[k].first, 0.5, 0);
    cairo_set_font_size(cr, 11);
    for (std::size_t s = 0; s < groups[k].second.size() && s < per; ++s) {
      const double v = groups[k].second[s], bx = cx - slot * 0.4 + bar * s;
      if (!std::isfinite(v)) {
        cairo_set_source_rgb(cr, 0, 0, 0);
        cv.text(bx + bar / 2, y.a - 20, "failed", 0.5, 0.5, true);
        continue;
      }
      palette(cr, s);
      const double top_px = y.map(v);
      cairo_rectangle(cr, bx + 1, top_px, bar - 2, y.a - top_px);
      cairo_fill(cr);
      cairo_set_source_rgb(cr, 0, 0, 0);
      cv.text(bx + bar / 2, top_px - 4, number(v), 0.5, 1);
    }
    cairo_set_font_size(cr, 13);
  }
  for (std::size_t s = 0; s < series.size(); ++s) {
    const double ly = 50 + 22.0 * s;
    palette(cr, s);
    cairo_rectangle(cr, w - 135, ly, 14, 14);
    cairo_fill(cr);
    cairo_set_source_rgb(cr, 0, 0, 0);
    cv.text(w - 115, ly + 7, series[s], 0, 0.5);
  }
  cv.write(path);
}

void write_heatmap_panels(const std::string& path,
                          const std::vector<std::pair<std::string, HeightMap>>& panels,
                          const std::string& x_label, const std::string& y_label) {
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
  if (!(hi > lo)) lo = std::isfinite(lo) ? lo - 0.5 : -0.5, hi = lo + 1;
  const int side = 240, gap = 70, left = 70, top = 50, bar = 150;
  const int w = left + static_cast<int>(panels.size()) * (side + gap) - gap + bar,
            h = top + side + 70;
  Canvas cv(w, h);
  for (std::size_t k = 0; k < panels.size(); ++k) {
    const HeightMap& m = panels[k].second;
    const double px0 = left + static_cast<double>(k) * (side + gap);
    draw_map(cv, m, mean[k], lo, hi, px0, top, side, side);
    cv.text(px0 + side / 2.0, top + side + 26, x_label, 0.5, 0);
    cv.text(px0 + side / 2.0, top - 12, panels[k].first, 0.5, 1);
  }
  cv.text(14, top + side / 2.0, y_label, 0.5, 0, true);
  colour_bar(cv, w - bar + 20, top, 18, side, lo, hi, "h - mean (µm)");
  cv.write(path);
}

}  // namespace topomill
