// The residual of a simulated map, unrolled onto the arc: against a surface whose residual is a
// known function of the arc length, built here from the arc's polar form.
#include <catch2/catch.hpp>
#include <cmath>

#include "metrology/form_removal.hpp"
#include "support/builtin_models.hpp"
#include "topomill/surface_shape.hpp"

TEST_CASE("the unrolled residual of a spiral is its closed form at every node", "[form]") {
  // About the convex arc's centre (0, -r), the point at polar angle phi and distance
  // r - depth + a phi lies a phi off the cut surface along its normal, at arc length s = r phi:
  // the residual is (a / r) s, linear in s, so the interpolation between the Z-map's rows is
  // exact and a node sampled a row off is a ds / r off. The Z-map's heights at each row's y are
  // found here by fixed-point iteration on phi.
  const double r = 20, depth = 0.1, a = 0.05;  // mm, mm, mm per rad
  const auto arc = testing::make_model<topomill::SurfaceShape>("convex_arc", {{"radius", r}});
  topomill::Grid g;
  g.nx = 3, g.ny = 57, g.x0 = -0.01, g.dx = 0.01, g.y0 = 4.9, g.dy = 0.0111;
  topomill::HeightMap raw(g);
  for (std::size_t j = 0; j < g.ny; ++j) {
    const double y = g.y(j);
    double phi = std::asin(y / r);
    for (int k = 0; k < 100; ++k) phi = std::asin(y / (r - depth + a * phi));
    const double z = (r - depth + a * phi) * std::cos(phi) - r;
    for (std::size_t i = 0; i < g.nx; ++i) raw.at(i, j) = z;
  }
  const double s_lo = r * std::asin(5.0 / r), s_hi = r * std::asin(5.5 / r);
  const topomill::HeightMap out = topomill::unroll_residual(raw, *arc, depth, s_lo, s_hi, 0.007);
  REQUIRE(out.grid.y0 == s_lo);
  REQUIRE(out.grid.y(out.grid.ny - 1) == Approx(s_hi).epsilon(1e-14));
  double worst = 0;
  for (std::size_t k = 0; k < out.grid.ny; ++k)
    for (std::size_t i = 0; i < g.nx; ++i)
      worst = std::max(worst, std::abs(out.at(i, k) - a / r * out.grid.y(k)));
  INFO("largest difference " << worst * 1e6 << " nm");
  CHECK(worst < 1e-12);
}
