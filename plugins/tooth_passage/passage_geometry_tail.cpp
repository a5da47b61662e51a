// PassageGeometry's floor over a tail of its window, where the floor may have two minima: the
// nominal height bends down (a convex arc) and the ball's depth is flat while the node lies under
// the correction's box, so that the floor follows that height there (PassageSetup::FloorTail).
//
// From t on in direction dir, tau >= 0 later (or earlier), the floor is at least
//   psi(tau) = z + (z' - jump) tau - bend tau^2 / 2 - depth(rho(tau)),
// with z, z' the floor's nominal height and its slope that way at t (CentreTable::z_bend's
// Taylor bound), and rho(tau) = sqrt(gap^2 + e(tau)^2) a lower bound of the node's distance in
// plan from the box about the nominal centre: `gap` its least across the line (less how far the
// nominal strays from the line and the box's half width across), e(tau) = max(0, grow + lo_v
// tau, shrink - hi_v tau) its least along the line, the nominal leaving the node (grow) or
// coming towards it (shrink) at its least and greatest speeds along the line. Where no edge can
// be over the node (rho past the cutter's reach) there is no crossing, and the tail is bounded
// between. There -depth(rho(tau)) is convex (a convex non-decreasing function, the sphere's or
// the tube's hull's, of a convex distance), so over a piece [p, q] it lies above its tangent at p
// up to where that meets its tangent at q, and above the latter beyond; the quadratic is concave,
// so psi over the piece is at least its least at p, q and that meeting point. Pieces are halved
// until each is proven at or above the target.
#include <algorithm>
#include <cmath>

#include "passage_geometry.hpp"

