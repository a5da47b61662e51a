// The areal autocorrelation function (ACF) of a surface and the spatial parameters read from it.
//
// ACF(t) = <z(x) z(x + t)> / <z^2>: heights less the mean of the valid points, each lag's mean
// over the pairs of valid points it holds (the overlap; Gwyddion's normalisation), lags up to half
// the map in each direction (beyond that fewer than a quarter of the points pair up). Computed by
// FFT with enough zero padding that no lag wraps.
#pragma once

#include <cstddef>
#include <vector>

#include "metrology/surface.hpp"

namespace topomill {

class Autocorrelation {
 public:
  explicit Autocorrelation(const Surface& surface);

  // False for a surface without variance (every valid height the same): no ACF.
  bool defined() const { return defined_; }
  // At the lag (tx, ty) in mm, linear between lags; 0 beyond the lags computed.
  double at(double tx, double ty) const;
  // The lag along direction theta (rad from +X towards +Y) at which the ACF first falls to s,
  // linear between steps of a quarter node; +inf when it does not within the lags computed.
  double decay_length(double theta, double s) const;
  // The ACF on its lag grid, (2 hx + 1) x (2 hy + 1) lags centred on zero, for plots.
  HeightMap image() const;
  double max_lag_x() const { return hx_ * dx_; }
  double max_lag_y() const { return hy_ * dy_; }

 private:
  double lag(std::ptrdiff_t a, std::ptrdiff_t b) const;  // lag in nodes, |a| <= hx, |b| <= hy
  std::ptrdiff_t hx_ = 0, hy_ = 0;
  double dx_ = 1, dy_ = 1;
  std::vector<double> acf_;  // (2 hx + 1) x (2 hy + 1), x fastest, lag (0, 0) at the centre
  bool defined_ = false;
};

// ISO 25178-2's Sal (the fastest decay to s, in mm) and Str (fastest over slowest; 0 when some
// direction does not fall to s within the lags: a lay that runs through the map), over 720
// directions, 0.25 deg apart.
struct AcfDecay {
  bool decays = false;  // false: no direction falls to s (a flat map, or one wider than its ACF)
  double Sal = 0, Str = 0;
  double fastest_direction = 0;  // rad, [0, pi)
};
AcfDecay acf_decay(const Autocorrelation& acf, double s);

}  // namespace topomill
