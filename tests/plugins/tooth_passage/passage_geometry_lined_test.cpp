// tooth_passage's direct zone (PassageGeometry::crossings_lined, passage_geometry_lined.cpp): where
// the window's centre keeps to its line, the phase's turning points are solved as the zeros of a
// convex function and each tooth's levels between them. Its promise is crossings_in's: the
// crossings in [a, b] that can lie below `below` (the rest may be left out), so the lowest under
// the ball below `below` is found, and everything returned is a crossing. Checked here against
// crossings found with no bound and no rule (a tooth's phase sampled every 0.5 us, each sign
// change bisected: tests/support/passage_roots.hpp), for nodes 1 um to 50 um either side of two
// pass lines, windows of an eighth to a whole revolution at and around the axis's closest
// approach, every `below` that changes the answer (none, and a pm above and below each sampled
// crossing's height), on the paper's arc (loxodrome 30, both spindle directions, 2 and 4 teeth)
// and a flat plate (constant lead 0 and 30). It must also be of use: it applies to every window
// of every node from 2 um out, and the windows include turn-backs (a tooth crossing more often
// than the spindle alone would make it).
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <string>
#include <vector>

#include "support/passage_roots.hpp"

using topomill::plugins::PassageGeometry;
using topomill::plugins::PassageSetup;
using topomill::plugins::Probe;
using topomill::plugins::wrap;

namespace {

struct Sampled {
  int tooth;
  double t, height;
};

}  // namespace

TEST_CASE("the direct zone finds the lowest crossing the halving finds",
          "[tooth_passage][near-axis]") {
  // The line tests' four, and the arc with four teeth.
  std::vector<testing::LineCase> cases = testing::line_cases();
  cases.push_back({"convex arc, loxodrome 30, ccw, 4 teeth",
                   "plugin = 'convex_arc'\nradius = 50.0",
                   {"cutting.spindle_direction=ccw", "tool.teeth=4"}});
  const testing::LineCase c = GENERATE_COPY(from_range(cases));
  INFO(c.name);
  const topomill::Prepared m = testing::paper_patch(c.workpiece, "", c.overrides);
  const PassageSetup s = testing::passage_setup(m);
  REQUIRE(s.parallel);
  const std::size_t middle = testing::nearest_pass(s);
  REQUIRE(middle + 1 < s.window.size());
  int windows = 0, applied = 0, turn_backs = 0, calls = 0;
  double worst = 0;
  for (const std::size_t p : {middle, middle + 1})
    for (const double d :
         {-0.05, -0.02, -0.01, -0.005, -0.002, -0.001, 0.001, 0.002, 0.005, 0.01, 0.02, 0.05}) {
      const testing::NodeOnLine node = testing::node_by_line(s, p, d, 0.013);
      const double t0 = node.t0;
      REQUIRE(std::isfinite(t0));
      const PassageGeometry& geo = node.geo;
      REQUIRE(geo.lined());
      const double rev = s.rev;
      for (const auto& [from, length] : std::vector<std::pair<double, double>>{{-0.0625, 0.125},
                                                                               {-0.25, 0.5},
                                                                               {-0.5, 1.0},
                                                                               {-0.2, 0.3},
                                                                               {0.05, 0.45},
                                                                               {-0.9, 0.6}}) {
        // (Within the window, as the row sweep asks: beyond it the table does not reach.)
        const double a = std::max(t0 + from * rev, geo.t_lo());
        const double b = std::min(t0 + (from + length) * rev, geo.t_hi());
        if (!(b - a > 0.05 * rev)) continue;
        INFO("pass " << p << ", d " << d << " mm, window [" << from << ", " << from + length
                     << "] rev from the closest approach");
        ++windows;
        // Every tooth's crossings, sampled; those under the ball with their heights.
        std::vector<Sampled> all;
        for (int j = 0; j < s.teeth; ++j) {
          const auto roots = testing::sampled_roots(geo, j, a, b, 5e-7, 1e-14);
          if (static_cast<double>(roots.size()) > length + 1.0) ++turn_backs;
          for (const double t : roots)
            if (const Probe q = geo.probe(j, t); q.over) all.push_back({j, t, q.height});
        }
        std::sort(all.begin(), all.end(),
                  [](const Sampled& u, const Sampled& v) { return u.height < v.height; });
        // Every `below` that changes the answer: none, and just above and below each height (a
        // pm: the crossings' heights agree to a few fm, and at a tie either answer is right).
        std::vector<double> belows{INFINITY};
        for (const Sampled& r : all)
          belows.push_back(r.height + 1e-9), belows.push_back(r.height - 1e-9);
        bool used = true;
        for (const double start : belows) {
          double below = start;
          std::vector<PassageGeometry::Crossing> found;
          Probe ends[2];
          if (!geo.crossings_lined(-1, a, b, below, found, ends)) {
            used = false;
            CHECK(found.empty());
            CHECK(below == start);
            break;
          }
          ++calls;
          // Everything returned is a crossing of its tooth within [a, b].
          for (const auto& r : found) {
            CHECK(r.t >= a);
            CHECK(r.t <= b);
            CHECK(std::abs(wrap(geo.probe(r.tooth, r.t).g)) < 1e-8);
          }
          CHECK(ends[0].g == geo.probe(0, a).g);
          CHECK(ends[1].g == geo.probe(0, b).g);
          // The lowest below `start`, as sampled.
          double want = INFINITY, got = INFINITY;
          for (const Sampled& r : all)
            if (r.height < start) want = std::min(want, r.height);
          for (const auto& r : found)
            if (r.q.over && r.q.height < start) got = std::min(got, r.q.height);
          INFO("below " << start << ": sampled " << want << ", direct " << got);
          if (std::isfinite(want)) {
            REQUIRE(std::isfinite(got));
            worst = std::max(worst, std::abs(got - want));
            CHECK(std::abs(got - want) < 1e-9);  // mm: a pm
            CHECK(below == got);
          } else {
            CHECK(got == INFINITY);
            CHECK(below == start);
          }
        }
        if (used) ++applied;
        if (std::abs(d) >= 0.002) CHECK(used);
      }
    }
  INFO(windows << " windows, " << applied << " settled directly (" << calls << " calls), "
               << turn_backs << " turn-backs, worst " << worst << " mm");
  CHECK(applied >= windows * 5 / 6);
  CHECK(turn_backs > 0);
  WARN(c.name << ": " << windows << " windows, " << applied << " direct, " << turn_backs
              << " turn-backs, worst height " << worst << " mm");
}

