// The ball centre of one pass, cheap to evaluate: the nominal centre (smooth: a curve on the
// surface's offset) is tabulated and interpolated with cubics, the correction (piecewise linear
// already) is added exactly. A probe then costs a few multiplies instead of the surface's
// trigonometry. The step is halved until the interpolation is within `tolerance` of the nominal
// centre at every interval's midpoint, so the table is as good as the path at any surface.
//
// A table may hold one straight stretch of a bent pass (PassageSetup::Window): beyond the
// stretch's ends it continues the stretch's line instead of turning with the pass, so that the
// path it holds stays smooth (a corner would break every bound the walks prove by) and looks
// beyond the ends see where the stretch was going. The walks count crossings within the stretch
// only, where the table is the pass.
#pragma once

#include <array>
#include <cmath>
#include <memory>
#include <utility>
#include <vector>

#include "range_table.hpp"
#include "topomill/error.hpp"
#include "topomill/tool_path.hpp"

namespace topomill::plugins {

// A stretch [lo, hi] of a pass, a line at one speed, continued beyond its ends at its velocity (of
// the spindle's axis: the runout still circles about the continued line). The default is the whole
// pass as the path gives it.
struct Stretch {
  double lo = -INFINITY, hi = INFINITY;
  Vec3 v = Vec3::Zero();  // the stretch's one velocity (a line at one speed)
};

// A pass's correction samples indexed for range queries: entry k holds sample k's x, y, z and
// the speeds in plan and along z of piece k (from sample k to k + 1; none after the last sample,
// where the correction is held), so that one walk of the tree gives a span's box and top speeds
// together (span() asks both for every piece it bounds: two walks would be a third of its cost
// near the axis with effects). And the length of its path in plan up to each sample (prefix sums),
// for the length over any span in O(1). One per pass, shared by the tables of its windows (each
// would otherwise hold its own: 8 GB for the radial-then-spiral example's 2 735 windows with
// effects).
struct CorrectionIndex {
  using Entry = std::array<double, 5>;  // x, y, z, speed in plan, speed along z
  RangeTable<5> range;
  std::vector<double> plan_length;  // [k]: the path's length in plan from sample 0 to sample k
  explicit CorrectionIndex(const ToolPath::Correction& c) {
    const std::size_t n = c.values.size();
    if (n == 0) return;
    plan_length.assign(n, 0.0);
    for (std::size_t k = 1; k < n; ++k)
      plan_length[k] = plan_length[k - 1] + piece_speed(c, k - 1, true) * c.dt;
    range = RangeTable<5>(n, [&](std::size_t k) { return entry(c, k); });
  }
  static Entry entry(const ToolPath::Correction& c, std::size_t k) {
    const Vec3& v = c.values[k];
    if (k + 1 >= c.values.size()) return {v.x(), v.y(), v.z(), 0.0, 0.0};
    return {v.x(), v.y(), v.z(), piece_speed(c, k, true), piece_speed(c, k, false)};
  }
  // Piece k's speed in plan or along z.
  static double piece_speed(const ToolPath::Correction& c, std::size_t k, bool plan) {
    const Vec3 d = (c.values[k + 1] - c.values[k]) / c.dt;
    // (sqrt, not hypot: mm/s need no care for overflow, and a span's query reads this at its
    // ragged ends, where hypot would take half of the query's instructions.)
    return plan ? std::sqrt(d.x() * d.x() + d.y() * d.y()) : std::abs(d.z());
  }
};

// What the correction does over a span: the box it stays in, and its top speeds in plan and
// along z.
struct CorrectionBounds {
  Vec3 lo = Vec3::Zero(), hi = Vec3::Zero();
  double speed_xy = 0, speed_z = 0;
};

class CentreTable {
 public:
  // Covers [t_lo, t_hi]; outside it the path is asked directly. `spindle_axis`: the nominal
  // centre less the runout (the spindle's axis: smooth, where the centre circles about it), for
  // the walks' floor. `index`: the pass's correction index, if one was built (else its own).
  CentreTable(const ToolPath& path, std::size_t pass, double t_lo, double t_hi, double tolerance,
              bool spindle_axis = false, const Stretch& stretch = Stretch{},
              std::shared_ptr<const CorrectionIndex> index = nullptr)
      : path_(&path),
        pass_(pass),
        correction_(&path.correction_samples(pass)),
        spindle_axis_(spindle_axis),
        stretch_(stretch),
        index_(index ? std::move(index)
                     : std::make_shared<const CorrectionIndex>(path.correction_samples(pass))) {
    double dt = std::max((t_hi - t_lo) / 16, 1e-9);
    // At most 2^22 knots (200 MB): a smooth path needs far fewer, and a path that is not (NaN
    // off the surface's end) must not take all memory on the way to the refusal.
    Midpoint worst;
    for (int attempt = 0; attempt < 40 && (t_hi - t_lo) / dt < 4e6; ++attempt, dt /= 2) {
      build(t_lo, t_hi, dt);
      worst = max_midpoint_error();
      if (worst.error <= tolerance) return;
      if (!std::isfinite(worst.error)) break;
    }
    refuse(worst);
  }

