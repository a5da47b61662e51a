// How the edge's lag Psi turns with the distance rho from the tool's axis, as bounds for the phase
// of a crossing (PassageGeometry::span). Written in u = ln(rho), the lag's part of the phase's
// rate is Psi_u u' and its curvature Psi_uu u'^2 + Psi_u u'': with u' and u'' bounded by the
// centre's speed over rho (and rho^2), both stay finite at the axis for every lag that does
// (constant lead: Psi_u -> 0; loxodrome: Psi_u -> -tan(gamma), the log spiral).
//
// The tool is a plugin, so Psi_u and Psi_uu are sampled, not known in closed form: a table over
// rho keeps, per bin, their largest magnitudes at the bin's ends and middle, widened by 10 %,
// and the largest of those from the axis out to the bin (over()). That bounds them wherever they
// are monotone within a bin (both built-in edges everywhere; a bin is R / 4096 wide); the
// brute-force scan (node_walk.hpp) and the tests check the rest. The third derivative Psi_uuu is
// kept the same way for the direct zone's convexity bound (passage_geometry_lined.cpp,
// bend_rate_to).
//
// At the rim (rho -> R, the ball's equator) the slope has no bound: rho = R sin(alpha) stops
// growing while the lag still turns with alpha. The lag itself stays finite there (a loxodrome's
// is tan(helix) ln tan(alpha / 2)), so the table also keeps how far the lag turns across each
// bin (the same three samples, widened by 10 %), summed: over a short piece next to the rim the
// phase's turn is bounded by the piece's time at the other rates plus that variation, which
// shrinks with the piece (PassageGeometry::Span::jump).
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "cutter_profile.hpp"
#include "topomill/tool_geometry.hpp"

namespace topomill::plugins {

class LagShape {
 public:
  struct Bound {
    double k1;  // largest |dPsi / d ln rho|
    double k2;  // largest |d^2 Psi / d (ln rho)^2|
    bool kink;  // the range holds the tip radius, where a held lag makes the phase's rate jump
                // (the loxodrome's; an end mill's corner starts from its bottom's lag at slope 0)
  };

  // The table runs from the axis out to the profile's reach R (the ball's radius; a ringed
  // cutter's c + r, its slope rho Psi'(alpha) / (r cos alpha): CutterProfile::slope).
  explicit LagShape(const ToolGeometry& tool) : LagShape(tool, CutterProfile(tool)) {}
  LagShape(const ToolGeometry& tool, const CutterProfile& profile)
      : R_(profile.reach()), tip_(profile.tip()), profile_(profile) {
    jumps_ = tip_ > 0 && slope(tool, tip_) != 0;
    const double width = R_ / kBins;
    k1_.resize(kBins), k2_.resize(kBins), k3_.resize(kBins);
    turned_.assign(kBins + 1, 0.0);
    for (std::size_t b = 0; b < kBins; ++b) {
      const double start = static_cast<double>(b) * width;
      const double l0 = lag(tool, start), lm = lag(tool, start + 0.5 * width),
                   l1 = lag(tool, start + width);
      turned_[b + 1] = turned_[b] + 1.1 * (std::abs(lm - l0) + std::abs(l1 - lm));
      double m1 = 0, m2 = 0, m3 = 0;
      for (double f : {0.0, 0.5, 1.0}) {
        const double rho = (static_cast<double>(b) + f) * width, here = slope(tool, rho);
        m1 = std::max(m1, std::abs(here));
        // Central differences in ln(rho), a thousandth either side (the third derivative's
        // round-off is a few ulps of the slope over 1e-6: 1e-9 for the built-in edges).
        const double up = slope(tool, rho * 1.001), down = slope(tool, rho / 1.001);
        const double h = std::log(1.001);
        m2 = std::max(m2, std::abs(up - down) / (2 * h));
        m3 = std::max(m3, std::abs(up - 2 * here + down) / (h * h));
      }
      // Then the largest up to this bin, from the axis out (over()).
      k1_[b] = std::max(1.1 * m1, b ? k1_[b - 1] : 0.0);
      k2_[b] = std::max(1.1 * m2, b ? k2_[b - 1] : 0.0);
      k3_[b] = std::max(1.1 * m3, b ? k3_[b - 1] : 0.0);
    }
  }

