// The Armarego force against MODEL.md's closed form (no paper needed) and Eq. 20's geometry.
#include <Eigen/Dense>
#include <catch2/catch.hpp>
#include <cmath>

#include "support/builtin_models.hpp"
#include "topomill/force_model.hpp"
#include "topomill/tool_geometry.hpp"

using testing::make_model;

namespace {
// MODEL.md: zero helix, no edge forces, one tooth, alpha in [0, kappa_m], flat slot fed along +X,
// theta measured clockwise from +Y, chip thickness fz sin(theta) sin(alpha).
Eigen::Vector3d closed_form(double theta, double R, double fz, double ktc, double krc, double kac,
                            double km) {
  const double ap = R * (1 - std::cos(km));
  const double s2 = km / 2 - std::sin(2 * km) / 4, c1 = std::sin(km) * std::sin(km) / 2;
  const double st = std::sin(theta), ct = std::cos(theta);
  return {-ktc * fz * ap * st * ct - fz * R * st * st * (krc * s2 + kac * c1),
          ktc * fz * ap * st * st - fz * R * st * ct * (krc * s2 + kac * c1),
          fz * R * st * (krc * c1 - kac * s2)};
}
// The closed form's setting: one zero-helix tooth, no edge forces, a flat slot fed along +X
// (clockwise spindle: theta clockwise from +Y is phi = 90 deg - theta from +X).
auto closed_form_tool() {
  return make_model<topomill::ToolGeometry>("ball_end_constant_lead",
                                            {{"radius", 5}, {"teeth", 1}, {"helix_angle", 0}});
}
auto closed_form_force(double element_angle) {
  return make_model<topomill::ForceModel>("armarego", {{"Ktc", 2000},
                                                       {"Krc", 800},
                                                       {"Kac", 500},
                                                       {"Kte", 0},
                                                       {"Kre", 0},
                                                       {"Kae", 0},
                                                       {"element_angle", element_angle}});
}
topomill::CutState cut_state(const topomill::Vec3& feed, double alpha_min, double alpha_max) {
  topomill::CutState st;
  st.feed_direction = feed;
  st.feed_per_tooth = 0.1;
  st.alpha_min = alpha_min;
  st.alpha_max = alpha_max;
  st.spindle_rate = -1;
  return st;
}
}  // namespace

TEST_CASE("the ball-end force matches MODEL.md's closed form", "[force]") {
  auto tool = closed_form_tool();
  auto force = closed_form_force(0.0045);
  topomill::CutState st = cut_state({1, 0, 0}, 0, M_PI / 2);
  // MODEL.md's printed values, then the closed form at other angles and engagements.
  st.spindle_angle = 0;  // theta = 90 deg
  auto f = force->evaluate(*tool, st).force;
  CHECK(f.x() == Approx(-439.16).margin(0.01));
  CHECK(f.y() == Approx(1000.00).margin(0.01));
  CHECK(f.z() == Approx(3.65).margin(0.01));
  st.spindle_angle = M_PI / 4;  // theta = 45 deg
  f = force->evaluate(*tool, st).force;
  CHECK(f.x() == Approx(-719.58).margin(0.01));
  CHECK(f.y() == Approx(280.42).margin(0.01));
  CHECK(f.z() == Approx(2.58).margin(0.01));
  for (double km : {0.3, 1.0}) {
    for (double theta : {0.4, 1.2, 2.5}) {
      st.alpha_max = km;
      st.spindle_angle = M_PI / 2 - theta;
      const auto g = force->evaluate(*tool, st).force;
      const auto want = closed_form(theta, 5, 0.1, 2000, 800, 500, km);
      CHECK((g - want).norm() == Approx(0).margin(1e-3 * want.norm()));
    }
  }
  // Behind the tool (theta in (180, 360) deg) nothing is in cut.
  st.alpha_max = M_PI / 2;
  st.spindle_angle = M_PI / 2 - 4.0;
  CHECK(force->evaluate(*tool, st).force.norm() == 0.0);
}

TEST_CASE("Eq. 20's tangential, radial and axial directions are orthonormal", "[force]") {
  for (double a : {0.1, 0.7, 1.5})
    for (double t : {0.0, 1.0, 2.0, 4.0}) {
      Eigen::Matrix3d m;
      m << -std::cos(t), -std::sin(a) * std::sin(t), -std::cos(a) * std::sin(t),  //
          std::sin(t), -std::sin(a) * std::cos(t), -std::cos(a) * std::cos(t),    //
          0, std::cos(a), -std::sin(a);
      CHECK((m.transpose() * m - Eigen::Matrix3d::Identity()).norm() == Approx(0).margin(1e-14));
    }
}

TEST_CASE("the load centre is the force-weighted height of the engaged edge", "[force]") {
  auto tool = make_model<topomill::ToolGeometry>("ball_end_loxodrome", {{"radius", 5}});
  auto force = make_model<topomill::ForceModel>("armarego", {});
  topomill::CutState st = cut_state({0, 1, 0}, 0.3, 0.6);
  for (double spindle : {0.0, 1.0, 2.0}) {
    st.spindle_angle = spindle;
    const auto c = force->evaluate(*tool, st);
    if (c.force.norm() == 0) continue;
    CHECK(c.load_centre >= 5 * (1 - std::cos(0.3)) - 1e-12);
    CHECK(c.load_centre <= 5 * (1 - std::cos(0.6)) + 1e-12);
  }
}

// Elements are fixed on the tool; one the CATW's end cuts counts for the part inside. Without that
// share the error would fall only as the element size (a whole element in or out at each end).
TEST_CASE("elements cut by the CATW's ends count in part: second-order convergence", "[force]") {
  auto tool = closed_form_tool();
  topomill::CutState st = cut_state({1, 0, 0}, 0, 0.3077);  // not on any of the grids below
  st.spindle_angle = M_PI / 2 - 1.2;
  const auto want = closed_form(1.2, 5, 0.1, 2000, 800, 500, st.alpha_max);
  double previous = 0;
  for (double deg : {2.0, 1.0, 0.5}) {
    auto force = closed_form_force(deg);
    const double error = (force->evaluate(*tool, st).force - want).norm();
    if (previous > 0) CHECK(std::log2(previous / error) > 1.8);
    previous = error;
  }
}

// The force model tabulates the edge per tool; a second tool must get its own table.
TEST_CASE("one force model serves two tools, each with its own edge", "[force]") {
  auto force = make_model<topomill::ForceModel>("armarego", {});
  topomill::CutState st = cut_state({0, 1, 0}, 0.2, 0.8);
  st.spindle_angle = 0.4;
  for (double helix : {30.0, 10.0, 30.0}) {
    auto tool = make_model<topomill::ToolGeometry>("ball_end_loxodrome",
                                                   {{"radius", 5}, {"helix_angle", helix}});
    auto fresh = make_model<topomill::ForceModel>("armarego", {});
    CHECK(force->evaluate(*tool, st).force == fresh->evaluate(*tool, st).force);
  }
}
