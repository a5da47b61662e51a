// ISO 25178-2 spatial, functional and volume parameters against surfaces whose values are known in
// closed form: a pure sine (Sal from its period, Str 0, Std its direction), heights spread evenly
// (the material ratio curve is a line), two levels (volumes are areas of rectangles), and Gaussian
// random surfaces of known correlation length (Sal, Str near 1 when isotropic, 1/2 when
// stretched twice).
#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "metrology/autocorrelation.hpp"
#include "metrology/material_ratio.hpp"
#include "metrology/parameters.hpp"
#include "metrology/spectrum.hpp"

using namespace topomill;

namespace {
Surface grid_surface(std::size_t nx, std::size_t ny, double dx) {
  Surface s;
  Grid g;
  g.nx = nx, g.ny = ny, g.dx = dx, g.dy = dx;
  s.map = HeightMap(g);
  return s;
}

// A sine of wavelength `period` (mm) whose waves run at `angle` (rad) from +X.
Surface sine(double period, double angle, std::size_t n = 250, double dx = 0.002) {
  Surface s = grid_surface(n, n, dx);
  const Grid& g = s.map.grid;
  for (std::size_t j = 0; j < n; ++j)
    for (std::size_t i = 0; i < n; ++i)
      s.map.at(i, j) =
          1e-3 *
          std::sin(2 * M_PI * (g.x(i) * std::cos(angle) + g.y(j) * std::sin(angle)) / period);
  return s;
}

// Heights a + (k + 1/2) h / n, k = 0..n-1, one per node in a scrambled order.
Surface uniform_heights(double a, double h, std::size_t side) {
  Surface s = grid_surface(side, side, 0.001);
  const std::size_t n = side * side, stride = 7919;  // prime, so k -> k stride mod n permutes
  for (std::size_t k = 0; k < n; ++k)
    s.map.z[(k * stride) % n] = a + (static_cast<double>(k) + 0.5) * h / static_cast<double>(n);
  return s;
}

// White noise smoothed by a Gaussian of standard deviations sx, sy (nodes): its ACF is
// exp(-(tx^2 / (4 sx^2) + ty^2 / (4 sy^2))), which falls to s at 2 sigma sqrt(ln(1 / s)).
Surface gaussian_random(std::size_t n, double sx, double sy, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  const std::size_t pad = 5 * static_cast<std::size_t>(std::ceil(std::max(sx, sy))),
                    m = n + 2 * pad;
  std::vector<double> noise(m * m), rows(m * m, 0.0);
  for (double& v : noise) v = normal(rng);
  auto kernel = [](double sigma, int k) { return std::exp(-0.5 * k * k / (sigma * sigma)); };
  const int r = static_cast<int>(pad);
  for (std::size_t j = 0; j < m; ++j)
    for (std::size_t i = static_cast<std::size_t>(r); i + static_cast<std::size_t>(r) < m; ++i)
      for (int k = -r; k <= r; ++k)
        rows[j * m + i] += kernel(sx, k) * noise[j * m + i + static_cast<std::size_t>(k + r) - pad];
  Surface s = grid_surface(n, n, 0.001);
  for (std::size_t j = 0; j < n; ++j)
    for (std::size_t i = 0; i < n; ++i) {
      double v = 0;
      for (int k = -r; k <= r; ++k)
        v += kernel(sy, k) * rows[(j + static_cast<std::size_t>(k + r)) * m + i + pad];
      s.map.at(i, j) = 1e-3 * v;
    }
  return s;
}

// |a - b| for directions (rad), which repeat every pi.
double angle_apart(double a, double b) {
  const double d = std::fmod(std::abs(a - b), M_PI);
  return std::min(d, M_PI - d);
}

// The ACF at lag (a, b) nodes by its definition: mean over the overlapping pairs of heights less
// their mean, over the same at zero lag.
double acf_by_sums(const Surface& s, int a, int b) {
  const Grid& g = s.map.grid;
  double mean = 0;
  for (double z : s.map.z) mean += z;
  mean /= static_cast<double>(s.map.z.size());
  auto sum = [&](int u, int v) {
    double total = 0, n = 0;
    for (int j = 0; j < static_cast<int>(g.ny); ++j)
      for (int i = 0; i < static_cast<int>(g.nx); ++i) {
        const int i2 = i + u, j2 = j + v;
        if (i2 < 0 || j2 < 0 || i2 >= static_cast<int>(g.nx) || j2 >= static_cast<int>(g.ny))
          continue;
        total += (s.map.at(i, j) - mean) * (s.map.at(i2, j2) - mean), n += 1;
      }
    return total / n;
  };
  return sum(a, b) / sum(0, 0);
}

double value(const ParameterValues& v, const std::string& name) {
  for (const auto& r : v.reported)
    if (r.name == name) return r.value;
  FAIL("no " << name);
  return NAN;
}
}  // namespace

