// A crossing as the row sweep keeps it for the next node of the row, and how its place at that node
// is predicted.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace topomill::plugins {

struct Root {
  // The root, its move (since the node before when ideal; per unit x along the row when
  // corrected, where a root is not solved at every node), the secant there.
  double t, drift, slope;
  // Ideal paths: the root's backward differences of orders 2 to 5 over the row's last nodes
  // (bend the drift's change since the node before, then the bend's, and so on), and at how
  // many nodes before this one it was followed (a difference of order k needs k; until then it
  // is 0). The next node's root is predicted by extrapolating a polynomial through them
  // (ahead()). Near the axis a crossing lies 0.05-0.2 mm from it, where the root's time bends
  // so fast along the row that a quadratic's guess is 1e-7 to 1e-5 rad off the phase (a
  // Newton step at nearly every crossing) and the quintic's mostly under 1e-9 (the tolerance:
  // one probe); order 6 gains nothing more. Where the grid is coarse for the
  // root's bend the differences grow with the order instead of shrinking, and a high order
  // throws the guess far (at 20 um at lambda 0 onto other crossings, and the walk would then solve
  // revolution after revolution exactly), so ahead() adds an
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
  // bend out there costs more steps than it saves.
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

// The root of `roots` (sorted by time) nearest `t` within `reach`; null if none.
inline Root* nearest(std::vector<Root>& roots, double t, double reach) {
  Root* match = nullptr;
  const auto next = std::lower_bound(roots.begin(), roots.end(), t,
                                     [](const Root& r, double v) { return r.t < v; });
  for (auto it = next == roots.begin() ? next : next - 1; it != roots.end() && it <= next; ++it)
    if (std::abs(it->t - t) < reach) reach = std::abs(it->t - t), match = &*it;
  return match;
}

}  // namespace topomill::plugins
