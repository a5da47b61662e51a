// Heights between the nodes of a surface: Keys' cubic convolution (a = -1/2: exact for
// quadratics, continuous slope), the interpolation `compare` states for its common grid and its
// registration. A point is given where the nodes of its cell that weigh in are valid; a missing
// node around the cell is completed as one beyond the map's edge is (Keys' end condition), so a
// measurement's scattered dropouts cost the points at them, not their whole neighbourhood.
#pragma once

#include <functional>
#include <optional>
#include <utility>

#include "metrology/surface.hpp"

namespace topomill {

class CubicSampler {
 public:
  explicit CubicSampler(const Surface& surface) : s_(surface) {}
  // The height at (x, y) in mm, or nothing outside the nodes or in a cell with an invalid node.
  std::optional<double> at(double x, double y) const;

 private:
  const Surface& s_;
};

// The surface sampled on `grid` (cubic); nodes it cannot give are invalid. With `where`, node
// (x, y) takes the height at where(x, y) (a moved frame: registration's alignment).
Surface resample(const Surface& surface, const Grid& grid,
                 const std::function<std::pair<double, double>(double, double)>& where = {});

}  // namespace topomill
