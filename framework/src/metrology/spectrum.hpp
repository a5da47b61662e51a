// The areal power spectral density (PSD) of a surface, the texture direction read from it, and
// the dominant period of the profiles along a direction (the feed and step-over marks).
//
// Heights less their mean (invalid points at the mean), times a 2D Hann window (so that the map's
// edges do not put a cross of leakage along the axes, which would pull the texture direction to
// 0 or 90 deg); P(f) = |DFT|^2 dx dy / sum(w^2), one-sided in fx, in mm^4 (height^2 x area).
#pragma once

#include <complex>
#include <cstddef>
#include <vector>

#include "metrology/surface.hpp"

namespace topomill {

class PowerSpectrum {
 public:
  explicit PowerSpectrum(const Surface& surface);

  // At the frequency (fx, fy) in 1/mm, linear between bins; P(-f) = P(f). 0 beyond Nyquist.
  double at(double fx, double fy) const;
  // ISO 25178-2's angular spectrum: P summed along the ray at angle theta (rad, from +fx towards
  // +fy) from two of the map's frequency steps out (the window's main lobe about zero) to the
  // Nyquist circle.
  double angular(double theta) const;
  // log10 of P over the frequency plane, centred on zero (for plots); fx and fy in 1/mm.
  HeightMap image() const;
  double df_x() const { return 1.0 / (static_cast<double>(nx_) * dx_); }
  double df_y() const { return 1.0 / (static_cast<double>(ny_) * dy_); }

 private:
  double bin(std::ptrdiff_t kx, std::ptrdiff_t ky) const;  // any integer bin, by symmetry
  std::size_t nx_ = 0, ny_ = 0;
  double dx_ = 1, dy_ = 1;
  double lowest_ = 0;          // two frequency steps of the map (the window's main lobe about zero)
  std::vector<double> power_;  // ny rows of nx / 2 + 1
};

// ISO 25178-2's Std: the angle of the angular spectrum's largest value, rad in [0, pi), found over
// 720 directions 0.25 deg apart and refined by a parabola through the best and its neighbours.
// The direction of the marks' waves, so at right angles to the lay (the marks themselves).
double texture_direction(const PowerSpectrum& psd);

// The dominant period (mm) of the profiles along direction theta (rad from +X): a square of the
// map turned to theta (the largest inside it about its centre) sampled at the finer spacing by
// bilinear interpolation, each profile less its mean, Hann-windowed and zero-padded eight-fold, the
// profiles' power summed; the period of its highest peak beyond two of the square's wavelengths,
// refined by a parabola. 0 when the profiles carry no power.
double dominant_period(const Surface& surface, double theta);

}  // namespace topomill
