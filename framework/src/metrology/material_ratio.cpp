#include "metrology/material_ratio.hpp"

#include <algorithm>
#include <cmath>
#include <functional>

namespace topomill {

MaterialRatioCurve::MaterialRatioCurve(const Surface& surface) {
  const auto& z = surface.map.z;
  for (std::size_t i = 0; i < z.size(); ++i)
    if (surface.is_valid(i)) z_.push_back(z[i]);
  if (z_.empty()) return;
  const double mean = surface.mean();
  for (double& h : z_) h -= mean;
  std::sort(z_.begin(), z_.end(), std::greater<double>());
  n_ = static_cast<double>(z_.size());
  // Running integral of the curve up to each knot: level from 0 to mr_1, trapezoids after.
  area_.resize(z_.size());
  area_[0] = z_[0] * mr(0);
  for (std::size_t k = 1; k < z_.size(); ++k)
    area_[k] = area_[k - 1] + 0.5 * (z_[k - 1] + z_[k]) / n_;
}

double MaterialRatioCurve::height(double m) const {
  if (z_.empty()) return 0.0;
  const double u = m * n_ - 0.5;  // knot index, fractional
  if (!(u > 0)) return z_.front();
  if (u >= n_ - 1) return z_.back();
  const auto k = static_cast<std::size_t>(u);
  const double t = u - static_cast<double>(k);
  return z_[k] + t * (z_[k + 1] - z_[k]);
}

double MaterialRatioCurve::ratio(double c) const {
  if (z_.empty() || c > z_.front()) return 0.0;
  if (c <= z_.back()) return 1.0;
  // The last knot at or above c (z_ falls), then along the piece to the next one, below c.
  const auto below = std::upper_bound(z_.begin(), z_.end(), c, std::greater<double>());
  const auto k = static_cast<std::size_t>(below - z_.begin()) - 1;
  const double t = (z_[k] - c) / (z_[k] - z_[k + 1]);
  return mr(k) + t / n_;
}

double MaterialRatioCurve::integral(double m0, double m1) const {
  // F(m): the integral from 0 to m.
  auto F = [&](double m) {
    if (z_.empty() || m <= 0) return 0.0;
    if (m <= mr(0)) return z_.front() * m;
    const double u = m * n_ - 0.5;
    if (u >= n_ - 1) return area_.back() + (m - mr(z_.size() - 1)) * z_.back();
    const auto k = static_cast<std::size_t>(u);
    return area_[k] + 0.5 * (m - mr(k)) * (z_[k] + height(m));
  };
  return F(m1) - F(m0);
}

double MaterialRatioCurve::material_volume(double p) const {
  return integral(0, p) - p * height(p);
}

double MaterialRatioCurve::void_volume(double p) const {
  return (1 - p) * height(p) - integral(p, 1);
}

MaterialRatioCurve::Core MaterialRatioCurve::core() const {
  Core c;
  if (z_.size() < 2) return c;
  constexpr double kWindow = 0.4;
  // The secant's fall h(m) - h(m + 0.4) is linear between the knots of either end: its least
  // value is at one of them, or at m = 0 or 0.6. Ties go to the lowest m.
  auto fall = [&](double m) { return height(m) - height(m + kWindow); };
  double best_m = 0, best = fall(0);
  auto consider = [&](double m) {
    if (!(m >= 0 && m <= 1 - kWindow)) return;
    if (const double f = fall(m); f < best) best = f, best_m = m;
  };
  consider(1 - kWindow);
  for (std::size_t k = 0; k < z_.size(); ++k) consider(mr(k)), consider(mr(k) - kWindow);
  const double slope = best / kWindow;  // height lost per unit of material ratio
  const double top = height(best_m) + slope * best_m, bottom = top - slope;
  c.Sk = top - bottom;
  c.Smr1 = ratio(top);
  c.Smr2 = ratio(bottom);
  // Peaks: the curve above `top` over [0, Smr1]; valleys: below `bottom` over [Smr2, 1].
  const double peaks = integral(0, c.Smr1) - top * c.Smr1;
  const double valleys = bottom * (1 - c.Smr2) - integral(c.Smr2, 1);
  c.Spk = c.Smr1 > 0 ? 2 * std::max(peaks, 0.0) / c.Smr1 : 0.0;
  c.Svk = c.Smr2 < 1 ? 2 * std::max(valleys, 0.0) / (1 - c.Smr2) : 0.0;
  return c;
}

}  // namespace topomill
