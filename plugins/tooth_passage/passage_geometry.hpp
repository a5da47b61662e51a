// One node under one window of a pass of the ball (a straight stretch: PassageSetup::Window):
// where the ball is over it, how high, and when a tooth's edge crosses its vertical line. Both
// walks (the reference per node, the row sweep) are built from these probes.
//
// For a node at horizontal offset d(t) = node - centre(t) from the ball's axis, the ball point
// above it has sin(alpha) = |d| / R and height centre_z - sqrt(R^2 - |d|^2). Tooth j's edge is
// over the node when its azimuth theta_j + Psi(alpha) + spindle(t) equals the node's azimuth
// atan2(d): a root of g_j(t) = 0 mod 2 pi, g growing at about the spindle rate.
//
// A tilted tool (a fixed posture: docs/model.md, "Tool posture") changes only where that ball
// point lies on the tool: it is the same point of the same sphere, taken into the tool's frame,
// where its distance from the axis and its azimuth about it replace |d| and atan2(d) above. The
// bounds on the phase's rate (span) are the same functions of that point's path in the tool frame
// (its chord, speed and acceleration), which follow from the centre's through the sphere.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "lift_bounds.hpp"
#include "monotony.hpp"
#include "passage_setup.hpp"
#include "phase_span.hpp"
#include "probe.hpp"

namespace topomill::plugins {

class PassageGeometry {
 public:
  // The node (x, y) under window w (PassageSetup::Window) of a pass; with `part` given, under
  // its times [part.first, part.second] only, bounded by the split depth (a side of the axis's
  // closest approach: CutterProfile::splits).
  PassageGeometry(const PassageSetup& s, std::size_t w, double x, double y, double rho_lo,
                  double rho_hi, std::pair<double, double> part = {-INFINITY, INFINITY},
                  bool split = false)
      : s_(s),
        table_(s.window[w].centre),
        win_(w),
        src_(s.window[w].pass),
        x_(x),
        y_(y),
        rho_lo_(rho_lo),
        rho_hi_(rho_hi),
        phase_(s.path->pass(src_).phase),
        t_lo_(std::max(s.window[w].t_lo, part.first)),
        t_hi_(std::min(s.window[w].t_hi, part.second)),
        split_(split),
        tilted_(s.window[w].tilted),
        turning_(s.window[w].turn.on),
        to_tool_(s.window[w].to_tool) {
    const PassageSetup::PlanLine& l = s.window[w].plan_line;
    const double across = l.ux * (y - l.y) - l.uy * (x - l.x);
    line_gap_ = std::abs(across) - l.off;
    // -az' = (q x v) / rho^2 has the sign of -across (q x v above): with the spindle where that
    // is omega's.
    with_spindle_ = across * s.omega < 0;
  }

  const PassageSetup& setup() const { return s_; }
  std::size_t window() const { return win_; }
  double x() const { return x_; }
  double y() const { return y_; }
  // The window's times: crossings count within [t_lo, t_hi] only (beyond, its tables continue
  // its line, not the pass).
  double t_lo() const { return t_lo_; }
  double t_hi() const { return t_hi_; }
  bool within(double t) const { return t >= t_lo_ && t <= t_hi_; }
  bool split() const { return split_; }

  // Where the axis is at t and how fast it moves: what probe, span and rate read of the path,
  // taken once for each time (a subdivision's ends are shared by two pieces).
  struct Sample {
    double t;
    Vec3 c;      // the centre
    Vec3 v, dv;  // its velocity, nominal and the correction's (on the piece starting at t)
  };
  Sample sample(double t) const {
    return {t, table_(t), table_.nominal_velocity(t), table_.correction_slope(t)};
  }
  // The same, and the nominal centre at t (the centre less the correction) into `nominal`: for
  // the exact windows' ends, whose spans need it. (Kept apart from sample(t), which every Newton
  // probe builds: the nominal it would discard costs there.)
  Sample sample(double t, Vec3& nominal) const {
    nominal = table_.nominal(t);
    return {t, table_.corrected() ? Vec3(nominal + table_.correction(t)) : nominal,
            table_.nominal_velocity(t), table_.correction_slope(t)};
  }

