// The corrected follow: one window's passages over one node of a row on a corrected path (a
// correction or a runout moves the centre about its smooth path, so the envelope wiggles and has
// dips anywhere). Every passage is visited outwards from the floor's bottom until the floor proves
// that no later one can lower the node (no rule of thumb: the correction makes heights jump from
// passage to passage), each proven the next of the last (PassageGeometry::next_crossing); but a
// passage whose height, solved at an earlier node of the row, cannot have fallen below the best
// since (fall_rate) is not solved again. Anything irregular (no such proof, a crossing that does
// not converge) is left to the reference walk, so that the result is the reference's to round-off.
#pragma once

#include <cstdint>
#include <vector>

#include "node_walk.hpp"
#include "root.hpp"

namespace topomill::plugins {

class CorrectedFollow {
 public:
  // Buffers reused from node to node, so that a node allocates nothing.
  struct Scratch {
    std::vector<std::vector<Root>> later, before;  // per tooth, this walk's passages each way
    std::vector<double> first;                     // per tooth, its first passage
  };
  // The lowest passage found below the best: its tooth (-1: none) and time.
  struct Lowest {
    int tooth = -1;
    double t = 0;
  };
  // `roots`: per tooth, every passage between the stops at the pass's last walk (sorted by time);
  // `stop`: where the floor was too high, before and after the bottom. Both are updated.
  CorrectedFollow(const PassageGeometry& geo, std::vector<std::vector<Root>>& roots,
                  double (&stop)[2], Scratch& scratch, NodeCounts& counts);
  // The pass's lowest passage below `best_node`, walked from t_b (the floor's bottom); +inf if
  // none. `irregular` set: the walk could not prove its steps, and the pass goes to the reference.
  double walk(double t_b, double best_node, bool& irregular);
  // The pass as last walked, again: every passage between its stops is known, and one whose bound
  // fails (it may have fallen below `best` since it was solved) is solved again where it is; the
  // rest stay (`solved` says whether any was). NaN when that is not enough and the pass must be
  // walked: no walk yet, the floor at a stop no longer rules out what lies beyond, or a passage
  // moved irregularly.
  double revisit(double best, bool& solved);
  const Lowest& lowest() const { return lowest_; }

 private:
  // The passage of `tooth` near `guess` (its root within `reach` of the time): skipped if its
  // bound allows, else solved; appended to `out`; false when irregular.
  bool visit(int tooth, double guess, double reach, double& t, std::vector<Root>& out);
  // Moves the stops to where the floor, past its bottom, is too high for any passage to go below
  // `target`.
  void place_stops(double t_b, double target);
  // Tooth `tooth`'s passages on side `side` (1: later) from its first; false when irregular.
  bool walk_side(int tooth, int side);

  const PassageSetup& s_;
  const PassageGeometry& geo_;
  std::vector<std::vector<Root>>& roots_;
  double (&stop_)[2];
  Scratch& scratch_;
  NodeCounts& counts_;
  double best_node_ = INFINITY, best_ = INFINITY;
  std::uint64_t visited_ = 0;
  Lowest lowest_;
};

// The passage of `tooth` solved at geo's node, started from `from` (the same passage at an
// earlier node) or else from `guess`; false when it does not converge. `q` is the probe there;
// `r` gets its height and bound when it lies within the window and under the ball.
bool solve_root(const PassageGeometry& geo, int tooth, const Root* from, double guess, Root& r,
                Probe& q);
// Whether a corrected passage, solved at an earlier node, is still at or above `target` at x by
// its fall-rate bound.
inline bool stays_above(const Root& r, double x, double target) {
  const double moved = std::abs(x - r.x);
  return moved <= r.reach && r.height - r.fall * moved >= target;
}
// How fast a corrected passage's height can fall along the row from its root t on window w (at
// distance rho from the axis, `plan` from the centre in plan: the same for a vertical tool), and
// for how far (`reach`) that holds; infinite when no bound holds.
double fall_rate(const PassageSetup& s, std::size_t w, double t, double rho, double plan,
                 double& reach);
// How fast window w's floor, where below `below`, can change along the row (mm/mm).
double floor_steepness(const PassageSetup& s, std::size_t w, double below);

}  // namespace topomill::plugins
