// tooth_passage's bound of the phase's rate from the side of a pass's line a node lies on
// (PassageGeometry::line_rates, line_gap). At nodes 1 um to 0.2 mm either side of the line of a
// pass that keeps to it (the raster on a flat plate and on the paper's convex arc, a loxodrome
// with a 30 deg helix and a constant-lead edge with none, both spindle directions), the phase's
// rate G' (the central difference of a probe's phase: the definition, no rate formula), sampled
// every 2 us while the node is within `out` of the axis, must lie within [w - fall, w + rise] in
// the spindle's sense; and a crossing of a tooth, found by sampling its phase and bisecting, must
// not follow the one before sooner than line_gap says. The bound must also be of use: on the side
// where the node's azimuth turns with the spindle it proves the phase monotone from 5 um out (3.3
// um for the loxodrome), and on the other side the dip it allows must be seen in the samples
// within a tenth of it: with the sides swapped the samples fall outside (mutate row 81).
#include <catch2/catch.hpp>
#include <cmath>
#include <string>
#include <vector>

#include "support/passage_roots.hpp"

using topomill::plugins::PassageGeometry;
using topomill::plugins::PassageSetup;
using topomill::plugins::wrap;

TEST_CASE("the side of a pass's line bounds the phase's rate", "[tooth_passage][near-axis]") {
  const testing::LineCase c = GENERATE(from_range(testing::line_cases()));
  INFO(c.name);
  const topomill::Prepared m = testing::paper_patch(c.workpiece, "", c.overrides);
  const PassageSetup s = testing::passage_setup(m);
  REQUIRE(s.parallel);
  const std::size_t middle = testing::nearest_pass(s);  // and the next pass
  REQUIRE(middle + 1 < s.window.size());
  const double w = std::abs(s.omega), sense = s.omega > 0 ? 1.0 : -1.0, out = 0.3;
  int samples = 0, outside = 0, gaps = 0, early = 0;
  double worst_with = 0;  // the largest fall sampled where the azimuth turns with the spindle
  for (const std::size_t p : {middle, middle + 1})
    for (const double d : {-0.2, -0.05, -0.02, -0.01, -0.005, -0.003, -0.001, 0.001, 0.003, 0.005,
                           0.01, 0.02, 0.05, 0.2}) {
      REQUIRE(s.window[p].plan_line.along_lo > 0);
      INFO("pass " << p << " (line " << s.window[p].line << " mm), d " << d << " mm");
      const testing::NodeOnLine node = testing::node_by_line(s, p, d, 0.0);
      const double t0 = node.t0;
      REQUIRE(std::isfinite(t0));
      const PassageGeometry& geo = node.geo;
      const auto [fall, rise] = geo.line_rates(out);
      REQUIRE(std::isfinite(fall));
      // The samples' extremes of the rate's departure from the spindle's, in its sense.
      double low = 0, high = 0;
      const double reach = out / s.window[p].plan_line.speed;  // the node beyond `out` after that
      for (double t = t0 - reach; t <= t0 + reach; t += 2e-6) {
        if (!(geo.distance(t) <= out)) continue;
        // G' by the central difference of the phase itself (a probe's, no rate formula), 10 ns
        // either side: its error (the third derivative times h^2 / 6, and the phases' round-off
        // over 2 h) came to 1.3e-4 rad/s at most against rate() here, well inside the slack.
        const double h = 1e-8;
        const double r = sense * wrap(geo.probe(0, t + h).g - geo.probe(0, t - h).g) / (2 * h) - w;
        ++samples;
        low = std::min(low, r), high = std::max(high, r);
        const double slack = 1e-3 + 1e-9 * std::max(fall, rise);
        if (r < -fall - slack || r > rise + slack) {
          ++outside;
          UNSCOPED_INFO("d " << d << " mm, t - t0 " << t - t0 << " s: G' - w " << r << " outside [-"
                             << fall << ", " << rise << "]");
        }
      }
      // Which side is which: the one whose rate dips (below the spindle's) by more.
      const bool with_side = -low < high;
      if (with_side && std::abs(d) >= 0.005) {
        CHECK(1.01 * fall < w);  // proven monotone there
        worst_with = std::max(worst_with, -low);
      }
      if (!with_side) CHECK(-low > 0.1 * fall);  // the bound's dip is there, within a tenth
      // Consecutive crossings of tooth 0 near the axis never closer than line_gap says.
      const auto roots =
          testing::sampled_roots(geo, 0, t0 - 2 * s.rev, t0 + 2 * s.rev, 2e-6, 1e-15);
      for (std::size_t k = 0; k + 1 < roots.size(); ++k) {
        const double rho = geo.distance(roots[k]);
        const double gap = geo.line_gap(rho, 1.1 * s.rev);
        if (!(gap > 0)) continue;
        ++gaps;
        if (roots[k + 1] - roots[k] < gap * (1 - 1e-9)) {
          ++early;
          UNSCOPED_INFO("d " << d << " mm: crossings at " << roots[k] << " and " << roots[k + 1]
                             << ", line_gap " << gap);
        }
      }
    }
  INFO(outside << " of " << samples << " rates outside the bound; " << early << " of " << gaps
               << " crossings sooner than line_gap; largest dip sampled on the with side "
               << worst_with << " rad/s");
  CHECK(samples > 10000);
  CHECK(outside == 0);
  CHECK(gaps > 20);
  CHECK(early == 0);
}
