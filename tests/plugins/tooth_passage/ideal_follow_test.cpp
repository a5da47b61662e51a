// tooth_passage's ideal follow (IdealFollow): along a row that crosses a pass's line, where the
// axis passes over or next to the nodes and a tooth's next crossing may come at once or after
// more than a revolution, each step from one crossing to the next is taken only where it is proven
// the next; a revolution that cannot be proven is solved exactly. A step that skipped a crossing
// would lose it, and with it the node's lowest passage where that was the one. Checked here at
// every node of such rows (1 um apart, 50 um either side of the line, followed in order as the row
// sweep does, so that each node starts from the last one's roots) against the reference walk
// (every revolution by the certified halving) to a picometre, and against crossings found with no
// bound and no rule (each tooth's phase sampled over two revolutions either side of the
// envelope's bottom, each sign change bisected): no sampled crossing under the ball lies below the
// follow's height.
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "support/passage_roots.hpp"
#include "tooth_passage/ideal_follow.hpp"

namespace tp = topomill::plugins;
using tp::IdealFollow;
using tp::PassageGeometry;

TEST_CASE("the ideal follow proves every step across a pass's line", "[tooth_passage][near-axis]") {
  const testing::LineCase c = GENERATE_COPY(from_range(testing::line_cases()));
  INFO(c.name);
  const topomill::Prepared m = testing::paper_patch(c.workpiece, "", c.overrides);
  const tp::PassageSetup s = testing::passage_setup(m);
  REQUIRE(s.parallel);
  REQUIRE_FALSE(s.wiggles);
  const std::size_t p = testing::nearest_pass(s);
  std::vector<std::vector<tp::Root>> roots(static_cast<std::size_t>(s.teeth));
  IdealFollow::Scratch scratch;
  tp::NodeCounts counts;
  std::vector<PassageGeometry::Crossing> reference_roots;
  int nodes = 0, followed = 0;
  double worst = 0;
  for (int k = -50; k <= 50; ++k) {
    const double d = 1e-3 * k;
    INFO("node " << d << " mm from the line");
    const testing::NodeOnLine node = testing::node_by_line(s, p, d, 0.013);
    REQUIRE(std::isfinite(node.t0));
    const PassageGeometry& geo = node.geo;
    const double t_b = geo.bottom_near(node.t0);
    IdealFollow follow(geo, roots, scratch, counts);
    const double h = follow.run(t_b, INFINITY);
    ++nodes;
    if (!follow.exact_used()) ++followed;
    std::uint64_t visited = 0;
    const double expected = geo.walk(t_b, reference_roots, visited);
    REQUIRE(std::isfinite(h));
    CHECK(std::abs(h - expected) < 1e-9);
    worst = std::max(worst, std::abs(h - expected));
    // No crossing found by sampling lies below it.
    for (int tooth = 0; tooth < s.teeth; ++tooth)
      for (const double t :
           testing::sampled_roots(geo, tooth, t_b - 2 * s.rev, t_b + 2 * s.rev, 1e-6, 1e-14)) {
        const auto q = geo.probe(tooth, t);
        if (geo.within(t) && q.over) CHECK(q.height >= h - 1e-9);
      }
  }
  INFO(followed << " of " << nodes << " nodes followed without an exact revolution; worst "
                << worst * 1e6 << " nm from the reference");
  // The rows must exercise the steps: many nodes are followed, not solved exactly.
  CHECK(followed > nodes / 3);
}

// The step proof itself (IdealFollow::proven_next), against crossings found with no bound and no
// rule: at nodes 1 um to 50 um either side of a pass's line, each tooth's crossings sampled over
// two revolutions either side of the envelope's bottom. From each crossing c0 with two more after
// it (or before it), c1 and c2, set up as the follow sets up a step from a root (the phase
// monotone ahead by the node's distance, or by a span, else no step is tried): a step to c2, which
// passes over c1, must never be proven; a step to c1 must be proven at most such crossings.
TEST_CASE("the ideal follow's step proof never passes over a crossing",
          "[tooth_passage][near-axis]") {
  const testing::LineCase c = GENERATE_COPY(from_range(testing::line_cases()));
  INFO(c.name);
  const topomill::Prepared m = testing::paper_patch(c.workpiece, "", c.overrides);
  const tp::PassageSetup s = testing::passage_setup(m);
  const std::size_t p = testing::nearest_pass(s);
  const double ahead = IdealFollow::kAhead * s.rev;
  int tried = 0, proven = 0;
  for (const double d :
       {-0.05, -0.02, -0.01, -0.005, -0.002, -0.001, 0.001, 0.002, 0.005, 0.01, 0.02, 0.05}) {
    const testing::NodeOnLine node = testing::node_by_line(s, p, d, 0.013);
    const PassageGeometry& geo = node.geo;
    const double t_b = geo.bottom_near(node.t0);
    for (int tooth = 0; tooth < s.teeth; ++tooth) {
      const std::vector<double> roots =
          testing::sampled_roots(geo, tooth, t_b - 2 * s.rev, t_b + 2 * s.rev, 5e-7, 1e-14);
      const auto n = static_cast<std::ptrdiff_t>(roots.size());
      for (std::ptrdiff_t i = 0; i < n; ++i)
        for (const int dir : {+1, -1}) {
          const std::ptrdiff_t i1 = i + dir, i2 = i + 2 * dir;
          if (i2 < 0 || i2 >= n) continue;
          INFO("node " << d << " mm from the line, tooth " << tooth << ", step from " << roots[i]
                       << " s towards " << dir);
          const double t = roots[i];
          const tp::Probe q0 = geo.probe(tooth, t);
          IdealFollow::Cursor cur{t, true, q0.rho, q0, 0.0, nullptr, {}, false};
          const PassageGeometry::Monotony mono = geo.monotony({t, t + dir * ahead, q0.rho, ahead});
          if (!mono.monotone) continue;  // the follow solves this revolution exactly
          ++tried;
          const double t1 = roots[i1], t2 = roots[i2];
          CHECK_FALSE(
              IdealFollow::proven_next(geo, tooth, dir, cur, t2, geo.probe(tooth, t2), mono, 0.0));
          if (IdealFollow::proven_next(geo, tooth, dir, cur, t1, geo.probe(tooth, t1), mono, 0.0))
            ++proven;
        }
    }
  }
  INFO(proven << " of " << tried << " true steps proven");
  CHECK(tried > 50);
  CHECK(proven > tried / 2);
}
