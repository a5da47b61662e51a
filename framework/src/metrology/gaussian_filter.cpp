#include "metrology/gaussian_filter.hpp"

#include <cmath>
#include <vector>

#include "interrupt.hpp"

namespace topomill {

namespace {
// Truncated at one cut-off, and at the map's length (n points): a point farther than the map is
// long never meets another, so the result is the same, and a cut-off of 1e6 mm no longer asks for
// a kernel of 1e9 weights (3 GB; 1e100 overflowed the count).
std::vector<double> kernel(double cutoff, double step, std::size_t n) {
  const double alpha = std::sqrt(std::log(2.0) / M_PI);
  const auto half =
      static_cast<long>(std::min(std::floor(cutoff / step), static_cast<double>(n - 1)));
  std::vector<double> k(static_cast<std::size_t>(2 * half + 1));
  for (long i = -half; i <= half; ++i) {
    const double u = i * step / (alpha * cutoff);
    k[static_cast<std::size_t>(i + half)] = std::exp(-M_PI * u * u);
  }
  return k;  // unnormalised: the normalised convolution divides by the weight sum
}

// out[i] = sum_k w[k] in[i + k - half] along one axis, for both the weighted heights and weights.
void convolve(const std::vector<double>& in, std::vector<double>& out, const Grid& g,
              const std::vector<double>& k, bool along_x) {
  const long half = static_cast<long>(k.size() / 2);
  const long n = static_cast<long>(along_x ? g.nx : g.ny),
             lines = static_cast<long>(along_x ? g.ny : g.nx);
  out.assign(in.size(), 0.0);
  for (long l = 0; l < lines; ++l) {
    throw_if_interrupted();  // a long kernel over a large map takes seconds
    for (long i = 0; i < n; ++i) {
      double sum = 0;
      for (long t = std::max(-half, -i); t <= std::min(half, n - 1 - i); ++t) {
        const long p = i + t;
        const std::size_t at = along_x ? g.index(p, l) : g.index(l, p);
        sum += k[static_cast<std::size_t>(t + half)] * in[at];
      }
      out[along_x ? g.index(i, l) : g.index(l, i)] = sum;
    }
  }
}
}  // namespace

Surface gaussian_lowpass(const Surface& s, double cutoff) {
  const Grid& g = s.map.grid;
  std::vector<double> zm(g.size()), m(g.size()), tmp;
  for (std::size_t i = 0; i < g.size(); ++i) {
    m[i] = s.is_valid(i) ? 1.0 : 0.0;
    zm[i] = s.is_valid(i) ? s.map.z[i] : 0.0;  // not m z: an invalid point may hold NaN
  }
  const auto kx = kernel(cutoff, g.dx, g.nx), ky = kernel(cutoff, g.dy, g.ny);
  convolve(zm, tmp, g, kx, true);
  convolve(tmp, zm, g, ky, false);
  convolve(m, tmp, g, kx, true);
  convolve(tmp, m, g, ky, false);
  Surface out = s;
  for (std::size_t i = 0; i < g.size(); ++i)
    if (s.is_valid(i)) out.map.z[i] = zm[i] / m[i];
  return out;
}

Surface s_filter(const Surface& s, double lambda_s) {
  return gaussian_lowpass(s, lambda_s);
}

Surface l_filter(const Surface& s, double lambda_c) {
  const Surface mean = gaussian_lowpass(s, lambda_c);
  Surface out = s;
  for (std::size_t i = 0; i < s.map.z.size(); ++i)
    if (s.is_valid(i)) out.map.z[i] -= mean.map.z[i];
  return out;
}

}  // namespace topomill
