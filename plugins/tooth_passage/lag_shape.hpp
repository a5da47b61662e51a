// How the edge's lag Psi turns with the distance rho from the tool's axis, as bounds for the phase
// of a crossing (PassageGeometry::span). Written in u = ln(rho), the lag's part of the phase's
// rate is Psi_u u' and its curvature Psi_uu u'^2 + Psi_u u'': with u' and u'' bounded by the
// centre's speed over rho (and rho^2), both stay finite at the axis for every lag that does
// (constant lead: Psi_u -> 0; loxodrome: Psi_u -> -tan(gamma), the log spiral).
//
// The tool is a plugin, so Psi_u and Psi_uu are sampled, not known in closed form: a table over
// rho keeps, per bin, their largest magnitudes at the bin's ends and middle, widened by 10 %.
// That bounds them wherever they are monotone within a bin (both built-in edges everywhere; a
// bin is R / 4096 wide); the brute-force scan (node_walk.hpp) and the tests check the rest.
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

#include "topomill/tool_geometry.hpp"

namespace topomill::plugins {

class LagShape {
 public:
  struct Bound {
    double k1;  // largest |dPsi / d ln rho|
    double k2;  // largest |d^2 Psi / d (ln rho)^2|
    bool kink;  // the range holds the tip radius, where a held lag makes the phase's rate jump
  };

  explicit LagShape(const ToolGeometry& tool)
      : R_(tool.radius()), tip_(tool.radius() * std::sin(tool.min_polar_angle())) {
    const double width = R_ / kBins;
    const std::size_t size = level(kLevels);
    k1_.resize(kBins), k2_.resize(kBins), k1_.reserve(size), k2_.reserve(size);
    turned_.assign(kBins + 1, 0.0);
    for (std::size_t b = 0; b < kBins; ++b) {
      const double start = static_cast<double>(b) * width;
      const double l0 = lag(tool, start), lm = lag(tool, start + 0.5 * width),
                   l1 = lag(tool, start + width);
      turned_[b + 1] = turned_[b] + 1.1 * (std::abs(lm - l0) + std::abs(l1 - lm));
      double m1 = 0, m2 = 0;
      for (double f : {0.0, 0.5, 1.0}) {
        const double rho = (static_cast<double>(b) + f) * width;
        m1 = std::max(m1, std::abs(slope(tool, rho)));
        // Central difference in ln(rho), a thousandth either side.
        const double up = slope(tool, rho * 1.001), down = slope(tool, rho / 1.001);
        m2 = std::max(m2, std::abs(up - down) / (2 * std::log(1.001)));
      }
      k1_[static_cast<std::size_t>(b)] = 1.1 * m1;
      k2_[static_cast<std::size_t>(b)] = 1.1 * m2;
    }
    // From the axis out: the largest slope and bend up to each bin (slope_to, up_to).
    k1_to_.resize(kBins), k2_to_.resize(kBins);
    for (std::size_t b = 0; b < kBins; ++b)
      k1_to_[b] = std::max(k1_[b], b ? k1_to_[b - 1] : 0.0),
      k2_to_[b] = std::max(k2_[b], b ? k2_to_[b - 1] : 0.0);
    // Range maxima by a sparse table: level L holds the maximum over 2^L bins from each bin,
    // so any range is the maximum of two overlapping entries (span() asks this for every piece).
    for (int L = 1; L < kLevels; ++L) {
      const std::size_t half = std::size_t{1} << (L - 1), base = level(L - 1);
      for (std::size_t b = 0; b + 2 * half <= kBins; ++b)
        k1_.push_back(std::max(k1_[base + b], k1_[base + b + half])),
            k2_.push_back(std::max(k2_[base + b], k2_[base + b + half]));
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

  // The largest |dPsi / d ln rho| from the axis out to rho (over(0, rho)'s k1, by one lookup).
  double slope_to(double rho) const { return rho >= R_ ? INFINITY : k1_to_[bin(rho)]; }
  // over(0, rho)'s k1 and k2 by one lookup each, without the tip's kink (the caller asks that
  // itself where it needs to: PassageGeometry::land).
  Bound up_to(double rho) const {
    if (rho >= R_) return {INFINITY, INFINITY, false};
    const std::size_t b = bin(rho);
    return {k1_to_[b], k2_to_[b], false};
  }

  Bound over(double lo, double hi) const {
    const std::size_t b0 = bin(lo), b1 = bin(hi);
    Bound r{0, 0, tip_ > 0 && lo <= tip_ && tip_ <= hi};
    // 2^L <= n < 2^(L + 1), from the leading zeros (span() asks this for every piece: a loop
    // doubling to n was 1.8 % of the ideal walk's instructions at lambda 0).
    const unsigned long long n = b1 - b0 + 1;
    const int L = 63 - __builtin_clzll(n);
    const std::size_t a = level(L) + b0, b = level(L) + b1 + 1 - (std::size_t{1} << L);
    r.k1 = std::max(k1_[a], k1_[b]), r.k2 = std::max(k2_[a], k2_[b]);
    if (hi >= R_) r.k1 = r.k2 = INFINITY;  // the rim: no bound
    return r;
  }

 private:
  static constexpr std::size_t kBins = 4096;
  static constexpr int kLevels = 13;  // 2^(kLevels - 1) = kBins
  // Where level L of the sparse table starts (level l holds kBins + 1 - 2^l entries).
  static constexpr std::size_t level(int L) {
    return static_cast<std::size_t>(L) * (kBins + 1) - (std::size_t{1} << L) + 1;
  }

  // The bin holding rho, clamped to the table (NaN to the first): truncation is floor where it
  // converts (rho is not negative there). A division, floor and clamp in doubles for each end
  // were 3 % of the ideal walk's instructions at lambda 0.
  std::size_t bin(double rho) const {
    const double x = rho * (kBins / R_);
    if (!(x > 0)) return 0;
    return x < static_cast<double>(kBins - 1) ? static_cast<std::size_t>(x) : kBins - 1;
  }

  double slope(const ToolGeometry& tool, double rho) const {
    const double s = std::min(rho / R_, 1.0), c = std::sqrt(1 - s * s);
    if (s <= 0 || c <= 0) return s <= 0 ? 0.0 : INFINITY;
    return slope(s, c, tool);
  }

  // The lag at rho, held below the tip radius as the edge holds it.
  double lag(const ToolGeometry& tool, double rho) const {
    const double s = std::clamp(std::max(rho, tip_) / R_, 0.0, 1.0), c = std::sqrt(1 - s * s);
    return tool.lag_sc(s, c);
  }

  double R_, tip_;
  std::vector<double> k1_, k2_;        // the sparse table, level 0 (the bins) first
  std::vector<double> k1_to_, k2_to_;  // k1_to_[b]: the largest k1 over bins 0 to b; k2 likewise
  std::vector<double> turned_;         // turned_[b]: the lag's variation summed over bins below b
};

}  // namespace topomill::plugins