namespace topomill::plugins {

namespace {
// The most pieces one proof may halve into before it gives up (the walk then goes on a
// revolution, and asks again from there).
constexpr int kTailPieces = 200;
// Round-off allowed in the convexity the tangent bound rests on (mm).
constexpr double kTailSlack = 1e-12;

// The floor's depth below its centre at a distance rho in plan, within the cutter's reach: the
// sphere's, or the hull's less the edge's rise (PassageGeometry::floor_envelope); and how fast it
// falls with rho there.
double floor_depth(const PassageSetup& s, double rho) {
  if (s.ringed) return s.profile.hull_depth(rho) - s.profile.up();
  return std::sqrt(s.R2 - std::min(rho * rho, s.R2));
}
double floor_fall(const PassageSetup& s, double rho) {
  if (s.ringed) return rho <= s.profile.ring() ? 0.0 : s.profile.steepness(rho);
  return rho < s.R ? rho / std::sqrt(s.R2 - rho * rho) : INFINITY;
}
}  // namespace

// Both out of line: the walks ask them only at stops and pass skips, and inlined there they cost
// the ideal walks 1 % more instructions under LTO (lambda 30, callgrind), where they do nothing.
[[gnu::noinline]] double PassageGeometry::lowest_bound(double t_b, double target) const {
  const double here = bound(t_b);
  if (!s_.window[win_].tail.on || here < target) return here;
  return std::min({here, tail_floor(t_b, 1.0, target), tail_floor(t_b, -1.0, target)});
}

[[gnu::noinline]] double PassageGeometry::tail_floor(double t, double dir, double target) const {
  const PassageSetup::Window& w = s_.window[win_];
  const PassageSetup::FloorTail& f = w.tail;
  const double length = dir > 0 ? t_hi_ - t : t - t_lo_;
  if (!(length >= 0)) return INFINITY;  // crossings count within the window only
  const CentreTable& table = s_.runout > 0 ? *w.spindle_axis : table_;
  Vec3 c = Vec3::Zero(), v = c, a = c;
  if (!table.nominal_jet(t, c, v, a)) c = table.nominal(t), v = table.nominal_velocity(t);
  const double z = c.z() + w.shift_lo.z(), slope = dir * v.z() - f.jump;
  const double across = std::abs(f.ux * (y_ - f.y) - f.uy * (x_ - f.x));
  const double gap = std::max(0.0, across - f.off - f.side);
  const double reach = s_.ringed ? s_.profile.reach() : s_.R;
  if (gap >= reach) return INFINITY;  // no edge over the node anywhere on the tail
  const double wide = std::sqrt(reach * reach - gap * gap);  // the reach along the line
  // Along the line: the nominal's lead over the node, the way the tail goes, grows by [lo_v,
  // hi_v] tau (the speeds along the line either way: going back, the lead is counted backwards
  // too); the node's distance from the box along the line is at least its lead less the box's
  // reach back (`grow`, from lo_v) and its lag less the box's reach ahead (`shrink`, from hi_v).
  const bool along = !std::isnan(f.along_lo);
  const double lead = dir * (f.ux * (c.x() - x_) + f.uy * (c.y() - y_));
  const double lo_v = f.along_lo, hi_v = f.along_hi;
  const double grow = lead - (dir > 0 ? f.behind : f.ahead);
  const double shrink = -lead - (dir > 0 ? f.ahead : f.behind);
  // Within the reach only where both terms are within `wide` (beyond, no edge is over the node):
  // each where a0 + slope tau <= wide, a half-line, or all or nothing with no slope.
  double start = 0, end = length;
  auto keep = [&](double a0, double rate) {
    if (rate > 0) end = std::min(end, (wide - a0) / rate);
    if (rate < 0) start = std::max(start, (wide - a0) / rate);
    if (rate == 0 && a0 > wide) end = -INFINITY;
  };
  if (along) keep(grow, lo_v), keep(shrink, -hi_v);
  if (!(start <= end)) return INFINITY;
  // -depth at tau and a slope of its tangent there (any one-sided one at a kink: it is convex).
  struct At {
    double depth, rise;
  };
  auto at = [&](double tau) {
    double e = 0, de = 0;
    if (along) {
      const double g = grow + lo_v * tau, k = shrink - hi_v * tau;
      if (g > 0 && g >= k) e = g, de = lo_v;
      if (k > 0 && k > g) e = k, de = -hi_v;
    }
    const double rho = std::sqrt(gap * gap + e * e);
    return At{floor_depth(s_, rho), rho > 0 ? floor_fall(s_, rho) * e * de / rho : 0.0};
  };
  auto quad = [&](double tau) { return z + tau * (slope - 0.5 * f.bend * tau); };
  // Pieces [p, q] with -depth's value and tangent at both ends.
  struct Piece {
    double p, q;
    At a, b;
  };
  constexpr int kStack = 64;
  Piece stack[kStack];
  int n = 0, pieces = 0;
  const At first = at(start);
  if (quad(start) - first.depth < target) return -INFINITY;  // (as below, before the far end)
  stack[n++] = {start, end, first, at(end)};
  double low = INFINITY;
  while (n > 0) {
    const Piece k = stack[--n];
    const double qp = quad(k.p), qq = quad(k.q);
    if (qp - k.a.depth < target || qq - k.b.depth < target)
      return -INFINITY;  // the bound itself reaches the target: not provable
    // -depth lies above its tangent at p over [p, x] and above its tangent at q over [x, q], and
    // the quadratic is concave: psi is least at p, x or q on those. Any x will do; where the
    // tangents meet is best (at an end where one is vertical, at the rim).
    const double rp = k.a.rise, rq = k.b.rise;
    double x = k.p;
    if (std::isfinite(rp) && !std::isfinite(rq)) x = k.q;
    if (std::isfinite(rp) && std::isfinite(rq) && rq > rp)
      x = std::clamp((k.a.depth - k.b.depth + rp * k.p - rq * k.q) / (rp - rq), k.p, k.q);
    const double tp = x > k.p ? -k.a.depth + rp * (x - k.p) : -k.a.depth;
    const double tq = x < k.q ? -k.b.depth - rq * (k.q - x) : -k.b.depth;
    const double bound =
        std::min({qp - k.a.depth, qq - k.b.depth, quad(x) + std::min(tp, tq)}) - kTailSlack;
    if (bound >= target) {
      low = std::min(low, bound);
      continue;
    }
    if (++pieces > kTailPieces || n + 2 > kStack) return -INFINITY;
    const double m = 0.5 * (k.p + k.q);
    const At mid = at(m);
    stack[n++] = {m, k.q, mid, k.b};
    stack[n++] = {k.p, m, k.a, mid};  // the nearer half first
  }
  return low;
}

}  // namespace topomill::plugins