  [[gnu::flatten]] Vec3 operator()(double t) const {
    Vec3 c = nominal(t);
    if (corrected()) c += correction(t);
    return c;
  }
  // Whether the pass has a correction.
  bool corrected() const { return !correction_->values.empty(); }
  // The correction at t (zero without one): operator() less nominal().
  Vec3 correction(double t) const { return correction_->at(t); }

  Vec3 nominal(double t) const {
    double s;
    const Cubic* c = piece(t, s);
    if (!c) return path_centre(t);
    return (*c)[0] + s * ((*c)[1] + s * ((*c)[2] + s * (*c)[3]));
  }

  // The correction's slope on its linear piece at t (at a knot, the piece that starts there).
  Vec3 correction_slope(double t) const {
    const auto& c = *correction_;
    if (c.values.size() >= 2 && t >= 0) {
      const auto k = static_cast<std::size_t>(t / c.dt);
      if (k + 1 < c.values.size()) return (c.values[k + 1] - c.values[k]) / c.dt;
    }
    return Vec3::Zero();
  }
  // The nominal centre's velocity (mm/s): the cubic's derivative.
  Vec3 nominal_velocity(double t) const {
    double s;
    const Cubic* c = piece(t, s);
    if (!c) {
      const double h = 1e-6 / inv_dt_;  // beyond the table (never in practice): the path itself
      return (path_centre(t + h) - path_centre(t - h)) / (2 * h);
    }
    return ((*c)[1] + s * (2 * (*c)[2] + 3 * s * (*c)[3])) * inv_dt_;
  }
  // The nominal centre, its velocity and its acceleration at t, from the cubic that holds t;
  // false beyond the table's cubics (the direct zone reads only the table:
  // passage_geometry_lined.cpp).
  bool nominal_jet(double t, Vec3& c, Vec3& v, Vec3& a) const {
    double s;
    const Cubic* p = piece(t, s);
    if (!p) return false;
    const Cubic& q = *p;
    c = q[0] + s * (q[1] + s * (q[2] + s * q[3]));
    v = (q[1] + s * (2 * q[2] + 3 * s * q[3])) * inv_dt_;
    a = (2 * q[2] + 6 * s * q[3]) * (inv_dt_ * inv_dt_);
    return true;
  }
  // An upper bound of the nominal centre's jerk in plan (mm/s^3): a cubic's third derivative is
  // one number per piece, so this is the largest, exact but for a margin of round-off.
  double jerk_xy() const { return jerk_xy_; }
  // An upper bound of the nominal centre's acceleration in plan (mm/s^2): the cubics' second
  // derivatives at their ends (where a cubic's, linear, is largest), with a margin. The
  // correction adds none within its linear pieces.
  double accel_xy() const { return accel_xy_; }
  // The same in space (mm/s^2): how far the centre strays from its tangent line (land()).
  double accel() const { return accel_; }

