#include "ring_rest.hpp"

#include <Eigen/Geometry>

#include <array>
#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

namespace topomill::detail {

namespace {

// The ring is sampled at this many points before the minima are refined. The distance from a
// curve of constant curvature to a circle's points, a trigonometric polynomial of degree 2 in the
// ring's angle, has at most two minima: 32 samples keep each in a bracket of its own.
constexpr int kSamples = 32;
// Brent's minimisation narrows each bracket to this (in the tangent of the half angle, about
// half the angle): the least distance is then off by about 2 c kAngle^2, below 1e-13 mm on a ring
// of 40 mm.
constexpr double kAngle = 3e-8;
constexpr int kMaxIterations = 100;
// The secant method stops where the ring's least distance is within kTolerance of the clearance,
// or its step is below kStep (mm): a surface far from its centre of curvature reads distances to
// round-off of its radius, and a step then only chases that.
constexpr double kTolerance = 1e-13, kStep = 1e-13;
constexpr int kMaxSteps = 60;
// The golden section's share of a bracket, where a parabola's step is refused.
const double kGoldenShare = (3 - std::sqrt(5.0)) / 2;

// Brent's minimisation of f within [a, b] from x: parabolas through the three best points, the
// golden section where a parabola's step is not trusted, to kAngle. x gets the minimum.
template <class F>
double brent(F f, double a, double b, double& x) {
  double fx = f(x), w = x, v = x, fw = fx, fv = fx, d = 0, e = 0;
  for (int it = 0; it < kMaxIterations; ++it) {
    const double m = 0.5 * (a + b);
    if (std::abs(x - m) <= 2 * kAngle - 0.5 * (b - a)) break;
    bool golden = true;
    if (std::abs(e) > kAngle) {
      const double r = (x - w) * (fx - fv);
      double q = (x - v) * (fx - fw), p = (x - v) * q - (x - w) * r;
      q = 2 * (q - r);
      if (q > 0) p = -p;
      q = std::abs(q);
      const double last = e;
      e = d;
      if (std::abs(p) < std::abs(0.5 * q * last) && p > q * (a - x) && p < q * (b - x)) {
        d = p / q;
        const double u = x + d;
        if (u - a < 2 * kAngle || b - u < 2 * kAngle) d = x < m ? kAngle : -kAngle;
        golden = false;
      }
    }
    if (golden) e = (x < m ? b : a) - x, d = kGoldenShare * e;
    const double u = std::abs(d) >= kAngle ? x + d : x + (d > 0 ? kAngle : -kAngle);
    const double fu = f(u);
    if (fu <= fx) {
      (u < x ? b : a) = x;
      v = w, fv = fw, w = x, fw = fx, x = u, fx = fu;
    } else {
      (u < x ? a : b) = u;
      if (fu <= fw || w == x) {
        v = w, fv = fw, w = u, fw = fu;
      } else if (fu <= fv || v == x || v == w) {
        v = u, fv = fu;
      }
    }
  }
  return fx;
}

// A direction in the ring's plane: the cosine and sine of its angle.
struct Turn {
  double c, s;
  // Turned on by the angle whose half has the tangent tau (a rational expression: no sine or
  // cosine in the minimisation's loop, where they would be most of its cost).
  Turn by(double tau) const {
    const double q = 1 / (1 + tau * tau), cd = (1 - tau * tau) * q, sd = 2 * tau * q;
    return {c * cd - s * sd, s * cd + c * sd};
  }
};

// The ring's sample directions, computed once.
const std::array<Turn, kSamples>& samples() {
  static const std::array<Turn, kSamples> table = [] {
    std::array<Turn, kSamples> t{};
    for (int i = 0; i < kSamples; ++i) {
      const double a = 2 * M_PI * i / kSamples;
      t[static_cast<std::size_t>(i)] = {std::cos(a), std::sin(a)};
    }
    return t;
  }();
  return table;
}

// The ring seen along X (the surface is a cylinder along X: only a point's y and z matter): an
// ellipse about the centre with semi-axes c along m, the ring's direction with no X part, and
// c |a_x| along w, at the angle psi from m's end. With a_x = 0 (an axis in the Y-Z plane) it is
// the segment along m, covered twice: the angles 0 and pi are folds, where the two halves meet.
// There the least of the distance over a half can lie next to the fold on both halves, with the
// fold itself a bump between them: every bracket ends at a fold, never straddles one.
class Ring {
 public:
  Ring(const SurfaceShape& surface, const Vec3& axis, double c) : surface_(surface) {
    const double n = std::hypot(axis.y(), axis.z());
    if (!(n > 0)) throw std::runtime_error("a ring about an axis along X has no place");
    my_ = c * axis.z() / n, mz_ = -c * axis.y() / n;
    const double b = c * std::abs(axis.x());
    wy_ = b * axis.y() / n, wz_ = b * axis.z() / n;
  }
  // The least distance with the ring centred at (y, z): over the whole ring the first time, then
  // about the minima found the last time, each followed within a sample's spacing either side
  // short of a fold (the secant's steps move the centre by the tangent plane's error at most, and
  // every point's distance by no more than that).
  double least(double y, double z) {
    y_ = y, z_ = z;
    double low = INFINITY;
    if (minima_.empty()) {
      const auto& table = samples();
      std::array<double, kSamples> f{};
      for (std::size_t i = 0; i < kSamples; ++i) f[i] = distance(table[i]);
      for (std::size_t i = 0; i < kSamples; ++i)
        if (f[i] <= f[(i + kSamples - 1) % kSamples] && f[i] <= f[(i + 1) % kSamples])
          for (const auto& [lo, hi] : {std::pair{-kHalfTan, 0.0}, std::pair{0.0, kHalfTan}}) {
            Turn d = table[i];
            low = std::min(low, refine(d, lo, hi));  // each side of the sample on its own
            minima_.push_back(d);
          }
      return low;
    }
    for (Turn& d : minima_) {
      // Up to a sample's spacing either side, short of the folds (psi = 0 and +-pi), as the
      // tangents of half the angles.
      const double psi = std::atan2(d.s, d.c);
      const double below = d.s >= 0 ? psi : psi + M_PI, above = d.s >= 0 ? M_PI - psi : -psi;
      const double lo = -std::tan(0.5 * std::min(kSpacing, below));
      const double hi = std::tan(0.5 * std::min(kSpacing, above));
      low = std::min(low, refine(d, lo, hi));
    }
    return low;
  }

