// PassageGeometry's reference walk: whole revolutions outwards from the bound's bottom, each
// solved exactly, until the bound proves nothing farther can lower the node.
#include "passage_geometry.hpp"

#include <algorithm>
#include <cstdint>

namespace topomill::plugins {

double PassageGeometry::walk(double t_b, std::vector<Crossing>& roots, std::uint64_t& visited,
                             double below, Crossing* lowest) const {
  const double t_lo = this->t_lo(), t_hi = this->t_hi(), rev = s_.rev;
  double best = INFINITY;
  for (int dir : {+1, -1}) {
    for (int m = (dir > 0 ? 0 : 1); m < 100000; ++m) {
      // Revolution m from t_b: [t_b + (m - 1/2) rev, t_b + (m + 1/2) rev], and beyond its near
      // edge all later ones: past the bound's bottom (t_b is within a 20th of a tooth period of
      // it), if the bound is too high there, nothing from here on can lower the node.
      const double lo = t_b + (dir * m - 0.5) * rev, hi = lo + rev;
      if (hi < t_lo || lo > t_hi) break;
      const double edge = dir > 0 ? lo : hi;
      if (m > 0 && ends_by_bound(t_b, dir, edge, std::min(best, below))) break;
      double limit = std::min(best, below);
      roots.clear();
      crossings_in(-1, std::max(lo, t_lo), std::min(hi, t_hi), limit, roots);  // every tooth
      for (const Crossing& r : roots) {
        const Probe& q = r.q;
        ++visited;
        if (q.over && std::isfinite(q.height) && q.height < best) {
          best = q.height;
          if (lowest) *lowest = r;
        }
      }
    }
  }
  return best;
}

double PassageGeometry::axis_distance(double t) const {
  if (!tilted_) return distance(t);
  const Vec3 c = table_(t);
  const double dx = x_ - c.x(), dy = y_ - c.y(), r2 = dx * dx + dy * dy;
  if (!(r2 < s_.R2)) return INFINITY;
  const Vec3 p = to_tool(t) * Vec3(dx, dy, -std::sqrt(s_.R2 - r2));
  return std::sqrt(p.x() * p.x() + p.y() * p.y());
}

double PassageGeometry::tip_height(double t0) const {
  const Probe q = probe(0, t0);
  return q.over && q.rho < kOnAxis ? q.height : INFINITY;
}

}  // namespace topomill::plugins