  // A lower bound of the centre's height over a short span [ta, tb]: the nominal part's lower
  // end less twice its bend (which the midpoint measures: for a parabola the chord lies
  // (za + zb - 2 zm) / 2 above the lowest point), plus the correction's lowest, which, linear
  // between samples, is at an end or at a sample inside.
  double lowest_z(double ta, double tb) const {
    return nominal_lowest_z(ta, tb) + correction_bounds(ta, tb).lo.z();
  }
  // Its nominal part (the caller may have the correction's box already).
  double nominal_lowest_z(double ta, double tb) const {
    return nominal_lowest_z(ta, tb, nominal(ta).z(), nominal(tb).z());
  }
  // The times [start, end] of the cubic that holds t (for tests).
  std::pair<double, double> cubic_span(double t) const {
    const double k = std::floor((t - t0_) * inv_dt_);
    return {t0_ + k / inv_dt_, t0_ + (k + 1) / inv_dt_};
  }
  // The same with the nominal heights at the ends known (za, zb).
  double nominal_lowest_z(double ta, double tb, double za, double zb) const {
    const double ua = (ta - t0_) * inv_dt_, ub = (tb - t0_) * inv_dt_, k = std::floor(ua);
    if (k >= 1 && k + 2 < static_cast<double>(knots_.size()) && ub <= k + 1) {
      // Within one cubic (every short piece): its least is at an end or where its slope
      // vanishes, exactly (to round-off). Near the tool's axis pieces shrink to nothing, and a
      // margin there would keep the ball's tip, the lowest point near it, from ruling them out.
      return cubic_lowest(cubic_[static_cast<std::size_t>(k)], ua - k, ub - k, std::min(za, zb));
    }
    const double zm = nominal(0.5 * (ta + tb)).z();
    return std::min(za, zb) - std::abs(za + zb - 2 * zm) - 1e-9;
  }

  // The tabulated nominal centre's least height over the whole table, exactly (to round-off).
  double nominal_lowest_z() const {
    double low = INFINITY;
    for (std::size_t i = 1; i + 2 < knots_.size(); ++i) {
      const Cubic& c = cubic_[i];
      low =
          std::min(low, cubic_lowest(c, 0, 1, std::min(c[0].z(), (c[0] + c[1] + c[2] + c[3]).z())));
    }
    return low;
  }

  // The box the correction stays in over [ta, tb] and its top speeds there: linear between its
  // samples and held beyond them, it lies within the range of the samples from the one at or
  // before ta to the one at or after tb, and moves along the pieces between those. Zero when
  // there is none.
  CorrectionBounds correction_bounds(double ta, double tb) const {
    CorrectionBounds out;
    if (index_->range.empty()) return out;
    const auto& c = *correction_;
    const auto [k0, k1] = knots(std::floor(ta / c.dt), std::ceil(tb / c.dt), c.values.size() - 1);
    // Entries k0 .. k1 - 1: their samples and the pieces from them (piece k1, which starts at or
    // after tb, is not in the span); sample k1 on its own.
    const Vec3& last = c.values[k1];
    out.lo = out.hi = last;
    if (k1 == k0) return out;
    const auto [lo, hi] =
        index_->range.over(k0, k1 - 1, [&](std::size_t k) { return CorrectionIndex::entry(c, k); });
    out.lo = out.lo.cwiseMin(Vec3(lo[0], lo[1], lo[2]));
    out.hi = out.hi.cwiseMax(Vec3(hi[0], hi[1], hi[2]));
    out.speed_xy = hi[3], out.speed_z = hi[4];
    return out;
  }

