#include "corrected_follow.hpp"

#include <algorithm>

namespace topomill::plugins {

namespace {
// A walk never takes more steps than this in one direction (a guard: the stops end it first).
constexpr int kMaxSteps = 100000;
// How far along the row a fall-rate bound is taken to hold (mm).
constexpr double kFallReach = 0.05;
}  // namespace

CorrectedFollow::CorrectedFollow(const PassageGeometry& geo, std::vector<std::vector<Root>>& roots,
                                 double (&stop)[2], Scratch& scratch, NodeCounts& counts)
    : s_(geo.setup()), geo_(geo), roots_(roots), stop_(stop), scratch_(scratch), counts_(counts) {}

bool CorrectedFollow::visit(int tooth, double guess, double reach, double& t,
                            std::vector<Root>& out) {
  const Root* match = nearest(roots_[static_cast<std::size_t>(tooth)], guess, reach);
  if (match && stays_above(*match, geo_.x(), std::min(best_, best_node_))) {
    out.push_back(*match);
    t = match->t;
    return true;
  }
  Root r{};
  Probe q{};
  // A secant that ran off (more than `reach` from the guess: one was seen 8 revolutions away,
  // outside the stops, which would end the walk at once) is irregular.
  if (!solve_root(geo_, tooth, match, guess, r, q) || std::abs(r.t - guess) > reach) return false;
  t = r.t;
  if (geo_.within(t) && std::isfinite(q.height)) {
    ++visited_;
    if (q.over && q.height < best_) best_ = q.height, lowest_ = {tooth, t};
  }
  out.push_back(r);
  return true;
}

double CorrectedFollow::walk(double t_b, double best_node, bool& irregular) {
  const double rev = s_.rev;
  best_node_ = best_node, best_ = INFINITY;
  // Each tooth's passage nearest the floor's bottom first, for a best to bound the rest by.
  std::vector<double>& first = scratch_.first;
  first.assign(static_cast<std::size_t>(s_.teeth), 0.0);
  for (int tooth = 0; tooth < s_.teeth; ++tooth) {
    const auto j = static_cast<std::size_t>(tooth);
    scratch_.later[j].clear(), scratch_.before[j].clear();
    if (!visit(tooth, t_b, 0.5 * rev, first[j], scratch_.later[j]))
      return irregular = true, INFINITY;
  }
  place_stops(t_b, std::min(best_, best_node));
  for (int tooth = 0; tooth < s_.teeth; ++tooth)
    for (int side = 1; side >= 0; --side)
      if (!walk_side(tooth, side)) return irregular = true, INFINITY;
  for (int tooth = 0; tooth < s_.teeth; ++tooth) {
    const auto j = static_cast<std::size_t>(tooth);
    std::vector<Root>& prev = roots_[j];
    prev.assign(scratch_.before[j].rbegin(), scratch_.before[j].rend());
    prev.insert(prev.end(), scratch_.later[j].begin(), scratch_.later[j].end());
  }
  counts_.passages += visited_;
  return best_;
}

// Where the floor, past its bottom, is too high for any passage to lower the node, on each side:
// moved from the last node's, which it is close to. The best only falls from here on, which can
// only bring these nearer: they stay true.
void CorrectedFollow::place_stops(double t_b, double target) {
  const double rev = s_.rev, span = geo_.t_hi() - geo_.t_lo();
  const double beyond = kBottomTolerance * s_.period;
  for (int side = 0; side < 2; ++side) {
    const double dir = side ? 1.0 : -1.0;
    double& stop = stop_[side];
    if (std::isnan(stop) || dir * (stop - t_b) < beyond) stop = t_b + dir * beyond;
    while (!geo_.beyond_reach(stop, dir, target) && dir * (stop - t_b) < span + rev &&
           !s_.stopped())
      stop += dir * 0.5 * rev;
    while (geo_.ends_by_bound(t_b, dir, stop - dir * 0.5 * rev, target)) stop -= dir * 0.5 * rev;
  }
}

bool CorrectedFollow::walk_side(int tooth, int side) {
  const double rev = s_.rev, t_lo = geo_.t_lo(), t_hi = geo_.t_hi(), dir = side ? 1.0 : -1.0;
  const auto j = static_cast<std::size_t>(tooth);
  std::vector<Root>& out = side ? scratch_.later[j] : scratch_.before[j];
  double t_prev = scratch_.first[j];
  for (int m = 1; m < kMaxSteps && !s_.stopped(); ++m) {
    // Past the window's end (the first passage may lie beyond its other end): every passage from
    // the first to one beyond the end is visited, each proven the next of the last
    // (next_crossing), so that none inside is passed over (a node near the axis is crossed again
    // within a revolution, which no step of one revolution would see).
    if (dir > 0 ? t_prev > t_hi : t_prev < t_lo) break;
    const double guess = t_prev + dir * rev;
    // Every later passage lies beyond the next one's least gap (at most half a revolution).
    if (dir * (t_prev + dir * 0.5 * rev - stop_[side]) >= 0 &&
        dir * (t_prev + dir * geo_.next_gap(t_prev, geo_.axis_distance(t_prev), dir) -
               stop_[side]) >=
            0)
      break;
    double t = 0;
    if (!visit(tooth, guess, kSamePassage * rev, t, out) || !geo_.next_crossing(t_prev, t))
      return false;
    t_prev = t;
  }
  return true;
}

double CorrectedFollow::revisit(double best, bool& solved) {
  if (std::isnan(stop_[0]) || !std::isfinite(best)) return NAN;
  if (!geo_.beyond_reach(stop_[0], -1.0, best) || !geo_.beyond_reach(stop_[1], 1.0, best))
    return NAN;
  const double x = geo_.x(), rev = s_.rev, t_lo = geo_.t_lo(), t_hi = geo_.t_hi();
  double low = INFINITY;
  bool any = false;
  for (int tooth = 0; tooth < s_.teeth; ++tooth) {
    // Passages beyond the window are solved again too (they count for nothing there, but move
    // with the node and can come in): where the last walk ended at the window's end rather than
    // at a stop, the tooth's known passages must still reach past that end, or one not known
    // may have come into the window.
    double first = INFINITY, last = -INFINITY;
    for (Root& r : roots_[static_cast<std::size_t>(tooth)]) {
      any = true;
      const double target = std::min(best, low);
      if (stays_above(r, x, target)) continue;
      Root again{};
      Probe q{};
      // The same passage, and no other of this tooth born within a revolution of it (the phase
      // monotone there): else the pass is walked again.
      if (!solve_root(geo_, tooth, &r, 0.0, again, q) ||
          std::abs(again.t - r.t) > kSamePassage * rev ||
          !geo_.monotony({again.t - rev, again.t + rev}).monotone)
        return NAN;
      r = again, solved = true;
      first = std::min(first, r.t), last = std::max(last, r.t);
      if (geo_.within(r.t) && std::isfinite(q.height)) {
        ++counts_.passages;
        if (q.over && q.height < low) low = q.height, lowest_ = {tooth, r.t};
      }
    }
    if ((stop_[0] < t_lo && !(first <= t_lo)) || (stop_[1] > t_hi && !(last >= t_hi))) return NAN;
  }
  return any ? low : NAN;
}

bool solve_root(const PassageGeometry& geo, int tooth, const Root* from, double guess, Root& r,
                Probe& q) {
  const PassageSetup& s = geo.setup();
  const double x = geo.x();
  double slope = from ? from->slope : s.omega;
  const double t =
      geo.crossing(tooth, from ? from->t + from->drift * (x - from->x) : guess, slope, q);
  if (!PassageGeometry::converged(q)) return false;
  r = Root{t, from && x != from->x ? (t - from->t) / (x - from->x) : 0.0, slope};
  if (geo.within(t) && std::isfinite(q.height))
    r.x = x, r.height = q.height,
    r.fall = fall_rate(s, geo.window(), t, q.rho,
                       s.window[geo.window()].tilted ? geo.distance(t) : q.rho, r.reach);
  return true;
}

double floor_steepness(const PassageSetup& s, std::size_t w, double below) {
  // Points `depth` below the ball's centre are no steeper than R / depth, past its rim than 1; a
  // ringed cutter's section likewise (its bottom is flat): CutterProfile::steepest_below.
  return s.profile.steepest_below(s.window[w].lowest_centre + s.profile.up() - below);
}

// On a corrected path a passage's height along the row, h(x) = E(t(x), x) (E the ball's surface
// over the node, t(x) the passage's root), falls at most at
//   |dE/dx| + |dE/dt| |dt/dx| <= tan(alpha) + (vz + tan(alpha) vxy) bx,
// where bx = |g_x| / |g_t| bounds the root's move: |g_x| <= 1/rho + k (the node's azimuth and the
// lag, k = |lag'| / (R cos alpha)), |g_t| >= |omega| - vxy sqrt(1/rho^2 + k^2). All with the
// centre's top speeds (vxy, vz) over a window either side of the root (eight correction steps)
// and rho over what the node and the axis can move in it, so the bound holds while the root stays
// in the window (reach = window / bx) and the node within kFallReach. Where the correction jerks
// the axis sideways faster than the edge sweeps (|g_t| could vanish), there is no bound. A tilted
// tool: alpha and the height's slope are the plan's (the ball is the same sphere), while rho, k and
// the azimuth are the ball point's in the tool frame, which moves at most L = R / h (h = sqrt(R^2 -
// rho_plan^2)) times as far as the plan offset does (the lift, lifted_rates): so |g_x| <= L (1/rho
// + k) and |g_t| >= |omega| - L vxy sqrt(1/rho^2 + k^2). L = 1 when vertical.
namespace {
// The same for a ringed cutter, whose axis is vertical (L = 1, rho the plan offset's): the lag's
// slope in rho at most LagShape's in ln(rho) over rho_lo, and the surface's slope the tube's
// tan(alpha) (CutterProfile::steepest; 0 on the flat bottom).
double ringed_fall_rate(const PassageSetup& s, double rho, double moved, double vxy, double vz,
                        double w, double& reach) {
  const double rho_lo = rho - moved, rho_hi = rho + moved;
  if (rho_lo <= 0 || rho_hi >= s.profile.rim_out(kRimFraction)) return INFINITY;
  const double k = s.lag_shape.over(rho_lo, rho_hi).k1 / rho_lo;
  if (!std::isfinite(k)) return INFINITY;
  const double sweep = std::abs(s.omega) - vxy * std::sqrt(1 / (rho_lo * rho_lo) + k * k);
  if (sweep <= 0.2 * std::abs(s.omega)) return INFINITY;
  const double bx = (1 / rho_lo + k) / sweep;
  reach = std::min(kFallReach, w / bx);
  const double tan_hi = s.profile.steepest(rho_lo, rho_hi);
  return tan_hi + (vz + tan_hi * vxy) * bx;
}
}  // namespace

double fall_rate(const PassageSetup& s, std::size_t p, double t, double rho, double plan,
                 double& reach) {
  // The window either side of t: eight correction steps, or with none (a runout alone) a
  // quarter revolution, within which the next node's root stays.
  const double step = s.path->correction_step(s.window[p].pass);
  const double w = step > 0 ? 8 * step : kSamePassage * s.rev;
  const auto [vxy, vz] = s.top_speed(p, t - w, t + w);
  const double moved = vxy * w + kFallReach;  // how far the plan offset can go in the window
  const double plan_hi = plan + moved;
  if (s.ringed) return ringed_fall_rate(s, rho, moved, vxy, vz, w, reach);
  if (plan_hi >= kRimFraction * s.R) return INFINITY;
  const double sp_hi = plan_hi / s.R, cp_hi = std::sqrt(1 - sp_hi * sp_hi);
  const double L = s.window[p].tilted ? 1 / cp_hi : 1.0;
  // A turning frame moves the point by up to |theta'| R more a second (lifted_rates).
  const double turned = s.window[p].turn.on ? s.window[p].turn.rate * s.R : 0.0;
  const double rho_lo = rho - (L * moved + turned * w), rho_hi = rho + L * moved + turned * w;
  if (rho_lo <= 0 || rho_hi >= kRimFraction * s.R) return INFINITY;
  const double s_lo = rho_lo / s.R, s_hi = rho_hi / s.R;
  const double c_lo = std::sqrt(1 - s_lo * s_lo), c_hi = std::sqrt(1 - s_hi * s_hi);
  const double lag_slope = std::max(std::abs(s.tool->lag_slope_sc(s_lo, c_lo)),
                                    std::abs(s.tool->lag_slope_sc(s_hi, c_hi)));
  const double k = lag_slope / (s.R * c_hi);
  const double sweep =
      std::abs(s.omega) - (L * vxy + turned) * std::sqrt(1 / (rho_lo * rho_lo) + k * k);
  if (sweep <= 0.2 * std::abs(s.omega)) return INFINITY;
  const double bx = L * (1 / rho_lo + k) / sweep;
  reach = std::min(kFallReach, w / bx);
  const double tan_hi = sp_hi / cp_hi;
  return tan_hi + (vz + tan_hi * vxy) * bx;
}

}  // namespace topomill::plugins