  Probe probe(int tooth, double t) const { return probe(tooth, t, table_(t)); }
  // The ball point over the node, (dx, dy, -below) from the centre, taken into the tool frame
  // (the frame map: the identity for a vertical tool), where its distance from the axis and its
  // azimuth are the crossing equation's. Its polar angle from the tip is taken as asin(rho / R),
  // the lag's argument: past a tilted tool's equator that folds back, which keeps g continuous
  // (the bounds hold for it), and no edge is there (not over). Beyond the ball in plan the point
  // is taken on its equator's plane and the lag held at the rim's, as LagShape continues it: the
  // phase goes on continuously for the bounds and turns read across the rim.
  Probe probe(int tooth, double t, const Vec3& c) const {
    if (s_.ringed) return probe_ringed(tooth, t, c);
    const double dx = x_ - c.x(), dy = y_ - c.y(), r2 = dx * dx + dy * dy;
    if (!(r2 < s_.R2)) return probe_past_rim(tooth, t, dx, dy);
    const double below = std::sqrt(s_.R2 - r2);
    const Vec3 p = tilted_ ? Vec3(to_tool(t) * Vec3(dx, dy, -below)) : Vec3(dx, dy, -below);
    const double rho = std::sqrt(p.x() * p.x() + p.y() * p.y()), sin_a = rho / s_.R;
    const double lag =
        sin_a < s_.sin_tip ? s_.lag_tip : s_.tool->lag_sc(sin_a, std::abs(p.z()) / s_.R);
    return {p.z() <= 0 && rho >= rho_lo_ && rho <= rho_hi_, phase(tooth, t, lag, p.x(), p.y()),
            c.z() - below, rho, lag};
  }
  // The crossing equation's g: tooth `tooth`'s edge, lagging by `lag`, against the azimuth of the
  // point (x, y) in the tool frame at t, wrapped to one turn. One expression for every probe.
  [[gnu::always_inline]] double phase(int tooth, double t, double lag, double x, double y) const {
    return wrap(s_.tooth_angle[tooth] + lag + phase_ + s_.omega * t - std::atan2(y, x));
  }
  // The same past the ball in plan (the node's plan offset dx, dy; out of line: rarely asked).
  Probe probe_past_rim(int tooth, double t, double dx, double dy) const;

  // A ringed cutter's probe (a vertical axis): its profile over the node
  // (passage_geometry_ringed.hpp).
  Probe probe_ringed(int tooth, double t, const Vec3& c) const;

  // How far the phase G (unwrapped) turns from probe a at ta to probe b at tb, exactly, where
  // the axis cannot come round the node between: wherever the centre stays in a convex region
  // that leaves the node out (span's rho_lo > 0: the chord thickened by its sagitta), the node's
  // azimuth turns by less than pi, so of G's increment omega (tb - ta) + lag_b - lag_a - turn of
  // the azimuth all but the last is known and the wrapped phases fix the rest.
  double advance(double ta, const Probe& a, double tb, const Probe& b) const {
    const double known = s_.omega * (tb - ta) + b.lag - a.lag;
    return known + wrap(b.g - a.g - known);
  }

  // Whether the phase turns by `turn` (in magnitude, to round-off) from probe a at ta to probe b
  // at tb (and on to c at tc), all of one tooth: advance's exact increments, so only where the
  // axis stays in a convex region that leaves the node out over each (a span there with
  // rho_lo > 0), and the phase monotone over all.
  bool turned(double turn, double ta, const Probe& a, double tb, const Probe& b) const {
    return std::abs(std::abs(advance(ta, a, tb, b)) - turn) < 1e-6;
  }
  bool turned(double turn, double ta, const Probe& a, double tb, const Probe& b, double tc,
              const Probe& c) const {
    return std::abs(std::abs(advance(ta, a, tb, b) + advance(tb, b, tc, c)) - turn) < 1e-6;
  }