  // An upper bound of the length of the correction's path in plan over [ta, tb] (mm): its pieces'
  // lengths, the end pieces' in proportion (linear within a piece, held beyond the samples). A
  // jerk (one fast piece) adds only its own length: the phase's turn over a span bounded by it
  // stays tight where the top speed over the span would not (PassageGeometry::Span::sweep).
  double correction_length(double ta, double tb) const {
    const auto& len = index_->plan_length;
    if (len.size() < 2 || !(tb > ta)) return 0.0;
    const double dt = correction_->dt, end = static_cast<double>(len.size() - 1);
    // The path length from sample 0 to time t: whole pieces by the prefix sums, the last in
    // proportion.
    auto upto = [&](double t) {
      const double u = std::clamp(t / dt, 0.0, end), k = std::min(std::floor(u), end - 1);
      const auto i = static_cast<std::size_t>(k);
      return len[i] + (u - k) * (len[i + 1] - len[i]);
    };
    // The prefix sums' round-off is relative to the pass's whole length.
    return upto(tb) - upto(ta) + 1e-12 * (1 + len.back());
  }

  // How far, at most, the tabulated nominal centre strays in plan from the line through p along
  // the unit vector (ux, uy), over the whole table: on each cubic piece the distance across the
  // line is a cubic in s whose chord is known at the ends and whose bend is at most a fourth of
  // its largest second derivative, taken at an end (it is linear).
  double plan_deviation(const Vec3& p, double ux, double uy) const {
    auto across = [&](const Vec3& v) { return ux * v.y() - uy * v.x(); };
    double worst = 0;
    for (std::size_t i = 1; i + 2 < knots_.size(); ++i) {
      const Cubic& c = cubic_[i];
      const double f0 = across(c[0] - p), f1 = f0 + across(c[1] + c[2] + c[3]);
      const double d2 =
          std::max(std::abs(2 * across(c[2])), std::abs(2 * across(c[2]) + 6 * across(c[3])));
      worst = std::max(worst, std::max(std::abs(f0), std::abs(f1)) + d2 / 8);
    }
    return worst;
  }

  // The tabulated nominal centre's velocity in plan along the unit (ux, uy) and across it, over
  // the whole table: the least and greatest along, the greatest across in size (mm/s). Exact on
  // each cubic piece, where either component is a quadratic in the piece's parameter.
  struct LineSpeeds {
    double along_lo, along_hi, across_hi;
  };
  LineSpeeds line_speeds(double ux, double uy) const {
    // The range of a1 + 2 a2 s + 3 a3 s^2 over s in [0, 1] (per unit s).
    auto range = [](double a1, double a2, double a3) {
      const double end = a1 + 2 * a2 + 3 * a3;
      double lo = std::min(a1, end), hi = std::max(a1, end);
      if (const double s = a3 != 0 ? -a2 / (3 * a3) : -1; s > 0 && s < 1) {
        const double v = a1 + 2 * a2 * s + 3 * a3 * s * s;
        lo = std::min(lo, v), hi = std::max(hi, v);
      }
      return std::make_pair(lo, hi);
    };
    auto along = [&](const Vec3& v) { return ux * v.x() + uy * v.y(); };
    auto across = [&](const Vec3& v) { return ux * v.y() - uy * v.x(); };
    LineSpeeds out{INFINITY, -INFINITY, 0.0};
    for (std::size_t i = 1; i + 2 < knots_.size(); ++i) {
      const Cubic& c = cubic_[i];
      const auto [a_lo, a_hi] = range(along(c[1]), along(c[2]), along(c[3]));
      const auto [b_lo, b_hi] = range(across(c[1]), across(c[2]), across(c[3]));
      out.along_lo = std::min(out.along_lo, a_lo * inv_dt_);
      out.along_hi = std::max(out.along_hi, a_hi * inv_dt_);
      out.across_hi = std::max(out.across_hi, std::max(-b_lo, b_hi) * inv_dt_);
    }
    return out;
  }

