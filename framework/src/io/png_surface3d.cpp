#include "io/png_surface3d.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

#include "io/cairo_canvas.hpp"

namespace topomill {

namespace {

// A 1-2-5 number near v (the exaggeration is stated, so it should read plainly).
double round125(double v) {
  const double p = std::pow(10.0, std::floor(std::log10(v)));
  for (double m : {1.0, 2.0, 5.0})
    if (m * p >= v * 0.75) return m * p;
  return 10 * p;
}

struct View {
  double ca, sa, ce, se;  // azimuth and elevation
  double scale = 1, ox = 0, oy = 0;
  // Screen position of (x, y, z) (all in mm, z already exaggerated), and depth (larger: farther).
  void project(double x, double y, double z, double& u, double& v) const {
    const double xr = x * ca - y * sa, yr = x * sa + y * ca;
    u = ox + scale * xr;
    v = oy - scale * (z * ce + yr * se);
  }
  double depth(double x, double y) const { return x * sa + y * ca; }
};

// What the drawing needs of the map: the nodes drawn (every k-th, and the last), heights in um
// about the mean of the finite ones (non-finite nodes drawn at the mean) within [lo, hi], the
// lateral extent in mm, the vertical exaggeration and the view.
struct Drawing {
  const Grid& g;
  const HeightMap& map;
  std::vector<std::size_t> is, js;
  double mean = 0, lo = 0, hi = 0, xw = 0, yw = 0, exaggeration = 1;
  View view{};

