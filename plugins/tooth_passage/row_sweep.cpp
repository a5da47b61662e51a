#include "row_sweep.hpp"

#include <algorithm>
#include <numeric>

namespace topomill::plugins {

namespace {
// Whether a corrected passage, solved at an earlier node, is still at or above `target` at x by
// its fall-rate bound (RowSweep::fall_rate).
template <class Root>
bool stays_above(const Root& r, double x, double target) {
  const double moved = std::abs(x - r.x);
  return moved <= r.reach && r.height - r.fall * moved >= target;
}
}  // namespace

RowSweep::RowSweep(const PassageSetup& s)
    : s_(s),
      by_line_(s.window.size()),
      state_(s.window.size()),
      later_(static_cast<std::size_t>(s.teeth)),
      before_(static_cast<std::size_t>(s.teeth)) {
  std::iota(by_line_.begin(), by_line_.end(), std::size_t{0});
  if (s.parallel)
    std::sort(by_line_.begin(), by_line_.end(),
              [&](std::size_t a, std::size_t b) { return s.window[a].line < s.window[b].line; });
  for (auto& st : state_) st.roots.resize(static_cast<std::size_t>(s.teeth));
}

void RowSweep::row(double y, const std::vector<double>& xs, double* z, NodeCounts& counts) {
  win_pass_ = kNone;
  for (auto& st : state_) {
    st.active = st.have_bottom = false;
    st.wait = st.waited = 0;
    st.floor_x = NAN;
    st.stop[0] = st.stop[1] = NAN;
    for (auto& r : st.roots) r.clear();
  }
  const auto n = static_cast<std::ptrdiff_t>(by_line_.size());
  // A pass that cannot lower the node ends its side; with a correction (each pass has its own),
  // only the second in a row does.
  const int misses_to_stop = s_.wiggles ? 2 : 1;
  // The parallel pass (its place in by_line_) that gave the last node its height; -1 if none.
  std::ptrdiff_t winner = -1;
  for (std::size_t i = 0; i < xs.size(); ++i) {
    if (s_.stopped()) return;  // the map is discarded
    const double x = xs[i], key = s_.along_y ? x : y;
    exact_used_ = fallback_used_ = false;
    // Corrected: the passage that was lowest at the node before, solved here first, gives a
    // height to bound all others by from the start (it is a real crossing of this node).
    double best = s_.wiggles ? seed(x, y, counts) : INFINITY;
    const std::size_t seeded = win_pass_;
    // Window p's lowest passage below `best`, if any; false when it cannot lower the node.
    auto visit = [&](std::size_t p) {
      bool can_lower = true;
      walk_tooth_ = -1, walk_fallback_ = false;
      const double h = pass_height(p, x, y, best, can_lower, counts);
      if (h < best) {
        best = h, win_pass_ = walk_tooth_ >= 0 ? p : kNone;
        win_tooth_ = walk_tooth_, win_t_ = walk_t_;
        win_fallback_ = walk_fallback_, win_fallback_root_ = fallback_root_;
      }
      return can_lower;
    };
    if (!s_.parallel) {
      // Windows of bent passes lie every way: each one that can reach the node is asked, lowest
      // possible first, until none left can go below the best.
      s_.near(x, y, near_);
      for (const auto& entry : near_) {
        if (entry.first >= best) break;
        visit(entry.second);
      }
    }
    // Passes outwards on both sides from a start: the pass that gave the node before its height,
    // where that one reaches this node, else the nearest line. A side ends at its first pass
    // that cannot lower the node. That is exact from any start as long as the passes' envelopes
    // over the node, taken in the order of their lines, fall to one lowest and rise beyond it
    // (the walk assumed that from the nearest line before). A pass out of reach ends a side only
    // because the farther ones are farther still: true from a start within reach. On a face
    // inclined across the passes the pass that cuts a node has its line R sin(lambda) from it
    // in plan, so from the nearest line every pass in between was walked first (lambda 30 with
    // the passes along the cylinder's axis: 12.1 passages a node, 3.0 from the last winner).
    // The line of the pass at place i of by_line_.
    auto line_at = [&](std::ptrdiff_t i) {
      return s_.window[by_line_[static_cast<std::size_t>(i)]].line;
    };
    std::ptrdiff_t right = 0;
    double from = key;  // where the sides are measured from
    if (s_.parallel) {
      const bool winner_reaches = winner >= 0 && std::abs(key - line_at(winner)) < s_.reach;
      if (winner_reaches)
        right = winner, from = line_at(winner);
      else
        right = std::lower_bound(by_line_.begin(), by_line_.end(), key,
                                 [&](std::size_t p, double v) { return s_.window[p].line < v; }) -
                by_line_.begin();
    }
    std::ptrdiff_t left = right - 1;
    bool left_open = s_.parallel && left >= 0, right_open = s_.parallel && right < n;
    int misses[2] = {0, 0};
    winner = -1;
    while (left_open || right_open) {
      const bool take_left =
          !right_open || (left_open && from - line_at(left) <= line_at(right) - from);
      std::ptrdiff_t& at = take_left ? left : right;
      bool& open = take_left ? left_open : right_open;
      int& missed = misses[take_left ? 0 : 1];
      const std::size_t p = by_line_[static_cast<std::size_t>(at)];
      const double before = best;
      const bool can_lower = std::abs(key - s_.window[p].line) < s_.reach && visit(p);
      if (best < before) winner = at;
      // The seed's pass is skipped as a matter of course: that is not a side's end.
      missed = can_lower || p == seeded ? 0 : missed + 1;
      at += take_left ? -1 : 1;
      open = missed < misses_to_stop && at >= 0 && at < n;
    }
    if (best < z[i]) z[i] = best, ++counts.updates;
    ++(fallback_used_ ? counts.nodes_fallback
       : exact_used_  ? counts.nodes_exact
                      : counts.nodes_followed);
  }
}

double RowSweep::pass_height(std::size_t p, double x, double y, double best, bool& can_lower,
                             NodeCounts& counts) {
  PassState& st = state_[p];
  // The pass's level time is needed only off the fast path: found at most once.
  double level = -INFINITY;
  auto t0 = [&] { return level == -INFINITY ? level = s_.level_time(p, x, y) : level; };
  if (!st.active) {
    if (std::isnan(t0())) return INFINITY;  // never level with this node: look further
    const auto radii = s_.contact_radii(p, t0());
    st.rho_lo = radii.first, st.rho_hi = radii.second, st.active = true;
  }
  const PassageGeometry geo(s_, p, x, y, st.rho_lo, st.rho_hi);
  const bool ideal = !s_.wiggles;
  // The tip's cut where the node lies on the pass's line (+inf elsewhere), found at most once.
  double tip = NAN;
  auto tip_cut = [&] { return std::isnan(tip) ? tip = tip_height(geo, t0) : tip; };
  double t_b;
  if (ideal) {
    // The envelope has a single minimum: its bottom, followed from node to node, is the pass's
    // lowest point, and a pass farther out on this side lies higher still.
    // Along the row the bottom's height changes at the ball's slope across (the envelope
    // theorem: d/dx of the height at fixed t), so a pass found too high stays too high for a
    // while without being looked at again (twice the slope, for the slope's own change over
    // up to a fiftieth of the radius).
    const double moved = std::abs(x - st.floor_x);
    if (moved < 0.02 * s_.R && st.floor - st.floor_slope * moved >= best)
      return can_lower = false, INFINITY;
    t_b = bottom([&](double t) { return geo.envelope(t); }, geo, st, x, t0);
    if (std::isnan(t_b)) return INFINITY;
    const double low = geo.envelope(t_b);
    if (low >= best) {
      const Vec3 c = s_.window[p].centre(t_b);
      const double dx = x - c.x(), dy = y - c.y(), r2 = dx * dx + dy * dy;
      st.floor = low, st.floor_x = x;
      st.floor_slope = r2 < 0.81 * s_.R2 ? 2 * std::abs(dx) / std::sqrt(s_.R2 - r2)
                                         : INFINITY;  // near the rim: no bound, look each time
      return can_lower = false, INFINITY;
    }
  } else {
    // A corrected envelope wiggles: its floor (the nominal centre moved by the correction's
    // whole range) is a true bound with a single minimum; it rules out the passes that cannot
    // come close and ends the walk (walk_corrected).
    // A pass whose floor was too high at an earlier node stays too high for a while: where the
    // floor is below its height H there, the ball's lower cap is no steeper than R / (zc - H)
    // (zc the centre's height), past the rim no steeper than 1, and the floor must climb
    // from `best` to H between the two nodes.
    if (!std::isnan(st.floor_x) &&
        st.floor - floor_steepness(p, st.floor) * std::abs(x - st.floor_x) >= best)
      return can_lower = false, INFINITY;
    bool solved = false;
    if (const double h = revisit(geo, st, best, counts, solved); !std::isnan(h))
      return can_lower = solved, std::min(h, tip_cut());
    t_b = bottom([&](double t) { return geo.floor_envelope(t); }, geo, st, x, t0);
    if (std::isnan(t_b)) return INFINITY;
    if (const double low = geo.floor_envelope(t_b) - 1e-9; low >= best)
      return st.floor = low, st.floor_x = x, can_lower = false, INFINITY;
  }
  bool irregular = false;
  // On the tip's line the tip cuts the node as the axis passes; with its height as the best
  // from the start, the exact windows rule out every piece next to that instant whose ball
  // cannot go lower (on a level pass, all of them) instead of halving towards it.
  if (ideal) best = std::min(best, tip_cut());
  double h = INFINITY;
  if (ideal) {
    h = walk(geo, st, t_b, best, counts);
  } else if (st.wait > 0) {
    --st.wait, irregular = true;  // irregular at the last nodes: the reference walk at once
  } else {
    h = walk_corrected(geo, st, t_b, best, counts, irregular);
    st.waited = irregular ? std::min(2 * st.waited + 1, kMaxWait) : 0, st.wait = st.waited;
  }
  if (s_.stopped()) return INFINITY;  // a walk cut short is not irregular: the map is discarded
  if (irregular) {
    // The reference's own walk, from the reference's own bottom (which the corrected branch
    // has already), so that the result is its.
    ++counts.fallbacks, fallback_used_ = true;
    for (auto& r : st.roots) r.clear();
    PassageGeometry::Crossing low{-1, 0.0, {}};
    h = geo.walk(ideal ? geo.bottom_near(t0()) : t_b, roots_, counts.passages, best, &low);
    // Its lowest passage seeds the next node (seed()), as a corrected walk's would.
    if (!ideal && low.tooth >= 0) {
      walk_tooth_ = low.tooth, walk_t_ = low.t, walk_fallback_ = true;
      fallback_root_ = Root{low.t, 0.0, s_.omega};
      fallback_root_.x = x;
    }
  }
  return std::min(h, tip_cut());
}

template <class T0>
double RowSweep::tip_height(const PassageGeometry& geo, T0 t0) const {
  const std::size_t p = geo.window();
  if (!s_.on_tip_line(p, geo.x(), geo.y())) return INFINITY;
  return geo.tip_height(s_.window[p].tilted ? s_.tip_time(p, geo.x(), geo.y()) : t0());
}

// The bottom moves little from one node to the next: a parabola through three heights around
// the predicted bottom finds it; the golden section over the reference's window when that fails
// (first node of the row, or a function that is not convex there).
template <class F, class T0>
double RowSweep::bottom(F f, const PassageGeometry& geo, PassState& st, double x, T0 t0) {
  double t_b = NAN;
  if (st.have_bottom) {
    const double tp = st.tb + st.tb_rate * (x - st.tb_x), w = 0.1 * s_.period;
    const double fm = f(tp - w), f0 = f(tp), fp = f(tp + w);
    const double curvature = fp - 2 * f0 + fm;
    if (curvature > 0) {
      const double shift = 0.5 * w * (fm - fp) / curvature;
      if (std::abs(shift) <= w) t_b = std::clamp(tp + shift, geo.t_lo(), geo.t_hi());
    }
  }
  if (std::isnan(t_b)) {
    if (std::isnan(t0())) return NAN;
    t_b = geo.bottom_near(f, t0());
  }
  st.tb_rate = st.have_bottom && x != st.tb_x ? (t_b - st.tb) / (x - st.tb_x) : 0.0;
  st.tb = t_b, st.tb_x = x, st.have_bottom = true;
  return t_b;
}

// Each tooth's passages are followed outwards from t_b, root to root (each solved from the last
// node's), as long as the phase is proven monotone between them (PassageGeometry::next_crossing).
// Where it is not (the axis passes close to the node: its azimuth turns faster than the spindle
// and a passage may cross it three times), that revolution is solved exactly in place
// (crossings_lined where the window keeps to its line, else crossings_in) and the walk goes on
// from its far edge. The time around t_b that cannot be followed (the axis's closest approach)
// is solved first, for all teeth at once (the teeth's phases differ by a constant: one solve
// serves them all): a zone reaching out by eighths of a revolution until the phase beyond each
// edge is proven monotone. The teeth are followed from its edges, and its crossings kept as
// roots for the next node, as the walk's own are.
double RowSweep::walk(const PassageGeometry& geo, PassState& st, double t_b, double best_node,
                      NodeCounts& counts) {
  const double rev = s_.rev, t_lo = geo.t_lo(), t_hi = geo.t_hi(), w = std::abs(s_.omega);
  const double beyond = 0.05 * s_.period;  // how near t_b may be off the envelope's bottom
  double best = INFINITY;
  std::uint64_t visited = 0;
  // A crossing's height, if it lies within the window.
  auto take = [&](int tooth, double t, const Probe* known) {
    if (!geo.within(t)) return double(INFINITY);
    const Probe q = known ? *known : geo.probe(tooth, t);
    ++visited;
    if (!std::isfinite(q.height)) return double(INFINITY);
    if (q.over) best = std::min(best, q.height);
    return q.height;
  };
  // A crossing found exactly, kept as a root for the next node (its move from the last node's
  // root nearest it, if any): the walk's steps and first crossings next to an exact revolution
  // then start from the last node's roots too.
  zone_roots_.clear();
  auto keep = [&](const PassageGeometry::Crossing& c, std::vector<Root>& into) {
    const Root* match = nearest(st.roots[static_cast<std::size_t>(c.tooth)], c.t, 0.25 * rev);
    into.push_back(Root::followed(c.t, match, match ? match->slope : s_.omega));
  };
  // Tooth 0's probes at the ends of the zone's last exact solve, and where: the walks from the
  // zone's edges start there (after the zone grew on one side, the other's no longer matches its
  // edge, and is probed again).
  Probe edge_probe[2];
  double edge_probe_at[2] = {NAN, NAN};
  // Every crossing in [lo, hi], exactly (kept: the zone's for every tooth, else `tooth`'s).
  auto exact = [&](int tooth, double lo, double hi) {
    ++counts.exact_windows, exact_used_ = true;
    double limit = std::min(best, best_node);
    roots_.clear();
    const double a = std::max(lo, t_lo), b = std::min(hi, t_hi);
    if (tooth < 0) edge_probe_at[0] = a, edge_probe_at[1] = b;
    // Directly where the window keeps to its line (its solves started from the last node's
    // roots), else by halving.
    bool direct = false;
    if (geo.lined()) {
      hints_.clear();
      for (int j = std::max(tooth, 0); j < (tooth < 0 ? s_.teeth : tooth + 1); ++j)
        for (const Root& r : st.roots[static_cast<std::size_t>(j)])
          hints_.push_back({j, r.ahead()});
      direct = geo.crossings_lined(tooth, a, b, limit, roots_, tooth < 0 ? edge_probe : nullptr,
                                   &hints_);
    }
    if (!direct) geo.crossings_in(tooth, a, b, limit, roots_, tooth < 0 ? edge_probe : nullptr);
    for (const auto& r : roots_) {
      take(r.tooth, r.t, &r.q);
      if (tooth < 0)
        zone_roots_.push_back(r);
      else
        keep(r, fresh_);
    }
  };
  // The zone around t_b solved for all teeth: [zone[0], zone[1]], empty when the phase is proven
  // monotone around t_b (then each tooth's first crossing is followed from the last node's).
  double zone[2] = {t_b, t_b};
  // The span over 1.1 revolutions beyond each edge, where proven monotone there: the first step
  // of every tooth's walk from that edge needs no other.
  PassageGeometry::Span beyond_edge[2]{};
  bool edge_proven[2] = {false, false};
  auto prove_edge = [&](int side) {
    const double edge = zone[side], far = edge + (side ? 1.1 : -1.1) * rev;
    beyond_edge[side] = geo.span(std::min(edge, far), std::max(edge, far));
    return edge_proven[side] = beyond_edge[side].monotone(w);
  };
  if (!geo.monotone_around(t_b, 0.8 * rev) && !geo.monotone(t_b - 0.8 * rev, t_b + 0.8 * rev)) {
    // Each edge as near t_b as the phase is proven monotone beyond it, by eighths of a
    // revolution (the axis's closest approach holds the turn-backs, so a whole revolution solved
    // exactly was mostly pieces far from it); from half a revolution out, by whole ones (below).
    for (int side = 0; side < 2; ++side) {
      const double dir = side ? 1.0 : -1.0;
      for (int k = 1; k <= 4; ++k)
        if (zone[side] = t_b + dir * k * rev / 8; k == 4 || prove_edge(side)) break;
    }
    exact(-1, zone[0], zone[1]);
    for (int side = 0; side < 2; ++side) {
      const double dir = side ? 1.0 : -1.0;
      double& edge = zone[side];
      // (On a steep face this can walk a whole pass, revolution by revolution, for one node:
      // a stop request is checked at each.)
      while (!edge_proven[side] && (dir > 0 ? edge < t_hi + rev / 2 : edge > t_lo - rev / 2) &&
             !s_.stopped() && geo.envelope(edge) < std::min(best, best_node) && !prove_edge(side)) {
        exact(-1, std::min(edge, edge + dir * rev), std::max(edge, edge + dir * rev));
        edge += dir * rev;
      }
    }
  }
  const bool zoned = zone[1] > zone[0];
  for (int tooth = 0; tooth < s_.teeth; ++tooth) {
    std::vector<Root>& prev = st.roots[static_cast<std::size_t>(tooth)];
    fresh_.clear();
    for (const auto& r : zone_roots_)
      if (r.tooth == tooth) keep(r, fresh_);
    // The crossing near `guess`, started from the previous node's root predicted nearest to it
    // (within `reach`); NaN when it did not converge.
    // `matched` gets the root started from (null if none). `hint`, where given, is started from
    // instead of the one nearest `guess`.
    auto solve = [&](double guess, double reach, Probe& q, const Root*& matched,
                     const Root* hint = nullptr) {
      const Root* match = hint;
      if (!match)
        for (const Root& r : prev)
          if (std::abs(r.t + r.drift - guess) < reach)
            reach = std::abs(r.t + r.drift - guess), match = &r;
      matched = match;
      double slope = match ? match->slope : s_.omega;
      // Started where the root's last moves say it goes on to (Root::ahead: on smooth passes the
      // guess is then often within the tolerance and one probe settles it; 7 % of the
      // instructions at lambda 30 with the last two moves, and 7-8 % near the axis with five).
      const double t = geo.crossing(tooth, match ? match->ahead() : guess, slope, q);
      if (!PassageGeometry::converged(q)) return double(NAN);
      // The root kept for the next node is one more Newton step on (no probe): the probed time
      // is up to 1e-9 rad off, which the extrapolation above amplifies, so that on smooth passes
      // the next node's guess often missed the tolerance by that alone (lambda 30: 15 % of the
      // instructions). The height stays the probe's.
      fresh_.push_back(Root::followed(t - q.g / slope, match, slope));
      return t;
    };
    // The first crossing: near t_b where the phase is monotone around it (the secant can run
    // off elsewhere: then, as where it is not monotone, the revolution around t_b exactly).
    Probe first{};
    double t_first = NAN;
    const Root* first_match = nullptr;
    if (!zoned) {
      t_first = solve(t_b, 0.75 * rev, first, first_match);
      if (std::isnan(t_first) || std::abs(t_first - t_b) > 0.75 * rev) {
        t_first = NAN;
        exact(tooth, t_b - 0.5 * rev, t_b + 0.5 * rev);
      }
    }
    const bool first_root = !std::isnan(t_first);
    const double first_height = first_root ? take(tooth, t_first, &first) : INFINITY;
    const double first_rate = first_root ? fresh_.back().slope : NAN;  // (solve's, just pushed)
    for (int dir : {+1, -1}) {
      // Where the walk stands: a crossing, or the edge of a revolution solved exactly.
      double t_prev = first_root ? t_first : zoned ? zone[dir > 0] : t_b + dir * 0.5 * rev;
      bool at_root = first_root;
      double rho_prev = first.rho;    // the root's distance from the axis, when at one
      Probe q_prev = first;           // the tooth's probe at t_prev (when at a root, or once asked)
      double rate_prev = first_rate;  // the phase's rate at t_prev, when at a root
      const Root* from = first_root ? first_match : nullptr;  // the last node's root at t_prev
      RiseCount rise;
      if (first_root) rise.add(first_height);
      for (int m = 1; m < 100000 && !rise.done(); ++m) {
        // Past the window's end the walk goes (the first root may lie beyond its other end: a
        // window can be shorter than a revolution).
        if (dir > 0 ? t_prev > t_hi + rev / 2 : t_prev < t_lo - rev / 2) break;
        // Every later crossing lies beyond t_bound; past the bottom the envelope only rises, so
        // if it is already too high there, no later passage can lower the node. The gap to the
        // next crossing (at most half a revolution) is asked only where that would end the walk.
        auto ends_at = [&](double t_bound) {
          return dir * (t_bound - t_b) >= beyond &&
                 geo.envelope(t_bound) >= std::min(best, best_node);
        };
        // (Past the bottom the envelope only rises: where it is too high at the root itself, it is
        // at the next crossing however soon that comes, and the gap need not be proven.)
        if (ends_at(at_root ? t_prev + dir * 0.5 * rev : t_prev)) {
          if (!at_root || ends_at(t_prev) ||
              ends_at(t_prev + dir * geo.next_gap(t_prev, rho_prev, dir)))
            break;
        } else if (at_root && geo.lined() && std::abs(rate_prev) < w &&
                   ends_at(t_prev + dir * kTwoPi / std::abs(rate_prev))) {
          // Where the phase runs slow (the node's azimuth turning against the spindle as the
          // axis passes), the next crossing can lie more than half a revolution on, where the
          // envelope is already too high: the pass's line bounds how soon it can come
          // (line_gap), and the walk ends without solving it. Asked only where the rate at the
          // root says the next crossing comes that late, too high. (Lambda 0: 12 % fewer
          // passages solved and 3 % fewer instructions; the flat vertical case 17 % and 5 %.)
          if (const double line = geo.line_gap(rho_prev, 1.1 * rev);
              line > 0.5 * rev && ends_at(t_prev + dir * line))
            break;
        }
        // The next revolution exactly, where the next crossing cannot be proven the next.
        auto solve_revolution = [&] {
          exact(tooth, std::min(t_prev, t_prev + dir * rev), std::max(t_prev, t_prev + dir * rev));
          t_prev += dir * rev, at_root = false;
        };
        const double far = t_prev + dir * 1.1 * rev;
        // Where the phase is monotone all along (most nodes), no span is asked: the step's turn
        // is read exactly from its probes below.
        const bool easy = at_root && geo.monotone_from(rho_prev, 1.1 * rev);
        PassageGeometry::Span ahead{};
        if (!easy) {
          const int side = dir > 0;
          ahead = !at_root && zoned && t_prev == zone[side] && edge_proven[side]
                      ? beyond_edge[side]
                      : geo.span(std::min(t_prev, far), std::max(t_prev, far));
          if (!ahead.monotone(w)) {
            solve_revolution();
            continue;
          }
        }
        double guess = t_prev + dir * rev, gap = 0;
        if (at_root) {
          // From a root: a turn at the phase's rate there (Newton's last slope), where that is
          // within a factor 2 of the spindle's. Near the axis the rate differs from the spindle's
          // by the node's azimuth rate, and a revolution's guess took two more Newton steps where
          // the last node gave no root to start from (flat plate: 4 % of the walk's instructions).
          const double r = std::abs(rate_prev);
          if (r > 0.5 * w && r < 2 * w) guess = t_prev + dir * kTwoPi / r;
        } else {
          // From an edge: the next crossing is where the phase has turned on to its next zero.
          const int side = dir > 0;
          q_prev = t_prev == edge_probe_at[side] ? geo.turned_to(edge_probe[side], tooth)
                                                 : geo.probe(tooth, t_prev);
          const double g = q_prev.g;
          gap = dir * s_.omega > 0 ? -g : g;
          gap -= kTwoPi * std::floor(gap / kTwoPi);  // the turn still to go, in [0, 2 pi)
          // That turn takes at least gap / top (the span just proven monotone bounds the rate):
          // where the envelope is already too high there, no crossing beyond the edge can lower
          // the node.
          if (ends_at(t_prev + dir * gap / ahead.top(w))) break;
          guess = t_prev + dir * gap / w;
        }
        // From a root that was the last node's too, the next is where the last node's next was
        // (where the rate at the root would put it, the phase may speed up across the axis's
        // closest approach and the guess skip a crossing: a revolution then solved exactly).
        const Root* hint = nullptr;
        if (at_root && from) {
          const std::ptrdiff_t next = (from - prev.data()) + dir;  // (prev is sorted by time)
          if (next >= 0 && next < static_cast<std::ptrdiff_t>(prev.size()) &&
              dir * (prev[next].t + prev[next].drift - t_prev) > 0.25 * rev)
            hint = &prev[next];
        }
        Probe q{};
        const double t = solve(guess, 0.25 * rev, q, from, hint);
        // After a crossing, t must be the next; after an edge, the first beyond it (a crossing
        // before it was found by the exact solve already: the walk goes on from there). The
        // phase turns by `need` plus whole turns from t_prev to t (both ends say so): t is the
        // next when it cannot have turned one more, which the span just proven monotone often
        // shows by its own bound. Else the turn is found exactly: on a span proven monotone the
        // axis stays in a convex region that leaves the node out (monotone needs rho_lo > 0), so
        // the phase's turn across it is known from the probes at its ends (advance); where t
        // lies beyond `far` (the phase slowed: near the axis, on the side where the node's
        // azimuth turns against the spindle), a second span from `far` to t must be monotone too.
        const double moved = dir * (t - t_prev), need = at_root ? kTwoPi : gap;
        bool ok = false;
        if (!std::isnan(t) && !at_root && moved < 0) {
          ok = true;  // behind the edge: the exact solve has it already
        } else if (!std::isnan(t) && moved > (at_root ? 0.25 * rev : 0)) {
          if (moved <= 1.1 * rev) {
            // (Less by a margin: where the bound is tight, G' = omega on a pass's line, a solve
            // that went one turn too far has top * moved = need + 2 pi but for round-off.)
            ok = (!easy && ahead.top(w) * moved < need + kTwoPi - 1e-6) ||
                 geo.turned(need, t_prev, q_prev, t, q);
          } else if ((at_root && geo.monotone_from(rho_prev, moved)) || geo.monotone(far, t)) {
            // (Where the centre keeps to a strip that leaves the node out, the turn over the
            // whole step is exact at once: no probe at `far`.)
            if (geo.off_strip()) {
              ok = geo.turned(need, t_prev, q_prev, t, q);
            } else {
              const Probe q_far = geo.probe(tooth, far);
              ok = geo.turned(need, t_prev, q_prev, far, q_far, t, q);
            }
          }
        }
        if (!ok) {
          solve_revolution();
          continue;
        }
        t_prev = t, at_root = true, rho_prev = q.rho, q_prev = q, rate_prev = fresh_.back().slope;
        rise.add(take(tooth, t, &q));
      }
    }
    std::sort(fresh_.begin(), fresh_.end(), [](const Root& a, const Root& b) { return a.t < b.t; });
    prev.swap(fresh_);
  }
  counts.passages += visited;
  return best;
}

double RowSweep::seed(double x, double y, NodeCounts& counts) {
  if (win_pass_ == kNone) return INFINITY;
  PassState& st = state_[win_pass_];
  const PassageGeometry geo(s_, win_pass_, x, y, st.rho_lo, st.rho_hi);
  Root* r = win_fallback_
                ? &win_fallback_root_
                : nearest(st.roots[static_cast<std::size_t>(win_tooth_)], win_t_, 0.25 * s_.rev);
  if (!r) return INFINITY;
  Root solved{};
  Probe q{};
  if (!solve_root(geo, win_tooth_, r, 0.0, solved, q) || !geo.within(solved.t) ||
      !std::isfinite(q.height) || std::abs(solved.t - r->t) > 0.25 * s_.rev)
    return INFINITY;
  ++counts.passages;
  *r = solved;  // the walk finds this passage solved here and does not solve it again
  win_t_ = solved.t;
  return q.over ? q.height : INFINITY;
}

RowSweep::Root* RowSweep::nearest(std::vector<Root>& roots, double t, double reach) {
  Root* match = nullptr;
  const auto next = std::lower_bound(roots.begin(), roots.end(), t,
                                     [](const Root& r, double v) { return r.t < v; });
  for (auto it = next == roots.begin() ? next : next - 1; it != roots.end() && it <= next; ++it)
    if (std::abs(it->t - t) < reach) reach = std::abs(it->t - t), match = &*it;
  return match;
}

bool RowSweep::solve_root(const PassageGeometry& geo, int tooth, const Root* from, double guess,
                          Root& r, Probe& q) const {
  const double x = geo.x();
  double slope = from ? from->slope : s_.omega;
  const double t =
      geo.crossing(tooth, from ? from->t + from->drift * (x - from->x) : guess, slope, q);
  if (!PassageGeometry::converged(q)) return false;
  r = Root{t, from && x != from->x ? (t - from->t) / (x - from->x) : 0.0, slope};
  if (geo.within(t) && std::isfinite(q.height))
    r.x = x, r.height = q.height,
    r.fall = fall_rate(geo.window(), t, q.rho,
                       s_.window[geo.window()].tilted ? geo.distance(t) : q.rho, r.reach);
  return true;
}

// The pass as last walked, again: every passage between its stops is known, and one whose bound
// fails (it may have fallen below `best` since it was solved) is solved again where it is; the
// rest stay. NaN when that is not enough and the pass must be walked: no walk yet, the floor
// at a stop no longer rules out what lies beyond, or a passage moved irregularly.
double RowSweep::revisit(const PassageGeometry& geo, PassState& st, double best, NodeCounts& counts,
                         bool& solved) {
  if (std::isnan(st.stop[0]) || !std::isfinite(best)) return NAN;
  if (geo.floor_envelope(st.stop[0]) < best || geo.floor_envelope(st.stop[1]) < best) return NAN;
  const double x = geo.x(), rev = s_.rev, t_lo = geo.t_lo(), t_hi = geo.t_hi();
  double low = INFINITY;
  bool any = false;
  for (int tooth = 0; tooth < s_.teeth; ++tooth) {
    // Passages beyond the window are solved again too (they count for nothing there, but move
    // with the node and can come in): where the last walk ended at the window's end rather than
    // at a stop, the tooth's known passages must still reach past that end, or one not known
    // may have come into the window.
    double first = INFINITY, last = -INFINITY;
    for (Root& r : st.roots[static_cast<std::size_t>(tooth)]) {
      any = true;
      const double target = std::min(best, low);
      if (stays_above(r, x, target)) continue;
      Root again{};
      Probe q{};
      // The same passage, and no other of this tooth born within a revolution of it (the phase
      // monotone there): else the pass is walked again.
      if (!solve_root(geo, tooth, &r, 0.0, again, q) || std::abs(again.t - r.t) > 0.25 * rev ||
          !geo.monotone(again.t - rev, again.t + rev))
        return NAN;
      r = again, solved = true;
      first = std::min(first, r.t), last = std::max(last, r.t);
      if (geo.within(r.t) && std::isfinite(q.height)) {
        ++counts.passages;
        if (q.over && q.height < low) low = q.height, walk_tooth_ = tooth, walk_t_ = r.t;
      }
    }
    if ((st.stop[0] < t_lo && !(first <= t_lo)) || (st.stop[1] > t_hi && !(last >= t_hi)))
      return NAN;
  }
  return any ? low : NAN;
}

double RowSweep::floor_steepness(std::size_t p, double below) const {
  const double depth = s_.window[p].lowest_centre - below;
  return depth > 0 ? std::max(1.0, s_.R / depth) : INFINITY;
}

// On a corrected path a passage's height along the row, h(x) = E(t(x), x) (E the ball's surface
// over the node, t(x) the passage's root), falls at most at
//   |dE/dx| + |dE/dt| |dt/dx| <= tan(alpha) + (vz + tan(alpha) vxy) bx,
// where bx = |g_x| / |g_t| bounds the root's move: |g_x| <= 1/rho + k (the node's azimuth and the
// lag, k = |lag'| / (R cos alpha)), |g_t| >= |omega| - vxy sqrt(1/rho^2 + k^2). All with the
// centre's top speeds (vxy, vz) over a window either side of the root (eight correction steps)
// and rho over what the node and the axis can move in it, so the bound holds while the root stays
// in the window (reach = window / bx) and the node within kReach. Where the correction jerks the
// axis sideways faster than the edge sweeps (|g_t| could vanish), there is no bound.
// A tilted tool: alpha and the height's slope are the plan's (the ball is the same sphere), while
// rho, k and the azimuth are the ball point's in the tool frame, which moves at most L = R / h
// (h = sqrt(R^2 - rho_plan^2)) times as far as the plan offset does (the lift, span_tilted): so
// |g_x| <= L (1/rho + k) and |g_t| >= |omega| - L vxy sqrt(1/rho^2 + k^2). L = 1 when vertical.
double RowSweep::fall_rate(std::size_t p, double t, double rho, double plan, double& reach) const {
  constexpr double kReach = 0.05;  // mm along the row
  // The window either side of t: eight correction steps, or with none (a runout alone) a
  // quarter revolution, within which the next node's root stays.
  const double step = s_.path->correction_step(s_.window[p].pass);
  const double w = step > 0 ? 8 * step : 0.25 * s_.rev;
  const auto [vxy, vz] = s_.top_speed(p, t - w, t + w);
  const double moved = vxy * w + kReach;  // how far the plan offset can go in the window
  const double plan_hi = plan + moved;
  if (plan_hi >= 0.95 * s_.R) return INFINITY;
  const double sp_hi = plan_hi / s_.R, cp_hi = std::sqrt(1 - sp_hi * sp_hi);
  const double L = s_.window[p].tilted ? 1 / cp_hi : 1.0;
  // A turning frame moves the point by up to |theta'| R more a second (span_tilted).
  const double turned = s_.window[p].turn.on ? s_.window[p].turn.rate * s_.R : 0.0;
  const double rho_lo = rho - (L * moved + turned * w), rho_hi = rho + L * moved + turned * w;
  if (rho_lo <= 0 || rho_hi >= 0.95 * s_.R) return INFINITY;
  const double s_lo = rho_lo / s_.R, s_hi = rho_hi / s_.R;
  const double c_lo = std::sqrt(1 - s_lo * s_lo), c_hi = std::sqrt(1 - s_hi * s_hi);
  const double lag_slope = std::max(std::abs(s_.tool->lag_slope_sc(s_lo, c_lo)),
                                    std::abs(s_.tool->lag_slope_sc(s_hi, c_hi)));
  const double k = lag_slope / (s_.R * c_hi);
  const double sweep =
      std::abs(s_.omega) - (L * vxy + turned) * std::sqrt(1 / (rho_lo * rho_lo) + k * k);
  if (sweep <= 0.2 * std::abs(s_.omega)) return INFINITY;
  const double bx = L * (1 / rho_lo + k) / sweep;
  reach = std::min(kReach, w / bx);
  const double tan_hi = sp_hi / cp_hi;
  return tan_hi + (vz + tan_hi * vxy) * bx;
}

// Every passage is visited outwards from t_b until the floor proves that no later one can lower
// the node (no rule of thumb: the correction makes heights jump from passage to passage), but a
// passage whose height, solved at an earlier node of the row, cannot have fallen below the best
// since (fall_rate) is not solved again.
double RowSweep::walk_corrected(const PassageGeometry& geo, PassState& st, double t_b,
                                double best_node, NodeCounts& counts, bool& irregular) {
  const double rev = s_.rev, t_lo = geo.t_lo(), t_hi = geo.t_hi(), x = geo.x();
  const double beyond = 0.05 * s_.period;  // how near t_b may be off the floor's bottom
  double best = INFINITY;
  std::uint64_t visited = 0;
  // The passage of `tooth` near `guess` (its root within `reach` of the time): skipped if its
  // bound allows, else solved; appended to `out`; false when irregular.
  auto visit = [&](int tooth, double guess, double reach, double& t, std::vector<Root>& out) {
    const Root* match = nearest(st.roots[static_cast<std::size_t>(tooth)], guess, reach);
    if (match && stays_above(*match, x, std::min(best, best_node))) {
      out.push_back(*match);
      t = match->t;
      return true;
    }
    Root r{};
    Probe q{};
    // A secant that ran off (more than `reach` from the guess: the first one was seen 8
    // revolutions away, outside the stops, which ended the walk at once) is irregular.
    if (!solve_root(geo, tooth, match, guess, r, q) || std::abs(r.t - guess) > reach) return false;
    t = r.t;
    if (geo.within(t) && std::isfinite(q.height)) {
      ++visited;
      if (q.over && q.height < best) best = q.height, walk_tooth_ = tooth, walk_t_ = t;
    }
    out.push_back(r);
    return true;
  };
  // Each tooth's passage nearest the floor's bottom first, for a best to bound the rest by.
  std::vector<double>& first = first_;
  first.assign(static_cast<std::size_t>(s_.teeth), 0.0);
  for (int tooth = 0; tooth < s_.teeth; ++tooth) {
    const auto j = static_cast<std::size_t>(tooth);
    later_[j].clear(), before_[j].clear();
    if (!visit(tooth, t_b, 0.5 * rev, first[j], later_[j])) return irregular = true, INFINITY;
  }
  // Where the floor, past its bottom, is too high for any passage to lower the node, on each
  // side: moved from the last node's, which it is close to. The best only falls from here on,
  // which can only bring these nearer: they stay true.
  const double target = std::min(best, best_node);
  for (int side = 0; side < 2; ++side) {
    const double dir = side ? 1.0 : -1.0;
    double& stop = st.stop[side];
    if (std::isnan(stop) || dir * (stop - t_b) < beyond) stop = t_b + dir * beyond;
    while (geo.bound(stop) < target && dir * (stop - t_b) < t_hi - t_lo + rev && !s_.stopped())
      stop += dir * 0.5 * rev;
    while (dir * (stop - dir * 0.5 * rev - t_b) >= beyond &&
           geo.bound(stop - dir * 0.5 * rev) >= target)
      stop -= dir * 0.5 * rev;
  }
  for (int tooth = 0; tooth < s_.teeth; ++tooth) {
    const auto j = static_cast<std::size_t>(tooth);
    for (int side = 1; side >= 0; --side) {
      const double dir = side ? 1.0 : -1.0;
      std::vector<Root>& out = side ? later_[j] : before_[j];
      double t_prev = first[j];
      for (int m = 1; m < 100000 && !s_.stopped(); ++m) {
        // Past the window's end (the first passage may lie beyond its other end): every
        // passage from the first to one beyond the end is visited, each proven the next of the
        // last (next_crossing), so that none inside is passed over (a node near the axis is
        // crossed again within a revolution, which no step of one revolution would see).
        if (dir > 0 ? t_prev > t_hi : t_prev < t_lo) break;
        const double guess = t_prev + dir * rev;
        // Every later passage lies beyond the next one's least gap (at most half a revolution).
        if (dir * (t_prev + dir * 0.5 * rev - st.stop[side]) >= 0 &&
            dir * (t_prev + dir * geo.next_gap(t_prev, geo.axis_distance(t_prev), dir) -
                   st.stop[side]) >=
                0)
          break;
        double t = 0;
        if (!visit(tooth, guess, 0.25 * rev, t, out) || !geo.next_crossing(t_prev, t))
          return irregular = true, INFINITY;
        t_prev = t;
      }
    }
  }
  for (int tooth = 0; tooth < s_.teeth; ++tooth) {
    const auto j = static_cast<std::size_t>(tooth);
    std::vector<Root>& prev = st.roots[j];
    prev.assign(before_[j].rbegin(), before_[j].rend());
    prev.insert(prev.end(), later_[j].begin(), later_[j].end());
  }
  counts.passages += visited;
  return best;
}

}  // namespace topomill::plugins