  // A lower bound of envelope(t) whatever the correction and the runout within their ranges: the
  // spindle axis's nominal centre moved by the range's lowest z and as close to the node as the
  // range allows. It has a single minimum, as the ideal envelope, but where the nominal height
  // bends down (PassageSetup::FloorTail).
  double floor_envelope(double t) const {
    const Vec3 c = s_.runout > 0 ? s_.window[win_].spindle_axis->nominal(t) : table_.nominal(t);
    const Vec3 &lo = s_.window[win_].shift_lo, &hi = s_.window[win_].shift_hi;
    const double dx = x_ - c.x(), dy = y_ - c.y();
    const double ex = dx - std::clamp(dx, lo.x(), hi.x()), ey = dy - std::clamp(dy, lo.y(), hi.y());
    const double r2 = ex * ex + ey * ey, z = c.z() + lo.z();
    if (s_.ringed) return z + s_.profile.up() - s_.profile.hull_depth(std::sqrt(r2));
    return r2 < s_.R2 ? z - std::sqrt(s_.R2 - r2) : z + (std::sqrt(r2) - s_.R);
  }

  // The node's distance from the centre in plan at t.
  double distance(double t) const {
    const Vec3 c = table_(t);
    return std::hypot(x_ - c.x(), y_ - c.y());
  }
  // The ball point over the node's distance from the tool's axis at t (Probe::rho): the same as
  // distance() for a vertical tool; +inf off the ball.
  double axis_distance(double t) const;

  // The ball's height over the node, continued past its rim so that it stays unimodal (a ringed
  // cutter's hull: CutterProfile).
  double envelope(double t) const {
    const Vec3 c = table_(t);
    const double dx = x_ - c.x(), dy = y_ - c.y(), r2 = dx * dx + dy * dy;
    if (s_.ringed) {
      const double rho = std::sqrt(r2);
      return c.z() + s_.profile.up() -
             (split_ ? s_.profile.split_depth(rho) : s_.profile.hull_depth(rho));
    }
    return r2 < s_.R2 ? c.z() - std::sqrt(s_.R2 - r2) : c.z() + (std::sqrt(r2) - s_.R);
  }

  // The crossing of one tooth near `t`: Newton's iteration on g with the phase's rate (rate()),
  // where that is too flat or undefined (on the axis) the last secant, or `slope` (the spindle
  // rate when nothing better is known). Returns the time; `slope` gets the last step's slope and
  // `last` the last probe, which is at the returned time when it converged (|last.g| < 1e-9 rad:
  // the time to 1e-9 / omega, about 2e-12 s, the height to about 1e-11 mm; or the last step
  // proven to land within 1e-10 rad, land()).
  double crossing(int tooth, double t, double& slope, Probe& last) const;
  double crossing(int tooth, double t) const {
    double slope = s_.omega;
    Probe last{};
    return crossing(tooth, t, slope, last);
  }
  static bool converged(const Probe& q) { return std::abs(q.g) < 1e-9; }
  // Newton's step from probe q at `at` (the phase's rate there r, the lag's part of it lag_rate)
  // without a probe to check it, where it is proven to land: |G| <= C h^2 / 2 after a step of
  // length h, C the bound of |G''| (phase_curvature.hpp) over the step, and that must be at most
  // 1e-10 rad, a tenth of converged()'s tolerance. Then `t` gets the step's end and `q` its
  // probe in place of the one at `at`: the phase 0, the ball's height and rho from the centre's
  // tangent line (which strays at most accel h^2 / 2 <= 1e-13 mm from the centre), the lag from its
  // rate (within C h^2 / 2: C bounds the lag's own second derivative; advance() reads it to 1e-6).
  // False where that is not proven (a knot or the tip radius within the step, a turning frame,
  // too long a step): a probe must check the step. Near the axis a guess from the last node is 1e-7
  // to 1e-6 rad off, and this takes the second probe, with its atan2 and lag, off most crossings
  // there.
  bool land(const Sample& at, double r, double lag_rate, double& t, Probe& q) const;

