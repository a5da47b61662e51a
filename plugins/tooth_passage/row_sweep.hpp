// The fast walk: a row's nodes are taken in order and every tooth passage is followed from one
// node to the next, so each crossing starts a hair from its root (the previous node's roots
// extrapolated along the row: Root::ahead) and converges in one or two probes. Passes are taken
// outwards from the one that gave the last node its height, and stop on a side at the first one
// whose envelope cannot lower the node; along a passage the walk stops as soon as the envelope,
// which has a single minimum, proves that no later passage can go below the best height found. On a
// corrected path the floor takes the envelope's place and every passage between its stops is
// visited, but one whose height, solved at an earlier node, cannot have fallen below the best since
// is not solved again (walk_corrected); a pass walked before is revisited in place, its failing
// passages solved again (revisit). A step from one passage to the next is taken only where the
// phase bounds prove it the next (PassageGeometry::next_crossing); on an ideal path a revolution
// that cannot be proven is solved exactly in place (crossings_lined or crossings_in: near the
// tool's axis). On a corrected path anything irregular (no such proof, a crossing that does not
// converge) is handed to the reference walk for that node and pass, so the result is the
// reference's to round-off.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "node_walk.hpp"
#include "rise_count.hpp"

namespace topomill::plugins {

class RowSweep {
 public:
  explicit RowSweep(const PassageSetup& s);
  // Lowers z[i] (the nodes x[i] of the row at y, in order) wherever an edge passes below.
  void row(double y, const std::vector<double>& x, double* z, NodeCounts& counts);

  // A crossing as the walks keep it for the next node of the row.
  struct Root {
    // The root, its move (since the node before when ideal; per unit x along the row when
    // corrected, where a root is not solved at every node), the secant there.
    double t, drift, slope;
    // Ideal paths: the root's backward differences of orders 2 to 5 over the row's last nodes
    // (bend the drift's change since the node before, then the bend's, and so on), and at how
    // many nodes before this one it was followed (a difference of order k needs k; until then it
    // is 0). The next node's root is predicted by extrapolating a polynomial through them
    // (ahead()). Near the axis a crossing lies 0.05-0.2 mm from it, where the root's time bends
    // so fast along the row that the quadratic's guess was 1e-7 to 1e-5 rad off the phase (a
    // Newton step at nearly every crossing) and the quintic's mostly under 1e-9 (the tolerance:
    // one probe); order 6 gains nothing more. Where the grid is coarse for the
    // root's bend the differences grow with the order instead of shrinking, and a high order
    // throws the guess far (at 20 um at lambda 0 onto other crossings, and the walk then solved
    // revolution after revolution exactly: 80 times the instructions), so ahead() adds an
    // order only while its difference is smaller than the one below.
    static constexpr int kOrder = 5;  // the extrapolation's highest order
    double bend = 0;
    std::array<double, kOrder - 2> higher{};
    int known = 0;
    // Corrected paths only: where it was solved, the edge's height there, and how fast that
    // height can fall along the row (mm/mm) for `reach` either side; infinite when unknown.
    double x = 0, height = INFINITY, fall = INFINITY, reach = 0;

    // Ideal paths: the root at t followed from `last`, the same crossing at the node before (if
    // any), with the phase's rate `slope` there. A root met for the first time has no move
    // (drift 0), so the node after it takes its whole first move as the bend too: leaving the
    // bend out there measured 0.6 % more instructions, not fewer.
    static Root followed(double t, const Root* last, double slope) {
      if (!last) return Root{t, 0.0, slope};
      Root r{t, t - last->t, slope};
      r.bend = r.drift - last->drift;
      r.known = std::min(last->known + 1, kOrder);
      r.higher[0] = r.known >= 3 ? r.bend - last->bend : 0.0;
      r.higher[1] = r.known >= 4 ? r.higher[0] - last->higher[0] : 0.0;
      r.higher[2] = r.known >= 5 ? r.higher[1] - last->higher[1] : 0.0;
      return r;
    }
    // Where the root will be at the next node of the row (ideal paths): the orders while their
    // differences shrink.
    double ahead() const {
      double at = t + drift + bend, last = bend;
      for (const double h : higher) {
        if (!(std::abs(h) < std::abs(last))) break;
        at += h, last = h;
      }
      return at;
    }
  };