  // How the tabulated nominal height can fall below its tangent at any time, over the whole
  // table: the most its slope falls per second within a cubic (-z'', linear on each, so largest at
  // an end; 0 where every cubic bends up) and the most it jumps at a knot (the cubics meet with a
  // slope off by their interpolation error). Then z(t + h) >= z(t) + (z'(t) - jump) h -
  // (bend + jump / dt) h^2 / 2 either way, where dt the knots' step (at most h / dt + 1 knots lie
  // within h).
  struct Bend {
    double bend, jump;
  };
  Bend z_bend() const {
    Bend out{0.0, 0.0};
    for (std::size_t i = 1; i + 2 < knots_.size(); ++i) {
      const Cubic& c = cubic_[i];
      const double z2 = 2 * c[2].z(), end = z2 + 6 * c[3].z();
      out.bend = std::max(out.bend, -std::min(z2, end) * inv_dt_ * inv_dt_);
      if (i + 3 < knots_.size()) {  // the slope at the cubic's end against the next one's start
        const double left = c[1].z() + z2 + 3 * c[3].z(), right = cubic_[i + 1][1].z();
        out.jump = std::max(out.jump, std::abs(left - right) * inv_dt_);
      }
    }
    // (A margin for the round-off in the coefficients.)
    out.bend = 1.01 * out.bend, out.jump = 1.01 * out.jump + 1e-15;
    out.bend += out.jump * inv_dt_;
    return out;
  }

  // Upper bounds of the nominal centre's horizontal and vertical speed (mm/s): the knots' chords,
  // with a margin for the bend between them.
  std::pair<double, double> top_speed() const {
    double h = 0, v = 0;
    for (std::size_t i = 0; i + 1 < knots_.size(); ++i) {
      const Vec3 d = (knots_[i + 1] - knots_[i]) * inv_dt_;
      h = std::max(h, std::hypot(d.x(), d.y())), v = std::max(v, std::abs(d.z()));
    }
    return {1.05 * h, 1.05 * v};
  }

 private:
  // Sample (or piece) indices k0 <= k1 from times in units of the step, clamped to [0, last].
  static std::pair<std::size_t, std::size_t> knots(double k0, double k1, std::size_t last) {
    const auto top = static_cast<double>(last);
    return {static_cast<std::size_t>(std::clamp(k0, 0.0, top)),
            static_cast<std::size_t>(std::clamp(std::max(k0, k1), 0.0, top))};
  }
  void build(double t_lo, double t_hi, double dt) {
    t0_ = t_lo - 2 * dt;
    inv_dt_ = 1 / dt;
    const auto n = static_cast<std::size_t>(std::ceil((t_hi - t0_) / dt)) + 3;
    knots_.resize(n);
    pieces_end_ = static_cast<double>(n) - 2;
    for (std::size_t i = 0; i < n; ++i) knots_[i] = path_centre(t0_ + static_cast<double>(i) * dt);
    // On [i, i + 1] the cubic through knots i-1 .. i+2 (Lagrange), in powers of s = u - i: three
    // multiply-adds a probe instead of four weights and four scaled knots.
    cubic_.assign(n, Cubic{});
    for (std::size_t i = 1; i + 2 < n; ++i) {
      const Vec3 &m = knots_[i - 1], &a = knots_[i], &b = knots_[i + 1], &c = knots_[i + 2];
      cubic_[i] = {a, -m / 3 - a / 2 + b - c / 6, m / 2 - a + b / 2, (c - m) / 6 + (a - b) / 2};
    }
    accel_xy_ = accel_ = 0;
    for (std::size_t i = 1; i + 2 < n; ++i)
      for (const Vec3& d2 : {Vec3(2 * cubic_[i][2]), Vec3(2 * cubic_[i][2] + 6 * cubic_[i][3])}) {
        accel_xy_ = std::max(accel_xy_, std::hypot(d2.x(), d2.y()) * inv_dt_ * inv_dt_);
        accel_ = std::max(accel_, d2.norm() * inv_dt_ * inv_dt_);
      }
    accel_xy_ = 1.25 * accel_xy_ + 1e-9, accel_ = 1.25 * accel_ + 1e-9;
    jerk_xy_ = 0;
    for (std::size_t i = 1; i + 2 < n; ++i)
      jerk_xy_ = std::max(jerk_xy_, 6 * std::hypot(cubic_[i][3].x(), cubic_[i][3].y()));
    jerk_xy_ = 1.01 * jerk_xy_ * inv_dt_ * inv_dt_ * inv_dt_ + 1e-9;
  }
  // The worst interpolation error at the intervals' midpoints, and where it is.
  struct Midpoint {
    double error = 0, t = 0;
  };
  Midpoint max_midpoint_error() const {
    Midpoint worst;
    for (std::size_t i = 1; i + 2 < knots_.size(); ++i) {
      const double t = t0_ + (static_cast<double>(i) + 0.5) / inv_dt_;
      const double e = (nominal(t) - path_centre(t)).cwiseAbs().maxCoeff();
      if (!(e <= worst.error)) worst = {e, t};  // NaN wins, and stays
      if (std::isnan(e)) break;
    }
    return worst;
  }
  // A path the cubics cannot follow: one that turns a corner (a ringed cutter resting on both
  // walls of a concave surface pivots from one to the other), or leaves the surface. Refused as
  // a scene this evaluator cannot represent, at its plugin key (ParamError).
  // Out of line and cold (passage_setup.cpp): its message would otherwise weigh on the inlining
  // of the table's hot members.
  [[noreturn, gnu::cold, gnu::noinline]] void refuse(const Midpoint& worst) const;

