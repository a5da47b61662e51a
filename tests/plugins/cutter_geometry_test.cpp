// The cutters other than the ball end against their defining geometry: the torus their edges lie
// on, the ball end they become at r = D/2, and the projects' definition of an insert's rakes.
#include <catch2/catch.hpp>
#include <cmath>

#include "support/builtin_models.hpp"
#include "topomill/error.hpp"
#include "topomill/tool_geometry.hpp"

using testing::make_model;
using topomill::ToolGeometry;
using topomill::Vec3;

namespace {
constexpr double kDeg = M_PI / 180.0;

// Distance of p from the tube of radius r centred on the ring c about Z in the plane z = 0.
double off_torus(const Vec3& p, double c, double r) {
  return std::hypot(std::hypot(p.x(), p.y()) - c, p.z()) - r;
}
}  // namespace

TEST_CASE("a bull-nose with r = D/2 is the constant-lead ball end, to the bit", "[tool][cutter]") {
  auto ball = make_model<ToolGeometry>("ball_end_constant_lead",
                                       {{"radius", 5}, {"teeth", 3}, {"helix_angle", 30}});
  auto bull = make_model<ToolGeometry>(
      "bull_nose", {{"diameter", 10}, {"corner_radius", 5}, {"teeth", 3}, {"helix_angle", 30}});
  CHECK(bull->ring() == 0.0);
  CHECK_FALSE(bull->has_bottom());
  for (double a : {0.0, 1e-7, 0.2, 0.9, M_PI / 2})
    for (int j = 0; j < 3; ++j) {
      INFO("alpha " << a << ", tooth " << j);
      const Vec3 p = ball->edge_point(j, a, 0.37), q = bull->edge_point(j, a, 0.37);
      CHECK(p.x() == q.x());
      CHECK(p.y() == q.y());
      CHECK(p.z() == q.z());
      CHECK(ball->lag_slope(a) == bull->lag_slope(a));
    }
}

TEST_CASE("bull-nose and flat-end edges lie on their torus and bottom", "[tool][cutter]") {
  for (const auto& [name, corner] :
       {std::pair<std::string, double>{"bull_nose", 1.5}, {"flat_end", 0.4}, {"flat_end", 0.0}}) {
    INFO(name << ", corner " << corner);
    auto tool = make_model<ToolGeometry>(
        name, {{"diameter", 8}, {"corner_radius", corner}, {"teeth", 4}, {"helix_angle", 35}});
    const double c = 4 - corner;
    CHECK(tool->ring() == c);
    CHECK(tool->radius() == corner);
    CHECK(tool->reach() == Approx(4.0).epsilon(1e-15));
    CHECK(tool->has_bottom());
    for (double a : {0.0, 0.3, 1.1, M_PI / 2})
      for (int j = 0; j < 4; ++j)
        CHECK(off_torus(tool->edge_point(j, a, 1.3), c, corner) == Approx(0).margin(1e-14));
    // The bottom: flat at the tube's lowest point, radial at the edge's lowest lag.
    for (double rho : {0.0, 0.5 * c, 0.99 * c}) {
      const Vec3 b = tool->bottom_point(1, rho, 0.4), e = tool->edge_point(1, 0.0, 0.4);
      CHECK(b.z() == -corner);
      CHECK(std::hypot(b.x(), b.y()) == Approx(rho).margin(1e-14));
      if (rho > 0)
        CHECK(std::atan2(b.y(), b.x()) == Approx(std::atan2(e.y(), e.x())).margin(1e-14));
    }
    // Constant lead: the lag's turn per mm of height is the side's tan(gamma) / (D/2).
    if (corner > 0) {
      const double a0 = 0.4, a1 = 0.5;
      const double turn = tool->lag(a0) - tool->lag(a1);
      const double rise = corner * (std::cos(a0) - std::cos(a1));
      CHECK(turn / rise == Approx(std::tan(35 * kDeg) / 4).epsilon(1e-12));
    }
  }
}

