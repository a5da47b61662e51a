// How fast the ball point over a node moves when the node's plan offset from the centre does: the
// lift into a tilted tool's frame (PassageGeometry::lifted_rates, land, next_gap).
#pragma once

#include <cmath>

namespace topomill::plugins {

// The lift P(q) = (q, -sqrt(R^2 - |q|^2)) of a plan offset q that stays within `plan` of the
// centre and moves at most at v with acceleration at most A: |P'| <= L v with L = R / hz,
// hz = sqrt(R^2 - plan^2) (|P'|^2 = |q'|^2 + (q . q')^2 / (R^2 - |q|^2)), and |P''| <= accel
// (the same differentiated once more); a fixed rotation into the tool frame keeps both. hz is
// 0 off the ball, and the bounds then meaningless.
// tests/plugins/tooth_passage/passage_geometry_phase_test.cpp samples them.
struct BallLift {
  double hz, L, accel;
};
inline BallLift ball_lift_bounds(double R, double plan, double v, double A) {
  const double hz = plan < R ? std::sqrt(R * R - plan * plan) : 0.0;
  return {hz, R / hz, A + (v * v + plan * A) / hz + plan * plan * v * v / (hz * hz * hz)};
}

}  // namespace topomill::plugins