TEST_CASE("A pure sine: Sal from its period, Str 0, Std its direction, its period", "[iso]") {
  const double period = 0.1, s = 0.2;
  const Surface across_x = sine(period, 0.0);  // five whole periods over the map
  const Autocorrelation acf(across_x);
  REQUIRE(acf.defined());
  // ACF(t) = cos(2 pi tx / period): it falls to s at period acos(s) / (2 pi), never along Y.
  // On a finite map the overlap's sums of a sine add terms of the order of period / length to
  // the cosine: the closed form within 3 %, the sums themselves (here) to round-off.
  for (int a : {0, 5, 11, 12, 40, 125})
    for (int b : {0, 3, -60})
      CHECK(acf.at(a * 0.002, b * 0.002) == Approx(acf_by_sums(across_x, a, b)).margin(1e-12));
  const AcfDecay d = acf_decay(acf, s);
  CHECK(d.decays);
  CHECK(d.Sal == Approx(period * std::acos(s) / (2 * M_PI)).epsilon(0.03));
  const double below = acf_by_sums(across_x, 11, 0), above = acf_by_sums(across_x, 12, 0);
  REQUIRE((below > s && above < s));  // the fall to s between lags 11 and 12, linear between
  CHECK(d.Sal == Approx(0.002 * (11 + (below - s) / (below - above))).epsilon(1e-3));
  CHECK(d.Str == 0.0);
  CHECK(angle_apart(d.fastest_direction, 0) < 1e-9);
  CHECK(angle_apart(texture_direction(PowerSpectrum(across_x)), 0) < 0.25 * M_PI / 180);
  CHECK(dominant_period(across_x, 0.0) == Approx(period).epsilon(0.005));

  // Std at every 7.3 deg, 5 and 20 waves across the map: a peak as wide as a map's frequency step
  // leaves the angle within 1 deg at 5 waves, 0.2 deg at 20 (0.35 with the spectrum padded only
  // twice: spectrum.cpp). The ACF's fastest decay is flat about its direction: 1.5 deg.
  for (double deg = 1.0; deg < 180; deg += 7.3)
    for (const auto& [waves, tolerance] : {std::pair{5.0, 1.0}, std::pair{20.0, 0.2}}) {
      const double angle = deg * M_PI / 180, wavelength = 256 * 0.002 / waves;
      const Surface turned = sine(wavelength, angle, 256);
      CHECK(angle_apart(texture_direction(PowerSpectrum(turned)), angle) * 180 / M_PI < tolerance);
      CHECK(dominant_period(turned, angle) == Approx(wavelength).epsilon(0.01));
      const AcfDecay t = acf_decay(Autocorrelation(turned), s);
      CHECK(t.Sal == Approx(wavelength * std::acos(s) / (2 * M_PI)).epsilon(0.03));
      CHECK(angle_apart(t.fastest_direction, angle) * 180 / M_PI < 1.5);
      CHECK(t.Str == 0.0);
    }
}

TEST_CASE("Missing points do not change the sine's autocorrelation", "[iso]") {
  const double period = 0.1, s = 0.2;
  Surface holed = sine(period, 0.0);
  holed.valid.assign(holed.map.z.size(), 1);
  for (std::size_t k = 0; k < holed.valid.size(); k += 7) holed.valid[k] = 0, holed.map.z[k] = 1e9;
  const AcfDecay d = acf_decay(Autocorrelation(holed), s);
  CHECK(d.Sal == Approx(acf_decay(Autocorrelation(sine(period, 0.0)), s).Sal).epsilon(0.01));
  CHECK(angle_apart(texture_direction(PowerSpectrum(holed)), 0) < 0.25 * M_PI / 180);
}

