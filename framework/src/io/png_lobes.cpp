#include "io/png_lobes.hpp"

#include <algorithm>
#include <cmath>

#include "io/chart_axes.hpp"

namespace topomill {

namespace {

constexpr int kWidth = 980, kHeight = 520;
constexpr double kHeadroom = 1.25;  // the depth axis above the highest boundary shown

void set_rgb(cairo_t* cr, const double (&c)[3]) {
  cairo_set_source_rgb(cr, c[0], c[1], c[2]);
}
constexpr double kStableFill[3] = {0.86, 0.95, 0.86}, kUnstableFill[3] = {0.98, 0.85, 0.84};
constexpr double kHopf[3] = {0.0, 0.45, 0.70}, kFlip[3] = {0.84, 0.37, 0.0};

}  // namespace

void write_lobes_chart(const std::string& path, const LobeCurve& c) {
  Canvas cv(kWidth, kHeight);
  cairo_t* cr = *cv;
  double top = c.operating_depth;
  for (double d : c.depth)
    if (std::isfinite(d)) top = std::max(top, d);
  top = std::min(c.depth_max, top * kHeadroom);
  if (!(top > 0)) top = c.depth_max;
  const Axis x{c.rpm.front(), c.rpm.back(), false, 80, kWidth - 170.0};
  const Axis y{0, top, false, kHeight - 60.0, 40};
  // Stable below the boundary (a speed stable to depth_max: the whole column), unstable above.
  set_rgb(cr, kUnstableFill);
  cairo_rectangle(cr, x.a, y.b, x.b - x.a, y.a - y.b);
  cairo_fill(cr);
  auto depth_px = [&](std::size_t i) {
    return y.map(std::isfinite(c.depth[i]) ? std::min(c.depth[i], top) : top);
  };
  set_rgb(cr, kStableFill);
  cairo_move_to(cr, x.map(c.rpm.front()), y.a);
  for (std::size_t i = 0; i < c.rpm.size(); ++i) cairo_line_to(cr, x.map(c.rpm[i]), depth_px(i));
  cairo_line_to(cr, x.map(c.rpm.back()), y.a);
  cairo_close_path(cr);
  cairo_fill(cr);
  ChartLabels lab;
  lab.title = c.title, lab.x = "spindle speed (rpm)", lab.y = "critical axial depth (mm)";
  draw_frame(cv, lab, x, y, kWidth, kHeight);
  // The boundary, each piece between two speeds coloured by its upper end's kind.
  cairo_save(cr);
  cairo_rectangle(cr, x.a, y.b, x.b - x.a, y.a - y.b);
  cairo_clip(cr);
  cairo_set_line_width(cr, 2.2);
  for (std::size_t i = 1; i < c.rpm.size(); ++i) {
    if (!std::isfinite(c.depth[i - 1]) || !std::isfinite(c.depth[i])) continue;
    set_rgb(cr, c.flip[i] && c.flip[i - 1] ? kFlip : kHopf);
    cairo_move_to(cr, x.map(c.rpm[i - 1]), depth_px(i - 1));
    cairo_line_to(cr, x.map(c.rpm[i]), depth_px(i));
    cairo_stroke(cr);
  }
  // The operating point.
  const double ox = x.map(c.operating_rpm), oy = y.map(std::min(c.operating_depth, top));
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_set_line_width(cr, 2.5);
  cairo_move_to(cr, ox - 7, oy - 7), cairo_line_to(cr, ox + 7, oy + 7);
  cairo_move_to(cr, ox - 7, oy + 7), cairo_line_to(cr, ox + 7, oy - 7);
  cairo_stroke(cr);
  cairo_restore(cr);
  cv.text(ox + 10, oy - 4, c.operating_stable ? "scene: stable" : "scene: unstable", 0, 1);
  // Legend.
  const double lx = kWidth - 160.0;
  struct Key {
    const double (*rgb)[3];
    const char* name;
    bool fill;
  };
  const Key keys[] = {{&kHopf, "Hopf boundary", false},
                      {&kFlip, "flip boundary", false},
                      {&kUnstableFill, "unstable", true},
                      {&kStableFill, "stable", true}};
  for (std::size_t k = 0; k < 4; ++k) {
    const double ly = 60 + 24.0 * k;
    set_rgb(cr, *keys[k].rgb);
    if (keys[k].fill) {
      cairo_rectangle(cr, lx, ly - 7, 22, 14);
      cairo_fill(cr);
    } else {
      cairo_set_line_width(cr, 2.2);
      cairo_move_to(cr, lx, ly), cairo_line_to(cr, lx + 22, ly);
      cairo_stroke(cr);
    }
    cairo_set_source_rgb(cr, 0, 0, 0);
    cv.text(lx + 30, ly, keys[k].name, 0, 0.5);
  }
  cv.write(path);
}

}  // namespace topomill
