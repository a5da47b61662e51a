// CATW (Eq. 39-42) against the intersection of the tool and workpiece circles computed directly.
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>

#include "catw.hpp"

namespace {
// Distance from the tool centre O1 to the chord where the circles meet, for centres D apart:
// x = (D^2 + R^2 - r^2) / (2 D), measured towards the workpiece centre (convex).
double o1h3_convex(double R, double ap, double r) {
  const double D = r + R - ap;
  return (D * D + R * R - r * r) / (2 * D);
}
// Concave: the workpiece centre is on the tool's side, D = r - (R - ap); the chord lies beyond O1.
double o1h3_concave(double R, double ap, double r) {
  const double D = r - (R - ap);
  return (r * r - R * R - D * D) / (2 * D);
}
}  // namespace

TEST_CASE("chord depth and kappa match the circle intersection", "[catw]") {
  for (double r : {3.0, 20.0, 50.0, 1e4}) {
    for (double ap : {0.01, 0.3, 2.0}) {
      CHECK(topomill::catw_chord_depth(5, ap, r) ==
            Approx(5 - o1h3_convex(5, ap, r)).epsilon(1e-10));
      CHECK(topomill::catw_kappa(5, ap, r) ==
            Approx(std::acos(o1h3_convex(5, ap, r) / 5)).epsilon(1e-10));
    }
  }
  for (double r : {6.0, 20.0}) {
    CHECK(topomill::catw_chord_depth(5, 0.3, -r) ==
          Approx(5 - o1h3_concave(5, 0.3, r)).epsilon(1e-10));
  }
}

TEST_CASE("the flat limit is exactly ap, with no inf/inf", "[catw]") {
  const double inf = std::numeric_limits<double>::infinity();
  CHECK(topomill::catw_chord_depth(5, 0.3, inf) == 0.3);
  CHECK(topomill::catw_kappa(5, 0.3, inf) == Approx(std::acos(4.7 / 5)).epsilon(1e-15));
  CHECK(topomill::catw_chord_depth(5, 0.3, 1e15) == Approx(0.3).epsilon(1e-12));
  // Convex curvature shrinks the contact, concave widens it.
  CHECK(topomill::catw_kappa(5, 0.3, 20) < topomill::catw_kappa(5, 0.3, inf));
  CHECK(topomill::catw_kappa(5, 0.3, -20) > topomill::catw_kappa(5, 0.3, inf));
}
