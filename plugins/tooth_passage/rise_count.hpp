// The rule that ends a walk along a pass in one direction when no height bound does.
#pragma once

#include <cmath>

namespace topomill::plugins {

// When a walk in one direction ends: after two passages in a row each higher than the one
// before, or off the ball (past the node). Both walks stop by it, so they stop alike.
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
