#include "row_sweep.hpp"

#include <algorithm>
#include <numeric>
#include <optional>

namespace topomill::plugins {

namespace {
// How far towards the rim (a fraction of the way from the axis, or from the ring) a pass's floor
// keeps a slope bound that holds over a fiftieth of the radius: beyond it the slope grows too fast.
constexpr double kSlopeOut = 0.9;
}  // namespace

RowSweep::RowSweep(const PassageSetup& s)
    : s_(s), by_line_(s.window.size()), state_(s.window.size()), far_side_(s.window.size()) {
  std::iota(by_line_.begin(), by_line_.end(), std::size_t{0});
  if (s.parallel)
    std::sort(by_line_.begin(), by_line_.end(),
              [&](std::size_t a, std::size_t b) { return s.window[a].line < s.window[b].line; });
  for (auto& st : state_) st.roots.resize(static_cast<std::size_t>(s.teeth));
  for (auto& st : far_side_) st.roots.resize(static_cast<std::size_t>(s.teeth));
  corrected_.later.resize(static_cast<std::size_t>(s.teeth));
  corrected_.before.resize(static_cast<std::size_t>(s.teeth));
}

void RowSweep::row(double y, const std::vector<double>& xs, double* z, NodeCounts& counts) {
  winner_ = Winner{};
  winner_line_ = -1;
  for (auto* sides : {&state_, &far_side_})
    for (auto& st : *sides) {
      st.active = st.have_bottom = false;
      st.wait = st.waited = 0;
      st.floor_x = NAN;
      st.stop[0] = st.stop[1] = NAN;
      for (auto& r : st.roots) r.clear();
    }
  for (std::size_t i = 0; i < xs.size(); ++i) {
    if (s_.stopped()) return;  // the map is discarded
    route_ = Route{};
    const double best = node_height(xs[i], y, counts);
    if (best < z[i]) z[i] = best, ++counts.updates;
    ++(route_.fallback ? counts.nodes_fallback
       : route_.exact  ? counts.nodes_exact
                       : counts.nodes_followed);
  }
}

double RowSweep::node_height(double x, double y, NodeCounts& counts) {
  const double key = s_.along_y ? x : y;
  // Corrected: the passage that was lowest at the node before, solved here first, gives a height
  // to bound all others by from the start (it is a real crossing of this node).
  double best = s_.wiggles ? seed(x, y, counts) : INFINITY;
  const std::size_t seeded = winner_.pass;
  // Window p's lowest passage below `best`, if any; false when it cannot lower the node.
  auto visit = [&](std::size_t p) {
    const PassResult r = pass_height(p, x, y, best, counts);
    if (r.height < best) {
      best = r.height;
      winner_.pass = r.tooth >= 0 ? p : Winner::kNone;
      winner_.tooth = r.tooth, winner_.t = r.t, winner_.fallback = r.fallback;
      // A passage of the reference walk's: its root is kept here, as a walk's would be.
      if (r.fallback) winner_.fallback_root = Root{r.t, 0.0, s_.omega}, winner_.fallback_root.x = x;
    }
    return r.can_lower;
  };
  if (!s_.parallel) {
    // Windows of bent passes lie every way: each one that can reach the node is asked, lowest
    // possible first, until none left can go below the best.
    s_.near(x, y, near_);
    for (const auto& entry : near_) {
      if (entry.first >= best) break;
      visit(entry.second);
    }
    return best;
  }
  // Passes outwards on both sides from a start: the pass that gave the node before its height,
  // where that one reaches this node, else the nearest line. A side ends at its first pass that
  // cannot lower the node (with a correction, each pass has its own: only at the second in a
  // row). That is exact from any start as long as the passes' envelopes over the node, taken in
  // the order of their lines, fall to one lowest and rise beyond it. A pass out of reach ends a
  // side only because the farther ones are farther still: true from a start within reach. On a
  // face inclined across the passes the pass that cuts a node has its line R sin(lambda) from it
  // in plan, so from the nearest line every pass in between would be walked first.
  const auto n = static_cast<std::ptrdiff_t>(by_line_.size());
  const int misses_to_stop = s_.wiggles ? 2 : 1;
  auto line_at = [&](std::ptrdiff_t i) {
    return s_.window[by_line_[static_cast<std::size_t>(i)]].line;
  };
  std::ptrdiff_t right = 0;
  double from = key;  // where the sides are measured from
  const std::ptrdiff_t winner = winner_line_;
  const bool winner_reaches = winner >= 0 && std::abs(key - line_at(winner)) < s_.reach;
  if (winner_reaches)
    right = winner, from = line_at(winner);
  else
    right = std::lower_bound(by_line_.begin(), by_line_.end(), key,
                             [&](std::size_t p, double v) { return s_.window[p].line < v; }) -
            by_line_.begin();
  std::ptrdiff_t left = right - 1;
  bool left_open = left >= 0, right_open = right < n;
  int misses[2] = {0, 0};
  winner_line_ = -1;
  while (left_open || right_open) {
    const bool take_left =
        !right_open || (left_open && from - line_at(left) <= line_at(right) - from);
    std::ptrdiff_t& at = take_left ? left : right;
    bool& open = take_left ? left_open : right_open;
    int& missed = misses[take_left ? 0 : 1];
    const std::size_t p = by_line_[static_cast<std::size_t>(at)];
    const double before = best;
    const bool can_lower = std::abs(key - s_.window[p].line) < s_.reach && visit(p);
    if (best < before) winner_line_ = at;
    // The seed's pass is skipped as a matter of course: that is not a side's end.
    missed = can_lower || p == seeded ? 0 : missed + 1;
    at += take_left ? -1 : 1;
    open = missed < misses_to_stop && at >= 0 && at < n;
  }
  return best;
}

RowSweep::PassResult RowSweep::pass_height(std::size_t p, double x, double y, double best,
                                           NodeCounts& counts) {
  PassResult out;
  PassState& st = state_[p];
  // The pass's level time is needed only off the fast path: found at most once.
  double level = -INFINITY;
  // On parallel passes along Y it depends on the node's y alone: found once a row.
  auto t0 = [&] {
    if (level != -INFINITY) return level;
    if (!s_.level_by_y()) return level = s_.level_time(p, x, y);
    if (!(st.level_y == y)) st.level_y = y, st.level_t = s_.level_time(p, x, y);
    return level = st.level_t;
  };
  if (!st.active) {
    if (std::isnan(t0())) return out;  // never level with this node: look further
    const auto radii = s_.contact_radii(p, t0());
    st.rho_lo = radii.first, st.rho_hi = radii.second, st.active = true;
  }
  if (!s_.profile.surface_is_hull() && !s_.wiggles && s_.profile.splits())
    return split_height(p, x, y, best, counts, t0());
  const PassageGeometry geo(s_, p, x, y, st.rho_lo, st.rho_hi);
  // The tip's cut where the node lies on the pass's line (+inf elsewhere), found at most once.
  double tip = NAN;
  auto tip_cut = [&] { return std::isnan(tip) ? tip = tip_height(geo, t0) : tip; };
  double t_b = NAN;
  if (!s_.profile.surface_is_hull()) {
    // Heights along the pass may have two minima (an insert's inner side, an edge moved off the
    // axis): the reference walk, which needs only the hull's bound.
    t_b = geo.bottom_near([&](double t) { return geo.bound(t); }, t0());
    if (std::isnan(t_b)) return out;
    const double slack = s_.wiggles ? kFloorSlack : 0.0;
    if (geo.lowest_bound(t_b, best + slack) - slack >= best) return out.can_lower = false, out;
    out.height = std::min(walk_reference(geo, st, t_b, best, counts, out), tip_cut());
    return out;
  }
  if (!s_.wiggles) {
    if (ideal_too_high(geo, st, best, t0, t_b)) return out.can_lower = false, out;
    if (std::isnan(t_b)) return out;
    // On the tip's line the tip cuts the node as the axis passes; with its height as the best
    // from the start, the exact solves rule out every piece next to that instant whose ball
    // cannot go lower (on a level pass, all of them) instead of halving towards it.
    IdealFollow follow(geo, st.roots, ideal_, counts);
    const double h = follow.run(t_b, std::min(best, tip_cut()));
    route_.exact = route_.exact || follow.exact_used();
    if (s_.stopped()) return out;  // the map is discarded
    out.height = std::min(h, tip_cut());
    return out;
  }
  // A corrected envelope wiggles: its floor (the nominal centre moved by the correction's whole
  // range) is a true bound with a single minimum, or with its tail's bound where it may have two
  // (FloorTail); it rules out the passes that cannot come close and ends the walk. A pass whose
  // floor was too high at an earlier node stays too high for a while: where the floor is below its
  // height H there, the ball's lower cap is no steeper than R / (zc - H) (zc the centre's height),
  // past the rim no steeper than 1, and the floor must climb from `best` to H between the two
  // nodes.
  if (!std::isnan(st.floor_x) &&
      st.floor - floor_steepness(s_, p, st.floor) * std::abs(x - st.floor_x) >= best)
    return out.can_lower = false, out;
  CorrectedFollow follow(geo, st.roots, st.stop, corrected_, counts);
  bool solved = false;
  if (const double h = follow.revisit(best, solved); !std::isnan(h)) {
    out.can_lower = solved, out.height = std::min(h, tip_cut());
    out.tooth = follow.lowest().tooth, out.t = follow.lowest().t;
    return out;
  }
  t_b = bottom([&](double t) { return geo.floor_envelope(t); }, geo, st, x, t0);
  if (std::isnan(t_b)) return out;
  if (const double low = geo.lowest_bound(t_b, best + kFloorSlack) - kFloorSlack; low >= best)
    return st.floor = low, st.floor_x = x, out.can_lower = false, out;
  bool irregular = false;
  double h = INFINITY;
  if (st.wait > 0) {
    --st.wait, irregular = true;  // irregular at the last nodes: the reference walk at once
  } else {
    h = follow.walk(t_b, best, irregular);
    st.waited = irregular ? std::min(2 * st.waited + 1, kMaxWait) : 0, st.wait = st.waited;
  }
  // The lowest passage the revisit or the walk found, unless the reference finds one.
  out.tooth = follow.lowest().tooth, out.t = follow.lowest().t;
  if (s_.stopped()) return out;  // a walk cut short is not irregular: the map is discarded
  if (irregular) h = reference(geo, st, t_b, best, counts, out);
  out.height = std::min(h, tip_cut());
  return out;
}

RowSweep::PassResult RowSweep::split_height(std::size_t p, double x, double y, double best,
                                            NodeCounts& counts, double t_m) {
  PassResult out;
  if (std::isnan(t_m)) return out;
  out.can_lower = false;
  // The sides overlap by a millionth of a tooth period: a crossing at t_m itself, solved from
  // either side, lands within round-off (1e-9 / omega) of it on one side or the other. Over so
  // short a piece the bound moves by far less than round-off.
  const double overlap = 1e-6 * s_.period;
  struct Side {
    std::optional<PassageGeometry> geo;
    double t_b = NAN, low = INFINITY;
  } sides[2];
  for (int side = 0; side < 2; ++side) {
    PassState& st = side ? far_side_[p] : state_[p];
    Side& sd = sides[side];
    sd.geo.emplace(s_, p, x, y, state_[p].rho_lo, state_[p].rho_hi,
                   side ? std::pair<double, double>{t_m - overlap, INFINITY}
                        : std::pair<double, double>{-INFINITY, t_m + overlap},
                   true);
    if (!(sd.geo->t_hi() > sd.geo->t_lo()) ||
        ideal_too_high(
            *sd.geo, st, best, [t_m] { return t_m; }, sd.t_b, &sd.low))
      continue;
    out.can_lower = true;
  }
  // The side whose envelope comes lower first: its lowest passage often rules the other out (the
  // ring's front and back cross a node at heights that differ by the feed's climb).
  const int first = sides[1].low < sides[0].low ? 1 : 0;
  for (int side : {first, 1 - first}) {
    const Side& sd = sides[side];
    if (!(sd.low < best)) continue;
    IdealFollow follow(*sd.geo, (side ? far_side_[p] : state_[p]).roots, ideal_, counts);
    const double h = follow.run(sd.t_b, best);
    route_.exact = route_.exact || follow.exact_used();
    if (s_.stopped()) return out;  // the map is discarded
    out.height = std::min(out.height, h), best = std::min(best, h);
  }
  return out;
}

template <class T0>
bool RowSweep::ideal_too_high(const PassageGeometry& geo, PassState& st, double best, T0 t0,
                              double& t_b, double* low_out) {
  // The envelope has a single minimum: its bottom, followed from node to node, is the pass's
  // lowest point, and a pass farther out on this side lies higher still. Along the row the
  // bottom's height changes at the ball's slope across (the envelope theorem: d/dx of the height
  // at fixed t), so a pass found too high stays too high for a while without being looked at
  // again (twice the slope, for the slope's own change over up to a fiftieth of the radius).
  const double x = geo.x(), moved = std::abs(x - st.floor_x);
  // (A ringed cutter's slope changes over its tube's radius, as the ball's over its own.)
  if (moved < 0.02 * s_.R && st.floor - st.floor_slope * moved >= best) return true;
  t_b = bottom([&](double t) { return geo.envelope(t); }, geo, st, x, t0);
  if (std::isnan(t_b)) return false;
  const double low = geo.envelope(t_b);
  if (low_out) *low_out = low;
  if (low < best) return false;
  const Vec3 c = s_.window[geo.window()].centre(t_b);
  const double dx = x - c.x(), dy = geo.y() - c.y(), r2 = dx * dx + dy * dy;
  st.floor = low, st.floor_x = x;
  // Near the rim (past kSlopeOut of the way to it) no bound: look each time.
  st.floor_slope =
      r2 < kSlopeOut * kSlopeOut * s_.R2 ? 2 * std::abs(dx) / std::sqrt(s_.R2 - r2) : INFINITY;
  if (s_.ringed) {
    // The hull's: its slope in rho times dx / rho (zero inside the ring).
    const double rho = std::sqrt(r2);
    st.floor_slope = rho <= s_.profile.ring() ? 0.0
                     : rho < s_.profile.rim_out(kSlopeOut)
                         ? 2 * s_.profile.steepness(rho) * std::abs(dx) / rho
                         : INFINITY;
  }
  return true;
}

// The reference's own walk, from the reference's own bottom (which the corrected branch has
// already), so that the result is its. Its lowest passage seeds the next node (seed()), as a
// corrected walk's would.
double RowSweep::reference(const PassageGeometry& geo, PassState& st, double t_b, double best,
                           NodeCounts& counts, PassResult& out) {
  ++counts.fallbacks, route_.fallback = true;
  return walk_reference(geo, st, t_b, best, counts, out);
}

double RowSweep::walk_reference(const PassageGeometry& geo, PassState& st, double t_b, double best,
                                NodeCounts& counts, PassResult& out) {
  for (auto& r : st.roots) r.clear();
  PassageGeometry::Crossing low{-1, 0.0, {}};
  const double h = geo.walk(t_b, roots_, counts.passages, best, &low);
  if (low.tooth >= 0) {
    out.tooth = low.tooth, out.t = low.t, out.fallback = true;
  }
  return h;
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
  // A ringed cutter's ideal envelope is flat over its bottom, where the parabola below finds no
  // curvature: the last node's bottom is this one's where the envelope is as low there as the
  // window's lowest centre allows (no lower anywhere).
  if (st.have_bottom && s_.ringed && !s_.wiggles) {
    const double tp = st.tb + st.tb_rate * (x - st.tb_x);
    const double floor = s_.window[geo.window()].lowest_nominal + s_.profile.up() - s_.R;
    if (geo.within(tp) && f(tp) <= floor) t_b = tp;
  }
  // A split pass's side is often lowest at its end, the axis's closest approach, where a
  // parabola's vertex lies beyond: the bound falling into that end over its last
  // kBottomTolerance of a period has, unimodal, its lowest within that of the end, as close as
  // the golden section finds it. Tried first where the last node's bottom was that end.
  const double w = 0.1 * s_.period, tol = kBottomTolerance * s_.period;
  auto at_end = [&](double end, double in, double f_end) {
    return geo.within(end + in) && f(end + in) > f_end;
  };
  const bool was_end = st.tb_end;
  st.tb_end = false;
  if (std::isnan(t_b) && st.have_bottom && was_end && geo.split()) {
    const double tp = st.tb + st.tb_rate * (x - st.tb_x);
    const bool hi = std::abs(tp - geo.t_hi()) <= std::abs(tp - geo.t_lo());
    const double end = hi ? geo.t_hi() : geo.t_lo();
    if (std::abs(tp - end) <= w && at_end(end, hi ? -tol : tol, f(end))) t_b = end;
  }
  if (std::isnan(t_b) && st.have_bottom) {
    const double tp = st.tb + st.tb_rate * (x - st.tb_x);
    const double fm = f(tp - w), f0 = f(tp), fp = f(tp + w);
    const double curvature = fp - 2 * f0 + fm;
    if (curvature > 0) {
      const double shift = 0.5 * w * (fm - fp) / curvature;
      if (std::abs(shift) <= w) t_b = std::clamp(tp + shift, geo.t_lo(), geo.t_hi());
    }
    if (std::isnan(t_b) && geo.split()) {
      const double end = fp < fm ? geo.t_hi() : geo.t_lo(), in = fp < fm ? -tol : tol;
      // (The last bottom was mostly that end: its height is f0 then.)
      if (std::abs(tp - end) <= w && at_end(end, in, tp == end ? f0 : f(end))) t_b = end;
    }
  }
  if (geo.split() && (t_b == geo.t_hi() || t_b == geo.t_lo())) st.tb_end = true;
  if (std::isnan(t_b)) {
    if (std::isnan(t0())) return NAN;
    t_b = geo.bottom_near(f, t0());
  }
  st.tb_rate = st.have_bottom && x != st.tb_x ? (t_b - st.tb) / (x - st.tb_x) : 0.0;
  st.tb = t_b, st.tb_x = x, st.have_bottom = true;
  return t_b;
}

double RowSweep::seed(double x, double y, NodeCounts& counts) {
  if (winner_.pass == Winner::kNone) return INFINITY;
  PassState& st = state_[winner_.pass];
  const PassageGeometry geo(s_, winner_.pass, x, y, st.rho_lo, st.rho_hi);
  Root* r = winner_.fallback ? &winner_.fallback_root
                             : nearest(st.roots[static_cast<std::size_t>(winner_.tooth)], winner_.t,
                                       kSamePassage * s_.rev);
  if (!r) return INFINITY;
  Root solved{};
  Probe q{};
  if (!solve_root(geo, winner_.tooth, r, 0.0, solved, q) || !geo.within(solved.t) ||
      !std::isfinite(q.height) || std::abs(solved.t - r->t) > kSamePassage * s_.rev)
    return INFINITY;
  ++counts.passages;
  *r = solved;  // the walk finds this passage solved here and does not solve it again
  winner_.t = solved.t;
  return q.over ? q.height : INFINITY;
}

}  // namespace topomill::plugins
