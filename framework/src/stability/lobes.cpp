#include "stability/lobes.hpp"

#include <algorithm>
#include <cmath>

namespace topomill::stability {

namespace {

constexpr double kDepthTolerance = 1e-6;  // of depth_max
// A multiplier this close to the real axis (relative to its modulus) is real.
constexpr double kReal = 1e-6;

Onset onset_of(std::complex<double> mu) {
  if (std::abs(mu.imag()) > kReal * std::abs(mu)) return Onset::kHopf;
  return mu.real() < 0 ? Onset::kFlip : Onset::kFold;
}

}  // namespace

const char* onset_name(Onset o) {
  switch (o) {
    case Onset::kFlip:
      return "flip";
    case Onset::kHopf:
      return "hopf";
    case Onset::kFold:
      return "fold";
    case Onset::kNone:
      break;
  }
  return "none";
}

namespace {

double fastest_hz(const LobeSetup& s) {
  double fastest = 0;
  for (const ModalMode& m : s.modes) fastest = std::max(fastest, m.omega / (2 * M_PI));
  return fastest;
}

}  // namespace

double slowest_speed(const LobeSetup& s) {
  return 60 * kStepsPerCycle * fastest_hz(s) / (s.tool->teeth() * double{kMaxAutoSteps});
}

int steps_at(const LobeSetup& s, double rpm) {
  if (s.steps > 0) return s.steps;
  const double fastest = fastest_hz(s);
  const double period = 60 / (rpm * s.tool->teeth());
  const double wanted = std::ceil(kStepsPerCycle * fastest * period);
  return static_cast<int>(std::clamp(wanted, double{kMinSteps}, double{kMaxAutoSteps}));
}

Multiplier multiplier_at(const LobeSetup& s, double rpm, double depth) {
  MillingModel m;
  Engagement e = s.engagement;
  e.depth = depth;
  m.elements = cutting_elements(*s.tool, e, s.elements_per_mm);
  m.teeth = s.tool->teeth();
  m.feed_azimuth = e.feed_azimuth;
  m.sense = s.sense;
  m.k = s.k;
  m.modes = s.modes;
  std::vector<Eigen::Matrix3d> averages;
  return dominant_multiplier(milling_system(m, rpm, steps_at(s, rpm), averages));
}

LobePoint critical_depth(const LobeSetup& s, double rpm) {
  LobePoint out;
  out.rpm = rpm;
  out.depth = NAN;
  double stable = 0, unstable = NAN;
  Multiplier mu{};
  for (double depth = s.scan_from * s.depth_max;;
       depth = std::min(depth * s.scan_ratio, s.depth_max)) {
    mu = multiplier_at(s, rpm, depth);
    if (mu.modulus() >= 1) {
      unstable = depth;
      break;
    }
    stable = depth;
    if (depth >= s.depth_max) break;
  }
  if (std::isnan(unstable)) return out;
  while (unstable - stable > kDepthTolerance * s.depth_max) {
    const double mid = 0.5 * (stable + unstable);
    const Multiplier m = multiplier_at(s, rpm, mid);
    if (m.modulus() >= 1)
      unstable = mid, mu = m;
    else
      stable = mid;
  }
  out.depth = 0.5 * (stable + unstable);
  out.multiplier = mu.value;
  out.onset = onset_of(mu.value);
  return out;
}

}  // namespace topomill::stability
