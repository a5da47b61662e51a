#include "form_removal.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace topomill {

HeightMap unroll_residual(const HeightMap& raw, const SurfaceShape& surface, double depth,
                          double s_lo, double s_hi, double spacing) {
  const Grid& g = raw.grid;
  Grid out_grid = g;
  out_grid.ny = static_cast<std::size_t>(std::llround((s_hi - s_lo) / spacing)) + 1;
  out_grid.dy = (s_hi - s_lo) / static_cast<double>(out_grid.ny - 1);
  out_grid.y0 = s_lo;
  HeightMap out(out_grid);

  std::vector<double> s(g.ny), h(g.ny);
  for (std::size_t i = 0; i < g.nx; ++i) {
    for (std::size_t j = 0; j < g.ny; ++j) {
      const double y = g.y(j), z = raw.at(i, j);
      s[j] = surface.arc_coordinate(y, z);  // where the normal through the point meets the surface
      h[j] = surface.normal_residual(y, z, depth);
    }
    std::size_t j = 0;
    for (std::size_t k = 0; k < out_grid.ny; ++k) {
      const double sk = out_grid.y(k);
      while (j + 2 < g.ny && s[j + 1] < sk) ++j;
      const double w = std::clamp((sk - s[j]) / (s[j + 1] - s[j]), 0.0, 1.0);
      out.at(i, k) = (1 - w) * h[j] + w * h[j + 1];
    }
  }
  return out;
}

}  // namespace topomill
