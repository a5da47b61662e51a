#include "node_walk.hpp"

#include <algorithm>

namespace topomill::plugins {

double node_height_reference(const PassageSetup& s, double x, double y, NodeCounts& counts,
                             std::vector<std::pair<double, std::size_t>>& order,
                             std::vector<PassageGeometry::Crossing>& roots) {
  s.near(x, y, order);
  double best = INFINITY;
  for (const auto& entry : order) {
    if (!s.parallel && entry.first >= best) break;  // none left can lower the node (near())
    const std::size_t p = entry.second;
    const double t0 = s.level_time(p, x, y);
    if (std::isnan(t0)) continue;
    const auto radii = s.contact_radii(p, t0);
    const PassageGeometry geo(s, p, x, y, radii.first, radii.second);
    // The walk starts from the bound's bottom: a corrected envelope wiggles with the tooth
    // period and a golden section on it can stop in any dip, while its floor (the nominal centre
    // moved by the correction's whole range) has a single minimum near the ball's lowest passage
    // over the node, or where it may have two (FloorTail) a bound of the rest (lowest_bound).
    const double t_b = geo.bottom_near([&](double t) { return geo.bound(t); }, t0);
    const double slack = s.wiggles ? kFloorSlack : 0.0;
    if (geo.lowest_bound(t_b, best + slack) - slack >= best) continue;  // it cannot lower the node
    best = std::min(best, geo.walk(t_b, roots, counts.passages, best));
    if (s.on_tip_line(p, x, y))
      best = std::min(best, geo.tip_height(s.window[p].tilted ? s.tip_time(p, x, y) : t0));
  }
  return best;
}

double node_height_scan(const PassageSetup& s, double x, double y, double step,
                        NodeCounts& counts) {
  double best = INFINITY;
  std::vector<std::pair<double, std::size_t>> order;
  s.near(x, y, order);
  for (const auto& entry : order) {
    const std::size_t p = entry.second;
    const double t0 = s.level_time(p, x, y);
    if (std::isnan(t0)) continue;
    const auto radii = s.contact_radii(p, t0);
    const PassageGeometry geo(s, p, x, y, radii.first, radii.second);
    // The centre moves along the feed at least at the feed speed: farther than this from t0 it
    // is more than `reach` away.
    const double ta = std::max(geo.t_lo(), t0 - s.reach / s.speed);
    const double tb = std::min(geo.t_hi(), t0 + s.reach / s.speed);
    for (int tooth = 0; tooth < s.teeth; ++tooth) {
      double t_prev = ta, g_prev = geo.probe(tooth, ta).g;
      for (double t = ta + step; t_prev < tb; t += step) {
        t = std::min(t, tb);
        const double g = geo.probe(tooth, t).g;
        if (PassageGeometry::crosses(g_prev, g)) {
          const Probe q = geo.probe(tooth, geo.bisect(tooth, t_prev, t, g_prev));
          ++counts.passages;
          if (q.over && std::isfinite(q.height)) best = std::min(best, q.height);
        }
        t_prev = t, g_prev = g;
      }
    }
  }
  return best;
}

}  // namespace topomill::plugins
