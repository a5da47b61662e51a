// Heights between the nodes of a surface: Keys' cubic convolution (a = -1/2: exact for
// quadratics, continuous slope), the interpolation `compare` states for its common grid and its
// registration. A point counts only where its 4 x 4 nodes are all valid.
#pragma once

#include <functional>
#include <optional>
#include <utility>

#include "metrology/surface.hpp"

namespace topomill {

class CubicSampler {
 public:
  explicit CubicSampler(const Surface& surface) : s_(surface) {}
  // The height at (x, y) in mm, or nothing outside the nodes or next to an invalid one.
  std::optional<double> at(double x, double y) const;

 private:
  const Surface& s_;
};

// The surface sampled on `grid` (cubic); nodes it cannot give are invalid. With `where`, node
// (x, y) takes the height at where(x, y) (a moved frame: registration's alignment).
Surface resample(const Surface& surface, const Grid& grid,
                 const std::function<std::pair<double, double>(double, double)>& where = {});

}  // namespace topomill