  // The bottom of `f` (envelope or floor_envelope) within [a, b] (golden section to a 20th of
  // a tooth period). Where the bracket still holds an end of [a, b] and f is lower there, that
  // end: a window's envelope can fall all the way to its end (the node lies beyond it), and its
  // height at the end, not a bracket's width inside, is the window's lowest (the walks' first
  // test, whether a window can lower the node at all, reads it).
  template <class F>
  double bottom(F f, double a, double b) const;
  // The bottom of `f` within the travel of a ball's diameter either side of t0 (the
  // reference's window); of the envelope when no `f` is given. A ringed cutter's hull is flat
  // over its bottom, where the golden section stops anywhere: t0 (the level time, the axis's
  // closest approach) where it is as low, so that the walks start where the node is farthest
  // from the rim, and any point of a flat bottom is one. (Both in passage_geometry_bottom.hpp.)
  template <class F>
  double bottom_near(F f, double t0) const;
  double bottom_near(double t0) const {
    return bottom_near([this](double t) { return envelope(t); }, t0);
  }

  // Whether g, sampled twice, went through zero between (and not through its wrap at +-pi).
  static bool crosses(double ga, double gb) {
    return (ga < 0) != (gb < 0) && std::abs(gb - ga) < M_PI;
  }
  // That zero, by bisection of [lo, hi] (g(lo) = g_lo) to 1e-13 of a revolution.
  double bisect(int tooth, double lo, double hi, double g_lo) const;

  // What bounds the phase's turn on a span [a, b] of the pass (phase_span.hpp).
  using Span = PhaseSpan;

