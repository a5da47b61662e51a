#include "swept_path.hpp"

#include <algorithm>

namespace topomill {

SweptPath::SweptPath(const ToolPath& path) {
  for (std::size_t p = 0; p < path.passes(); ++p) {
    const auto& w = path.pass(p).waypoints;
    for (std::size_t k = 0; k + 1 < w.size(); ++k) {
      if (k % kChunk == 0)
        chunks_.push_back({segments_.size(), segments_.size(), w[k].centre, w[k].centre});
      segments_.push_back({w[k].centre, w[k + 1].centre, p, path.waypoint_time(p, k + 1)});
      Chunk& c = chunks_.back();
      c.last = segments_.size();
      c.lo = c.lo.cwiseMin(w[k + 1].centre), c.hi = c.hi.cwiseMax(w[k + 1].centre);
    }
  }
}

double SweptPath::distance(const Vec3& x, const Vec3& a, const Vec3& b) {
  const Vec3 d = b - a;
  const double len2 = d.squaredNorm();
  const double u = len2 > 0 ? std::clamp((x - a).dot(d) / len2, 0.0, 1.0) : 0.0;
  return (x - a - u * d).norm();
}

bool SweptPath::swept(std::size_t p, double until, const Vec3& x, double R) const {
  for (const Chunk& c : chunks_) {
    const std::size_t pass = segments_[c.first].pass;
    if (pass > p) break;  // segments are in pass order
    const Vec3 gap = (c.lo - x).cwiseMax(x - c.hi).cwiseMax(0.0);
    if (gap.squaredNorm() >= R * R) continue;
    for (std::size_t i = c.first; i < c.last; ++i) {
      const Segment& s = segments_[i];
      // On pass p, only what the centre left before `until` (segments are in time order: the
      // rest of the chunk is later still).
      if (s.pass == p && s.t_end > until) break;
      if (distance(x, s.a, s.b) < R) return true;
    }
  }
  return false;
}

}  // namespace topomill