TEST_CASE("Heights spread evenly: the material ratio curve is a line", "[iso]") {
  const double a = -0.002, h = 0.005;  // mm
  const std::size_t side = 100, n = side * side;
  const Surface u = uniform_heights(a, h, side);
  const MaterialRatioCurve curve(u);
  // About the mean a + h/2 the curve is h/2 - h mr between the half-steps at either end.
  const double tol = 2 * h / static_cast<double>(n);
  for (double mr : {0.01, 0.1, 0.37, 0.5, 0.8, 0.99})
    CHECK(curve.height(mr) == Approx(h / 2 - h * mr).margin(tol));
  for (double c : {-0.002, 0.0, 0.0011})
    CHECK(curve.ratio(c) == Approx((h / 2 - c) / h).margin(1.0 / n));
  // Vm(p) = h p^2 / 2, Vv(p) = h (1 - p)^2 / 2.
  for (double p : {0.1, 0.5, 0.8}) {
    CHECK(curve.material_volume(p) == Approx(h * p * p / 2).margin(tol));
    CHECK(curve.void_volume(p) == Approx(h * (1 - p) * (1 - p) / 2).margin(tol));
  }
  // A line is its own least-gradient secant: the core is the whole height, no peaks, no valleys.
  const auto core = curve.core();
  CHECK(core.Sk == Approx(h).margin(2 * tol));
  CHECK(core.Smr1 == Approx(0).margin(2.0 / n));
  CHECK(core.Smr2 == Approx(1).margin(2.0 / n));
  CHECK(core.Spk == Approx(0).margin(tol));
  CHECK(core.Svk == Approx(0).margin(tol));

  // The report, in its units (um, %, ml/m2 = um), at ISO 25178-3's p = 10 %, q = 80 % and
  // Sxp's 2.5 % and 50 %.
  const ParameterValues v = compute_parameters(u, select_parameters({"functional", "volume"}), {});
  const double hu = h * 1e3, tu = 2 * hu / static_cast<double>(n);
  CHECK(value(v, "Sxp") == Approx(hu * (0.5 - 0.025)).margin(tu));
  CHECK(value(v, "Smr") == Approx(50.0).margin(100.0 / n));
  CHECK(value(v, "Smc") == Approx(hu * (0.5 - 0.1)).margin(tu));
  CHECK(value(v, "Vmp") == Approx(hu * 0.01 / 2).margin(tu));
  CHECK(value(v, "Vmc") == Approx(hu * (0.64 - 0.01) / 2).margin(tu));
  CHECK(value(v, "Vvc") == Approx(hu * (0.81 - 0.04) / 2).margin(tu));
  CHECK(value(v, "Vvv") == Approx(hu * 0.04 / 2).margin(tu));
  CHECK(value(v, "Sk") == Approx(hu).margin(2 * tu));
}

TEST_CASE("Peaks and valleys as triangles: Spk and Svk are their heights", "[iso]") {
  // ISO 13565-2 (ISO 25178-2's Spk, Svk): Spk is the height of the triangle on base Smr1 whose
  // area is the peaks' above the core line, Svk the same for the valleys below it. Heights spread
  // so that the material ratio curve is a core line from `top` falling `sk` over the whole ratio,
  // with a wedge H high over [0, m1] above it and one V deep over [m2, 1] below it: the peaks'
  // area is H m1 / 2, so Spk = H, and Svk = V. The core's steepest parts are the wedges, so its
  // least-gradient 40 % secant is the core line.
  const double top = 0.002, sk = 0.002, H = 0.003, V = 0.004, m1 = 0.1, m2 = 0.8;  // mm
  const std::size_t side = 200, n = side * side;
  Surface s = grid_surface(side, side, 0.001);
  for (std::size_t k = 0; k < n; ++k) {
    const double m = (static_cast<double>(k) + 0.5) / static_cast<double>(n);  // k-th highest
    const double z = m < m1   ? top + H * (1 - m / m1)
                     : m < m2 ? top - sk * m
                              : top - sk - V * (m - m2) / (1 - m2);
    s.map.z[(k * 7919) % n] = z;
  }
  const auto core = MaterialRatioCurve(s).core();
  // The curve is linear between knots 1 / n apart: each step between a wedge and the core is
  // smeared over one knot, moving Smr1 and Smr2 by up to 1 / n and Spk and Svk by about what a
  // wedge falls over one (0.37 and 0.25 nm seen); twice that is allowed.
  const double ratio_tol = 1.0 / static_cast<double>(n);
  const double tol = 2 * std::max(H / m1, V / (1 - m2)) * ratio_tol;
  CHECK(core.Sk == Approx(sk).margin(tol));
  CHECK(core.Smr1 == Approx(m1).margin(ratio_tol));
  CHECK(core.Smr2 == Approx(m2).margin(ratio_tol));
  CHECK(core.Spk == Approx(H).margin(tol));
  CHECK(core.Svk == Approx(V).margin(tol));
  // The report, in um.
  const ParameterValues v = compute_parameters(s, select_parameters({"functional"}), {});
  CHECK(value(v, "Spk") == Approx(H * 1e3).margin(tol * 1e3));
  CHECK(value(v, "Svk") == Approx(V * 1e3).margin(tol * 1e3));
}