  // Rigorous bounds over [a, b]: from the chord of the centre's motion (less its sagitta) when no
  // correction knot lies inside, else from the nominal chord moved by the correction's box there.
  Span span(double a, double b) const { return span(sample(a), sample(b)); }
  // `na`, `nb`: the nominal centres at a and b where the caller has them (else the table's).
  Span span(const Sample& a, const Sample& b, const Vec3* na = nullptr,
            const Vec3* nb = nullptr) const;
  // The bounds from the moving point's path over a piece: its distance from the axis within
  // [rho_lo, rho_hi], its speed at most v, its moment about the axis (q x v, v = -q') within
  // [c_lo, c_hi], its acceleration at most `accel` (infinite curvature bound with a knot inside),
  // the length of its path over the piece at most `length` (+inf: not known; Span::sweep).
  Span bound_rates(double rho_lo, double rho_hi, double v, double c_lo, double c_hi, double accel,
                   bool knot_inside, double length = INFINITY) const;
  // The region in plan the centre keeps to over a piece (passage_geometry_bounds.cpp): a chord
  // thickened by `grow`, the node's least and greatest distance from it, the centre's top speed.
  struct PlanRegion {
    Vec3 ca, cb;
    double grow = 0, v = 0, lo = 0, hi = 0;
    bool knot_inside = false;
    double box_z_lo = NAN;     // the correction's lowest, where its box was read (knots inside)
    double length = INFINITY;  // the centre's path in plan over the piece, where known
  };
  PlanRegion plan_region(const Sample& a, const Sample& b, const Vec3* na, const Vec3* nb) const;
  // The bounds from the region: a vertical tool's (the node's offset from the axis moves), and a
  // tilted tool's (the ball point over the node in the tool frame, lifted from the plan).
  Span plan_rates(const Sample& a, const Sample& b, const PlanRegion& r) const;
  Span lifted_rates(const Sample& a, const Sample& b, const PlanRegion& r) const;
  // The ball's lift from the plan into the tool frame (lift_bounds.hpp).
  using Lift = BallLift;
  static Lift lift_bounds(double R, double plan, double v, double A) {
    return ball_lift_bounds(R, plan, v, A);
  }
  // The ball point over the node relative to the centre in the tool frame, and its velocity, for
  // the centre at c moving at v (plan offset q = node - c) at time t (the frame's, which may
  // turn): false off the ball.
  bool lifted(double t, const Vec3& c, const Vec3& v, Vec3& p, Vec3& dp) const;
  // The tool frame's transpose at t.
  Eigen::Matrix3d to_tool(double t) const { return turning_ ? s_.to_tool_at(win_, t) : to_tool_; }
  // What the frame's turn adds to the ball point's speed in the tool frame (at most |theta'| R:
  // a turn of a point at R from the centre) and to its acceleration, given the point's own speed
  // v there (2 |theta'| v + (|theta''| + theta'^2) R); zero on a fixed frame.
  double turn_speed() const { return turning_ ? s_.window[win_].turn.rate * s_.R : 0.0; }
  double turn_accel(double v) const {
    const PassageSetup::Turn& q = s_.window[win_].turn;
    return turning_ ? 2 * q.rate * v + (q.accel + q.rate * q.rate) * s_.R : 0.0;
  }
  // G'(t), the phase's rate (rad/s): the same for every tooth. `dv` is the correction's slope on
  // the side of t asked for (sample's is the right: a piece ending at a knot asks for the left).
  // `lag_rate`, where given, gets the lag's part of it.
  double rate(const Sample& at, const Vec3& dv, double* lag_rate = nullptr) const;
  using Stretch = PhaseStretch;
  using Monotony = PhaseMonotony;
  // The stretch `reach` either side of t, with the node's distance at t read from the table where
  // the window can use it (a vertical tool on a fixed frame).
  Stretch around(double t, double reach) const {
    if (tilted_ || turning_) return {t - reach, t + reach};  // (the distance never helps there)
    const Vec3 c = table_(t);
    return {t - reach, t + reach, norm(x_ - c.x(), y_ - c.y()), reach};
  }
  // What the bounds prove of the phase over a stretch: every follow's one question before it
  // steps, ends a walk or trusts a turn. Answered first, inline, by a reason that holds all along
  // the window, from the node's distance (monotone_by_distance: most steps end there), else by
  // the span over the stretch.
  Monotony monotony(const Stretch& s) const {
    if (!std::isnan(s.rho) && monotone_by_distance(s.rho, s.reach))
      return {true, INFINITY, any_turn_exact()};
    return monotony_by_span(s);
  }
  // Whether line_rates can know anything here: a window that keeps to its line, the node off it.
  bool lined() const { return s_.window[win_].plan_line.along_lo > 0 && line_gap_ > 0; }
  // The phase's rate on a window whose centre keeps to its line (PlanLine::along_lo > 0), at every
  // time the node is within `out` of the axis, from the side of the line the node lies on:
  // within [w - fall, w + rise] in the spindle's sense, returned as (fall, rise); infinite where
  // not known (another window, the node in the line's strip, `out` past the rim). One lookup for
  // the whole pass, where a span near the axis bounds the rate by v / rho_lo at best (the proof
  // is at its definition, passage_geometry_bounds.cpp).
  std::pair<double, double> line_rates(double out) const;
  // How soon after a crossing `rho` from the axis the same tooth can cross again by line_rates
  // (a whole turn at the top rate, the phase monotone), up to `cap`; 0 where that is not known.
  double line_gap(double rho, double cap) const;
  // How far from the axis the moving point (moving at most at `speed`) must stay for
  // |G' - omega| < omega / 1.01 while it is within `out` of the axis: S v / omega, S from the
  // lag's slope out to there (LagShape::slope_to).
  double clearance(double out, double speed) const;
  // How soon after (dir > 0) or before (dir < 0) a crossing at t, rho from the axis, the same
  // tooth can cross again: half a revolution where the phase's rate stays within (0, 2 omega)
  // there (PassageSetup::gap_rho; or where the axis stays far enough from the node over that
  // half revolution: PlanLine), a whole turn at the top rate where it is monotone, and none
  // where it can turn back (near the axis the next crossing can come at once, as the node's
  // azimuth swings round). The walks end on it.
  double next_gap(double t, double rho, double dir) const;
  // Whether t is the crossing right after (or before) the crossing t_prev of the same tooth: the
  // phase is monotone between and turns by exactly one turn (nothing between).
  bool next_crossing(double t_prev, double t) const {
    return std::abs(t - t_prev) > kSamePassage * s_.rev &&
           turns_by(std::min(t, t_prev), std::max(t, t_prev), kTwoPi);
  }

