// ISO 16610-61 areal Gaussian filter: weighting s(r) ~ exp(-pi (r / (alpha lc))^2), alpha =
// sqrt(ln 2 / pi) (sigma = lc / pi * sqrt(ln 2 / 2)), so a wavelength equal to the cut-off passes
// at 50 %. Separable, truncated at +-lc. Edges and invalid points: normalised convolution, i.e. the
// weights of the points present are renormalised to sum to one (no padding, no mirroring).
#pragma once

#include "metrology/surface.hpp"

namespace topomill {

// The mean surface at cut-off `cutoff_mm` (the low-pass part).
Surface gaussian_lowpass(const Surface& surface, double cutoff_mm);

// S-filter: removes wavelengths shorter than lambda_s (the low-pass at lambda_s).
Surface s_filter(const Surface& surface, double lambda_s_mm);
// L-filter: removes wavelengths longer than lambda_c (the surface less its low-pass at lambda_c).
Surface l_filter(const Surface& surface, double lambda_c_mm);

}  // namespace topomill
