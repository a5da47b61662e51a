// tooth_passage's exact window (PassageGeometry::crossings_in) where the phase turns at exactly the
// rate its bounds allow: a node on a pass's line, cut by a vertical edge with no lag (constant
// lead, helix 0). There the node's azimuth stands still on either side of the axis's passage and
// G' = omega, so a piece holding a crossing has |g_a| + |g_b| equal to the largest turn its bounds
// allow, but for round-off. Every crossing after the axis passed, found here by sampling the phase
// and bisecting it with probes, must be found by crossings_in over windows around it of every
// width. Without the round-off allowance it rules out such a crossing in 158 of these 360
// windows; on the convex case's pass line one 0.11 nm below the tip's cut is lost so.
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "support/passage_roots.hpp"

using topomill::plugins::PassageGeometry;
using topomill::plugins::PassageSetup;

TEST_CASE("an exact window finds a crossing where the phase turns at exactly its bound's rate",
          "[tooth_passage][near-axis]") {
  const topomill::Prepared m =
      testing::paper_arc("", {"tool.plugin=ball_end_constant_lead", "tool.helix_angle=0",
                              "cutting.depth_of_cut=0.02", "cutting.spindle_direction=ccw"});
  const PassageSetup s = testing::passage_setup(m);
  REQUIRE(s.parallel);
  const std::size_t p = testing::nearest_pass(s);  // nodes exactly on its line
  std::mt19937 rng(25);
  std::uniform_real_distribution<double> along(-0.08, 0.08), unit(0.0, 1.0);
  int windows = 0, missed = 0;
  for (int n = 0; n < 20; ++n) {
    const double x = s.along_y ? s.window[p].line : along(rng),
                 y = s.along_y ? along(rng) : s.window[p].line;
    const double t0 = s.level_time(p, x, y);
    REQUIRE(std::isfinite(t0));
    const auto radii = s.contact_radii(p, t0);
    const PassageGeometry geo(s, p, x, y, radii.first, radii.second);
    // Each tooth's crossings in contact over the half revolution after the axis passed (from 10 us
    // on, where the node is 0.1 um from the axis), by sampling every 2 us and bisecting to
    // round-off.
    for (int tooth = 0; tooth < s.teeth; ++tooth) {
      for (const double root :
           testing::sampled_roots(geo, tooth, t0 + 1e-5, t0 + 0.5 * s.rev, 2e-6, 1e-15)) {
        if (!geo.probe(tooth, root).over) continue;  // out of contact: no window need find it
        // Windows around it, 1e-8 to 1e-4 s either side (none reaching back to the axis).
        for (int k = 0; k < 40; ++k) {
          const double before = std::min(std::pow(10.0, -8 + 4 * unit(rng)), root - t0 - 1e-6);
          const double after = std::pow(10.0, -8 + 4 * unit(rng));
          double below = INFINITY;
          std::vector<PassageGeometry::Crossing> roots;
          geo.crossings_in(-1, root - before, root + after, below, roots);
          bool found = false;
          for (const auto& r : roots) found |= r.tooth == tooth && std::abs(r.t - root) < 1e-9;
          ++windows;
          if (!found) {
            ++missed;
            UNSCOPED_INFO("node (" << x << ", " << y << "), tooth " << tooth << ", crossing at "
                                   << root << ", window " << before << " before, " << after
                                   << " after");
          }
        }
      }
    }
  }
  INFO(missed << " of " << windows << " windows missed their crossing");
  CHECK(windows > 200);
  CHECK(missed == 0);
}
