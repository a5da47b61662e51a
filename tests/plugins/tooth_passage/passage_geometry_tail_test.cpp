// tooth_passage's lower bound of the floor over a window's tail (PassageGeometry::tail_floor),
// against the floor itself sampled along the tail. On the paper's convex arc with vibration,
// deflection and a 50 um runout (the ball, and a bull-nose), at nodes on a pass's line and out to
// the next passes, from times all along the window, both ways: the floor sampled every 20 us
// where an edge can be over the node (the floor below its centre's height) gives the tail's least
// m; no proof may claim more (a target 1e-7 mm above m must not be proven), and with a target
// 1 um below m most of the ball's tails that start within 50 um of m (where the walks ask: from a
// bottom, or a stop past it) must be proven (the bound is of use). On a plane the nominal height
// does not bend down, and the tail stays off: the walks keep the single-minimum rule there.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <string>
#include <vector>

#include "support/passage_roots.hpp"

using topomill::plugins::PassageGeometry;
using topomill::plugins::PassageSetup;

namespace {

constexpr double kStep = 2e-5;       // s between samples of the floor
constexpr double kNearLeast = 0.05;  // mm: a tail that starts this near its least
const std::string kRunout = "[runout]\noffset = 0.05\n";

// The least of the floor sampled over the tail from t in direction dir, where an edge can be over
// the node (+inf if nowhere).
double sampled_tail(const PassageSetup& s, const PassageGeometry& geo, double t, double dir) {
  const PassageSetup::Window& w = s.window[geo.window()];
  const topomill::plugins::CentreTable& axis = w.spindle_axis ? *w.spindle_axis : w.centre;
  const double end = dir > 0 ? geo.t_hi() : geo.t_lo();
  double low = INFINITY;
  for (double u = t;; u += dir * kStep) {
    if (dir * (u - end) > 0) u = end;
    const double f = geo.floor_envelope(u);
    if (f < axis.nominal(u).z() + w.shift_lo.z() + s.profile.up()) low = std::min(low, f);
    if (u == end) break;
  }
  return low;
}

// The paper's scene on the convex arc (r 50) at lambda 0 with `tool` for its [tool] table,
// `extra` appended and `overrides` applied, prepared (testing::paper_patch with another cutter).
topomill::Prepared arc_scene(const std::string& tool, const std::string& extra,
                             const std::vector<std::string>& overrides) {
  std::string text =
      testing::paper_scene("plugin = 'convex_arc'\nradius = 50.0", 0.0, 0.2, 0.2, 0.01) + extra;
  const std::string ball = "plugin = 'ball_end_loxodrome'\nradius = 5.0\n";
  text.replace(text.find(ball), ball.size(), tool);
  auto doc = topomill::SceneDocument::parse_string(text, "tail.toml");
  for (const auto& o : overrides) doc.apply_override(o);
  topomill::PluginCatalog catalog({{topomill::PluginCatalog::builtin_dir(), "built-in"}});
  return topomill::prepare(doc.resolve(catalog), catalog);
}

struct Tally {
  int tails = 0, near = 0, proven = 0;  // proven: of the tails near their least
};

// Every tail of nodes across two passes of the scene: no proof above the sampled least, most
// proven 1 um below it.
Tally check_tails(const topomill::Prepared& m) {
  const PassageSetup s = testing::passage_setup(m);
  const std::size_t p = testing::nearest_pass(s);
  REQUIRE(s.window[p].tail.on);
  Tally n;
  // Along the pass, about its middle (the patch's).
  const double mid =
      s.window[p].centre.nominal(0.5 * (s.window[p].t_lo + s.window[p].t_hi))[s.along_y ? 1 : 0];
  for (const double d : {0.0, 0.02, 0.06, 0.15, 0.3, 0.45})
    for (const double along : {-0.05, 0.05}) {
      const testing::NodeOnLine node = testing::node_by_line(s, p, d, mid + along);
      const PassageGeometry& geo = node.geo;
      const double span = geo.t_hi() - geo.t_lo();
      for (int k = 0; k <= 24; ++k)
        for (const double dir : {-1.0, 1.0}) {
          const double t = geo.t_lo() + span * k / 24;
          const double least = sampled_tail(s, geo, t, dir);
          if (!std::isfinite(least)) continue;
          INFO("d " << d << " mm, along " << along << " mm, t " << t << " s, dir " << dir
                    << ": sampled least " << least << " mm");
          ++n.tails;
          const double claim = least + 1e-7;
          CHECK(geo.tail_floor(t, dir, claim) < claim);
          const double target = least - 1e-3;  // 1 um
          const double v = geo.tail_floor(t, dir, target);
          if (v >= target) CHECK(v <= least);
          // Of use where the walks ask: from a bottom or a stop, near the tail's least (a
          // tail from far before it adds the height's bend all the way there).
          if (geo.floor_envelope(t) - least <= kNearLeast) ++n.near, n.proven += v >= target;
        }
    }
  return n;
}

}  // namespace

TEST_CASE("the floor's tail bound holds under the sampled floor on a convex arc",
          "[tooth_passage]") {
  const std::string effects = testing::dynamics_tables() + kRunout;
  const std::string ball = "plugin = 'ball_end_loxodrome'\nradius = 5.0\n";
  struct Case {
    const char* name;
    std::string tool;
    std::vector<std::string> overrides;
    bool of_use;  // whether most tails must be proven 1 um below the sampled least
  };
  // The bull-nose's tails are seldom proven (a quarter of those near the least): its depth stays
  // level while the node is under the flat bottom, so a proof must reach on until the node leaves
  // the ring, over which the nominal height's bend (the window's greatest) outgrows the rise.
  const Case c = GENERATE_COPY(Case{"ball end, 3 teeth", ball, {"tool.teeth=3"}, true},
                               Case{"ball end at lambda 30", ball, {"region.lambda=30"}, true},
                               Case{"bull-nose D 10 r 2",
                                    "plugin = 'bull_nose'\ndiameter = 10.0\ncorner_radius = 2.0\n",
                                    {},
                                    false});
  INFO(c.name);
  const Tally n = check_tails(arc_scene(c.tool, effects, c.overrides));
  INFO(n.proven << " of " << n.near << " tails near their least (of " << n.tails
                << ") proven 1 um below it");
  CHECK(n.near > 100);
  if (c.of_use) CHECK(n.proven >= 0.9 * n.near);
}

TEST_CASE("the floor's tail stays off where the nominal height does not bend down",
          "[tooth_passage]") {
  const topomill::Prepared m =
      testing::paper_patch("plugin = 'inclined_plane'\nangle = 30.0",
                           testing::dynamics_tables() + kRunout, {"region.lambda=30"});
  const PassageSetup s = testing::passage_setup(m);
  REQUIRE(s.wiggles);
  for (const PassageSetup::Window& w : s.window) CHECK_FALSE(w.tail.on);
}
