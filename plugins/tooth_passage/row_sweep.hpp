// The row sweep: a row's nodes are taken in order and every tooth passage is followed from one
// node to the next, so each crossing starts a hair from its root (the previous node's roots
// extrapolated along the row: Root::ahead) and converges in one or two probes. Passes are taken
// outwards from the one that gave the last node its height, and stop on a side at the first one
// whose envelope cannot lower the node. Within a pass, an ideal path is followed by IdealFollow
// (exact everywhere: revolutions it cannot prove are solved in place), a corrected one by
// CorrectedFollow, which hands anything irregular to the reference walk for that node and pass, so
// that the result is the reference's to round-off.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "corrected_follow.hpp"
#include "ideal_follow.hpp"
#include "node_walk.hpp"

namespace topomill::plugins {

class RowSweep {
 public:
  explicit RowSweep(const PassageSetup& s);
  // Lowers z[i] (the nodes x[i] of the row at y, in order) wherever an edge passes below.
  // (A call of its own, never inlined: scripts/bench and bench-pair count a row's instructions
  // from its entry.)
  [[gnu::noinline]] void row(double y, const std::vector<double>& x, double* z, NodeCounts& counts);

 private:
  // What the sweep keeps of one window along the row.
  struct PassState {
    bool active = false;
    double rho_lo = 0, rho_hi = 0;  // the contact range (from the level time at the first node)
    bool have_bottom = false, tb_end = false;  // tb_end: the last bottom was a split side's end
    double tb = 0, tb_x = 0, tb_rate = 0;      // last bottom, where, and its rate along x
    double level_y = NAN, level_t = NAN;       // the level time at a row's y (level_by_y)
    double floor = 0, floor_x = NAN;           // the last bottom found too high, and where
    double floor_slope = 0;                    // ideal: how fast that bottom can fall along the row
    // Per tooth, the last node's roots (ideal), or every passage between the stops at the last
    // walk (corrected).
    std::vector<std::vector<Root>> roots;
    double stop[2] = {NAN, NAN};  // corrected: beyond these the floor is too high (earlier, later)
    // Corrected: after a walk found the pass irregular, the next `wait` nodes of the row go to
    // the reference walk at once (near the axis with effects a pass is irregular at node after
    // node, and the walk finds that out only after solving most of its passages); each failure
    // again doubles the wait, up to kMaxWait nodes, and a walk that gets through ends it.
    int wait = 0, waited = 0;
  };
  static constexpr int kMaxWait = 32;

  // The passage that gave a node its height, on a corrected path: the next node solves it first.
  struct Winner {
    static constexpr std::size_t kNone = static_cast<std::size_t>(-1);
    std::size_t pass = kNone;
    int tooth = -1;
    double t = 0;
    // Whether it came from the reference walk (a pass handed to it): its root is then kept here,
    // not among the pass's roots (which revisit() takes for every passage between the stops).
    bool fallback = false;
    Root fallback_root{};
  };
  // One window's answer at a node.
  struct PassResult {
    double height = INFINITY;  // its lowest passage below the best, else +inf
    bool can_lower = true;     // false: its envelope (or floor) proves it cannot lower the node
    // Corrected: which passage gave `height` (tooth -1: not known), and whether the reference
    // walk found it.
    int tooth = -1;
    double t = 0;
    bool fallback = false;
  };
  // How the node in hand was solved, for the work counts.
  struct Route {
    bool exact = false, fallback = false;
  };

  PassResult pass_height(std::size_t p, double x, double y, double best, NodeCounts& counts);
  // An ideal pass of a cutter whose profile splits (CutterProfile::splits): each side of its
  // level time t_m (the axis's closest approach) followed as a window of its own, whose heights
  // have one minimum.
  PassResult split_height(std::size_t p, double x, double y, double best, NodeCounts& counts,
                          double t_m);
  // The passes outwards from the last node's winner (parallel passes) or every window near the
  // node (others): the node's best height.
  double node_height(double x, double y, NodeCounts& counts);
  // Ideal paths: whether the pass's envelope bottom proves it cannot lower the node (then
  // `t_b` is untouched); else its bottom into t_b (NaN: never level with the node), and the
  // envelope there into `low` where given.
  template <class T0>
  bool ideal_too_high(const PassageGeometry& geo, PassState& st, double best, T0 t0, double& t_b,
                      double* low = nullptr);
  // The reference walk for the node and pass, seeding the next node from its lowest passage.
  double reference(const PassageGeometry& geo, PassState& st, double t_b, double best,
                   NodeCounts& counts, PassResult& out);
  // The same walk without counting it a fallback: every pass of a cutter whose surface is not its
  // hull (CutterProfile::surface_is_hull).
  double walk_reference(const PassageGeometry& geo, PassState& st, double t_b, double best,
                        NodeCounts& counts, PassResult& out);
  // t0() gives the pass's level time (computed when first asked).
  template <class F, class T0>
  double bottom(F f, const PassageGeometry& geo, PassState& st, double x, T0 t0);
  // The tip's height where the node lies on the pass's line (the tip cuts it as the axis
  // passes over: PassageGeometry::tip_height), else +inf.
  template <class T0>
  double tip_height(const PassageGeometry& geo, T0 t0) const;
  // Corrected: the last node's lowest passage solved at (x, y); its height if in contact.
  double seed(double x, double y, NodeCounts& counts);

  const PassageSetup& s_;
  std::vector<std::size_t> by_line_;                  // parallel: passes sorted by their line
  std::vector<std::pair<double, std::size_t>> near_;  // else: the windows near the node
  std::vector<PassState> state_;
  std::vector<PassState> far_side_;  // a split pass's side after its level time (split_height)
  IdealFollow::Scratch ideal_;
  CorrectedFollow::Scratch corrected_;
  std::vector<PassageGeometry::Crossing> roots_;  // the reference walk's
  Winner winner_;                                 // corrected: the last node's
  std::ptrdiff_t winner_line_ = -1;  // parallel: the last node's winning pass in by_line_
  Route route_;
};

}  // namespace topomill::plugins