TEST_CASE("Two levels: volumes are rectangles", "[iso]") {
  // 30 % of the nodes at H, the rest at 0: about the mean 0.3 H the curve is 0.7 H up to
  // mr = 0.3 and -0.3 H after.
  const double H = 0.004;
  Surface s = grid_surface(100, 100, 0.001);
  for (std::size_t k = 0; k < s.map.z.size(); ++k) s.map.z[k] = (k * 7919) % 10 < 3 ? H : 0.0;
  const ParameterValues v = compute_parameters(s, select_parameters({"all"}), {});
  const double Hu = H * 1e3;
  CHECK(value(v, "Vmp") == Approx(0).margin(1e-12));
  CHECK(value(v, "Vmc") == Approx(0.3 * Hu));
  CHECK(value(v, "Vvc") == Approx(0.7 * Hu));
  CHECK(value(v, "Vvv") == Approx(0).margin(1e-12));
  CHECK(value(v, "Vm") == Approx(0).margin(1e-12));
  CHECK(value(v, "Vv") == Approx(0.7 * Hu));
  CHECK(value(v, "Sa") == Approx(2 * 0.3 * 0.7 * Hu));
  CHECK(value(v, "Sz") == Approx(Hu));
  CHECK(value(v, "Smr") == Approx(30).margin(0.01));  // c = 0: the mean plane, below the top level
}

TEST_CASE("Gaussian random surfaces: Sal from the correlation length, Str from the stretch",
          "[iso]") {
  const double s = 0.2, sigma = 4;                                        // nodes of 1 um
  const double expected = 2 * sigma * std::sqrt(std::log(1 / s)) * 1e-3;  // mm
  const Surface iso = gaussian_random(256, sigma, sigma, 1);
  const AcfDecay d = acf_decay(Autocorrelation(iso), s);
  CHECK(d.Sal == Approx(expected).epsilon(0.1));
  CHECK(d.Str > 0.8);
  // Twice as long along Y: the ACF falls twice as slowly there.
  const AcfDecay stretched =
      acf_decay(Autocorrelation(gaussian_random(256, sigma, 2 * sigma, 2)), s);
  CHECK(stretched.Sal == Approx(expected).epsilon(0.1));
  CHECK(stretched.Str == Approx(0.5).margin(0.08));
  CHECK(angle_apart(stretched.fastest_direction, 0) < 10 * M_PI / 180);  // the fast decay along X
}

TEST_CASE("A flat map has no autocorrelation: Sal and Str are reported undefined", "[iso]") {
  Surface flat = grid_surface(32, 32, 0.001);
  const ParameterValues v = compute_parameters(flat, select_parameters({"Sal", "Str", "Sa"}), {});
  REQUIRE(v.reported.size() == 1);
  CHECK(v.reported[0].name == "Sa");
  REQUIRE(v.undefined.size() == 2);
  CHECK(v.undefined[0].first == "Sal");
}

TEST_CASE("Parameter words select names in catalogue order", "[iso]") {
  CHECK(select_parameters({"default"}) == std::vector<std::string>{"Sa", "Sq", "Sp", "Sv", "Sz",
                                                                   "Ssk", "Sku", "Sdq", "Sdr",
                                                                   "Sdr_gwyddion"});
  CHECK(select_parameters({"Vvv", "spatial", "Sa", "Sa"}) ==
        std::vector<std::string>{"Sa", "Sal", "Str", "Std", "Vvv"});
  CHECK(select_parameters({"all"}).size() == parameter_catalogue().size());
}
