#include "metrology/resample.hpp"

#include <cmath>

namespace topomill {

namespace {
// Keys (1981) cubic convolution weights for the nodes at offsets -1, 0, 1, 2 from the point's
// cell start, t in [0, 1].
void keys_weights(double t, double w[4]) {
  const double t2 = t * t, t3 = t2 * t;
  w[0] = -0.5 * t3 + t2 - 0.5 * t;
  w[1] = 1.5 * t3 - 2.5 * t2 + 1;
  w[2] = -1.5 * t3 + 2 * t2 + 0.5 * t;
  w[3] = 0.5 * t3 - 0.5 * t2;
}

// One cubic convolution over four values f at offsets -1, 0, 1, 2, of which `ok` says which are
// given. The two inner ones must be where their weight is not zero. An outer one that is not given
// (beyond the map's edge or a missing point, alike) is Keys' end condition from the other three,
// f(-1) = 3 f(0) - 3 f(1) + f(2), or, both outer ones missing, the line through the inner two:
// either keeps the interpolant exact for the polynomials the remaining values determine. Terms of
// weight zero are left out, so a missing value never enters as 0 x NaN.
std::optional<double> convolve(const double f_in[4], const bool ok[4], const double w[4]) {
  if ((w[1] != 0 && !ok[1]) || (w[2] != 0 && !ok[2])) return std::nullopt;
  double f[4] = {f_in[0], f_in[1], f_in[2], f_in[3]};
  // Outer weights are not zero only inside the cell (0 < t < 1), where the inner two are given.
  const bool outer_needed = w[0] != 0 || w[3] != 0;
  if (outer_needed && !ok[0] && !ok[3]) {
    f[0] = 2 * f[1] - f[2];
    f[3] = 2 * f[2] - f[1];
  } else if (outer_needed && !ok[0]) {
    f[0] = 3 * f[1] - 3 * f[2] + f[3];
  } else if (outer_needed && !ok[3]) {
    f[3] = 3 * f[2] - 3 * f[1] + f[0];
  }
  double sum = 0;
  for (int a = 0; a < 4; ++a)
    if (w[a] != 0) sum += w[a] * f[a];
  return sum;
}

// A point this share of a cell beyond the first or last node is taken as on it: a node's position
// computed another way (a registered frame's sines and cosines, x0 + i dx against a spacing with
// no exact binary form) lands some ulps off, and an edge node must not be dropped for that. A
// millionth of a cell moves the height by at most the slope times that.
constexpr double kEdgeRoundOff = 1e-6;

// The point's place in cells along one axis, snapped onto the end nodes within round-off; NaN
// outside.
double cell_place(double x, double x0, double d, std::size_t n) {
  const double u = (x - x0) / d, last = static_cast<double>(n - 1);
  if (u < 0 && u >= -kEdgeRoundOff) return 0.0;
  if (u > last && u <= last + kEdgeRoundOff) return last;
  return u >= 0 && u <= last ? u : NAN;
}
}  // namespace

std::optional<double> CubicSampler::at(double x, double y) const {
  const Grid& g = s_.map.grid;
  if (g.nx < 3 || g.ny < 3) return std::nullopt;
  const double u = cell_place(x, g.x0, g.dx, g.nx), v = cell_place(y, g.y0, g.dy, g.ny);
  const auto nx = static_cast<std::ptrdiff_t>(g.nx), ny = static_cast<std::ptrdiff_t>(g.ny);
  if (std::isnan(u) || std::isnan(v)) return std::nullopt;
  // The cell (i, j) holding the point; the last node's point uses the cell before it.
  const auto i = std::min(static_cast<std::ptrdiff_t>(u), nx - 2);
  const auto j = std::min(static_cast<std::ptrdiff_t>(v), ny - 2);
  double wx[4], wy[4];
  keys_weights(u - static_cast<double>(i), wx);
  keys_weights(v - static_cast<double>(j), wy);
  // Each of the four rows interpolated along x; a row beyond the map or without its inner
  // values is missing, and the column of rows is completed as a row's values are.
  double rows[4] = {0, 0, 0, 0};
  bool rows_ok[4] = {false, false, false, false};
  for (int b = 0; b < 4; ++b) {
    const std::ptrdiff_t jj = j - 1 + b;
    if (wy[b] == 0 || jj < 0 || jj >= ny) continue;
    double f[4] = {0, 0, 0, 0};
    bool ok[4] = {false, false, false, false};
    for (int a = 0; a < 4; ++a) {
      const std::ptrdiff_t kk = i - 1 + a;
      if (wx[a] == 0 || kk < 0 || kk >= nx) continue;
      const std::size_t idx = g.index(static_cast<std::size_t>(kk), static_cast<std::size_t>(jj));
      ok[a] = s_.is_valid(idx);
      if (ok[a]) f[a] = s_.map.z[idx];
    }
    if (const auto r = convolve(f, ok, wx)) rows[b] = *r, rows_ok[b] = true;
  }
  return convolve(rows, rows_ok, wy);
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
