// Test the model on its own, against answers that do not come from it.
#define CATCH_CONFIG_MAIN
#include <catch2/catch.hpp>
#include <cmath>

#include "ball_end_worn.hpp"

namespace {
topomill::Params params(double radius, double wear) {
  topomill::Params p;
  p.set("radius", radius);
  p.set("wear", wear);
  p.set("teeth", std::int64_t{2});
  p.set("helix_angle", 30.0);
  return p;
}
}  // namespace

TEST_CASE("wear shrinks the edge's sphere") {
  worn::BallEndWorn tool(params(5.0, 0.02));
  CHECK(tool.radius() == Approx(4.98));
  for (double a : {0.1, 0.8, 1.5}) CHECK(tool.edge_point(1, a, 0.3).norm() == Approx(4.98));
}

TEST_CASE("too much wear is refused with the key to blame") {
  CHECK_THROWS_AS(worn::BallEndWorn(params(5.0, 5.0)), topomill::ParamError);
}
