#include "roughness.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace topomill {

std::map<std::string, double> Roughness::named() const {
  return {{"Sa", Sa},   {"Sq", Sq},   {"Sp", Sp},   {"Sv", Sv},  {"Sz", Sz},
          {"Ssk", Ssk}, {"Sku", Sku}, {"Sdq", Sdq}, {"Sdr", Sdr}};
}

std::map<std::string, double> Roughness::reported_um() const {
  auto out = named();
  for (const char* height : {"Sa", "Sq", "Sp", "Sv", "Sz"}) out[height] *= 1e3;
  return out;
}

namespace {
// Area of triangle abc less its projected area `flat`, without the cancellation of A - flat for
// nearly flat triangles: (A^2 - flat^2) / (A + flat).
double excess_area(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                   double flat) {
  const double a2 = 0.25 * (b - a).cross(c - a).squaredNorm();
  return (a2 - flat * flat) / (std::sqrt(a2) + flat);
}
}  // namespace

Roughness roughness(const HeightMap& map, const std::vector<std::uint8_t>& valid) {
  Roughness r;
  const auto& z = map.z;
  auto ok = [&](std::size_t i) { return valid.empty() || valid[i] != 0; };
  double n = 0, sum = 0;
  for (std::size_t i = 0; i < z.size(); ++i)
    if (ok(i)) sum += z[i], n += 1;
  if (n == 0) return r;
  r.mean = sum / n;
  double m1 = 0, m2 = 0, m3 = 0, m4 = 0, hi = -INFINITY, lo = INFINITY;
  for (std::size_t i = 0; i < z.size(); ++i) {
    if (!ok(i)) continue;
    const double d = z[i] - r.mean, d2 = d * d;
    m1 += std::abs(d), m2 += d2, m3 += d2 * d, m4 += d2 * d2;
    hi = std::max(hi, d), lo = std::min(lo, d);
  }
  r.Sa = m1 / n;
  r.Sq = std::sqrt(m2 / n);
  r.Sp = hi;
  r.Sv = -lo;
  r.Sz = r.Sp + r.Sv;
  r.Ssk = r.Sq > 0 ? m3 / n / (r.Sq * r.Sq * r.Sq) : 0.0;
  r.Sku = r.Sq > 0 ? m4 / n / (r.Sq * r.Sq * r.Sq * r.Sq) : 0.0;

  const Grid& g = map.grid;
  double slopes = 0, pairs = 0;
  for (std::size_t j = 0; j < g.ny; ++j)
    for (std::size_t i = 0; i + 1 < g.nx; ++i) {
      if (!ok(g.index(i, j)) || !ok(g.index(i + 1, j))) continue;
      const double d = (map.at(i + 1, j) - map.at(i, j)) / g.dx;
      slopes += d * d, pairs += 1;
    }
  for (std::size_t j = 0; j + 1 < g.ny; ++j)
    for (std::size_t i = 0; i < g.nx; ++i) {
      if (!ok(g.index(i, j)) || !ok(g.index(i, j + 1))) continue;
      const double d = (map.at(i, j + 1) - map.at(i, j)) / g.dy;
      slopes += d * d, pairs += 1;
    }
  r.Sdq = pairs > 0 ? std::sqrt(2 * slopes / pairs) : 0.0;

  double excess = 0, flat = 0;
  for (std::size_t j = 0; j + 1 < g.ny; ++j)
    for (std::size_t i = 0; i + 1 < g.nx; ++i) {
      if (!ok(g.index(i, j)) || !ok(g.index(i + 1, j)) || !ok(g.index(i, j + 1)) ||
          !ok(g.index(i + 1, j + 1)))
        continue;
      const Eigen::Vector3d a(0, 0, map.at(i, j)), b(g.dx, 0, map.at(i + 1, j)),
          c(g.dx, g.dy, map.at(i + 1, j + 1)), d(0, g.dy, map.at(i, j + 1));
      const double half = g.dx * g.dy / 2;
      excess += excess_area(a, b, c, half) + excess_area(a, c, d, half);
      flat += g.dx * g.dy;
    }
  r.Sdr = flat > 0 ? 100.0 * excess / flat : 0.0;
  return r;
}

}  // namespace topomill
