#include "stability/cutting_elements.hpp"

#include <algorithm>
#include <cmath>

namespace topomill::stability {

namespace {

constexpr int kMinElements = 16;
// The side edge's elements: each turns the lag by at most this (rad); a straight flute is one.
constexpr double kSideLagStep = M_PI / 360;
constexpr int kBisections = 60;

// The common arc of "faces the feed" and "in the material the last pass left" for an element of
// radius rho whose normal points outwards (sin(alpha) > 0), relative to the feed's azimuth.
bool cut_arc(double rho, const Engagement& e, double& lo, double& hi) {
  const double c = std::clamp(1 - e.stepover / rho, -1.0, 1.0), gamma = std::acos(c);
  if (e.side > 0) {
    lo = std::max(-M_PI / 2, M_PI / 2 - gamma), hi = M_PI / 2;
  } else {
    lo = -M_PI / 2, hi = std::min(M_PI / 2, -M_PI / 2 + gamma);
  }
  return hi > lo;
}

// The polar angle at which the section rises `depth` above its lowest point (alpha = 0), or
// pi/2 where it stays below.
double top_angle(const ToolGeometry& tool, double depth) {
  const double z0 = tool.section(0.0).y();
  if (tool.section(M_PI / 2).y() - z0 <= depth) return M_PI / 2;
  double a = 0, b = M_PI / 2;
  for (int k = 0; k < kBisections; ++k) {
    const double m = 0.5 * (a + b);
    (tool.section(m).y() - z0 <= depth ? a : b) = m;
  }
  return 0.5 * (a + b);
}

}  // namespace

std::vector<CuttingElement> cutting_elements(const ToolGeometry& tool, const Engagement& e,
                                             double per_mm) {
  std::vector<CuttingElement> out;
  auto add = [&](double rho, double psi0, double sin_a, double cos_a, double width) {
    CuttingElement el{psi0, sin_a, cos_a, width, 0, 0};
    if (width > 0 && rho > 0 && sin_a > 0 && cut_arc(rho, e, el.lo, el.hi)) out.push_back(el);
  };
  // The section, from its lowest point to where it leaves the material (or its side).
  const double a0 = std::max(0.0, tool.min_polar_angle()), a1 = top_angle(tool, e.depth);
  if (a1 > a0) {
    const double length = (tool.section(a1) - tool.section(a0)).norm() * M_PI / 2;
    const int n = std::max(kMinElements, static_cast<int>(std::ceil(length * per_mm)));
    for (int k = 0; k < n; ++k) {
      const double lo = a0 + (a1 - a0) * k / n, hi = a0 + (a1 - a0) * (k + 1) / n;
      const double mid = 0.5 * (lo + hi);
      const Vec3 p = tool.edge_point(0, mid, 0.0);
      add(std::hypot(p.x(), p.y()), std::atan2(p.y(), p.x()), std::sin(mid), std::cos(mid),
          (tool.section(hi) - tool.section(lo)).norm());
    }
  }
  // The side edge above the tube's centre plane (an end mill's, a ball end's shank flutes), its
  // lag falling by side_lead() per mm of height. An insert has none.
  const double z0 = tool.section(0.0).y(), top = tool.section(M_PI / 2).y();
  const double side = e.depth - (top - z0);
  if (side > 0 && tool.first_polar_angle() >= 0) {
    const int n =
        std::max(1, static_cast<int>(std::ceil(side * std::abs(tool.side_lead()) / kSideLagStep)));
    const Vec3 p = tool.edge_point(0, M_PI / 2, 0.0);
    const double rho = std::hypot(p.x(), p.y()), psi = std::atan2(p.y(), p.x());
    for (int k = 0; k < n; ++k) {
      const double z = side * (k + 0.5) / n;
      add(rho, psi - tool.side_lead() * z, 1.0, 0.0, side / n);
    }
  }
  return out;
}

}  // namespace topomill::stability