 private:
  struct PassState {
    bool active = false, have_bottom = false;
    double rho_lo = 0, rho_hi = 0;
    double tb = 0, tb_x = 0, tb_rate = 0;  // last bottom, where, and its rate along x
    double floor = 0, floor_x = NAN;       // the last bottom found too high, and where
    double floor_slope = 0;                // ideal: how fast that bottom can fall along the row
    std::vector<std::vector<Root>> roots;  // per tooth, the last node's crossings
    double stop[2] = {NAN, NAN};  // corrected: beyond these the floor is too high (earlier, later)
    // Corrected: after a walk found the pass irregular, the next `wait` nodes of the row go to
    // the reference walk at once (near the axis with effects a pass is irregular at node after
    // node, and the walk found that out only after solving most of its passages: 11 % of the
    // instructions at lambda 0 with vibration and deflection); each failure again doubles the
    // wait, up to kMaxWait nodes, and a walk that gets through ends it.
    int wait = 0, waited = 0;
  };
  static constexpr int kMaxWait = 32;

  double pass_height(std::size_t p, double x, double y, double best, bool& can_lower,
                     NodeCounts& counts);
  // t0() gives the pass's level time (computed when first asked).
  template <class F, class T0>
  double bottom(F f, const PassageGeometry& geo, PassState& st, double x, T0 t0);
  // Ideal paths: exact everywhere (revolutions it cannot follow are solved in place).
  double walk(const PassageGeometry& geo, PassState& st, double t_b, double best,
              NodeCounts& counts);
  // Corrected: the pass's lowest passage below `best` from its last walk's passages, solving
  // again only those whose bound fails (`solved` says whether any was); NaN when it needs a walk.
  double revisit(const PassageGeometry& geo, PassState& st, double best, NodeCounts& counts,
                 bool& solved);
  // The tip's height where the node lies on the pass's line (the tip cuts it as the axis
  // passes over: PassageGeometry::tip_height), else +inf.
  template <class T0>
  double tip_height(const PassageGeometry& geo, T0 t0) const;
  // Corrected: the last node's lowest passage solved at (x, y); its height if in contact.
  double seed(double x, double y, NodeCounts& counts);
  // The root of `roots` (sorted by time) nearest `t` within `reach`; null if none.
  static Root* nearest(std::vector<Root>& roots, double t, double reach);
  // Corrected: the passage of `tooth` solved at geo's node, started from `from` (the same
  // passage at an earlier node) or else from `guess`; false when it does not converge. `q` is the
  // probe there; `r` gets its height and bound when it lies within the pass and under the ball.
  bool solve_root(const PassageGeometry& geo, int tooth, const Root* from, double guess, Root& r,
                  Probe& q) const;
  double walk_corrected(const PassageGeometry& geo, PassState& st, double t_b, double best_node,
                        NodeCounts& counts, bool& irregular);
  // How fast pass p's floor, where below `below`, can change along the row (mm/mm).
  double floor_steepness(std::size_t p, double below) const;
  // How fast a corrected passage's height can fall along the row from its root t (at distance
  // rho from the axis, `plan` from the centre in plan: the same for a vertical tool), and for how
  // far (`reach`) that holds; infinite when no bound holds.
  double fall_rate(std::size_t pass, double t, double rho, double plan, double& reach) const;

  const PassageSetup& s_;
  std::vector<std::size_t> by_line_;                  // parallel: passes sorted by their line
  std::vector<std::pair<double, std::size_t>> near_;  // else: the windows near the node
  std::vector<PassState> state_;
  std::vector<Root> fresh_;
  std::vector<std::vector<Root>> later_, before_;  // per tooth, for walk_corrected
  std::vector<double> first_;
  // Corrected: which passage gave the last node its height (pass, tooth, root), if known.
  static constexpr std::size_t kNone = static_cast<std::size_t>(-1);
  std::size_t win_pass_ = kNone;
  int win_tooth_ = -1, walk_tooth_ = -1;  // walk_*: the last corrected walk's lowest passage
  double win_t_ = 0, walk_t_ = 0;
  // Whether that passage came from the reference walk (a pass handed to it): its root is then
  // kept here, not among the pass's roots (which revisit() takes for every passage between the
  // stops), and seeds the next node all the same.
  bool win_fallback_ = false, walk_fallback_ = false;
  Root fallback_root_{}, win_fallback_root_{};
  std::vector<PassageGeometry::Crossing> roots_;
  std::vector<PassageGeometry::Crossing> zone_roots_;  // walk: the zone's exact crossings
  std::vector<PassageGeometry::Hint> hints_;           // walk: where the last node's crossings lead
  bool exact_used_ = false, fallback_used_ = false;    // the route of the node in hand
};

}  // namespace topomill::plugins
