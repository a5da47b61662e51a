// Milling's regenerative delay system (Insperger and Stepan; Altintas, "Manufacturing
// Automation", ch. 3): the structure's modes driven by the dynamic chip force
//
//   F(t) = D(t) (r(t) - r(t - tau)),   D(t) = sum over cutting elements of
//          -(Kt v + Kr n + Ka a) n^T width,
//
// r the tool's displacement (the sum of each axis's modes), tau the tooth period, n, a the
// element's normal and meridian tangent, v its cutting direction (stepping the edge's motion:
// the force opposes it). Each mode i along axis k obeys q'' + 2 zeta omega q' + omega^2 q =
// (omega^2 / k_i) F_k. D(t) is averaged over each step exactly: every element's arc of cut is cut
// out of the step's and the rest integrated by 3-point Gauss-Legendre (the integrand is a
// trigonometric polynomial of degree 2).
#pragma once

#include <vector>

#include "stability/cutting_elements.hpp"
#include "stability/semi_discretisation.hpp"
#include "topomill/dynamics_model.hpp"
#include "topomill/force_model.hpp"

namespace topomill::stability {

struct MillingModel {
  std::vector<CuttingElement> elements;  // one tooth's
  int teeth = 1;
  double feed_azimuth = 0;
  double sense = 1;  // +1 counter-clockwise from above, -1 clockwise
  ChipCoefficients k{};
  std::vector<ModalMode> modes;
};

// D averaged over each of `steps` steps of the tooth period at `rpm` (3 x 3, N/mm).
std::vector<Eigen::Matrix3d> directional_averages(const MillingModel& m, double rpm, int steps);

// The delay system at `rpm` with `steps` steps per tooth period; its state is each mode's
// displacement (m) and velocity.
DelaySystem milling_system(const MillingModel& m, double rpm, int steps,
                           std::vector<Eigen::Matrix3d>& averages);

}  // namespace topomill::stability
