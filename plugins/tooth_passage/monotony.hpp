// The one question the follows ask of the bounds (PassageGeometry::monotony): over a stretch of
// a window, is the phase monotone, how fast can it turn, and is its turn exact from two probes.
#pragma once

#include <cmath>

namespace topomill::plugins {

// A stretch [a, b] of a window (either order) to ask the phase about, and where known the node's
// distance `rho` from the axis at a time within `reach` of every time of it (NaN when not known:
// then only a span over the stretch can prove anything).
struct PhaseStretch {
  double a, b;
  double rho = NAN, reach = 0;
};

// What the bounds prove of the phase G over a stretch.
struct PhaseMonotony {
  bool monotone = false;  // G' > 0 in the spindle's sense all along
  // |G'| <= top, where a span proved it; +inf where the node's distance did (the sign is then all
  // that is known).
  double top = INFINITY;
  // The centre keeps to a strip that leaves the node out (a vertical tool on a fixed frame, the
  // node off its line's strip): the turn between any two times of the window is exact from their
  // probes (PassageGeometry::advance).
  bool any_turn_exact = false;
};

}  // namespace topomill::plugins
