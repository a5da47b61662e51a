// What a pass swept, as the effects' material test asks it: the solid the cutter fills, moved
// along a straight line.
#pragma once

#include <algorithm>

#include "topomill/types.hpp"

namespace topomill {

// Whether q, from a point of a straight pass's centre line (along the unit `feed`), lies in what
// that pass swept: within R of the line for a ball (ring 0). For a tube of radius R on a ring
// about the unit axis: below the tube's centre plane the solid torus with its bottom disc
// filled, above it the cutter's body, a cylinder out to ring + R (an end mill's side, a face
// mill's body), each swept along the line.
inline bool in_swept(const Vec3& q, const Vec3& feed, const Vec3& axis, double R, double ring) {
  const Vec3 across = q - q.dot(feed) * feed;
  if (ring == 0) return across.squaredNorm() < R * R;
  const double up = across.dot(axis), lateral = (across - up * axis).norm();
  if (up >= 0) return lateral < ring + R;
  const double out = std::max(0.0, lateral - ring);
  return out * out + up * up < R * R;
}

}  // namespace topomill
