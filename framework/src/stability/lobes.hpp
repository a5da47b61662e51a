// Stability lobes: at each spindle speed, the least axial depth at which the regenerative milling
// system (milling_system.hpp) turns unstable, by semi-discretisation, and how it does so: a
// period doubling (flip: the critical Floquet multiplier crosses the unit circle at -1) or a
// secondary Hopf bifurcation (a complex pair crosses it: quasi-periodic chatter).
#pragma once

#include <string>
#include <vector>

#include "stability/milling_system.hpp"

namespace topomill::stability {

struct LobeSetup {
  const ToolGeometry* tool = nullptr;
  Engagement engagement{};  // depth set per trial
  double sense = 1;         // spindle sense: +1 counter-clockwise from above
  ChipCoefficients k{};
  std::vector<ModalMode> modes;
  // Steps per tooth period: `steps` if positive, else at least kMinSteps and kStepsPerCycle per
  // cycle of the fastest mode (at low speed a tooth period holds several: steps_at()).
  int steps = 0;
  double depth_max = 50;    // mm: the deepest looked at
  double scan_from = 1e-3;  // of depth_max: the first depth tried
  double scan_ratio = 1.1;  // each depth tried this much deeper than the last
  double elements_per_mm = 20;
};

enum class Onset { kNone, kFlip, kHopf, kFold };
const char* onset_name(Onset o);

struct LobePoint {
  double rpm = 0;
  double depth = 0;  // mm; NaN when stable up to depth_max
  Onset onset = Onset::kNone;
  std::complex<double> multiplier{};  // the critical multiplier just past the boundary
};

inline constexpr int kMinSteps = 40;
inline constexpr int kStepsPerCycle = 30;
// The automatic steps' ceiling: a slow spindle under a fast mode would ask for millions.
inline constexpr int kMaxAutoSteps = 2000;
// The steps per tooth period used at `rpm`.
int steps_at(const LobeSetup& s, double rpm);
// The slowest speed whose tooth period the automatic steps resolve (kStepsPerCycle per cycle of
// the fastest mode within kMaxAutoSteps): below it a period holds more cycles than that, and the
// analysis is refused.
double slowest_speed(const LobeSetup& s);

// The dominant multiplier at a speed and depth.
Multiplier multiplier_at(const LobeSetup& s, double rpm, double depth);

// The boundary at one speed: depths tried from scan_from depth_max up, each scan_ratio times the
// last, until one is unstable; the step to it halved to 1e-6 of depth_max. An unstable band
// narrower than that ratio (10 %) below the first one found can be missed.
LobePoint critical_depth(const LobeSetup& s, double rpm);

}  // namespace topomill::stability
