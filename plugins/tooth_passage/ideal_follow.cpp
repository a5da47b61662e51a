#include "ideal_follow.hpp"

#include <algorithm>

namespace topomill::plugins {

namespace {
// A walk never takes more steps than this in one direction (a guard: the stops end it first).
constexpr int kMaxSteps = 100000;
}  // namespace

IdealFollow::IdealFollow(const PassageGeometry& geo, std::vector<std::vector<Root>>& roots,
                         Scratch& scratch, NodeCounts& counts)
    : s_(geo.setup()),
      geo_(geo),
      roots_(roots),
      scratch_(scratch),
      counts_(counts),
      rev_(s_.rev),
      t_lo_(geo.t_lo()),
      t_hi_(geo.t_hi()),
      w_(std::abs(s_.omega)) {}

double IdealFollow::run(double t_b, double best_node) {
  t_b_ = t_b, best_node_ = best_node, best_ = INFINITY;
  cut_[0] = cut_[1] = Cut{};
  scratch_.zone.clear();
  seeded_ = false;
  zone_[0] = zone_[1] = t_b;
  solve_zone();
  for (int tooth = 0; tooth < s_.teeth; ++tooth) follow(tooth);
  counts_.passages += visited_;
  return best_;
}

inline double IdealFollow::take(int tooth, double t, const Probe* known) {
  if (!geo_.within(t)) return INFINITY;
  const Probe q = known ? *known : geo_.probe(tooth, t);
  ++visited_;
  if (!std::isfinite(q.height)) return INFINITY;
  if (q.over) best_ = std::min(best_, q.height);
  return q.height;
}

inline void IdealFollow::keep(const PassageGeometry::Crossing& c, std::vector<Root>& into) {
  const Root* match = nearest(roots_[static_cast<std::size_t>(c.tooth)], c.t, kSamePassage * rev_);
  into.push_back(Root::followed(c.t, match, match ? match->slope : s_.omega));
}

inline void IdealFollow::exact(int tooth, double lo, double hi) {
  ++counts_.exact_windows, exact_used_ = true;
  double limit = std::min(best_, best_node_);
  std::vector<PassageGeometry::Crossing>& found = scratch_.found;
  found.clear();
  const double a = std::max(lo, t_lo_), b = std::min(hi, t_hi_);
  if (tooth < 0) edge_probe_at_[0] = a, edge_probe_at_[1] = b;
  // The direct solve starts from where the last node's roots lead.
  scratch_.hints.clear();
  if (geo_.lined())
    for (int j = std::max(tooth, 0); j < (tooth < 0 ? s_.teeth : tooth + 1); ++j)
      for (const Root& r : roots_[static_cast<std::size_t>(j)])
        scratch_.hints.push_back({j, r.ahead()});
  geo_.crossings(tooth, a, b, limit, found, tooth < 0 ? edge_probe_ : nullptr, &scratch_.hints);
  for (const auto& r : found) {
    take(r.tooth, r.t, &r.q);
    if (tooth < 0)
      scratch_.zone.push_back(r);
    else
      keep(r, scratch_.fresh);
  }
}

inline bool IdealFollow::prove_edge(int side) {
  const double edge = zone_[side], far = edge + (side ? kAhead : -kAhead) * rev_;
  beyond_edge_[side] = geo_.monotony({edge, far});
  return edge_proven_[side] = beyond_edge_[side].monotone;
}

inline double IdealFollow::cut(int dir, double from, double far) const {
  // (Halved to an eighth of the stretch: close enough that the rest is not needlessly long.)
  constexpr int kHalvings = 3;
  if (!std::isfinite(std::min(best_, best_node_)) || !ends_at(dir, far)) return NAN;
  double in = from, out = far;
  for (int k = 0; k < kHalvings; ++k) {
    const double mid = 0.5 * (in + out);
    (ends_at(dir, mid) ? out : in) = mid;
  }
  return out;
}

inline PassageGeometry::Monotony IdealFollow::cut_ahead(int dir, double from, double far,
                                                        double& until) {
  Cut& k = cut_[dir > 0];
  if (!(dir * (k.at - from) > 0 && dir * (k.at - far) <= 0)) {
    k.at = cut(dir, from, far), k.from = NAN;
    if (std::isnan(k.at)) return {};
  }
  until = k.at;
  if (!(k.proven.monotone && dir * (from - k.from) >= 0))
    k.proven = geo_.monotony({from, k.at}), k.from = from;
  return k.proven;
}

inline bool IdealFollow::nears_rim(double t, double reach) const {
  const PassageSetup::Window& w = s_.window[geo_.window()];
  return !w.tilted && !w.turn.on && geo_.distance(t) + w.plan_line.speed * reach > geo_.rim();
}

inline void IdealFollow::seed_limit() {
  scratch_.seeded.assign(static_cast<std::size_t>(s_.teeth), Seeded{});
  seeded_ = true;
  for (int tooth = 0; tooth < s_.teeth; ++tooth) {
    const Root* near = nearest(roots_[static_cast<std::size_t>(tooth)], t_b_, 0.75 * rev_);
    if (!near) continue;
    double slope = near->slope;
    Probe q{};
    const double t = geo_.crossing(tooth, near->ahead(), slope, q);
    scratch_.seeded[static_cast<std::size_t>(tooth)] = {near, t, slope, q};
    if (PassageGeometry::converged(q)) take(tooth, t, &q);
  }
}

inline bool IdealFollow::proven_to_cuts(double reach) {
  const double t_b = t_b_;
  if (!nears_rim(t_b, reach)) return false;
  if (!std::isfinite(best_node_)) seed_limit();
  const double lo = cut(-1, t_b, t_b - reach), hi = cut(+1, t_b, t_b + reach);
  if (std::isnan(lo) && std::isnan(hi)) return false;
  const double a = std::isnan(lo) ? t_b - reach : lo, b = std::isnan(hi) ? t_b + reach : hi;
  const PassageGeometry::Monotony m = geo_.monotony({a, b});
  if (!m.monotone) return false;
  // (What it proves stands for the steps up to each cut.)
  if (!std::isnan(lo)) cut_[0] = {lo, b, m};
  if (!std::isnan(hi)) cut_[1] = {hi, a, m};
  return true;
}

inline void IdealFollow::solve_zone() {
  const double t_b = t_b_, rev = rev_, reach = 0.8 * rev;
  // Where the tube is narrower than the pass moves in that reach (a flat end's corner), the rim is
  // within reach of wherever the cutter cuts, and a whole revolution is seldom proven monotone:
  // the cuts are tried first.
  const bool cuts_first = s_.window[geo_.window()].plan_line.speed * reach >= s_.profile.tube();
  if (cuts_first && proven_to_cuts(reach)) return;
  if (geo_.monotony(geo_.around(t_b, reach)).monotone || (!cuts_first && proven_to_cuts(reach)))
    return;
  // Each edge as near t_b as the phase is proven monotone beyond it, by eighths of a revolution
  // (the axis's closest approach holds the turn-backs, so a whole revolution solved exactly is
  // mostly pieces far from it); from half a revolution out, by whole ones (below).
  for (int side = 0; side < 2; ++side) {
    const double dir = side ? 1.0 : -1.0;
    for (int k = 1; k <= 4; ++k)
      if (zone_[side] = t_b + dir * k * rev / 8; k == 4 || prove_edge(side)) break;
  }
  exact(-1, zone_[0], zone_[1]);
  for (int side = 0; side < 2; ++side) {
    const double dir = side ? 1.0 : -1.0;
    double& edge = zone_[side];
    // (On a steep face this can walk a whole pass, revolution by revolution, for one node: a
    // stop request is checked at each.)
    while (!edge_proven_[side] && (dir > 0 ? edge < t_hi_ + rev / 2 : edge > t_lo_ - rev / 2) &&
           !s_.stopped() && geo_.envelope(edge) < std::min(best_, best_node_) &&
           !prove_edge(side)) {
      exact(-1, std::min(edge, edge + dir * rev), std::max(edge, edge + dir * rev));
      edge += dir * rev;
    }
  }
}

inline double IdealFollow::solve(int tooth, double guess, double reach, Probe& q,
                                 const Root*& matched, const Root* hint) {
  const Root* match = hint;
  if (!match)
    for (const Root& r : *prev_)
      if (std::abs(r.t + r.drift - guess) < reach)
        reach = std::abs(r.t + r.drift - guess), match = &r;
  matched = match;
  double slope = match ? match->slope : s_.omega;
  // Started where the root's last moves say it goes on to (Root::ahead: on smooth passes the
  // guess is then often within the tolerance, and one probe settles it); solved already where
  // seed_limit started from the same root.
  const Seeded* seeded = seeded_ ? &scratch_.seeded[static_cast<std::size_t>(tooth)] : nullptr;
  const double t = match && seeded && seeded->from == match
                       ? (slope = seeded->slope, q = seeded->q, seeded->t)
                       : geo_.crossing(tooth, match ? match->ahead() : guess, slope, q);
  if (!PassageGeometry::converged(q)) return NAN;
  // The root kept for the next node is one more Newton step on (no probe): the probed time is up
  // to 1e-9 rad off, which the extrapolation amplifies, so that on smooth passes the next node's
  // guess would often miss the tolerance by that alone. The height stays the probe's.
  scratch_.fresh.push_back(Root::followed(t - q.g / slope, match, slope));
  return t;
}

inline void IdealFollow::follow(int tooth) {
  prev_ = &roots_[static_cast<std::size_t>(tooth)];
  std::vector<Root>& fresh = scratch_.fresh;
  fresh.clear();
  for (const auto& r : scratch_.zone)
    if (r.tooth == tooth) keep(r, fresh);
  const bool zoned = zone_[1] > zone_[0];
  // The first crossing: near t_b where the phase is monotone around it (the secant can run off
  // elsewhere: then, as where it is not monotone, the revolution around t_b exactly).
  Probe first{};
  double t_first = NAN;
  const Root* first_match = nullptr;
  if (!zoned) {
    t_first = solve(tooth, t_b_, 0.75 * rev_, first, first_match);
    if (std::isnan(t_first) || std::abs(t_first - t_b_) > 0.75 * rev_) {
      t_first = NAN;
      exact(tooth, t_b_ - 0.5 * rev_, t_b_ + 0.5 * rev_);
    }
  }
  const bool first_root = !std::isnan(t_first);
  const double first_height = first_root ? take(tooth, t_first, &first) : INFINITY;
  const double first_rate = first_root ? fresh.back().slope : NAN;  // (solve's, just pushed)
  for (int dir : {+1, -1}) {
    Cursor c{first_root ? t_first
             : zoned    ? zone_[dir > 0]
                        : t_b_ + dir * 0.5 * rev_,
             first_root,
             first.rho,
             first,
             first_rate,
             first_root ? first_match : nullptr,
             {},
             false};
    if (first_root) c.rise.add(first_height);
    for (int m = 1; m < kMaxSteps && !c.rise.done(); ++m)
      if (!step(tooth, dir, c)) break;
  }
  std::sort(fresh.begin(), fresh.end(), [](const Root& a, const Root& b) { return a.t < b.t; });
  prev_->swap(fresh);
}

inline bool IdealFollow::ends_at(int dir, double t_bound) const {
  // Past the bottom the envelope only rises: if it is already too high at t_bound, no later
  // passage can lower the node.
  return geo_.ends_by_bound(t_b_, dir, t_bound, std::min(best_, best_node_));
}

inline bool IdealFollow::ends_before_next(int dir, const Cursor& c) const {
  // The gap to the next crossing (at most half a revolution) is asked only where that would end
  // the walk; where the envelope is too high at the root itself, it is at the next crossing
  // however soon that comes, and the gap need not be proven.
  if (ends_at(dir, c.at_root ? c.t + dir * 0.5 * rev_ : c.t))
    return !c.at_root || ends_at(dir, c.t) ||
           ends_at(dir, c.t + dir * geo_.next_gap(c.t, c.rho, dir));
  // Where the phase runs slow (the node's azimuth turning against the spindle as the axis
  // passes), the next crossing can lie more than half a revolution on, where the envelope is
  // already too high: the pass's line bounds how soon it can come (line_gap), and the walk ends
  // without solving it. Asked only where the rate at the root says the next crossing comes that
  // late, too high.
  if (c.at_root && geo_.lined() && std::abs(c.rate) < w_ &&
      ends_at(dir, c.t + dir * kTwoPi / std::abs(c.rate))) {
    const double line = geo_.line_gap(c.rho, kAhead * rev_);
    return line > 0.5 * rev_ && ends_at(dir, c.t + dir * line);
  }
  return false;
}

inline void IdealFollow::solve_revolution(int tooth, int dir, Cursor& c) {
  exact(tooth, std::min(c.t, c.t + dir * rev_), std::max(c.t, c.t + dir * rev_));
  c.t += dir * rev_, c.at_root = false, c.jumped = false;
}

inline bool IdealFollow::step(int tooth, int dir, Cursor& c) {
  // Past the window's end the walk goes (the first root may lie beyond its other end: a window
  // can be shorter than a revolution).
  if (dir > 0 ? c.t > t_hi_ + rev_ / 2 : c.t < t_lo_ - rev_ / 2) return false;
  if (ends_before_next(dir, c)) return false;
  double far = c.t + dir * kAhead * rev_;
  // Where the phase is monotone all along by the root's distance from the axis (most nodes), no
  // span is asked: the step's turn is read exactly from its probes (proven_next).
  const int side = dir > 0;
  PassageGeometry::Monotony look =
      !c.at_root && zone_[1] > zone_[0] && c.t == zone_[side] && edge_proven_[side]
          ? beyond_edge_[side]
          : geo_.monotony({c.t, far, c.at_root ? c.rho : NAN, kAhead * rev_});
  // Where the whole look ahead is not proven, the part of it the bound leaves to the walk may be.
  // A cursor on the far side of where the bound leaves crossings to the walk (a root past a
  // ringed cutter's reach, where the phase goes on with no edge): nothing between it and where the
  // bound allows again can lower the node, and the walk goes on from there as from an edge, where
  // the stretch ahead no longer runs past the rim.
  const bool near_rim = !look.monotone && nears_rim(c.t, kAhead * rev_);
  if (near_rim && ends_at(-dir, c.t)) {
    const double in = cut(-dir, t_b_, c.t);
    if (dir * (in - c.t) > 0) {
      c.t = in, c.at_root = false, c.jumped = true, far = c.t + dir * kAhead * rev_;
      look = geo_.monotony({c.t, far});
    }
  }
  double until = far;
  const PassageGeometry::Monotony ahead =
      look.monotone || !near_rim ? look : cut_ahead(dir, c.t, far, until);
  if (!ahead.monotone) return solve_revolution(tooth, dir, c), true;
  double guess = c.t + dir * rev_, gap = 0;
  if (c.at_root) {
    // From a root: a turn at the phase's rate there (Newton's last slope), where that is within a
    // factor 2 of the spindle's. Near the axis the rate differs from the spindle's by the node's
    // azimuth rate, and a revolution's guess would take two more Newton steps where the last node
    // gave no root to start from.
    const double r = std::abs(c.rate);
    if (r > 0.5 * w_ && r < 2 * w_) guess = c.t + dir * kTwoPi / r;
  } else {
    // From an edge: the next crossing is where the phase has turned on to its next zero.
    c.q = c.t == edge_probe_at_[side] ? geo_.turned_to(edge_probe_[side], tooth)
                                      : geo_.probe(tooth, c.t);
    gap = dir * s_.omega > 0 ? -c.q.g : c.q.g;
    gap -= kTwoPi * std::floor(gap / kTwoPi);  // the turn still to go, in [0, 2 pi)
    // That turn takes at least gap / top (the span just proven monotone bounds the rate): where
    // the envelope is already too high there, no crossing beyond the edge can lower the node.
    if (ends_at(dir, c.t + dir * gap / ahead.top)) return false;
    guess = c.t + dir * gap / w_;
  }
  // From a root that was the last node's too, the next is where the last node's next was (where
  // the rate at the root would put it, the phase may speed up across the axis's closest approach
  // and the guess skip a crossing: a revolution then solved exactly).
  const Root* hint = nullptr;
  if (c.at_root && c.from) {
    const std::vector<Root>& prev = *prev_;
    const std::ptrdiff_t next = (c.from - prev.data()) + dir;  // (prev is sorted by time)
    if (next >= 0 && next < static_cast<std::ptrdiff_t>(prev.size()) &&
        dir * (prev[next].t + prev[next].drift - c.t) > kSamePassage * rev_)
      hint = &prev[next];
  }
  Probe q{};
  const double t = solve(tooth, guess, kSamePassage * rev_, q, c.from, hint);
  if (until != far && !(dir * (t - until) <= 0)) {
    // Nothing from `until` on can lower the node: the walk ends there unless the phase, monotone
    // up to it, turns far enough to cross before (exact from the probes at both ends).
    const double need = c.at_root ? kTwoPi : gap;
    if (ahead.top * std::abs(until - c.t) < need) return false;
    if (std::abs(geo_.advance(c.t, c.q, until, geo_.probe(tooth, until))) < need) return false;
    return solve_revolution(tooth, dir, c), true;
  }
  if (!proven_next(geo_, tooth, dir, c, t, q, ahead, gap))
    return solve_revolution(tooth, dir, c), true;
  c.t = t, c.at_root = true, c.jumped = false, c.rho = q.rho, c.q = q,
  c.rate = scratch_.fresh.back().slope;
  c.rise.add(take(tooth, t, &q));
  return true;
}

// After a crossing, t must be the next; after an edge, the first beyond it (a crossing before it
// was found by the exact solve already: the walk goes on from there). The phase turns by `need`
// plus whole turns from c.t to t (both ends say so): t is the next when it cannot have turned one
// more, which the span just proven monotone often shows by its own bound. Else the turn is found
// exactly: on a span proven monotone the axis stays in a convex region that leaves the node out
// (monotone needs rho_lo > 0), so the phase's turn across it is known from the probes at its ends
// (advance); where t lies beyond `far` (the phase slowed: near the axis, on the side where the
// node's azimuth turns against the spindle), a second span from `far` to t must be monotone too.
bool IdealFollow::proven_next(const PassageGeometry& geo, int tooth, int dir, const Cursor& c,
                              double t, const Probe& q, const PassageGeometry::Monotony& ahead,
                              double gap) {
  const double rev = geo.setup().rev;
  if (std::isnan(t)) return false;
  const double moved = dir * (t - c.t), need = c.at_root ? kTwoPi : gap;
  // Behind the edge the exact solve has it already (not behind one the walk jumped to).
  if (!c.at_root && moved < 0) return !c.jumped;
  if (!(moved > (c.at_root ? kSamePassage * rev : 0))) return false;
  if (moved <= kAhead * rev)
    // (Less by a margin: where the bound is tight, G' = omega on a pass's line, a solve that went
    // one turn too far has top * moved = need + 2 pi but for round-off.)
    return ahead.top * moved < need + kTwoPi - 1e-6 || geo.turned(need, c.t, c.q, t, q);
  const double far = c.t + dir * kAhead * rev;
  const PassageGeometry::Monotony beyond = geo.monotony({far, t, c.at_root ? c.rho : NAN, moved});
  if (!beyond.monotone) return false;
  // (Where the centre keeps to a strip that leaves the node out, the turn over the whole step is
  // exact at once: no probe at `far`.)
  if (beyond.any_turn_exact) return geo.turned(need, c.t, c.q, t, q);
  const Probe q_far = geo.probe(tooth, far);
  return geo.turned(need, c.t, c.q, far, q_far, t, q);
}

}  // namespace topomill::plugins