  // Every crossing of `tooth` (of every tooth when -1) in [a, b] that can lie below `below` (the
  // rest may be left out), exactly: [a, b] is cut in halves until on each piece the phase is
  // proven monotone and known unwrapped (its crossings solved in their brackets), or proven not
  // to reach a crossing, or the ball proven too high. `below` comes back lowered by the crossings
  // found under the ball. `ends`, where given, gets tooth 0's probes at a and b (any tooth's is
  // that one turned by the tooth's angle: turned_to).
  struct Crossing {
    int tooth;
    double t;
    Probe q;  // the tooth's probe there
  };
  void crossings_in(int tooth, double a, double b, double& below, std::vector<Crossing>& roots,
                    Probe* ends = nullptr) const;
  // The same directly, where the window's centre keeps to its line (lined()): the phase's turning
  // points solved as the zeros of K = rho^2 G', proven convex (lined_convexity), then each
  // tooth's levels between (passage_geometry_lined.cpp). False, with nothing found and `below`
  // untouched, where that proof fails (the tip radius or the rim within reach, the node next to the
  // line) or the zeros do not settle: crossings_in then, which stays the reference
  // (tests/plugins/tooth_passage/passage_geometry_lined_test.cpp). `hints`, where given: where
  // crossings are expected (the row sweep's last node's, carried on), each solve starting from the
  // one of its tooth nearest its place.
  struct Hint {
    int tooth;
    double t;
  };
  bool crossings_lined(int tooth, double a, double b, double& below, std::vector<Crossing>& roots,
                       Probe* ends = nullptr, const std::vector<Hint>* hints = nullptr) const;
  // Where lined(), a lower bound of K'' in the spindle's sense while the node is at most rho_hi
  // from the axis: where it is positive, K has at most two zeros. -inf where none is known (the
  // tip radius or the rim within reach). `k2`, where given, gets the lag's bend it took.
  double lined_convexity(double rho_hi, double* k2 = nullptr) const;
  // The one entry point: every crossing of `tooth` (every tooth when -1) in [a, b] that can lie
  // below `below`, exactly, directly where the window keeps to its line (crossings_lined) and by
  // the certified halving wherever that proof fails (crossings_in).
  void crossings(int tooth, double a, double b, double& below, std::vector<Crossing>& roots,
                 Probe* ends, const std::vector<Hint>* hints) const {
    if (lined() && crossings_lined(tooth, a, b, below, roots, ends, hints)) return;
    crossings_in(tooth, a, b, below, roots, ends);
  }
  // Tooth 0's probe q as tooth j's (the same but for the phase, turned by the tooth's angle).
  Probe turned_to(const Probe& q, int j) const {
    Probe out = q;
    out.g = wrap(q.g + s_.tooth_angle[j] - s_.tooth_angle[0]);
    return out;
  }
  // Where crossings_in cuts a piece [lo, hi]: at a correction knot where there is one inside (G'
  // jumps only at knots, so the halves' bounds then hold without one), and of the knots in the
  // piece's middle half at the one whose index has the most trailing zeros: the pieces then keep
  // to the range table's blocks, whose queries need no scan of ragged ends (a few per
  // cent of the instructions near the axis with vibration and deflection). Else the knot nearest
  // the middle, else the middle.
  double split_time(double lo, double hi) const;
  // The one crossing in [lo, hi], where g is monotone and changes sign (regula falsi, Illinois).
  double solve_bracket(int tooth, double lo, double hi, double g_lo, double g_hi) const;