  // dPsi / d ln(rho) at rho (zero below the tip radius, where the lag is held).
  double slope(double sin_a, double cos_a, const ToolGeometry& tool) const {
    if (sin_a * R_ < tip_) return 0.0;
    return sin_a / cos_a * tool.lag_slope_sc(sin_a, cos_a);
  }

  // At most how far the lag turns between any two distances within [lo, hi] (infinite where
  // the lag is: then nothing is pruned by it).
  double variation(double lo, double hi) const {
    const double width = R_ / kBins;
    const auto b0 =
        static_cast<std::size_t>(std::clamp(std::floor(lo / width), 0.0, double(kBins)));
    const auto b1 = static_cast<std::size_t>(std::clamp(std::ceil(hi / width), 0.0, double(kBins)));
    const double v = turned_[std::max(b0, b1)] - turned_[std::min(b0, b1)];
    return std::isnan(v) ? INFINITY : v;
  }

  // Bounds over [lo, hi], read from the axis out to hi (one lookup): a tool's lag turns faster
  // away from its tip (both built-in edges: the loxodrome's slope grows from tan(helix) at the
  // tip to twice that at 0.95 R), so the largest up to hi is the range's own there. An edge
  // whose slope falls outwards is bounded more loosely than its range, never too low. (A
  // sparse table of range maxima would give the built-in edges the same bits for more
  // instructions.)
  Bound over(double lo, double hi) const {
    const bool kink = jumps_ && lo <= tip_ && tip_ <= hi;
    if (hi >= R_) return {INFINITY, INFINITY, kink};  // the rim: no bound
    const std::size_t b = bin(hi);
    return {k1_[b], k2_[b], kink};
  }
  // The largest |d^3 Psi / d (ln rho)^3| from the axis out to hi (passage_geometry_lined.cpp's
  // proof; kept out of Bound, which the spans read at every piece), +inf at the rim.
  double bend_rate_to(double hi) const { return hi < R_ ? k3_[bin(hi)] : INFINITY; }
  // The largest |dPsi / d ln rho| from the axis out to rho.
  double slope_to(double rho) const { return over(0.0, rho).k1; }

 private:
  static constexpr std::size_t kBins = 4096;

  // The bin holding rho, clamped to the table (NaN to the first): truncation is floor where it
  // converts (rho is not negative there). A division, floor and clamp in doubles would cost a few
  // per cent of the ideal walk's instructions near the axis, where a range reads two bins.
  std::size_t bin(double rho) const {
    const double x = rho * (kBins / R_);
    if (!(x > 0)) return 0;
    return x < static_cast<double>(kBins - 1) ? static_cast<std::size_t>(x) : kBins - 1;
  }

  double slope(const ToolGeometry& tool, double rho) const {
    if (profile_.ringed()) return rho < R_ ? profile_.slope(tool, rho, profile_.at(rho)) : INFINITY;
    const double s = std::min(rho / R_, 1.0), c = std::sqrt(1 - s * s);
    if (s <= 0 || c <= 0) return s <= 0 ? 0.0 : INFINITY;
    return slope(s, c, tool);
  }

  // The lag at rho, held below the tip radius as the edge holds it.
  double lag(const ToolGeometry& tool, double rho) const {
    if (profile_.ringed()) return profile_.lag(tool, rho, profile_.at(rho));
    const double s = std::clamp(std::max(rho, tip_) / R_, 0.0, 1.0), c = std::sqrt(1 - s * s);
    return tool.lag_sc(s, c);
  }

  double R_, tip_;
  bool jumps_;  // whether the lag's slope jumps at the tip radius (from the held lag's zero)
  CutterProfile profile_;
  // k1_[b]: the largest slope over bins 0 to b; k2_ its first derivative's, k3_ its second's.
  std::vector<double> k1_, k2_, k3_;
  std::vector<double> turned_;  // turned_[b]: the lag's variation summed over bins below b
};

}  // namespace topomill::plugins