 private:
  static constexpr double kSpacing = 2 * M_PI / kSamples;  // the samples' (rad)
  // Half a sample's spacing, as the tangent of half the angle.
  const double kHalfTan = std::tan(M_PI / kSamples);
  double distance(const Turn& d) const {
    return surface_.normal_residual(y_ + d.c * my_ + d.s * wy_, z_ + d.c * mz_ + d.s * wz_, 0.0);
  }
  // The least within [lo, hi] (tangents of half the angle from d); d gets its direction.
  double refine(Turn& d, double lo, double hi) const {
    double tau = 0;
    const double low = brent([&](double t) { return distance(d.by(t)); }, lo, hi, tau);
    d = d.by(tau);
    return low;
  }

  const SurfaceShape& surface_;
  double y_ = 0, z_ = 0;
  double my_, mz_, wy_, wz_;  // the ellipse's semi-axes in the Y-Z plane
  std::vector<Turn> minima_;  // the directions of the last minima
};

}  // namespace

double ring_rest(const SurfaceShape& surface, double y, const Vec3& axis, double ring,
                 double clearance) {
  const double lambda = surface.inclination(y), h = surface.height(y);
  const double ny = std::sin(lambda), nz = std::cos(lambda);
  Ring r(surface, axis, ring);
  auto miss = [&](double s) { return r.least(y + s * ny, h + s * nz) - clearance; };
  // From the tangent plane's distance; the first step at slope 1.
  double s0 = clearance + ring * Vec3(0.0, ny, nz).cross(axis).norm(), g0 = miss(s0);
  if (std::abs(g0) <= kTolerance) return s0;
  double s1 = s0 - g0, g1 = miss(s1);
  for (int k = 0; k < kMaxSteps && std::isfinite(g1); ++k) {
    if (std::abs(g1) <= kTolerance || std::abs(s1 - s0) <= kStep) return s1;
    const double slope = (g1 - g0) / (s1 - s0);
    if (!(slope > 0)) break;
    s0 = s1, g0 = g1, s1 -= g1 / slope, g1 = miss(s1);
  }
  throw std::runtime_error(
      "no place found for the cutter's ring over the surface at y = " + std::to_string(y) + " mm");
}

}  // namespace topomill::detail
