// Edge geometry against docs/model.md's numbers and the defining properties of each edge.
#include <catch2/catch.hpp>
#include <cmath>

#include "support/builtin_models.hpp"
#include "topomill/tool_geometry.hpp"

using testing::make_model;
using topomill::ToolGeometry;

namespace {
constexpr double kDeg = M_PI / 180.0;
}

TEST_CASE("lag angles at alpha = 10 deg, helix 30 deg, match docs/model.md", "[tool]") {
  auto lox = make_model<ToolGeometry>("ball_end_loxodrome", {{"radius", 5}, {"helix_angle", 30}});
  auto lead =
      make_model<ToolGeometry>("ball_end_constant_lead", {{"radius", 5}, {"helix_angle", 30}});
  CHECK(lox->lag(10 * kDeg) / kDeg == Approx(80.6).margin(0.05));
  CHECK(lead->lag(10 * kDeg) / kDeg == Approx(32.6).margin(0.05));
  // Both meet the shank helix with zero lag.
  CHECK(lox->lag(90 * kDeg) == Approx(0).margin(1e-12));
  CHECK(lead->lag(90 * kDeg) == Approx(0).margin(1e-12));
}

TEST_CASE("the closed forms in sin and cos agree with lag and lag_slope", "[tool]") {
  // The fast evaluator and the force model call lag_sc and lag_slope_sc instead of lag and
  // lag_slope; an override that drifted from its function would change every surface silently.
  for (const std::string name : {"ball_end_loxodrome", "ball_end_constant_lead"}) {
    auto tool = make_model<ToolGeometry>(name, {{"radius", 5}, {"helix_angle", 30}});
    for (double a : {0.001, 0.05, 0.3, 0.7, 1.2, M_PI / 2}) {
      INFO(name << " at alpha " << a);
      CHECK(tool->lag_sc(std::sin(a), std::cos(a)) == Approx(tool->lag(a)).margin(1e-13));
      CHECK(tool->lag_slope_sc(std::sin(a), std::cos(a)) ==
            Approx(tool->lag_slope(a)).epsilon(1e-13));
    }
  }
}

TEST_CASE("every edge point lies on the ball and teeth are evenly spaced", "[tool]") {
  for (const std::string name : {"ball_end_loxodrome", "ball_end_constant_lead"}) {
    auto tool = make_model<ToolGeometry>(name, {{"radius", 5}, {"teeth", 3}, {"helix_angle", 30}});
    for (double a : {0.0, 1e-6, 0.01, 0.3, 1.0, M_PI / 2}) {
      for (int j = 0; j < 3; ++j) {
        const auto p = tool->edge_point(j, a, 0.7);
        CHECK(p.norm() == Approx(5.0).epsilon(1e-13));
        CHECK(p.z() == Approx(-5.0 * std::cos(a)).epsilon(1e-13));
      }
      // Tooth j+1 is tooth j turned by 2 pi / 3 about the axis.
      const auto p1 = tool->edge_point(1, a, 0.2);
      const auto r0 = tool->edge_point(0, a, 0.2 + 2 * M_PI / 3);
      CHECK((p1 - r0).norm() == Approx(0).margin(1e-12));
    }
  }
}

TEST_CASE("the loxodrome keeps its helix angle all the way down, the tip excepted", "[tool]") {
  // Helix angle of the edge against the meridian, from a numerical derivative of edge_point:
  // tan(helix) = (circumferential speed) / (meridional speed) = R sin(a) dPsi/da / R.
  auto tool = make_model<ToolGeometry>("ball_end_loxodrome", {{"radius", 5}, {"helix_angle", 30}});
  for (double a : {0.05, 0.2, 0.6, 1.0, 1.4}) {
    const double h = 1e-6;
    const Eigen::Vector3d d =
        (tool->edge_point(0, a + h, 0) - tool->edge_point(0, a - h, 0)) / (2 * h);
    const double meridional = 5.0;  // |dp/da| along the meridian is R
    const double circumferential =
        std::sqrt(std::max(0.0, d.squaredNorm() - meridional * meridional));
    CHECK(std::atan2(circumferential, meridional) / kDeg == Approx(30.0).margin(1e-4));
    CHECK(tool->lag_slope(a) ==
          Approx((tool->lag(a + h) - tool->lag(a - h)) / (2 * h)).epsilon(1e-6));
  }
  // Below tip_angle the lag is held: finite at the tip itself.
  CHECK(std::isfinite(tool->edge_point(0, 0.0, 0).x()));
  CHECK(tool->min_polar_angle() == Approx(0.01 * kDeg));
}