  double h_um(std::size_t i, std::size_t j) const {
    const double z = map.at(i, j);
    return std::isfinite(z) ? (z - mean) * 1e3 : 0.0;
  }
  double zed(double um) const { return um * 1e-3 * exaggeration; }  // mm on the drawing
  void line3(cairo_t* cr, double x0, double y0, double z0, double x1, double y1, double z1) const {
    double u0, v0, u1, v1;
    view.project(x0, y0, z0, u0, v0);
    view.project(x1, y1, z1, u1, v1);
    cairo_move_to(cr, u0, v0), cairo_line_to(cr, u1, v1), cairo_stroke(cr);
  }
  void cells(cairo_t* cr) const;
  void wall(cairo_t* cr, bool along_x) const;
  void axes(Canvas& cv, const std::string& x_label, const std::string& y_label) const;
};

void Drawing::cells(cairo_t* cr) const {
  // Cells from the farthest to the nearest (painter's order), each lit from the upper left.
  struct Cell {
    std::size_t a, b;
    double depth;
  };
  std::vector<Cell> cells;
  for (std::size_t b = 0; b + 1 < js.size(); ++b)
    for (std::size_t a = 0; a + 1 < is.size(); ++a) {
      const double cx = 0.5 * (is[a] + is[a + 1]) * g.dx, cy = 0.5 * (js[b] + js[b + 1]) * g.dy;
      cells.push_back({a, b, view.depth(cx, cy)});
    }
  std::sort(cells.begin(), cells.end(),
            [](const Cell& p, const Cell& q) { return p.depth > q.depth; });
  const double lx = -0.45, ly = -0.35, lz = 0.82;  // towards the light, unit length
  for (const Cell& c : cells) {
    const std::size_t i0 = is[c.a], i1 = is[c.a + 1], j0 = js[c.b], j1 = js[c.b + 1];
    const double x0 = i0 * g.dx, x1 = i1 * g.dx, y0 = j0 * g.dy, y1 = j1 * g.dy;
    const double z00 = h_um(i0, j0), z10 = h_um(i1, j0), z11 = h_um(i1, j1), z01 = h_um(i0, j1);
    // The normal of the drawn (exaggerated) surface.
    const double gx = zed(0.5 * (z10 + z11 - z00 - z01)) / (x1 - x0),
                 gy = zed(0.5 * (z01 + z11 - z00 - z10)) / (y1 - y0);
    const double nn = std::sqrt(gx * gx + gy * gy + 1);
    const double lit = std::max(0.0, (-gx * lx - gy * ly + lz) / nn);
    double rgb[3];
    viridis((0.25 * (z00 + z10 + z11 + z01) - lo) / (hi - lo), rgb);
    const double shade = 0.35 + 0.65 * lit;
    cairo_set_source_rgb(cr, rgb[0] * shade, rgb[1] * shade, rgb[2] * shade);
    double u, v;
    view.project(x0, y0, zed(z00), u, v), cairo_move_to(cr, u, v);
    view.project(x1, y0, zed(z10), u, v), cairo_line_to(cr, u, v);
    view.project(x1, y1, zed(z11), u, v), cairo_line_to(cr, u, v);
    view.project(x0, y1, zed(z01), u, v), cairo_line_to(cr, u, v);
    cairo_close_path(cr);
    // Filled and outlined in its own colour: neighbours meet without light seams.
    cairo_fill_preserve(cr);
    cairo_set_line_width(cr, 0.7);
    cairo_stroke(cr);
  }
}

// A near side wall (y = 0 along x, else x = 0) from the surface's edge down to the base, in grey:
// the block reads as a solid.
void Drawing::wall(cairo_t* cr, bool along_x) const {
  const auto& idx = along_x ? is : js;
  double u, v;
  cairo_new_path(cr);
  for (std::size_t a = 0; a < idx.size(); ++a) {
    const std::size_t i = along_x ? idx[a] : 0, j = along_x ? 0 : idx[a];
    view.project(i * g.dx, j * g.dy, zed(h_um(i, j)), u, v);
    a == 0 ? cairo_move_to(cr, u, v) : cairo_line_to(cr, u, v);
  }
  view.project(along_x ? xw : 0, along_x ? 0 : yw, zed(lo), u, v), cairo_line_to(cr, u, v);
  view.project(0, 0, zed(lo), u, v), cairo_line_to(cr, u, v);
  cairo_close_path(cr);
  cairo_set_source_rgb(cr, along_x ? 0.80 : 0.70, along_x ? 0.80 : 0.70, along_x ? 0.80 : 0.70);
  cairo_fill_preserve(cr);
  cairo_set_source_rgb(cr, 0.35, 0.35, 0.35);
  cairo_set_line_width(cr, 0.8);
  cairo_stroke(cr);
}

// The front base edges with ticks: x along y = 0, s along x = 0; the height axis at the back-left
// corner.
void Drawing::axes(Canvas& cv, const std::string& x_label, const std::string& y_label) const {
  cairo_t* cr = *cv;
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_set_line_width(cr, 1);
  for (double t : ticks(g.x0, g.x0 + xw, false)) {
    double u, v;
    view.project(t - g.x0, 0, zed(lo), u, v);
    cairo_move_to(cr, u, v), cairo_line_to(cr, u, v + 5), cairo_stroke(cr);
    cv.text(u, v + 8, number(t), 0.5, 0);
  }
  for (double t : ticks(g.y0, g.y0 + yw, false)) {
    double u, v;
    view.project(0, t - g.y0, zed(lo), u, v);
    cairo_move_to(cr, u, v), cairo_line_to(cr, u - 5, v), cairo_stroke(cr);
    cv.text(u - 8, v + 2, number(t), 1, 0);
  }
  {
    double u, v;
    view.project(xw / 2, 0, zed(lo), u, v);
    cv.text(u + 10, v + 30, x_label, 0, 0);
    view.project(0, yw / 2, zed(lo), u, v);
    cv.text(u - 60, v + 30, y_label, 1, 0);
  }
  for (double t : ticks(lo, hi, false, 2)) {  // a short axis: 2 to 5 ticks
    double u, v;
    view.project(0, yw, zed(t), u, v);
    cairo_move_to(cr, u - 5, v), cairo_line_to(cr, u, v), cairo_stroke(cr);
    cv.text(u - 8, v, number(t), 1, 0.5);
  }
  {
    double u, v;
    view.project(0, yw, zed(hi), u, v);
    cv.text(u, v - 12, "h (µm)", 0.5, 1);
  }
}

}  // namespace

void write_png_surface3d(const std::string& path, const HeightMap& map, const std::string& title,
                         const std::string& x_label, const std::string& y_label) {
  const Grid& g = map.grid;
  Drawing d{g, map, {}, {}};
  const std::size_t k = std::max<std::size_t>(1, (std::max(g.nx, g.ny) + 159) / 160);
  for (std::size_t i = 0; i < g.nx; i += k) d.is.push_back(i);
  for (std::size_t j = 0; j < g.ny; j += k) d.js.push_back(j);
  if (d.is.back() != g.nx - 1) d.is.push_back(g.nx - 1);
  if (d.js.back() != g.ny - 1) d.js.push_back(g.ny - 1);
  double sum = 0, n = 0, lo = INFINITY, hi = -INFINITY;
  for (double z : map.z)
    if (std::isfinite(z)) sum += z, n += 1, lo = std::min(lo, z), hi = std::max(hi, z);
  d.mean = n > 0 ? sum / n : 0;
  lo = n > 0 ? (lo - d.mean) * 1e3 : -0.5, hi = n > 0 ? (hi - d.mean) * 1e3 : 0.5;
  if (!(hi > lo)) lo -= 0.5, hi += 0.5;
  d.lo = lo, d.hi = hi;
  // Lateral extent in mm; the height range shown as about a fifth of it.
  const double xw = std::max(1e-12, (g.nx - 1) * g.dx), yw = std::max(1e-12, (g.ny - 1) * g.dy);
  d.xw = xw, d.yw = yw;
  d.exaggeration = round125(0.2 * std::max(xw, yw) / ((hi - lo) * 1e-3));

  const double az = 35 * M_PI / 180, el = 30 * M_PI / 180;
  View& view = d.view;
  view = View{std::cos(az), std::sin(az), std::cos(el), std::sin(el)};
  // Fit the box (base at lo, top at hi) into the drawing area.
  const int w = 900, h = 620;
  const double left = 70, top = 70, area_w = 640, area_h = 480;
  double umin = INFINITY, umax = -INFINITY, vmin = INFINITY, vmax = -INFINITY;
  for (double x : {0.0, xw})
    for (double y : {0.0, yw})
      for (double z : {d.zed(lo), d.zed(hi)}) {
        double u, v;
        view.project(x, y, z, u, v);
        umin = std::min(umin, u), umax = std::max(umax, u), vmin = std::min(vmin, v),
        vmax = std::max(vmax, v);
      }
  view.scale = std::min(area_w / (umax - umin), area_h / (vmax - vmin));
  view.ox = left + (area_w - view.scale * (umax - umin)) / 2 - view.scale * umin;
  view.oy = top + (area_h - view.scale * (vmax - vmin)) / 2 - view.scale * vmin;

  Canvas cv(w, h);
  cairo_t* cr = *cv;
  // The base's back edges first (the surface hides what is behind it).
  cairo_set_line_width(cr, 1);
  cairo_set_source_rgb(cr, 0.6, 0.6, 0.6);
  d.line3(cr, 0, yw, d.zed(lo), xw, yw, d.zed(lo));
  d.line3(cr, xw, 0, d.zed(lo), xw, yw, d.zed(lo));
  d.line3(cr, 0, yw, d.zed(lo), 0, yw, d.zed(hi));
  d.cells(cr);
  d.wall(cr, true), d.wall(cr, false);
  d.axes(cv, x_label, y_label);
  colour_bar(cv, w - 110, top + 40, 18, 300, lo, hi, "h - mean (µm)");
  cairo_set_font_size(cr, 15);
  cv.text(w / 2.0, 14, title, 0.5, 0);
  cairo_set_font_size(cr, 13);
  char note[96];
  std::snprintf(note, sizeof note, "vertical exaggeration %g : 1 (heights in µm, lateral in mm)",
                d.exaggeration);
  cv.text(w / 2.0, 38, note, 0.5, 0);
  cv.write(path);
}

}  // namespace topomill
