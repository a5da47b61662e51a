// tooth_passage's frame for cutter-location data whose axis turns (BlendFrame): within a segment
// it is the tool frame of the normalised blend (ToolPath::axis_of), its angular velocity is the
// frame's own rate of turn (a central difference of the frames, computed here), and beyond the
// segment it turns on at the end's rate, continuously and without degenerating.
#include <catch2/catch.hpp>
#include <cmath>

#include "tooth_passage/blend_frame.hpp"

using topomill::Vec3;

namespace {
// Omega from frames at t - h and t + h: [Omega]x = Q' Q^T, Q' by a central difference.
Vec3 omega_by_difference(const topomill::plugins::BlendFrame& f, double t, double h) {
  const Eigen::Matrix3d w = (f.at(t + h) - f.at(t - h)) / (2 * h) * f.at(t).transpose();
  return 0.5 * Vec3(w(2, 1) - w(1, 2), w(0, 2) - w(2, 0), w(1, 0) - w(0, 1));
}
}  // namespace

TEST_CASE("a blended CL frame turns as its axis does, and on at the same rate beyond",
          "[tooth_passage][cl]") {
  // Axes 12 and 20 deg off vertical leaning different ways, 2 ms apart (a fast 5-axis move).
  const Vec3 a0 = Vec3(std::sin(0.21), 0, std::cos(0.21));
  const Vec3 a1 = Vec3(0.2 * std::cos(2.0), 0.2 * std::sin(2.0), 1.0).normalized();
  const double t0 = 0.004, t1 = 0.006;
  const topomill::plugins::BlendFrame f(a0, a1, t0, t1);
  for (double t : {t0, 0.0047, 0.0055, t1}) {
    INFO("t " << t);
    const double s = (t - t0) / (t1 - t0);
    // The frame's definition (docs/model.md, "Tool posture"): x_t the workpiece's X projected
    // normal to the axis, y_t = a x x_t.
    const Vec3 a = (a0 + s * (a1 - a0)).normalized();
    const Vec3 x = (Vec3::UnitX() - a.x() * a).normalized();
    Eigen::Matrix3d want;
    want.col(0) = x, want.col(1) = a.cross(x), want.col(2) = a;
    CHECK((f.at(t) - want).cwiseAbs().maxCoeff() < 1e-15);
  }
  for (double t : {-0.02, 0.0, 0.0039, t0, 0.005, t1, 0.0061, 0.01, 0.03}) {
    INFO("t " << t);
    Vec3 omega;
    const Eigen::Matrix3d q = f.at(t, omega);
    CHECK((q.transpose() * q - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() < 1e-14);
    CHECK(q.determinant() == Approx(1.0).epsilon(1e-14));
    // Its angular velocity is the frames' own turn (at an end, either side's).
    const double h = t == t0 || t == t1 ? 1e-9 : 1e-7;
    const Vec3 seen = omega_by_difference(f, t, h);
    CHECK((omega - seen).norm() < 1e-5 * omega.norm());
    CHECK(omega.norm() > 10);  // rad/s: about 0.3 rad over the 2 ms
  }
  // Beyond each end the rate is the end's, constant.
  Vec3 at_end, far;
  f.at(t1, at_end);
  f.at(0.05, far);
  CHECK((far - at_end).norm() < 1e-12 * at_end.norm());
  f.at(t0, at_end);
  f.at(-0.05, far);
  CHECK((far - at_end).norm() < 1e-12 * at_end.norm());
}
