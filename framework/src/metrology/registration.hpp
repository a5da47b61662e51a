// Registration of a measured surface onto a reference (the simulation): the in-plane move that
// takes the reference onto the measurement, MEAS(R(angle) (p - o) + o + t) = REF(p) + offset,
// with o the reference map's centre. Found in two steps:
//  1. whole nodes: the normalised cross-correlation of the two over every shift (by FFT; means
//     and energies over each shift's overlap), its best among shifts whose overlap holds at least
//     half of the smaller map and, when max_shift > 0, no longer than it;
//  2. below a node (and the angle, when asked): least squares of MEAS(T(p)) - REF(p) - offset
//     over the reference's nodes, Gauss-Newton from step 1, MEAS between its nodes by Keys' cubic
//     (resample.hpp).
// Both surfaces must have the same node spacing (compare resamples them to the coarser first).
// A surface with marks of one period matches itself a period away as well: max_shift below half
// the period removes that ambiguity when the two are known to be roughly in place.
#pragma once

#include "metrology/surface.hpp"

namespace topomill {

struct RegistrationOptions {
  bool rotation = false;   // find the angle too (from angle_guess)
  double angle_guess = 0;  // rad: e.g. the difference of the two lays (Std)
  double max_shift = 0;    // mm; 0: any shift with enough overlap
};

struct Registration {
  double tx = 0, ty = 0;    // mm
  double angle = 0;         // rad
  double offset = 0;        // mm: the measurement's height above the reference's, on the overlap
  double correlation = 0;   // normalised cross-correlation of step 1, -1..1
  double rms = 0;           // mm: of MEAS(T(p)) - REF(p) - offset over the overlap
  std::size_t overlap = 0;  // reference nodes with a measured height
  int iterations = 0;
  bool converged = false;
};

// Throws InputError when no shift leaves the maps overlapping by half of the smaller.
Registration register_surfaces(const Surface& reference, const Surface& measured,
                               const RegistrationOptions& options);

// The measurement in the reference's frame and grid, less the offset (nodes it cannot give are
// invalid).
Surface align(const Surface& measured, const Surface& reference, const Registration& r);

}  // namespace topomill
