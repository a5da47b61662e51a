#include "catw.hpp"

#include <algorithm>
#include <cmath>

namespace topomill {

double catw_chord_depth(double R, double ap, double r) {
  const double k = 1.0 / r;  // 0 for a plane
  return (2.0 * ap - ap * ap * k) / (2.0 * ((R - ap) * k + 1.0));
}

double catw_kappa(double R, double ap, double r) {
  if (!(R > 0)) return M_PI / 2;  // a sharp corner: the whole corner, a point, may cut
  const double o1h3 = R - catw_chord_depth(R, ap, r);
  return std::acos(std::clamp(o1h3 / R, -1.0, 1.0));
}

}  // namespace topomill
