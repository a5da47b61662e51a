// PassageGeometry's certified halving: every crossing of [a, b] below a height, by subdivision
// until each piece is proven, and the bracketed solves it ends in.
#include "passage_geometry.hpp"

#include <algorithm>

#include <cstdint>
#include <limits>
#include "phase_curvature.hpp"

namespace topomill::plugins {

double PassageGeometry::split_time(double lo, double hi) const {
  const double step = s_.path->correction_step(src_), mid = 0.5 * (lo + hi);
  if (!(step > 0)) return mid;
  const double top = last_knot() / step;  // the last knot's index
  // The middle half's knots, ka .. kb: of those, the one with the most trailing zeros is kb with
  // its bits below the highest bit where ka and kb differ cleared.
  const double ka = std::max(std::ceil((lo + 0.25 * (hi - lo)) / step), 0.0);
  const double kb = std::min(std::floor((hi - 0.25 * (hi - lo)) / step), top);
  if (ka <= kb && kb < 0x1p52) {
    const auto a = static_cast<std::uint64_t>(ka), b = static_cast<std::uint64_t>(kb);
    const std::uint64_t k =
        a == b ? b : b & ~((std::uint64_t{1} << (63 - __builtin_clzll(a ^ b))) - 1);
    if (const double t = static_cast<double>(k) * step; t > lo && t < hi) return t;
  }
  // A piece shorter than two steps: the knot nearest the middle, if any.
  for (const double k : {std::round(mid / step), std::floor(mid / step), std::ceil(mid / step)})
    if (const double t = k * step; t > lo && t < hi && k >= 0 && k <= top) return t;
  return mid;
}

// Cut [a, b] in halves until each piece is settled. On a piece of length h with ends' phases
// g_a, g_b (each tooth's, wrapped to its nearest crossing):
// - no tooth can cross there: |g_a| + |g_b| > top h for each (top the bound of |G'|), the phase
//   cannot reach zero and back;
// - no crossing under the ball can lie below `below` there (the ball too high, or out of contact);
// - G monotone (fall < |omega|, rise < -|omega|, or G' of one sign at both ends with room for
//   the curvature): G is known unwrapped across the piece (advance: the bounds need rho_lo > 0,
//   so the axis cannot come round the node), and every tooth's crossings are the levels it
//   passes, each solved in its bracket (solve_level). Far from the axis a whole revolution
//   settles at once;
// - the axis within kOnAxis of the node all along: the tip cuts it there.
// Pieces are split at a correction knot inside first (G' jumps there: split_time), else at the
// middle; below a 1e-10 revolution the sign change alone decides (a touch of the edge no grid can
// resolve).
// One call's halving: the teeth asked for, the best height so far and the crossings found, and
// how each piece is settled.
struct PassageGeometry::Halving {
  struct End {
    Sample at;
    Probe q;      // tooth 0's
    double rate;  // NaN until needed
    Vec3 n;       // the nominal centre (span's, where knots lie inside: not read from the table)
  };
  struct Piece {
    End lo, hi;
  };
  const PassageGeometry& geo;
  const int first, last;
  double& below;
  std::vector<Crossing>& roots;
  const double w, min_len, roundoff;

