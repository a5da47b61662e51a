// The ideal follow: one window's passages over one node of a row on an ideal path (no correction,
// no runout). Each tooth's passages are followed outwards from the envelope's bottom, root to
// root, each solved from the last node's (Root::ahead), as long as the phase is proven monotone
// between them (a step is taken only where the next crossing is proven the next). Where it is not
// (the axis passes close to the node: its azimuth turns faster than the spindle and a passage may
// cross it three times), that revolution is solved exactly in place (PassageGeometry::crossings)
// and the walk goes on from its far edge. The time around the bottom that cannot be followed (the
// axis's closest approach) is solved first, for all teeth at once (the teeth's phases differ by a
// constant: one solve serves them all): a zone reaching out by eighths of a revolution until the
// phase beyond each edge is proven monotone. The teeth are followed from its edges, and its
// crossings kept as roots for the next node, as the walk's own are. Exact everywhere: a step
// either is proven (ideal_follow_test.cpp) or the revolution is solved by the certified halving.
#pragma once

#include <cstdint>
#include <vector>

#include "node_walk.hpp"
#include "rise_count.hpp"
#include "root.hpp"

namespace topomill::plugins {

class IdealFollow {
 public:
  // A crossing solved from a last-node root (seed_limit), per tooth: a walk that starts from
  // the same root takes it rather than solving it again (the solve is a function of the root).
  struct Seeded {
    const Root* from = nullptr;
    double t = NAN, slope = 0;
    Probe q{};
  };
  // Buffers reused from node to node, so that a node allocates nothing.
  struct Scratch {
    std::vector<Root> fresh;                             // the tooth in hand's roots here
    std::vector<PassageGeometry::Crossing> found, zone;  // an exact solve's, the zone's
    std::vector<PassageGeometry::Hint> hints;            // where the last node's roots lead
    std::vector<Seeded> seeded;                          // this node's, by tooth
  };
  // `roots`: per tooth, the last node's roots on this window (sorted by time); replaced by this
  // node's.
  IdealFollow(const PassageGeometry& geo, std::vector<std::vector<Root>>& roots, Scratch& scratch,
              NodeCounts& counts);
  // The lowest passage over the node below `best_node`, from t_b (the envelope's bottom); +inf if
  // none.
  double run(double t_b, double best_node);
  // Whether some revolution was solved exactly (the node's route, for the work counts).
  bool exact_used() const { return exact_used_; }

  // Where a tooth's walk in one direction stands: at a crossing (a root), or at the edge of a
  // revolution solved exactly.
  struct Cursor {
    double t;
    bool at_root;
    double rho = 0;    // the root's distance from the axis, when at one
    Probe q{};         // the tooth's probe at t (when at a root, or once asked)
    double rate = 0;   // the phase's rate at t, when at a root
    const Root* from;  // the last node's root at t, if any
    RiseCount rise;
    // At an edge the walk jumped to past crossings that cannot lower the node (step): nothing
    // behind it was solved, and a crossing found behind it is not taken as the next.
    bool jumped = false;
  };
  // The step proof: whether t (probe q there) is proven the crossing of `tooth` right after c's
  // in direction dir (after an edge: the first beyond it, the phase still to turn by `gap`).
  // `ahead`: the phase proven monotone over 1.1 revolutions from c (by c's distance from the
  // axis, or by a span that bounds its rate: PassageGeometry::monotony).
  static bool proven_next(const PassageGeometry& geo, int tooth, int dir, const Cursor& c, double t,
                          const Probe& q, const PassageGeometry::Monotony& ahead, double gap);
  // How far a step looks ahead, in revolutions: a whole one and room for the phase's rate to vary.
  static constexpr double kAhead = 1.1;

