#include "metrology/autocorrelation.hpp"

#include <algorithm>
#include <cmath>
#include <complex>

#include "metrology/fft.hpp"

namespace topomill {

namespace {
// Sum over x of f(x) f(x + lag) for every lag, by FFT over a zero-padded px x py field: the lag
// (a, b) at ((a + px) % px, (b + py) % py).
std::vector<double> correlate(const std::vector<double>& field, std::size_t px, std::size_t py) {
  auto spectrum = fft_forward(field, px, py);
  for (auto& c : spectrum) c = std::norm(c);
  auto sums = fft_inverse(spectrum, px, py);
  const double n = static_cast<double>(px * py);  // FFTW's round trip multiplies by it
  for (double& s : sums) s /= n;
  return sums;
}
}  // namespace

Autocorrelation::Autocorrelation(const Surface& surface) {
  const Grid& g = surface.map.grid;
  dx_ = g.dx, dy_ = g.dy;
  hx_ = static_cast<std::ptrdiff_t>(g.nx / 2), hy_ = static_cast<std::ptrdiff_t>(g.ny / 2);
  if (surface.valid_count() < 2) return;
  const double mean = surface.mean();
  // Padding beyond the largest lag kept: no lag of interest wraps onto another.
  const std::size_t px = fft_size(g.nx + static_cast<std::size_t>(hx_) + 1);
  const std::size_t py = fft_size(g.ny + static_cast<std::size_t>(hy_) + 1);
  std::vector<double> z(px * py, 0.0), m;
  for (std::size_t j = 0; j < g.ny; ++j)
    for (std::size_t i = 0; i < g.nx; ++i)
      if (surface.is_valid(g.index(i, j))) z[j * px + i] = surface.map.at(i, j) - mean;
  const std::vector<double> sums = correlate(z, px, py);
  // The pairs at each lag: (nx - |a|)(ny - |b|) when every node is valid, else by FFT of the mask.
  std::vector<double> pairs;
  if (!surface.valid.empty()) {
    m.assign(px * py, 0.0);
    for (std::size_t j = 0; j < g.ny; ++j)
      for (std::size_t i = 0; i < g.nx; ++i) m[j * px + i] = surface.is_valid(g.index(i, j));
    pairs = correlate(m, px, py);
  }
  auto wrap = [](std::ptrdiff_t a, std::size_t p) {
    return static_cast<std::size_t>(a < 0 ? a + static_cast<std::ptrdiff_t>(p) : a);
  };
  const std::size_t w = static_cast<std::size_t>(2 * hx_ + 1);
  acf_.assign(w * static_cast<std::size_t>(2 * hy_ + 1), 0.0);
  for (std::ptrdiff_t b = -hy_; b <= hy_; ++b)
    for (std::ptrdiff_t a = -hx_; a <= hx_; ++a) {
      const std::size_t k = wrap(b, py) * px + wrap(a, px);
      const double n =
          pairs.empty() ? static_cast<double>(static_cast<std::ptrdiff_t>(g.nx) - std::abs(a)) *
                              static_cast<double>(static_cast<std::ptrdiff_t>(g.ny) - std::abs(b))
                        : std::round(pairs[k]);  // counts, to FFT round-off
      acf_[static_cast<std::size_t>(b + hy_) * w + static_cast<std::size_t>(a + hx_)] =
          n >= 1 ? sums[k] / n : 0.0;
    }
  const double zero = acf_[static_cast<std::size_t>(hy_) * w + static_cast<std::size_t>(hx_)];
  // A surface whose heights differ by round-off only has no shape to correlate.
  if (!(zero > 1e-30 * (1 + mean * mean))) return;
  for (double& v : acf_) v /= zero;
  defined_ = true;
}

double Autocorrelation::lag(std::ptrdiff_t a, std::ptrdiff_t b) const {
  return acf_[static_cast<std::size_t>(b + hy_) * static_cast<std::size_t>(2 * hx_ + 1) +
              static_cast<std::size_t>(a + hx_)];
}

double Autocorrelation::at(double tx, double ty) const {
  double u = tx / dx_, v = ty / dy_;
  // The last lag itself, reached by steps whose rounding lands an ulp beyond it, is still in.
  constexpr double kEdge = 1e-9;
  const double ex = static_cast<double>(hx_), ey = static_cast<double>(hy_);
  if (!(std::abs(u) <= ex + kEdge && std::abs(v) <= ey + kEdge)) return 0.0;
  u = std::clamp(u, -ex, ex), v = std::clamp(v, -ey, ey);
  if (hx_ == 0 || hy_ == 0) return lag(0, 0);  // a single row or column: no lag grid
  auto a = static_cast<std::ptrdiff_t>(std::floor(u)),
       b = static_cast<std::ptrdiff_t>(std::floor(v));
  a = std::min(a, hx_ - 1), b = std::min(b, hy_ - 1);  // the last lag: the piece before it
  const double s = u - static_cast<double>(a), t = v - static_cast<double>(b);
  return (1 - t) * ((1 - s) * lag(a, b) + s * lag(a + 1, b)) +
         t * ((1 - s) * lag(a, b + 1) + s * lag(a + 1, b + 1));
}

double Autocorrelation::decay_length(double theta, double s) const {
  if (!defined_) return INFINITY;
  const double c = std::cos(theta), sn = std::sin(theta), step = 0.25 * std::min(dx_, dy_);
  const double reach = std::min(std::abs(c) > 1e-12 ? max_lag_x() / std::abs(c) : INFINITY,
                                std::abs(sn) > 1e-12 ? max_lag_y() / std::abs(sn) : INFINITY);
  double prev = 1.0;
  for (double r = step; r <= reach; r += step) {
    const double f = at(r * c, r * sn);
    if (f <= s) return r - step * (f - s) / (f - prev);  // linear between the two steps
    prev = f;
  }
  return INFINITY;
}

HeightMap Autocorrelation::image() const {
  Grid g;
  g.nx = static_cast<std::size_t>(2 * hx_ + 1), g.ny = static_cast<std::size_t>(2 * hy_ + 1);
  g.dx = dx_, g.dy = dy_, g.x0 = -max_lag_x(), g.y0 = -max_lag_y();
  HeightMap m(g);
  m.z = acf_;
  return m;
}

AcfDecay acf_decay(const Autocorrelation& acf, double s) {
  AcfDecay d;
  if (!acf.defined()) return d;
  constexpr int kDirections = 720;
  double fastest = INFINITY, slowest = 0;
  for (int k = 0; k < kDirections; ++k) {
    const double theta = M_PI * k / kDirections, r = acf.decay_length(theta, s);
    if (r < fastest) fastest = r, d.fastest_direction = theta;
    slowest = std::max(slowest, r);
  }
  if (!std::isfinite(fastest)) return d;  // no direction falls to s: Sal and Str undefined
  d.decays = true;
  d.Sal = fastest;
  d.Str = std::isfinite(slowest) ? fastest / slowest : 0.0;
  return d;
}

}  // namespace topomill