  // A piece whose ball stays within round-off of `below` (which falls as crossings are found)
  // holds nothing lower that counts. Next to the tip (a point of every edge, and the ball's
  // lowest near the axis) the pieces' floor equals the tip's height but for round-off: without
  // the tie they would be halved down to kOnAxis before anything ruled them out.
  bool above(double floor) const {
    return floor >=
           below - 16 * std::numeric_limits<double>::epsilon() * (std::abs(below) + geo.s_.R);
  }
  // Tooth j's phase is tooth 0's turned by its angle: one probe serves all.
  double offset(int j) const { return geo.s_.tooth_angle[j] - geo.s_.tooth_angle[0]; }
  // The first whole turn m at or above phase v for tooth j: its level is m 2 pi - offset(j).
  double first_turn(double v, int j) const { return std::ceil((v + offset(j)) / kTwoPi); }
  End end(double t) const {
    Vec3 n;
    const Sample at = geo.sample(t, n);
    return End{at, geo.probe(0, t, at.c), NAN, n};
  }
  // The rate at an end on the side of a piece whose correction slope is dv (kept: an end is
  // shared by two pieces, on the same slope except at a knot).
  double rate_of(End& e, const Vec3& dv) const {
    if (e.at.dv != dv) return geo.rate(e.at, dv);
    if (std::isnan(e.rate)) e.rate = geo.rate(e.at, dv);
    return e.rate;
  }
  // The ball's lowest possible height over the node on a piece (a ringed cutter's hull's).
  double floor_of(const Piece& p, const Span& sp) const {
    const CutterProfile& f = geo.s_.profile;
    if (sp.plan_lo >= f.reach()) return INFINITY;
    const double ta = p.lo.at.t, tb = p.hi.at.t;
    // The nominal centre's lowest, and the correction's (its box's, where span read it).
    const double shift = !std::isnan(sp.box_z_lo) ? sp.box_z_lo
                         : geo.table_.corrected() ? geo.table_.correction_bounds(ta, tb).lo.z()
                                                  : 0.0;
    const double z = geo.table_.nominal_lowest_z(ta, tb, p.lo.n.z(), p.hi.n.z()) + shift;
    if (geo.s_.ringed) return z + f.up() - f.hull_depth(sp.plan_lo);
    return z - std::sqrt(geo.s_.R2 - sp.plan_lo * sp.plan_lo);
  }
  void found(int tooth, double t) {
    const Probe q = geo.probe(tooth, t);
    roots.push_back({tooth, t, q});
    if (q.over) below = std::min(below, q.height);
  }
  // Whether piece p is settled (its crossings, if any, found); false when it must be halved.
  bool settle(Piece& p);
  // Whether a piece that turns back is proven to hold no tooth's level, by the range its ends'
  // phases and rates allow under the curvature bound (phase_range).
  bool no_level(const Piece& p, const Span& sp, double ra, double rb, double h) const;
};

inline bool PassageGeometry::Halving::no_level(const Piece& p, const Span& sp, double ra, double rb,
                                               double h) const {
  const double g_lo = p.lo.q.g, g_hi = g_lo + geo.advance(p.lo.at.t, p.lo.q, p.hi.at.t, p.hi.q);
  const auto [v_lo, v_hi] = phase_range(g_lo, g_hi, ra, rb, sp.curve, h);
  for (int j = first; j <= last; ++j)
    if (first_turn(v_lo - 1e-9, j) * kTwoPi - offset(j) <= v_hi + 1e-9) return false;
  return true;
}

inline bool PassageGeometry::Halving::settle(Piece& p) {
  const double h = p.hi.at.t - p.lo.at.t;
  const Span sp = geo.span(p.lo.at, p.hi.at, &p.lo.n, &p.hi.n);
  if (sp.rho_hi <= kOnAxis) {
    // The axis within kOnAxis of the node all along: the tip, a point of every edge, cuts it
    // here (g jumps by pi rather than crossing zero, and no subdivision settles it).
    found(first, 0.5 * (p.lo.at.t + p.hi.at.t));
    return true;
  }
  const double reach = sp.turn(w, h) + roundoff;
  bool reachable = false;
  for (int j = first; j <= last && !reachable; ++j)
    reachable =
        std::abs(wrap(p.lo.q.g + offset(j))) + std::abs(wrap(p.hi.q.g + offset(j))) <= reach;
  if (!reachable) return true;
  if (sp.rho_lo > geo.rho_hi_ || sp.rho_hi < geo.rho_lo_ || above(floor_of(p, sp))) return true;
  // Monotone: turn < |omega|, or G' of one sign at both ends with room for the curvature (G' is
  // then at least half their sum less the curvature's fall between).
  bool mono = sp.sense(w) != 0;
  if (!mono && std::isfinite(sp.curve)) {
    const double ra = rate_of(p.lo, p.lo.at.dv), rb = rate_of(p.hi, p.lo.at.dv);
    mono = (ra > 0) == (rb > 0) && 0.5 * (std::abs(ra) + std::abs(rb) - sp.curve * h) > 0;
    // A turn-back inside: where no tooth's level lies in the range G can reach, no crossing does.
    if (!mono && no_level(p, sp, ra, rb, h)) return true;
  }
  if (mono) {
    // Unwrapped from the piece's start (rho_lo > 0: the turn is exact), every tooth's levels
    // G = 2 pi m - offset(j) between its ends.
    const double g_lo = p.lo.q.g, g_hi = g_lo + geo.advance(p.lo.at.t, p.lo.q, p.hi.at.t, p.hi.q);
    const double v_lo = std::min(g_lo, g_hi), v_hi = std::max(g_lo, g_hi);
    for (int j = first; j <= last; ++j)
      for (double m = first_turn(v_lo, j); m * kTwoPi - offset(j) <= v_hi; ++m)
        found(j, geo.solve_level(p.lo.at.t, p.lo.q, p.hi.at.t, g_hi, m * kTwoPi - offset(j)));
    return true;
  }
  if (h < min_len) {
    for (int j = first; j <= last; ++j) {
      const double ga = wrap(p.lo.q.g + offset(j)), gb = wrap(p.hi.q.g + offset(j));
      if (crosses(ga, gb)) found(j, geo.solve_bracket(j, p.lo.at.t, p.hi.at.t, ga, gb));
    }
    return true;
  }
  return false;
}

void PassageGeometry::crossings_in(int only, double a, double b, double& below,
                                   std::vector<Crossing>& roots, Probe* ends) const {
  const double w = std::abs(s_.omega);
  // The probes' phases carry round-off of a few ulps of their largest terms (omega t, the pass's
  // phase, the wrap). Where the phase turns at exactly its bound's rate (a node on the pass's line
  // with no lag turning there: the azimuth stands still, so G' = omega and the bound is tight), a
  // crossing inside a piece makes |g_a| + |g_b| equal its reach but for that round-off, which must
  // not rule the crossing out: without the allowance it does in 158 of the 360 windows of
  // tests/plugins/tooth_passage/passage_geometry_crossings_test.cpp, and on the convex case's pass
  // line a crossing 0.11 nm below the tip's cut is lost so.
  const double roundoff = 32 * std::numeric_limits<double>::epsilon() *
                          (w * std::max(std::abs(a), std::abs(b)) + std::abs(phase_) + 8 * M_PI);
  Halving run{
      *this,   only < 0 ? 0 : only, only < 0 ? s_.teeth - 1 : only, below, roots, w, 1e-10 * s_.rev,
      roundoff};
  using Piece = Halving::Piece;
  // The pieces still to settle, in storage kept by the caller's thread from call to call (an
  // allocation each call would be a few per cent of the halving's instructions near the axis),
  // taken into a local for the call: every use of a thread_local in a shared library is a call to
  // find it.
  thread_local std::vector<Piece> kept;
  std::vector<Piece> stack;
  stack.swap(kept);
  stack.clear();
  // Depth first, the piece in hand kept out of the stack (a push and a pop of two ends saved
  // at each halving, and the rate at the end it keeps).
  Piece p{run.end(a), run.end(b)};
  if (ends) ends[0] = p.lo.q, ends[1] = p.hi.q;
  // A stop request is honoured here too: on a steep face one node's pieces can take a minute.
  while (!s_.stopped()) {
    if (!run.settle(p)) {
      const Halving::End mid = run.end(split_time(p.lo.at.t, p.hi.at.t));
      // The half nearer the axis first: it holds the lowest crossings, which prune the other.
      if (p.lo.q.rho < p.hi.q.rho)
        stack.push_back(Piece{mid, p.hi}), p.hi = mid;
      else
        stack.push_back(Piece{p.lo, mid}), p.lo = mid;
      continue;
    }
    if (stack.empty()) break;
    p = stack.back();
    stack.pop_back();
  }
  kept.swap(stack);
}

namespace {
// The zero of f in [lo, hi], where f(lo) = f_lo and f(hi) = f_hi differ in sign and f is
// monotone: regula falsi with the Illinois rule (the end kept twice has its value halved), to
// |f| < 1e-9 or a bracket narrower than `width`.
template <class F>
double illinois(F f, double lo, double hi, double f_lo, double f_hi, double width) {
  if (f_lo == 0) return lo;
  if (f_hi == 0) return hi;
  int side = 0;
  for (int it = 0; it < 100 && hi - lo > width; ++it) {
    double t = (lo * f_hi - hi * f_lo) / (f_hi - f_lo);
    if (!(t > lo && t < hi)) t = 0.5 * (lo + hi);
    const double ft = f(t);
    if (std::abs(ft) < 1e-9) return t;
    if ((ft < 0) == (f_lo < 0)) {
      lo = t, f_lo = ft;
      if (side == -1) f_hi *= 0.5;
      side = -1;
    } else {
      hi = t, f_hi = ft;
      if (side == 1) f_lo *= 0.5;
      side = 1;
    }
  }
  return 0.5 * (lo + hi);
}

}  // namespace

double PassageGeometry::solve_level(double ta, const Probe& a, double b, double g_b,
                                    double level) const {
  // f = G - level, G unwrapped from ta (advance).
  return illinois([&](double t) { return a.g + advance(ta, a, t, probe(0, t)) - level; }, ta, b,
                  a.g - level, g_b - level, 1e-13 * s_.rev);
}

double PassageGeometry::solve_bracket(int tooth, double lo, double hi, double g_lo,
                                      double g_hi) const {
  return illinois([&](double t) { return probe(tooth, t).g; }, lo, hi, g_lo, g_hi, 1e-13 * s_.rev);
}

double PassageGeometry::bisect(int tooth, double lo, double hi, double g_lo) const {
  for (int it = 0; it < 200 && hi - lo > 1e-13 * s_.rev; ++it) {
    const double mid = 0.5 * (lo + hi), g_mid = probe(tooth, mid).g;
    if ((g_mid < 0) == (g_lo < 0))
      lo = mid, g_lo = g_mid;
    else
      hi = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace topomill::plugins
