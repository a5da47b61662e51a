// The Armarego force against docs/model.md's closed form (no paper needed) and Eq. 20's geometry.
#include <Eigen/Dense>
#include <catch2/catch.hpp>
#include <cmath>

#include "support/builtin_models.hpp"
#include "topomill/force_model.hpp"
#include "topomill/tool_geometry.hpp"

using testing::make_model;

namespace {
// docs/model.md: zero helix, no edge forces, one tooth, alpha in [0, kappa_m], flat slot fed along
// +X, theta measured clockwise from +Y, chip thickness fz sin(theta) sin(alpha).
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

TEST_CASE("the ball-end force matches docs/model.md's closed form", "[force]") {
  auto tool = closed_form_tool();
  auto force = closed_form_force(0.0045);
  topomill::CutState st = cut_state({1, 0, 0}, 0, M_PI / 2);
  // docs/model.md's printed values, then the closed form at other angles and engagements.
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

namespace {
struct Coefficients {
  double ktc, krc, kac, kte, kre, kae;
};
struct Quadrature {
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
  double load_centre = 0;
};
// Eq. 18-21 by a midpoint rule of 20000 pieces per tooth, written from docs/model.md and not from
// the plugin: the element's azimuth and its edge length from edge_point (a central difference for
// the length), Eq. 19's chip as the feed projected on the ball normal, Eq. 20 in Lee and
// Altintas' angle theta (clockwise from +Y, a cw tool). A ccw tool is the mirror image (x -> -x)
// of a cw one: its element at azimuth phi is the cw element at pi - phi under the mirrored feed,
// and its force the mirrored force. The load centre: the force-weighted mean height above the
// tip, weights |dF| per element and tooth.
Quadrature quadrature(const topomill::ToolGeometry& tool, const Coefficients& k,
                      const Eigen::Vector3d& feed, double fz, double a_lo, double a_hi,
                      double spindle, bool ccw) {
  const int n = 20000;
  const double R = tool.radius(), da = (a_hi - a_lo) / n;
  const Eigen::Vector3d f = ccw ? Eigen::Vector3d(-feed.x(), feed.y(), feed.z()) : feed;
  Quadrature q;
  double weight = 0, moment = 0;
  for (int j = 0; j < tool.teeth(); ++j)
    for (int m = 0; m < n; ++m) {
      const double a = a_lo + (m + 0.5) * da;
      const auto p = tool.edge_point(j, a, spindle);
      const double phi = std::atan2(p.y(), p.x());
      const double ds =
          (tool.edge_point(j, a + 1e-6, spindle) - tool.edge_point(j, a - 1e-6, spindle)).norm() /
          2e-6 * da;
      const double db = R * da;
      const double theta = M_PI / 2 - (ccw ? M_PI - phi : phi);
      const double sa = std::sin(a), ca = std::cos(a), st = std::sin(theta), ct = std::cos(theta);
      const double t = fz * f.dot(Eigen::Vector3d(sa * st, sa * ct, -ca));
      if (t <= 0) continue;
      const double ft = k.kte * ds + k.ktc * t * db, fr = k.kre * ds + k.krc * t * db,
                   fa = k.kae * ds + k.kac * t * db;
      Eigen::Vector3d d(-ft * ct - fr * sa * st - fa * ca * st,
                        ft * st - fr * sa * ct - fa * ca * ct, fr * ca - fa * sa);
      if (ccw) d.x() = -d.x();
      q.force += d;
      weight += d.norm(), moment += d.norm() * R * (1 - ca);
    }
  q.load_centre = weight > 0 ? moment / weight : 0;
  return q;
}
}  // namespace

TEST_CASE("the force equals a quadrature of Eq. 18-21 with helix, edge forces, teeth, directions",
          "[force]") {
  // Table 3's coefficients (edge terms included), three teeth, both edge models, both spindle
  // directions, level and sloped feeds, several spindle angles and engagements.
  const Coefficients k{1512.8, 656.8, -1123.4, 198.5, 110.1, -42.4};
  auto force = make_model<topomill::ForceModel>("armarego", {{"Ktc", k.ktc},
                                                             {"Krc", k.krc},
                                                             {"Kac", k.kac},
                                                             {"Kte", k.kte},
                                                             {"Kre", k.kre},
                                                             {"Kae", k.kae},
                                                             {"element_angle", 0.005}});
  const double slope = 20 * M_PI / 180;
  for (const char* edge : {"ball_end_loxodrome", "ball_end_constant_lead"})
    for (bool ccw : {false, true})
      for (const Eigen::Vector3d& feed :
           {Eigen::Vector3d(0, 1, 0), Eigen::Vector3d(0, std::cos(slope), -std::sin(slope)),
            Eigen::Vector3d(std::cos(slope), 0, std::sin(slope))})
        for (double spindle : {0.3, 1.9, 4.0}) {
          auto tool = make_model<topomill::ToolGeometry>(
              edge, {{"radius", 5}, {"teeth", 3}, {"helix_angle", 30}});
          topomill::CutState st = cut_state(feed, 0.15, 0.9);
          st.spindle_rate = ccw ? 1 : -1;
          st.spindle_angle = spindle;
          const auto got = force->evaluate(*tool, st);
          const auto want = quadrature(*tool, k, feed, 0.1, 0.15, 0.9, spindle, ccw);
          INFO(edge << (ccw ? " ccw" : " cw") << ", feed " << feed.transpose() << ", spindle "
                    << spindle << ": " << got.force.transpose() << " N against "
                    << want.force.transpose() << " N; load centre " << got.load_centre
                    << " against " << want.load_centre << " mm");
          CHECK((got.force - want.force).norm() < 2e-4 * want.force.norm() + 0.05);
          CHECK(got.load_centre == Approx(want.load_centre).epsilon(2e-4));
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

TEST_CASE("runout thickens the chip by how much farther a tooth reaches than the one before",
          "[force][runout]") {
  // Helix-free teeth, fed along +X, tooth 1 (j = 0) pointing along the feed. With the ball centre
  // e off the spindle axis towards tooth 1, an element at azimuth phi reaches e cos(psi - phi)
  // out, where the tooth before it at the same place reached e cos(psi_before - phi), psi_before
  // = psi - 2 pi / N in the spindle's sense: the chip grows by the difference times sin(alpha).
  // Two teeth: tooth 1 reaches 2e farther than tooth 2 did, so it cuts as the runout-free tool
  // does at fz + 2e (and at fz - 2e with the offset turned half round, towards tooth 2); the
  // other tooth, pointing back, is out of the cut either way.
  // Four teeth: tooth 1 reaches e farther (fz + e); the tooth a quarter turn behind it in the
  // spindle's sense (at +90 deg when turning clockwise, -90 counter-clockwise) reached e farther
  // towards its own azimuth then than it does now, and is out; the one a quarter turn ahead
  // reaches e farther than its predecessor did, across the feed: it cuts as a runout-free tool
  // fed towards it at e does.
  auto force = closed_form_force(0.0045);
  const double fz = 0.1, e = 0.004;
  for (int teeth : {2, 4}) {
    auto tool = make_model<topomill::ToolGeometry>(
        "ball_end_constant_lead", {{"radius", 5}, {"teeth", teeth}, {"helix_angle", 0}});
    for (double rate : {-1.0, 1.0}) {
      INFO(teeth << " teeth, spindle rate " << rate);
      auto state = [&](const topomill::Vec3& feed, double feed_per_tooth, double runout,
                       double angle) {
        topomill::CutState st = cut_state(feed, 0, M_PI / 2);
        st.spindle_rate = rate;
        st.feed_per_tooth = feed_per_tooth;
        st.spindle_angle = -tool->tooth_angle(0);  // tooth 1 along +X
        st.runout = runout;
        st.runout_angle = tool->tooth_angle(0) + angle;
        return st;
      };
      const topomill::Vec3 along(1, 0, 0), ahead(0, rate, 0);
      auto f = [&](const topomill::CutState& st) { return force->evaluate(*tool, st).force; };
      const topomill::Vec3 with = f(state(along, fz, e, 0));
      const topomill::Vec3 want =
          teeth == 2 ? f(state(along, fz + 2 * e, 0, 0))
                     : topomill::Vec3(f(state(along, fz + e, 0, 0)) + f(state(ahead, e, 0, 0)));
      CHECK((with - want).norm() <= 1e-9 * want.norm());
      if (teeth == 2) {
        const topomill::Vec3 turned = f(state(along, fz, e, M_PI)),
                             less = f(state(along, fz - 2 * e, 0, 0));
        CHECK((turned - less).norm() <= 1e-9 * less.norm());
      }
    }
  }
}

TEST_CASE("with one tooth runout leaves the chip as it is", "[force][runout]") {
  // The tooth before is the same tooth a turn earlier, offset the same way: no reach gained.
  auto force = closed_form_force(0.0045);
  auto tool = closed_form_tool();
  topomill::CutState st = cut_state({1, 0, 0}, 0, M_PI / 2);
  for (double angle : {0.0, 1.0, 2.5, 4.0}) {
    st.spindle_angle = angle;
    st.runout = 0;
    const topomill::Vec3 plain = force->evaluate(*tool, st).force;
    st.runout = 0.01, st.runout_angle = 0.7;
    CHECK((force->evaluate(*tool, st).force - plain).norm() <= 1e-9 * (1 + plain.norm()));
  }
}