TEST_CASE("a corner radius above D/2 is refused at its key", "[tool][cutter]") {
  try {
    make_model<ToolGeometry>("bull_nose", {{"diameter", 8}, {"corner_radius", 4.5}});
    FAIL("accepted");
  } catch (const std::exception& e) {
    const std::string what = e.what();
    CHECK(what.find("key 'corner_radius'") != std::string::npos);
    CHECK(what.find("more than half the diameter") != std::string::npos);
  }
}

TEST_CASE("a round insert's edge is the tube's lower half, in a half-plane turned by gamma_f",
          "[tool][cutter]") {
  auto tool = make_model<ToolGeometry>(
      "round_insert", {{"diameter", 10}, {"insert_radius", 5}, {"teeth", 2}, {"radial_rake", 6}});
  CHECK(tool->first_polar_angle() == -M_PI / 2);
  CHECK(tool->reach() == Approx(10).epsilon(1e-15));
  CHECK_FALSE(tool->has_bottom());
  for (double a : {-M_PI / 2, -0.7, 0.0, 0.4, M_PI / 2}) {
    const Vec3 p = tool->edge_point(1, a, 0.25);
    CHECK(off_torus(p, 5, 5) == Approx(0).margin(1e-14));
    // Every point of insert 1 at the azimuth of its half-plane: tooth angle + spindle + rake.
    if (std::hypot(p.x(), p.y()) > 1e-9) {
      const double az =
          std::remainder(std::atan2(p.y(), p.x()) - (M_PI + 0.25 + 6 * kDeg), 2 * M_PI);
      CHECK(az == Approx(0).margin(1e-13));
    }
  }
}

TEST_CASE("a large insert on a small circle ends at the axis", "[tool][cutter]") {
  auto tool = make_model<ToolGeometry>("round_insert", {{"diameter", 6}, {"insert_radius", 5}});
  // c + ri sin(alpha) = 0: alpha = -asin(3/5).
  CHECK(tool->first_polar_angle() == Approx(-std::asin(0.6)).margin(1e-12));
  CHECK(tool->section(tool->first_polar_angle()).x() >= 0);
}

TEST_CASE("an insert's axial rake follows the projects' definition", "[tool][cutter]") {
  // surf-topo and TIDE: a point l = ri sin(alpha) along the insert and z = ri (1 - cos(alpha))
  // above its lowest lies D/2 + l + z sin(gamma_p) from the axis, z cos(gamma_p) up; written here
  // from l, the insert's own coordinate, as TIDE's zeta(l) = (ri - sqrt(ri^2 - l^2)) cos(gamma_p).
  const double gp = 12 * kDeg, ri = 4;
  auto tool = make_model<ToolGeometry>(
      "round_insert", {{"diameter", 20}, {"insert_radius", ri}, {"axial_rake", 12}});
  for (double l : {-3.9, -1.0, 0.0, 0.7, 2.5, 4.0}) {
    const double z = ri - std::sqrt(ri * ri - l * l);
    const auto s = tool->section(std::asin(l / ri));
    CHECK(s.x() == Approx(10 + l + z * std::sin(gp)).epsilon(1e-14));
    CHECK(s.y() + ri == Approx(z * std::cos(gp)).margin(1e-14));
  }
}

TEST_CASE("an insert reaches as far as its section's farthest point", "[tool][cutter]") {
  // A negative axial rake folds the edge back before alpha = 90 deg: the reach is the section's
  // widest, found here by scanning it; a positive one (or none) ends at 90 deg.
  for (double rake : {-30.0, -8.0, 0.0, 8.0, 30.0}) {
    auto tool = make_model<ToolGeometry>(
        "round_insert", {{"diameter", 20}, {"insert_radius", 4}, {"axial_rake", rake}});
    double widest = -INFINITY;
    constexpr int kSamples = 200000;
    for (int k = 0; k <= kSamples; ++k)
      widest = std::max(widest, tool->section(M_PI / 2 * k / kSamples).x());
    INFO("axial rake " << rake);
    CHECK(tool->reach() == Approx(widest).epsilon(1e-10));
    CHECK(tool->reach() >= widest - 1e-12);
  }
}
