#include "node_walk.hpp"

#include <algorithm>

namespace topomill::plugins {

double node_height_reference(const PassageSetup& s, double x, double y, NodeCounts& counts,
                             std::vector<std::pair<double, std::size_t>>& order,
                             std::vector<double>& roots) {
  order.clear();
  for (std::size_t p = 0; p < s.line.size(); ++p) {
    const double across = std::abs((s.along_y ? x : y) - s.line[p]);
    if (across < s.reach) order.push_back({across, p});
  }
  std::sort(order.begin(), order.end());
  double best = INFINITY;
  for (const auto& entry : order) {
    const std::size_t p = entry.second;
    const double t0 = s.level_time(p, x, y);
    if (std::isnan(t0)) continue;
    const auto radii = s.contact_radii(p, t0);
    const PassageGeometry geo(s, p, x, y, radii.first, radii.second);
    const double t_b = geo.bottom_near(t0);
    if (geo.envelope(t_b) >= best) continue;  // this pass cannot lower the node
    best = std::min(best, geo.walk(t_b, roots, counts.passages));
  }
  return best;
}

}  // namespace topomill::plugins