// The proof behind it (PassageGeometry::lined_convexity): K = rho^2 G' bends in the spindle's
// sense by at least m wherever the node is within rho_hi of the axis. Sampled: G' by the central
// difference of a probe's phase (10 ns either side: the definition, no rate formula), K'' by the
// second difference of K every 100 us, at 8 nodes 1 um to 50 um either side of the line, over a
// revolution around the closest approach, allowing 0.1 % of m for their round-off (on the flat
// plate with no lag, where K'' is 2 |omega| v^2 and m the same but for the table's margins, they
// agree to 1e-5; at a 20 us step to 2.3e-4). m must also be of use: positive from 1 um out and
// within 10 % of the least K'' sampled (m falls short of K'' only by the lag's bends and the arc's
// acceleration).
TEST_CASE("the direct zone's convexity bound holds along the pass", "[tooth_passage][near-axis]") {
  const testing::LineCase c = GENERATE(from_range(testing::line_cases()));
  INFO(c.name);
  const topomill::Prepared m = testing::paper_patch(c.workpiece, "", c.overrides);
  const PassageSetup s = testing::passage_setup(m);
  const std::size_t p = testing::nearest_pass(s);
  const double sense = s.omega > 0 ? 1.0 : -1.0;
  double tightest = INFINITY;  // the least (K'' sampled) / m
  for (const double d : {-0.05, -0.01, -0.003, -0.001, 0.001, 0.003, 0.01, 0.05}) {
    INFO("d " << d << " mm");
    const double x = s.along_y ? s.window[p].line + d : 0.013,
                 y = s.along_y ? 0.013 : s.window[p].line + d;
    const double t0 = s.level_time(p, x, y);
    const auto radii = s.contact_radii(p, t0);
    const PassageGeometry geo(s, p, x, y, radii.first, radii.second);
    const double a = std::max(t0 - 0.5 * s.rev, geo.t_lo()),
                 b = std::min(t0 + 0.5 * s.rev, geo.t_hi());
    auto K = [&](double t) {
      const double h = 1e-8, rho = geo.probe(0, t).rho;
      return rho * rho * wrap(geo.probe(0, t + h).g - geo.probe(0, t - h).g) / (2 * h);
    };
    double rho_hi = 0;
    for (double t = a; t <= b; t += 1e-5) rho_hi = std::max(rho_hi, geo.probe(0, t).rho);
    const double bound = geo.lined_convexity(rho_hi + 1e-6);
    REQUIRE(bound > 0);
    const double H = 1e-4;
    double least = INFINITY;
    for (double t = a + H; t + H <= b; t += H)
      least = std::min(least, sense * (K(t + H) - 2 * K(t) + K(t - H)) / (H * H));
    INFO("least K'' sampled " << least << ", bound " << bound);
    CHECK(least >= bound * (1 - 1e-3));
    tightest = std::min(tightest, least / bound);
  }
  CHECK(tightest <= 1.1);
  WARN(c.name << ": the least K'' sampled is " << tightest << " times the bound");
}
