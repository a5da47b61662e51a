// What a run reports about its surface, recomputed here from the maps it returns: the form it
// removed and every parameter of summary.json, by formulas written in this file.
#include <Eigen/Dense>
#include <catch2/catch.hpp>
#include <cmath>

#include "support/scenes.hpp"

namespace {
const std::string kScene =
    testing::paper_scene("plugin = 'convex_arc'\nradius = 50.0", 30.0, 0.2, 0.16, 0.01);
}  // namespace

TEST_CASE("form = plane removes the least-squares plane of the raw map", "[analysis]") {
  // Before, "plane" was accepted, reported and computed as "nominal".
  const auto plane = testing::run_scene(kScene, {"analysis.form=plane"});
  const auto& raw = plane.raw;
  const auto& g = raw.grid;
  Eigen::Matrix3d a = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  for (std::size_t j = 0; j < g.ny; ++j)
    for (std::size_t i = 0; i < g.nx; ++i) {
      const Eigen::Vector3d row(1, g.x(i), g.y(j));
      a += row * row.transpose(), b += row * raw.at(i, j);
    }
  const Eigen::Vector3d c = a.ldlt().solve(b);
  REQUIRE(plane.residual.grid.nx == g.nx);
  REQUIRE(plane.residual.grid.ny == g.ny);
  double worst = 0;
  for (std::size_t j = 0; j < g.ny; ++j)
    for (std::size_t i = 0; i < g.nx; ++i)
      worst = std::max(worst, std::abs(plane.residual.at(i, j) -
                                       (raw.at(i, j) - c[0] - c[1] * g.x(i) - c[2] * g.y(j))));
  CHECK(worst < 1e-11);  // raw heights are about 40 mm: round-off
  const auto nominal = testing::run_scene(kScene, {"analysis.form=nominal"});
  CHECK(std::abs(plane.roughness.Sa / nominal.roughness.Sa - 1) > 0.05);
}

TEST_CASE("every reported parameter is the residual's, in the reported units", "[analysis]") {
  // ISO 25178-2 over the residual map as returned, computed here: heights in um, Ssk and Sku
  // dimensionless, Sdq from the forward differences along x and y, Sdr from two triangles per
  // cell (roughness.hpp's stated schemes).
  for (const char* form : {"nominal", "plane", "none"}) {
    const auto r = testing::run_scene(kScene, {std::string("analysis.form=") + form});
    const auto& m = r.residual;
    const auto& g = m.grid;
    const double n = static_cast<double>(m.z.size());
    double mean = 0;
    for (double z : m.z) mean += z / n;
    double sa = 0, sq = 0, s3 = 0, s4 = 0, hi = -INFINITY, lo = INFINITY;
    for (double z : m.z) {
      const double h = z - mean;
      sa += std::abs(h) / n, sq += h * h / n, s3 += h * h * h / n, s4 += h * h * h * h / n;
      hi = std::max(hi, h), lo = std::min(lo, h);
    }
    double gx = 0, gy = 0, area = 0;
    for (std::size_t j = 0; j < g.ny; ++j)
      for (std::size_t i = 0; i + 1 < g.nx; ++i)
        gx += std::pow((m.at(i + 1, j) - m.at(i, j)) / g.dx, 2) /
              static_cast<double>((g.nx - 1) * g.ny);
    for (std::size_t j = 0; j + 1 < g.ny; ++j)
      for (std::size_t i = 0; i < g.nx; ++i)
        gy += std::pow((m.at(i, j + 1) - m.at(i, j)) / g.dy, 2) /
              static_cast<double>(g.nx * (g.ny - 1));
    for (std::size_t j = 0; j + 1 < g.ny; ++j)
      for (std::size_t i = 0; i + 1 < g.nx; ++i) {
        const Eigen::Vector3d p00(0, 0, m.at(i, j)), p10(g.dx, 0, m.at(i + 1, j)),
            p11(g.dx, g.dy, m.at(i + 1, j + 1)), p01(0, g.dy, m.at(i, j + 1));
        area += 0.5 * ((p10 - p00).cross(p11 - p00).norm() + (p11 - p00).cross(p01 - p00).norm());
      }
    const double flat = static_cast<double>((g.nx - 1) * (g.ny - 1)) * g.dx * g.dy;
    const double rq = std::sqrt(sq);
    std::map<std::string, double> reported;
    for (const auto& p : r.roughness.reported()) reported[p.name] = p.value;
    INFO("form " << form);
    CHECK(reported.at("Sa") == Approx(1e3 * sa).epsilon(1e-12));
    CHECK(reported.at("Sq") == Approx(1e3 * rq).epsilon(1e-12));
    CHECK(reported.at("Sp") == Approx(1e3 * hi).epsilon(1e-12));
    CHECK(reported.at("Sv") == Approx(-1e3 * lo).epsilon(1e-12));
    CHECK(reported.at("Sz") == Approx(1e3 * (hi - lo)).epsilon(1e-12));
    CHECK(reported.at("Ssk") == Approx(s3 / (rq * rq * rq)).epsilon(1e-10));
    CHECK(reported.at("Sku") == Approx(s4 / (sq * sq)).epsilon(1e-10));
    CHECK(reported.at("Sdq") == Approx(std::sqrt(gx + gy)).epsilon(0.01));
    CHECK(reported.at("Sdr") == Approx(100 * (area - flat) / flat).epsilon(1e-6));
  }
}
