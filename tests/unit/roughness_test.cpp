// ISO 25178-2 parameters against closed forms and against the reference values agreed by
// independent implementations (tests/refdata/README.md).
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>

#include "io/sdf.hpp"
#include "metrology/roughness.hpp"

using topomill::Grid;
using topomill::HeightMap;

TEST_CASE("sdf-1.sdf gives the agreed reference values", "[roughness][refdata]") {
  const std::string path = std::string(TOPOMILL_REFDATA_DIR) + "/surfacetopography/sdf-1.sdf";
  REQUIRE(std::filesystem::exists(path));
  const topomill::Surface s = topomill::read_sdf(path);
  REQUIRE(s.map.grid.nx == 7);
  REQUIRE(s.map.grid.ny == 4);
  const auto r = topomill::roughness(s.map);  // mm; the reference is in metres
  CHECK(r.Sa * 1e-3 == Approx(1.15801275510204e-08).epsilon(1e-9));
  CHECK(r.Sq * 1e-3 == Approx(1.36028972894883e-08).epsilon(1e-9));
  CHECK(r.Sp * 1e-3 == Approx(1.64367857142856e-08).epsilon(1e-9));
  CHECK(r.Sv * 1e-3 == Approx(3.44932142857144e-08).epsilon(1e-9));
  CHECK(r.Sz * 1e-3 == Approx(5.093e-08).epsilon(1e-9));
  CHECK(r.Ssk == Approx(-0.64304606303356).epsilon(1e-9));
  CHECK(r.Sku == Approx(2.57727307520472).epsilon(1e-9));
  CHECK(r.Sdq == Approx(0.0171224878773825).epsilon(1e-9));
}

TEST_CASE("a sine surface has Sa = 2A/pi, Sq = A/sqrt2, Sku = 1.5, Ssk = 0", "[roughness]") {
  // z = A sin(2 pi x / L) over whole periods, finely sampled: the discrete sums converge to the
  // integrals with an error far below the tolerance.
  const double A = 2e-3, L = 0.1;
  Grid g;
  g.nx = 4000, g.ny = 3, g.dx = 2 * L / 4000, g.dy = 0.01;
  HeightMap m(g);
  for (std::size_t j = 0; j < g.ny; ++j)
    for (std::size_t i = 0; i < g.nx; ++i) m.at(i, j) = A * std::sin(2 * M_PI * g.x(i) / L);
  const auto r = topomill::roughness(m);
  CHECK(r.Sa == Approx(2 * A / M_PI).epsilon(1e-5));
  CHECK(r.Sq == Approx(A / std::sqrt(2.0)).epsilon(1e-5));
  CHECK(r.Sku == Approx(1.5).epsilon(1e-4));
  CHECK(r.Ssk == Approx(0).margin(1e-6));
  CHECK(r.Sz == Approx(2 * A).epsilon(1e-5));
  // RMS slope of the sine along x is A k / sqrt2; along y it is 0, and Sdq counts both directions.
  // The 3999 forward differences cover 2 periods less one step: their mean square is (A k)^2 / 2
  // to about 1 / 4000.
  const double k = 2 * M_PI / L;
  CHECK(r.Sdq ==
        Approx(A * k / std::sqrt(2.0) *
               std::sqrt(2.0 * (g.nx - 1) * g.ny / double((g.nx - 1) * g.ny + g.nx * (g.ny - 1))))
            .epsilon(5e-4));
}

TEST_CASE("a tilted plane's developed area ratio is sqrt(1 + p^2 + q^2) - 1, and Gwyddion's",
          "[roughness]") {
  Grid g;
  g.nx = 20, g.ny = 30, g.dx = 0.5, g.dy = 0.25;
  HeightMap m(g);
  const double p = 0.03, q = -0.02;
  for (std::size_t j = 0; j < g.ny; ++j)
    for (std::size_t i = 0; i < g.nx; ++i) m.at(i, j) = p * g.x(i) + q * g.y(j);
  const auto r = topomill::roughness(m);
  CHECK(r.Sdr == Approx(100 * (std::sqrt(1 + p * p + q * q) - 1)).epsilon(1e-10));
  // Gwyddion's scheme covers nx ny cells around the nodes: the (nx-1)(ny-1) cells between
  // nodes lie in the plane; the half-cell strips beyond the border rows carry the rows' heights
  // outwards, so they tilt along the border only (sqrt(1 + p^2) along x, sqrt(1 + q^2) along y);
  // the four corner quarters are flat.
  const double nx = g.nx, ny = g.ny;
  const double area = (nx - 1) * (ny - 1) * std::sqrt(1 + p * p + q * q) +
                      (nx - 1) * std::sqrt(1 + p * p) + (ny - 1) * std::sqrt(1 + q * q) + 1;
  CHECK(r.Sdr_gwyddion == Approx(100 * (area / (nx * ny) - 1)).epsilon(1e-10));
}
