// What a pass swept, as the effects' material test asks it: the solid the cutter fills, moved
// along a straight line.
#pragma once

#include <algorithm>

#include "topomill/types.hpp"

namespace topomill {

// Whether q, from a point of a straight pass's centre line (along the unit `feed`), lies in what
// that pass swept: within R of the line for a ball (ring 0); for a tube of radius R on a ring
// about the unit axis, the solid torus with its bottom disc filled, swept along the line.
inline bool in_swept(const Vec3& q, const Vec3& feed, const Vec3& axis, double R, double ring) {
  const Vec3 across = q - q.dot(feed) * feed;
  if (ring == 0) return across.squaredNorm() < R * R;
  const double up = across.dot(axis), out = std::max(0.0, (across - up * axis).norm() - ring);
  return out * out + up * up < R * R;
}

}  // namespace topomill
