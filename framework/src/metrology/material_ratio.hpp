// The areal material ratio curve (ISO 25178-2's Abbott-Firestone curve) of the valid heights and
// the functional and volume parameters read from it.
//
// The curve: the n heights sorted from the highest down, the k-th (k = 1..n) placed at the
// material ratio mr_k = (k - 1/2) / n, linear between them and level beyond the first and last.
// For heights spread evenly over [a, b] (a surface whose height distribution is uniform), this
// curve is the exact line b - (b - a) mr between mr_1 and mr_n, so the parameters below are exact
// there up to the half-step ends (tests/unit/iso_parameters_test.cpp).
#pragma once

#include <vector>

#include "metrology/surface.hpp"

namespace topomill {

class MaterialRatioCurve {
 public:
  // Heights relative to the mean of the valid points (the mean plane after form removal).
  explicit MaterialRatioCurve(const Surface& surface);

  // Smc(mr): the height at material ratio mr (0..1); inverse of smr.
  double height(double mr) const;
  // Smr(c): the material ratio at height c (the share of the curve at or above c), 0..1.
  double ratio(double c) const;
  // Integral of height(mr) over [m0, m1] (exact for the piecewise-linear curve).
  double integral(double m0, double m1) const;

  // Vm(p): material volume per unit area at ratio p, the integral over [0, p] of height -
  // height(p).
  double material_volume(double p) const;
  // Vv(p): void volume per unit area at ratio p, the integral over [p, 1] of height(p) - height.
  double void_volume(double p) const;

  // ISO 13565-2 / 25178-2's division of the curve: the secant over a 40 % window of material ratio
  // with the least gradient, extended to mr = 0 and 1 (the core); Sk the core's height, Smr1 and
  // Smr2 where the curve meets its top and bottom levels, Spk and Svk the heights of the triangles
  // whose areas equal the peaks' above the core and the valleys' below it.
  struct Core {
    double Sk = 0, Spk = 0, Svk = 0, Smr1 = 0, Smr2 = 1;
  };
  Core core() const;

  std::size_t size() const { return z_.size(); }

 private:
  std::vector<double> z_;     // heights, highest first
  std::vector<double> area_;  // the integral of the curve from mr = 0 to each knot
  double mr(std::size_t k) const { return (static_cast<double>(k) + 0.5) / n_; }
  double n_ = 0;
};

}  // namespace topomill