  // A true lower bound of every crossing's height at time t: the envelope itself when ideal, its
  // floor when it wiggles. It has a single minimum but where the floor's tail is on (FloorTail).
  double bound(double t) const { return s_.wiggles ? floor_envelope(t) : envelope(t); }
  // Whether no crossing from t on in direction dir can lower the node to `best`, t past the
  // bound's bottom: the bound at t is at or above it, and with the tail on, so is tail_floor.
  bool beyond_reach(double t, double dir, double best) const {
    return bound(t) >= best && (!s_.window[win_].tail.on || tail_floor(t, dir, best) >= best);
  }
  // The stop-by-bound rule every walk ends by: beyond_reach at t, at least kBottomTolerance of a
  // tooth period from the bound's bottom t_b in direction dir (t_b is found that close to it).
  bool ends_by_bound(double t_b, double dir, double t, double best) const {
    return dir * (t - t_b) >= kBottomTolerance * s_.period && beyond_reach(t, dir, best);
  }
  // A lower bound of the bound over the whole window, t_b its bottom: the bound there, and with
  // the tail on the least of that and both tails from there (passage_geometry_tail.cpp).
  double lowest_bound(double t_b, double target) const;
  // A lower bound of the floor over the window from t on in direction dir, proven where it is at
  // least `target` (else -inf): the floor's nominal height falls below its tangent at t by at
  // most its bend, while the ball's depth there falls as the node's least distance from the box
  // grows, at least at the nominal's least speed along its line (FloorTail).
  double tail_floor(double t, double dir, double target) const;

  // A node on the pass's line, which the axis passes within kOnAxis of at t0 (the level time), is
  // cut by the tip then; +inf otherwise.
  double tip_height(double t0) const;  // t0: PassageSetup::tip_time

  // The reference walk: revolutions outwards from t_b (the bound's bottom), every tooth's
  // crossings in each found exactly (crossings_in, one subdivision for all teeth), until the
  // bound proves that nothing farther can go lower; returns the lowest height over the node (+inf
  // if none).
  // `below` is the node's best height so far: nothing at or above it is looked for. `lowest`, if
  // given, gets the crossing that gave the returned height (untouched when none did).
  double walk(double t_b, std::vector<Crossing>& roots, std::uint64_t& visited,
              double below = INFINITY, Crossing* lowest = nullptr) const;

  // How far from the axis the lag's slope is bounded: kRimFraction of the tube from its centre.
  double rim() const { return s_.ringed ? s_.profile.rim_out(kRimFraction) : kRimFraction * s_.R; }

 private:
  // |(x, y)| without hypot's care for overflow, which costs here and is not needed (mm and mm/s).
  static double norm(double x, double y) { return std::sqrt(x * x + y * y); }
  // One call of crossings_in: its pieces and how each is settled (passage_geometry_crossings.cpp).
  struct Halving;
  // One call of crossings_lined: the zone's turning points and levels (passage_geometry_lined.cpp).
  struct LinedZone;
  // Where tooth 0's phase G, unwrapped from its value at probe `a` (time ta), equals `level` in
  // [ta, b], G(b) = g_b; G monotone there and the node out of the axis's way (advance).
  double solve_level(double ta, const Probe& a, double b, double g_b, double level) const;

