#include "metrology/roughness.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <functional>

namespace topomill {

namespace {
// Heights vary beyond round-off where Sq exceeds this share of the largest |height| (a level map
// far from zero has a mean a rounding off its heights, and Ssk, Sku of +-1 from that alone).
constexpr double kRoundOff = 1e-12;
}  // namespace

std::vector<std::pair<std::string, std::string>> Roughness::undefined() const {
  std::vector<std::pair<std::string, std::string>> out;
  if (!relief)
    for (const char* n : {"Ssk", "Sku"})
      out.emplace_back(n, "the heights do not vary beyond their round-off, and " + std::string(n) +
                              " divides by Sq");
  if (pairs == 0) out.emplace_back("Sdq", "no two valid points are neighbours");
  if (cells == 0) out.emplace_back("Sdr", "no cell has four valid corners");
  if (gwyddion_cells == 0)
    out.emplace_back("Sdr_gwyddion", "no cell or border strip has its valid corners");
  return out;
}

std::vector<Roughness::Reported> Roughness::reported() const {
  std::vector<Reported> all = {
      {"Sa", Sa * 1e3, "um", ""},
      {"Sq", Sq * 1e3, "um", ""},
      {"Sp", Sp * 1e3, "um", ""},
      {"Sv", Sv * 1e3, "um", ""},
      {"Sz", Sz * 1e3, "um", ""},
      {"Ssk", Ssk, "1", ""},
      {"Sku", Sku, "1", ""},
      {"Sdq", Sdq, "1", "forward differences over all horizontal and vertical neighbour pairs"},
      {"Sdr", Sdr, "%", "two triangles per cell between nodes, (nx-1)(ny-1) cells"},
      {"Sdr_gwyddion", Sdr_gwyddion, "%",
       "Gwyddion's: four triangles per cell about its mean height, half-cell border strips, "
       "nx ny cells"}};
  std::vector<Reported> out;
  const auto gone = undefined();
  for (auto& r : all)
    if (std::none_of(gone.begin(), gone.end(), [&](const auto& u) { return u.first == r.name; }))
      out.push_back(std::move(r));
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

// Gwyddion's scheme, in excess over the flat area: the triangle from the edge (za, zb), of
// length `along`, to the cell's centre at height zc, `across` / 2 away, has the area
// along across / 4 sqrt(1 + ((zb - za) / along)^2 + ((za + zb - 2 zc) / across)^2).
double excess_quarter(double za, double zb, double zc, double along, double across) {
  const double p = (zb - za) / along, q = (za + zb - 2 * zc) / across, s = p * p + q * q;
  return 0.25 * along * across * s / (std::sqrt(1 + s) + 1);  // sqrt(1 + s) - 1, no cancellation
}

// Excess area of the cell with corners z00 (i, j), z10 (i+1, j), z11, z01 over its flat area.
double excess_cell(double z00, double z10, double z11, double z01, double dx, double dy) {
  const double c = 0.25 * (z00 + z10 + z11 + z01);
  return excess_quarter(z00, z10, c, dx, dy) + excess_quarter(z10, z11, c, dy, dx) +
         excess_quarter(z11, z01, c, dx, dy) + excess_quarter(z01, z00, c, dy, dx);
}

// Sdr_gwyddion in percent, and the area of its cells and strips (0: no slope seen, undefined).
std::pair<double, double> sdr_gwyddion(const HeightMap& map,
                                       const std::function<bool(std::size_t)>& ok) {
  const Grid& g = map.grid;
  if (g.nx < 2 || g.ny < 2) return {0.0, 0.0};
  double excess = 0, flat = 0;
  for (std::size_t j = 0; j + 1 < g.ny; ++j)
    for (std::size_t i = 0; i + 1 < g.nx; ++i)
      if (ok(g.index(i, j)) && ok(g.index(i + 1, j)) && ok(g.index(i, j + 1)) &&
          ok(g.index(i + 1, j + 1))) {
        excess += excess_cell(map.at(i, j), map.at(i + 1, j), map.at(i + 1, j + 1),
                              map.at(i, j + 1), g.dx, g.dy);
        flat += g.dx * g.dy;
      }
  // Border strips: half of a cell whose outer edge repeats the border nodes' heights (the half
  // next to the nodes: its edge along them whole, its two side triangles by half).
  auto strip = [&](double za, double zb, double along, double across) {
    const double c = 0.5 * (za + zb);
    excess +=
        excess_quarter(za, zb, c, along, across) +
        0.5 * (excess_quarter(zb, zb, c, across, along) + excess_quarter(za, za, c, across, along));
    flat += 0.5 * along * across;
  };
  for (std::size_t i = 0; i + 1 < g.nx; ++i)
    for (std::size_t j : {std::size_t{0}, g.ny - 1})
      if (ok(g.index(i, j)) && ok(g.index(i + 1, j)))
        strip(map.at(i, j), map.at(i + 1, j), g.dx, g.dy);
  for (std::size_t j = 0; j + 1 < g.ny; ++j)
    for (std::size_t i : {std::size_t{0}, g.nx - 1})
      if (ok(g.index(i, j)) && ok(g.index(i, j + 1)))
        strip(map.at(i, j), map.at(i, j + 1), g.dy, g.dx);
  const double sloped = flat;  // cells and strips: where a slope is seen
  for (std::size_t k :
       {g.index(0, 0), g.index(g.nx - 1, 0), g.index(0, g.ny - 1), g.index(g.nx - 1, g.ny - 1)})
    if (ok(k)) flat += 0.25 * g.dx * g.dy;  // corner quarters, flat
  return {flat > 0 ? 100.0 * excess / flat : 0.0, sloped};
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
  double hi = -INFINITY, lo = INFINITY, top = 0;
  for (std::size_t i = 0; i < z.size(); ++i) {
    if (!ok(i)) continue;
    hi = std::max(hi, z[i] - r.mean), lo = std::min(lo, z[i] - r.mean);
    top = std::max(top, std::abs(z[i]));
  }
  // The moments of the deviations in units of a power of two near the largest one, so that
  // neither denormal heights (whose squares vanish: Sq would be 0 below Sa) nor huge ones (whose
  // fourth powers overflow) lose them; scaling by a power of two is exact, so the values are
  // those of the unscaled sums wherever those neither underflow nor overflow.
  int exponent = 0;
  std::frexp(std::max(hi, -lo), &exponent);
  const double unit = std::max(hi, -lo) > 0 ? std::ldexp(1.0, exponent) : 0.0;
  double m1 = 0, m2 = 0, m3 = 0, m4 = 0;
  if (unit > 0)
    for (std::size_t i = 0; i < z.size(); ++i) {
      if (!ok(i)) continue;
      const double d = (z[i] - r.mean) / unit, d2 = d * d;
      m1 += std::abs(d), m2 += d2, m3 += d2 * d, m4 += d2 * d2;
    }
  r.Sa = unit * (m1 / n);
  const double q = std::sqrt(m2 / n);  // Sq / unit
  r.Sq = unit * q;
  r.Sp = std::max(hi, 0.0);  // a flat map's mean can sit a rounding above every height
  r.Sv = std::max(-lo, 0.0);
  r.Sz = r.Sp + r.Sv;
  r.relief = r.Sq > kRoundOff * top;
  r.Ssk = r.relief ? m3 / n / (q * q * q) : 0.0;
  r.Sku = r.relief ? m4 / n / (q * q * q * q) : 0.0;

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
  r.pairs = pairs;

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
  r.cells = flat / (g.dx * g.dy);
  const auto [sdr_g, area_g] = sdr_gwyddion(map, ok);
  r.Sdr_gwyddion = sdr_g, r.gwyddion_cells = area_g / (g.dx * g.dy);
  return r;
}

}  // namespace topomill