  // What the table holds at t: the nominal centre, or the spindle's axis there; beyond a
  // stretch's ends, its line continued.
  Vec3 path_centre(double t) const {
    if (t < stretch_.lo || t > stretch_.hi) {
      const double end = t < stretch_.lo ? stretch_.lo : stretch_.hi;
      const Vec3 axis = path_->nominal_centre(pass_, end) - path_->runout_offset(pass_, end) +
                        stretch_.v * (t - end);
      return spindle_axis_ ? axis : Vec3(axis + path_->runout_offset(pass_, t));
    }
    return spindle_axis_ ? Vec3(path_->nominal_centre(pass_, t) - path_->runout_offset(pass_, t))
                         : path_->nominal_centre(pass_, t);
  }

  const ToolPath* path_;
  std::size_t pass_;
  const ToolPath::Correction* correction_;
  bool spindle_axis_;
  Stretch stretch_;
  double t0_ = 0, inv_dt_ = 1, accel_xy_ = 0, accel_ = 0, jerk_xy_ = 0;
  std::vector<Vec3> knots_;
  using Cubic = std::array<Vec3, 4>;  // coefficients of s^0 .. s^3
  // The least height of cubic c over s in (sa, sb), given `low`, the least at its ends: at an end
  // or where its slope vanishes, exactly (to round-off).
  static double cubic_lowest(const Cubic& c, double sa, double sb, double low) {
    const double c1 = c[1].z(), c2 = c[2].z(), c3 = c[3].z();
    auto at = [&](double s) {
      if (s > sa && s < sb) low = std::min(low, c[0].z() + s * (c1 + s * (c2 + s * c3)));
    };
    // c1 + 2 c2 s + 3 c3 s^2 = 0
    if (const double a = 3 * c3, disc = c2 * c2 - a * c1; a != 0 && disc >= 0) {
      const double q = -(c2 + std::copysign(std::sqrt(disc), c2));
      if (q != 0) at(c1 / q);
      at(q / a);
    } else if (a == 0 && c2 != 0) {
      at(-c1 / (2 * c2));
    }
    return low;
  }
  std::vector<Cubic> cubic_;
  // The cubic that holds t and t's place s in [0, 1) along it; null beyond the table's cubics.
  // (u >= 1: the truncation is the floor, and floor(u) + 2 < n is u < n - 2; the baseline x86-64
  // has no rounding instruction, and std::floor was a fifth of a probe's centre.)
  const Cubic* piece(double t, double& s) const {
    const double u = (t - t0_) * inv_dt_;
    if (!(u >= 1 && u < pieces_end_)) return nullptr;
    const auto k = static_cast<std::size_t>(u);
    s = u - static_cast<double>(k);
    return &cubic_[k];
  }
  double pieces_end_ = 0;  // the number of knots less 2: the first index past the cubics
  std::shared_ptr<const CorrectionIndex> index_;
};

}  // namespace topomill::plugins