  // The last correction knot's time (-inf on an ideal path): the correction is linear between
  // knots, so the phase's rate jumps only there.
  double last_knot() const {
    const double step = s_.path->correction_step(src_);
    return step > 0
               ? static_cast<double>(s_.path->correction_samples(src_).values.size() - 1) * step
               : -INFINITY;
  }
  // monotony's conditions other than the distance from the axis: a vertical tool, the node
  // farther from the window's line than S v / omega. next_gap settles most nodes by it too.
  bool far_from_line() const {
    return !tilted_ && !turning_ &&
           line_gap_ >= kRoom * s_.gap_lag * s_.window[win_].plan_line.speed / std::abs(s_.omega);
  }
  // Whether the phase is monotone over `reach` from (or to) a time when the node is `rho` from
  // the axis, by the reasons that hold all along the window (monotony). Far from the line G'
  // stays within (0, 2 omega): a vertical tool, the node farther from the window's line than
  // S v / omega (PlanLine; S from the lag's slope over the ball to 0.95 R: gap_lag, or out to as
  // far as the node gets: clears_line), and within 0.95 R of the axis all along (it moves away at
  // most at the centre's top speed v); all nodes but those within about v / omega of a pass's
  // line. Closer to it, on a pass that keeps to it (PlanLine::along_lo), the side the node lies
  // on settles it (line_rates): where the node's azimuth turns with the spindle the phase is
  // monotone from a few micrometres out (the paper's loxodrome at its feed: 3.3 um).
  bool monotone_by_distance(double rho, double reach) const {
    const double v = s_.window[win_].plan_line.speed, out = rho + v * reach;
    if (out > rim()) return false;
    return far_from_line() || clears_line(out) ||
           (lined() && kRoom * line_rates(out).first < std::abs(s_.omega));
  }
  // monotony's answer from the span over the stretch.
  Monotony monotony_by_span(const Stretch& s) const;
  // Monotony::any_turn_exact.
  bool any_turn_exact() const { return !tilted_ && !turning_ && line_gap_ > 0; }
  // Nearer the line: far_from_line with the lag's slope only as far out as the node gets, `out`
  // from the axis (gap_lag takes it to 0.95 R, where a loxodrome's is twice its tip's), as next_gap
  // does.
  bool clears_line(double out) const;
  // Whether the phase is monotone on [lo, hi] and turns by exactly `turn` there, given that it
  // turns by `turn` plus a whole number of turns (the phases at both ends tell): proven on four
  // equal parts, by the bounds (less than one more turn) or, where they are too loose, exactly
  // (advance).
  bool turns_by(double lo, double hi, double turn) const;
  // Where on the chord from a to b (0 to 1, in plan) the node's foot lies.
  double nearest_on_chord(const Vec3& a, const Vec3& b) const {
    const double ux = b.x() - a.x(), uy = b.y() - a.y(), len2 = ux * ux + uy * uy;
    return len2 > 0 ? std::clamp(((x_ - a.x()) * ux + (y_ - a.y()) * uy) / len2, 0.0, 1.0) : 0.0;
  }

  const PassageSetup& s_;
  const CentreTable& table_;
  std::size_t win_, src_;  // the window, and its pass
  double x_, y_, rho_lo_, rho_hi_, phase_, t_lo_, t_hi_;
  bool split_;  // a side of the closest approach, bounded by the split depth (constructor)
  bool tilted_, turning_;
  Eigen::Matrix3d to_tool_;  // the tool frame's transpose when tilted (at t = 0 when turning)
  double line_gap_;  // at most the axis's least distance from the node along the pass (PlanLine)
  // The side of the line the node lies on: as the centre passes, the node's azimuth turns with the
  // spindle (line_rates).
  bool with_spindle_;
};

}  // namespace topomill::plugins

#include "passage_geometry_bottom.hpp"
#include "passage_geometry_ringed.hpp"
