#include "metrology/spectrum.hpp"

#include <algorithm>
#include <cmath>

#include "metrology/fft.hpp"

namespace topomill {

namespace {
// The Hann window over n points, none of them zero: sin^2(pi (i + 1/2) / n).
std::vector<double> hann(std::size_t n) {
  std::vector<double> w(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double s = std::sin(M_PI * (static_cast<double>(i) + 0.5) / static_cast<double>(n));
    w[i] = s * s;
  }
  return w;
}

// The parabola's vertex through (-1, a), (0, b), (1, c), as an offset from 0 within [-1/2, 1/2].
double vertex(double a, double b, double c) {
  const double d = a - 2 * b + c;
  return d < 0 ? std::clamp(0.5 * (a - c) / d, -0.5, 0.5) : 0.0;
}
}  // namespace

PowerSpectrum::PowerSpectrum(const Surface& surface) {
  const Grid& g = surface.map.grid;
  dx_ = g.dx, dy_ = g.dy;
  // Zero-padded to four times the map each way, or twice, or not at all: the most that keeps
  // the padded field within 2^22 values (about 100 MB with its spectrum and the planner's copy,
  // whatever the map; unpadded, 24 bytes a node). Closer bins let the angular spectrum's rays
  // pass through a peak's shape, not between its samples (Std of a sine 20 waves across the map:
  // within 0.35 deg padded twice, 0.2 deg four times; tests/unit/iso_parameters_test.cpp).
  constexpr double kMaxPadded = 1 << 22;
  std::size_t factor = 4;
  while (factor > 1 &&
         static_cast<double>(factor * g.nx) * static_cast<double>(factor * g.ny) > kMaxPadded)
    factor /= 2;
  nx_ = fft_size(factor * g.nx), ny_ = fft_size(factor * g.ny);
  lowest_ =
      2 * std::max(1 / (static_cast<double>(g.nx) * dx_), 1 / (static_cast<double>(g.ny) * dy_));
  const double mean = surface.mean();
  const auto wx = hann(g.nx), wy = hann(g.ny);
  std::vector<double> field(nx_ * ny_, 0.0);
  double w2 = 0;
  for (std::size_t j = 0; j < g.ny; ++j)
    for (std::size_t i = 0; i < g.nx; ++i) {
      const double w = wx[i] * wy[j];
      w2 += w * w;
      if (surface.is_valid(g.index(i, j))) field[j * nx_ + i] = w * (surface.map.at(i, j) - mean);
    }
  const auto spectrum = fft_forward(field, nx_, ny_);
  power_.resize(spectrum.size());
  const double scale = dx_ * dy_ / w2;
  for (std::size_t k = 0; k < spectrum.size(); ++k) power_[k] = std::norm(spectrum[k]) * scale;
}

double PowerSpectrum::bin(std::ptrdiff_t kx, std::ptrdiff_t ky) const {
  if (kx < 0) kx = -kx, ky = -ky;  // P(-f) = P(f)
  const auto nx = static_cast<std::ptrdiff_t>(nx_), ny = static_cast<std::ptrdiff_t>(ny_);
  if (kx > nx / 2 || std::abs(ky) > ny / 2) return 0.0;
  const std::size_t row = static_cast<std::size_t>(ky < 0 ? ky + ny : ky);
  return power_[row * (nx_ / 2 + 1) + static_cast<std::size_t>(kx)];
}

double PowerSpectrum::at(double fx, double fy) const {
  const double u = fx / df_x(), v = fy / df_y();
  const auto a = static_cast<std::ptrdiff_t>(std::floor(u));
  const auto b = static_cast<std::ptrdiff_t>(std::floor(v));
  const double s = u - static_cast<double>(a), t = v - static_cast<double>(b);
  return (1 - t) * ((1 - s) * bin(a, b) + s * bin(a + 1, b)) +
         t * ((1 - s) * bin(a, b + 1) + s * bin(a + 1, b + 1));
}

double PowerSpectrum::angular(double theta) const {
  const double c = std::cos(theta), s = std::sin(theta);
  const double step = 0.5 * std::min(df_x(), df_y()), start = lowest_;
  const double end = std::min(0.5 / dx_, 0.5 / dy_);
  double sum = 0;
  for (double r = start; r <= end; r += step) sum += at(r * c, r * s) * r * step;
  return sum;
}

HeightMap PowerSpectrum::image() const {
  Grid g;
  const auto hx = static_cast<std::ptrdiff_t>(nx_ / 2), hy = static_cast<std::ptrdiff_t>(ny_ / 2);
  g.nx = static_cast<std::size_t>(2 * hx + 1), g.ny = static_cast<std::size_t>(2 * hy + 1);
  g.dx = df_x(), g.dy = df_y(), g.x0 = -static_cast<double>(hx) * g.dx,
  g.y0 = -static_cast<double>(hy) * g.dy;
  HeightMap m(g);
  double top = 0;
  for (double p : power_) top = std::max(top, p);
  const double floor = top > 0 ? top * 1e-12 : 1e-300;  // twelve decades below the top
  for (std::ptrdiff_t b = -hy; b <= hy; ++b)
    for (std::ptrdiff_t a = -hx; a <= hx; ++a)
      m.at(static_cast<std::size_t>(a + hx), static_cast<std::size_t>(b + hy)) =
          std::log10(std::max(bin(a, b), floor));
  return m;
}

double texture_direction(const PowerSpectrum& psd) {
  constexpr int kDirections = 720;
  std::vector<double> a(kDirections);
  for (int k = 0; k < kDirections; ++k) a[k] = psd.angular(M_PI * k / kDirections);
  const int best = static_cast<int>(std::max_element(a.begin(), a.end()) - a.begin());
  // The angular spectrum repeats every pi: the neighbours of 0 and of the last wrap round.
  const double d =
      vertex(a[(best + kDirections - 1) % kDirections], a[best], a[(best + 1) % kDirections]);
  const double theta = M_PI * (best + d) / kDirections;
  return theta < 0 ? theta + M_PI : theta >= M_PI ? theta - M_PI : theta;
}

double dominant_period(const Surface& surface, double theta) {
  const Grid& g = surface.map.grid;
  if (g.nx < 2 || g.ny < 2) return 0.0;
  const double c = std::cos(theta), s = std::sin(theta);
  const double lx = static_cast<double>(g.nx - 1) * g.dx, ly = static_cast<double>(g.ny - 1) * g.dy;
  const double side = std::min(lx, ly) / (std::abs(c) + std::abs(s));
  // Samples at the finer spacing, at most 1024 a side (a coarser step beyond: the marks of
  // interest are many samples long).
  constexpr std::size_t kMaxSamples = 1024, kChunk = 64;
  double h = std::min(g.dx, g.dy);
  std::size_t m = static_cast<std::size_t>(side / h) + 1;
  if (m > kMaxSamples) m = kMaxSamples, h = side / static_cast<double>(m - 1);
  if (m < 8) return 0.0;
  const double mean = surface.mean();
  const double xc = g.x0 + 0.5 * lx, yc = g.y0 + 0.5 * ly,
               half = 0.5 * h * static_cast<double>(m - 1);
  // Height at (x, y), bilinear between the four nodes about it; the mean where one is invalid.
  auto height = [&](double x, double y) {
    const double u = std::clamp((x - g.x0) / g.dx, 0.0, static_cast<double>(g.nx - 1));
    const double v = std::clamp((y - g.y0) / g.dy, 0.0, static_cast<double>(g.ny - 1));
    const std::size_t i = std::min(static_cast<std::size_t>(u), g.nx - 2);
    const std::size_t j = std::min(static_cast<std::size_t>(v), g.ny - 2);
    for (std::size_t k :
         {g.index(i, j), g.index(i + 1, j), g.index(i, j + 1), g.index(i + 1, j + 1)})
      if (!surface.is_valid(k)) return 0.0;
    const double a = u - static_cast<double>(i), b = v - static_cast<double>(j);
    return (1 - b) * ((1 - a) * surface.map.at(i, j) + a * surface.map.at(i + 1, j)) +
           b * ((1 - a) * surface.map.at(i, j + 1) + a * surface.map.at(i + 1, j + 1)) - mean;
  };
  const std::size_t n = fft_size(8 * m), bins = n / 2 + 1;
  const auto w = hann(m);
  std::vector<double> power(bins, 0.0);
  for (std::size_t r0 = 0; r0 < m; r0 += kChunk) {
    const std::size_t rows = std::min(kChunk, m - r0);
    std::vector<double> data(rows * n, 0.0);
    for (std::size_t r = 0; r < rows; ++r) {
      const double across = h * static_cast<double>(r0 + r) - half;
      double* row = &data[r * n];
      double sum = 0;
      for (std::size_t q = 0; q < m; ++q) {
        const double along = h * static_cast<double>(q) - half;
        row[q] = height(xc + along * c - across * s, yc + along * s + across * c);
        sum += row[q];
      }
      for (std::size_t q = 0; q < m; ++q) row[q] = (row[q] - sum / static_cast<double>(m)) * w[q];
    }
    const auto spectra = fft_rows(data, n, rows);
    for (std::size_t r = 0; r < rows; ++r)
      for (std::size_t k = 0; k < bins; ++k) power[k] += std::norm(spectra[r * bins + k]);
  }
  // Bin k is the frequency k / (n h); periods longer than half the square are left out.
  const double length = h * static_cast<double>(n);
  const auto first = static_cast<std::size_t>(std::ceil(2 * length / side));
  if (first + 1 >= bins) return 0.0;
  const std::size_t best = static_cast<std::size_t>(
      std::max_element(power.begin() + first, power.end() - 1) - power.begin());
  if (!(power[best] > 0)) return 0.0;
  const double f =
      (static_cast<double>(best) + vertex(power[best - 1], power[best], power[best + 1])) / length;
  return 1.0 / f;
}

}  // namespace topomill
