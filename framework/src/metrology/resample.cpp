#include "metrology/resample.hpp"

#include <cmath>

namespace topomill {

namespace {
// Keys (1981) cubic convolution weights for the nodes at offsets -1, 0, 1, 2 from the point's
// cell start, t in [0, 1).
void keys_weights(double t, double w[4]) {
  const double t2 = t * t, t3 = t2 * t;
  w[0] = -0.5 * t3 + t2 - 0.5 * t;
  w[1] = 1.5 * t3 - 2.5 * t2 + 1;
  w[2] = -1.5 * t3 + 2 * t2 + 0.5 * t;
  w[3] = 0.5 * t3 - 0.5 * t2;
}
}  // namespace

std::optional<double> CubicSampler::at(double x, double y) const {
  const Grid& g = s_.map.grid;
  if (g.nx < 3 || g.ny < 3) return std::nullopt;
  const double u = (x - g.x0) / g.dx, v = (y - g.y0) / g.dy;
  const auto nx = static_cast<std::ptrdiff_t>(g.nx), ny = static_cast<std::ptrdiff_t>(g.ny);
  if (!(u >= 0 && v >= 0 && u <= static_cast<double>(nx - 1) && v <= static_cast<double>(ny - 1)))
    return std::nullopt;
  // The cell (i, j) holding the point; the last node's point uses the cell before it.
  const auto i = std::min(static_cast<std::ptrdiff_t>(u), nx - 2);
  const auto j = std::min(static_cast<std::ptrdiff_t>(v), ny - 2);
  double wx[4], wy[4];
  keys_weights(u - static_cast<double>(i), wx);
  keys_weights(v - static_cast<double>(j), wy);
  bool ok = true;
  // Node k of row jj, with Keys' end condition beyond the map: f(-1) = 3 f(0) - 3 f(1) + f(2).
  auto node = [&](std::ptrdiff_t k, std::ptrdiff_t jj) {
    auto at = [&](std::ptrdiff_t kk) {
      const std::size_t idx = g.index(static_cast<std::size_t>(kk), static_cast<std::size_t>(jj));
      ok = ok && s_.is_valid(idx);
      return s_.map.z[idx];
    };
    if (k < 0) return 3 * at(0) - 3 * at(1) + at(2);
    if (k >= nx) return 3 * at(nx - 1) - 3 * at(nx - 2) + at(nx - 3);
    return at(k);
  };
  auto row = [&](std::ptrdiff_t jj) {
    double r = 0;
    for (int a = 0; a < 4; ++a) r += wx[a] * node(i - 1 + a, jj);
    return r;
  };
  auto row_at = [&](std::ptrdiff_t jj) {
    if (jj < 0) return 3 * row(0) - 3 * row(1) + row(2);
    if (jj >= ny) return 3 * row(ny - 1) - 3 * row(ny - 2) + row(ny - 3);
    return row(jj);
  };
  double sum = 0;
  for (int b = 0; b < 4; ++b) sum += wy[b] * row_at(j - 1 + b);
  if (!ok) return std::nullopt;
  return sum;
}

Surface resample(const Surface& surface, const Grid& grid,
                 const std::function<std::pair<double, double>(double, double)>& where) {
  Surface out;
  out.source = surface.source;
  out.map = HeightMap(grid);
  out.valid.assign(grid.size(), 0);
  const CubicSampler sample(surface);
  for (std::size_t j = 0; j < grid.ny; ++j)
    for (std::size_t i = 0; i < grid.nx; ++i) {
      const auto [x, y] =
          where ? where(grid.x(i), grid.y(j)) : std::pair<double, double>{grid.x(i), grid.y(j)};
      if (const auto z = sample.at(x, y)) {
        out.map.at(i, j) = *z;
        out.valid[grid.index(i, j)] = 1;
      }
    }
  return out;
}

}  // namespace topomill
