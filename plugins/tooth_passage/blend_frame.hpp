// The tool frame of one segment of cutter-location data whose axis turns: between its points
// (times t0, t1) the axis is the normalised blend a(s) = (a0 + s (a1 - a0)) / |...|, s = (t - t0)
// / (t1 - t0) (ToolPath::axis_of), and the frame is ToolPath::frame_of(a): x_t the workpiece's X
// projected normal to a, y_t = a x x_t. Its angular velocity Omega (Q' = [Omega]x Q) is computed
// from the blend's derivative, for the walks' bounds and rates.
//
// Beyond [t0, t1] the frame goes on turning at the angular velocity it has at the nearer end (a
// rotation at a constant rate): smooth to the first derivative, never degenerate however far the
// walks look, and the segment's own frame wherever crossings count (the window, which is the
// segment). Continuing the blend itself instead would swing the axis towards the blend's
// direction a1 - a0 (a horizontal one, when the points are close in time).
#pragma once

#include <Eigen/Geometry>

#include "topomill/tool_path.hpp"

namespace topomill::plugins {

class BlendFrame {
 public:
  BlendFrame() = default;
  BlendFrame(const Vec3& a0, const Vec3& a1, double t0, double t1)
      : a0_(a0), d_(a1 - a0), t0_(t0), t1_(t1) {
    end_[0] = inside(t0, omega_end_[0]);
    end_[1] = inside(t1, omega_end_[1]);
  }

  // The frame Q(t) (columns x_t, y_t, a) and its angular velocity Omega(t) in the workpiece.
  Eigen::Matrix3d at(double t, Vec3& omega) const {
    if (t >= t0_ && t <= t1_) return inside(t, omega);
    const int e = t < t0_ ? 0 : 1;
    omega = omega_end_[e];
    const double rate = omega.norm(), turn = rate * (t - (e ? t1_ : t0_));
    if (!(rate > 0)) return end_[e];
    return Eigen::AngleAxisd(turn, omega / rate).toRotationMatrix() * end_[e];
  }
  Eigen::Matrix3d at(double t) const {
    Vec3 omega;
    return at(t, omega);
  }

 private:
  // Within the segment: a = m / |m|, m = a0 + s d, so a' = (m' - a (a . m')) / |m| with m' = d s';
  // x = u / |u|, u = X - a_x a, so x' = (u' - x (x . u')) / |u| with u' = -(a_x' a + a_x a');
  // y = a x x. Then [Omega]x = Q' Q^T, whose entries give Omega.
  Eigen::Matrix3d inside(double t, Vec3& omega) const {
    const double s = (t - t0_) / (t1_ - t0_), ds = 1 / (t1_ - t0_);
    const Vec3 m = a0_ + s * d_;
    const double m_len = m.norm();
    const Vec3 a = m / m_len, da = (d_ * ds - a * a.dot(d_ * ds)) / m_len;
    const Vec3 u = Vec3::UnitX() - a.x() * a;
    const double u_len = u.norm();
    const Vec3 x = u / u_len, du = -(da.x() * a + a.x() * da);
    const Vec3 dx = (du - x * x.dot(du)) / u_len;
    const Vec3 y = a.cross(x), dy = da.cross(x) + a.cross(dx);
    Eigen::Matrix3d q, dq;
    q.col(0) = x, q.col(1) = y, q.col(2) = a;
    dq.col(0) = dx, dq.col(1) = dy, dq.col(2) = da;
    const Eigen::Matrix3d w = dq * q.transpose();
    omega = 0.5 * Vec3(w(2, 1) - w(1, 2), w(0, 2) - w(2, 0), w(1, 0) - w(0, 1));
    return q;
  }

  Vec3 a0_ = Vec3::UnitZ(), d_ = Vec3::Zero();
  double t0_ = 0, t1_ = 1;
  Eigen::Matrix3d end_[2];
  Vec3 omega_end_[2];
};

}  // namespace topomill::plugins
