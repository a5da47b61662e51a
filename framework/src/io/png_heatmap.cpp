#include "io/png_heatmap.hpp"

#include <algorithm>
#include <cmath>

#include "io/cairo_canvas.hpp"

namespace topomill {

void write_png_heatmap(const std::string& path, const HeightMap& map, const HeatmapLabels& labels) {
  const Grid& g = map.grid;
  double lo = INFINITY, hi = -INFINITY;
  for (double z : map.z)
    if (std::isfinite(z)) lo = std::min(lo, z * 1e3), hi = std::max(hi, z * 1e3);
  if (!(hi > lo)) lo = std::isfinite(lo) ? lo - 0.5 : 0, hi = lo + 1;
  // The field keeps its aspect: the longer side 600 px.
  const double xw = std::max(1e-12, (g.nx - 1) * g.dx), yw = std::max(1e-12, (g.ny - 1) * g.dy);
  const double side = 600, pw = xw >= yw ? side : side * xw / yw,
               ph = xw >= yw ? side * yw / xw : side;
  const double left = 80, top = 56, right = 130, bottom = 60;
  Canvas cv(static_cast<int>(left + pw + right), static_cast<int>(top + ph + bottom));
  cairo_t* cr = *cv;
  draw_map(cv, map, 0.0, lo, hi, left, top, pw, ph);
  cv.text(left + pw / 2, top + ph + 30, labels.x, 0.5, 0);
  cv.text(18, top + ph / 2, labels.y, 0.5, 0, true);
  colour_bar(cv, left + pw + 24, top, 18, ph, lo, hi, labels.z);
  cairo_set_font_size(cr, 15);
  cv.text(left + pw / 2, 14, labels.title, 0.5, 0);
  cv.write(path);
}

}  // namespace topomill
