// The ideal follow's second rule for ending a tooth's walk in one direction, beside the bound.
#pragma once

#include <cmath>

namespace topomill::plugins {

// After two passages in a row each higher than the one before, or off the ball (past the node).
// A rule, not a proof: the passages' heights follow the envelope, which has a single minimum; the
// bound (PassageGeometry::ends_by_bound) usually ends the walk first, and the brute-force tests
// (tests/integration/near_axis_test.cpp and the others against brute forces) hold both to it.
class RiseCount {
 public:
  void add(double lowest) {
    if (!std::isfinite(lowest))
      ++count_;
    else
      count_ = lowest > last_ ? count_ + 1 : 0, last_ = lowest;
  }
  bool done() const { return count_ >= 2; }

 private:
  double last_ = INFINITY;
  int count_ = 0;
};

}  // namespace topomill::plugins
