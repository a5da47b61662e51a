// The effects' material test of what a pass swept: a ball's cylinder, a ringed cutter's solid
// torus with its bottom filled and its body above, against points placed by hand about it.
#include <catch2/catch.hpp>

#include "run/swept_solid.hpp"

using topomill::in_swept;
using topomill::Vec3;

TEST_CASE("a ball sweeps the cylinder of its radius about the pass", "[unit][swept]") {
  const Vec3 feed(0, 1, 0), axis(0, 0, 1);
  CHECK(in_swept({0.99, 7.0, 0.0}, feed, axis, 1.0, 0.0));
  CHECK(in_swept({0.6, -3.0, -0.79}, feed, axis, 1.0, 0.0));
  CHECK_FALSE(in_swept({0.6, 0.0, -0.81}, feed, axis, 1.0, 0.0));
  CHECK_FALSE(in_swept({1.01, 0.0, 0.0}, feed, axis, 1.0, 0.0));
}

TEST_CASE("a ringed cutter sweeps its solid torus, its bottom filled, and its body",
          "[unit][swept]") {
  // Tube r = 0.5 on the ring c = 1.5: across the pass, out to c + r at the centre plane, r
  // deep over the bottom, and the tube's circle between.
  const Vec3 feed(0, 1, 0), axis(0, 0, 1);
  const double r = 0.5, c = 1.5;
  CHECK(in_swept({1.99, 4.0, 0.0}, feed, axis, r, c));
  CHECK_FALSE(in_swept({2.01, 4.0, 0.0}, feed, axis, r, c));
  CHECK(in_swept({0.3, 0.0, -0.49}, feed, axis, r, c));  // over the bottom
  CHECK_FALSE(in_swept({0.3, 0.0, -0.51}, feed, axis, r, c));
  CHECK(in_swept({-1.5 - 0.3, 0.0, -0.39}, feed, axis, r, c));  // 0.3^2 + 0.39^2 < 0.25
  CHECK_FALSE(in_swept({-1.5 - 0.3, 0.0, -0.41}, feed, axis, r, c));
  // Above the centre plane, the body: a cylinder out to c + r, however high.
  CHECK(in_swept({1.99, 0.0, 3.0}, feed, axis, r, c));
  CHECK_FALSE(in_swept({2.01, 0.0, 3.0}, feed, axis, r, c));
  // A sharp flat end (r = 0): its bottom disc, and its body above it.
  CHECK(in_swept({1.4, 0.0, 0.3}, feed, axis, 0.0, c));
  CHECK_FALSE(in_swept({1.6, 0.0, 0.3}, feed, axis, 0.0, c));
  CHECK_FALSE(in_swept({1.4, 0.0, -0.01}, feed, axis, 0.0, c));
  // A tilted axis: the same solid about it.
  const Vec3 tilted = Vec3(0.6, 0, 0.8);
  CHECK(in_swept(-0.45 * tilted, feed, tilted, r, c));
  CHECK_FALSE(in_swept(-0.55 * tilted, feed, tilted, r, c));
  CHECK(in_swept(5.0 * tilted, feed, tilted, r, c));
}