 private:
  // A crossing's height, if it lies within the window (and the best lowered if over the ball).
  double take(int tooth, double t, const Probe* known);
  // A crossing found exactly, kept as a root for the next node (its move from the last node's
  // root nearest it, if any): the steps and first crossings next to an exact revolution then
  // start from the last node's roots too.
  void keep(const PassageGeometry::Crossing& c, std::vector<Root>& into);
  // Every crossing in [lo, hi], exactly (kept: the zone's for every tooth when tooth < 0, else
  // `tooth`'s).
  void exact(int tooth, double lo, double hi);
  // Whether the phase is proven monotone over 1.1 revolutions beyond the zone's edge `side`.
  bool prove_edge(int side);
  // The zone around t_b, solved for all teeth where the phase is not proven monotone there.
  void solve_zone();
  // Tooth `tooth`'s passages, both ways from its first.
  void follow(int tooth);
  // The crossing near `guess`, started from the last node's root predicted nearest it (within
  // `reach`) or from `hint`; NaN when it did not converge. `matched` gets the root started from.
  double solve(int tooth, double guess, double reach, Probe& q, const Root*& matched,
               const Root* hint = nullptr);
  // One step of the walk in direction dir: false when the walk ends.
  bool step(int tooth, int dir, Cursor& c);
  // Whether every later crossing lies beyond t_bound, where the envelope is too high.
  bool ends_at(int dir, double t_bound) const;
  // Where the stretch from `from` to `far` (dir's way) ends for the walk: the first time found
  // by halving from which ends_at holds; NaN where it does not hold at `far`. A ringed cutter's
  // lag has no bounded rate at its rim, which a node near the bottom reaches within a revolution;
  // its crossings there are too high to matter, and the phase is proven monotone over the rest.
  double cut(int dir, double from, double far) const;
  // What the bounds prove of the phase from `from` (dir's way) up to the cut within `far`, which
  // goes to `until` (left alone where there is none). A cut stands as the walk goes on (the
  // limit only falls), and so does what was proven up to it: both are kept for the later steps
  // this way, of every tooth.
  PassageGeometry::Monotony cut_ahead(int dir, double from, double far, double& until);
  // Whether the node can get past the rim (PassageGeometry::rim) within `reach` of t, by a
  // vertical tool's distance at t and the centre's top speed: only there does a cut help.
  bool nears_rim(double t, double reach) const;
  // Whether the phase is proven monotone `reach` either side of t_b, but for what lies beyond
  // the cut on each side (cut()): then no zone is needed. Tried where the node nears the rim.
  bool proven_to_cuts(double reach);
  // Where the phase cannot be proven monotone around t_b: a real crossing's height from each
  // tooth's last-node root nearest t_b, so that the walk has a limit to cut by (cut()).
  void seed_limit();
  // Whether the walk ends before the next crossing, by the envelope and the gap to it.
  bool ends_before_next(int dir, const Cursor& c) const;
  // The next revolution exactly, where the next crossing cannot be proven the next.
  void solve_revolution(int tooth, int dir, Cursor& c);

  const PassageSetup& s_;
  const PassageGeometry& geo_;
  std::vector<std::vector<Root>>& roots_;
  Scratch& scratch_;
  NodeCounts& counts_;
  std::vector<Root>* prev_ = nullptr;  // the tooth in hand's last-node roots
  double rev_, t_lo_, t_hi_, w_;
  double t_b_ = 0, best_node_ = 0, best_ = 0;
  std::uint64_t visited_ = 0;
  bool exact_used_ = false;
  bool seeded_ = false;  // whether scratch_.seeded holds this node's (seed_limit ran)
  // The zone [zone_[0], zone_[1]] around t_b solved for all teeth, empty when the phase is proven
  // monotone around t_b (then each tooth's first crossing is followed from the last node's).
  double zone_[2] = {0, 0};
  // Tooth 0's probes at the ends of the zone's last exact solve, and where: the walks from the
  // zone's edges start there (after the zone grew on one side, the other's no longer matches its
  // edge, and is probed again).
  Probe edge_probe_[2];  // (read only where edge_probe_at_ says they were set)
  double edge_probe_at_[2] = {NAN, NAN};
  // The span over 1.1 revolutions beyond each edge, where proven monotone there: the first step
  // of every tooth's walk from that edge needs no other.
  PassageGeometry::Monotony beyond_edge_[2];  // (read only where edge_proven_)
  bool edge_proven_[2] = {false, false};
  // Each way (earlier, later), the cut last found (NaN: none) and what was proven from `from` up
  // to it (cut_ahead).
  struct Cut {
    double at = NAN, from = NAN;
    PassageGeometry::Monotony proven{};
  };
  Cut cut_[2];
};

}  // namespace topomill::plugins
