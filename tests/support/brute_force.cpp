#include "support/brute_force.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace testing {

namespace {
constexpr double kTwoPi = 2 * M_PI;
double wrap(double a) {
  return a - kTwoPi * std::floor(a / kTwoPi + 0.5);
}

}  // namespace

topomill::Vec3 posture_axis(const topomill::ToolPath& path, std::size_t p, double t) {
  using topomill::Vec3;
  const auto& pass = path.pass(p);
  if (pass.posture.given) {
    // CL data: the points' axes, blended linearly between them by time (each segment's time
    // its length over its speed) and normalised.
    const auto& w = pass.waypoints;
    double t0 = 0;
    for (std::size_t k = 0; k + 1 < w.size(); ++k) {
      const double t1 = t0 + (w[k + 1].centre - w[k].centre).norm() / w[k].speed;
      if (t <= t1 || k + 2 == w.size()) {
        const double u = std::clamp((t - t0) / (t1 - t0), 0.0, 1.0);
        return ((1 - u) * w[k].axis + u * w[k + 1].axis).normalized();
      }
      t0 = t1;
    }
  }
  const double lead = pass.posture.lead, tilt = pass.posture.tilt;
  const Vec3 Z(0, 0, 1);
  Vec3 n = Z, f(pass.dx, pass.dy, 0);
  if (pass.posture.normal) {
    const double y = path.surface_y(p, t), h = 1e-6;
    const double slope = (path.surface().height(y + h) - path.surface().height(y - h)) / (2 * h);
    n = Vec3(0, -slope, 1).normalized();  // z = height(y): the normal leans against the slope
    f = pass.dy != 0 ? Vec3(0, pass.dy, pass.dy * slope).normalized() : Vec3(pass.dx, 0, 0);
  }
  const Vec3 c = f.cross(n);
  return (std::cos(tilt) * (std::cos(lead) * n + std::sin(lead) * f) + std::sin(tilt) * c)
      .normalized();
}

double brute_force_height(const topomill::ToolGeometry& tool, const topomill::ToolPath& path,
                          double x, double y) {
  const double R = tool.radius(), rev = kTwoPi / std::abs(path.spindle_rate());
  const double uncut = path.surface().height(y);
  // Fastest the centre moves in plan: the feed (plus the offset's turn on a curve, within 10 %)
  // and the correction's steepest piece.
  double v =
      1.1 * path.feed_speed() * (1 + path.offset() / std::abs(path.surface().curvature_radius()));
  for (std::size_t p = 0; p < path.passes(); ++p) {
    const auto& c = path.correction_samples(p);
    for (std::size_t k = 0; k + 1 < c.values.size(); ++k)
      v = std::max(v, path.feed_speed() + std::hypot(c.values[k + 1].x() - c.values[k].x(),
                                                     c.values[k + 1].y() - c.values[k].y()) /
                                              c.dt);
  }
  double best = uncut;
  // rho: the ball point's distance from the tool's axis (in plan for a vertical tool).
  auto phase = [&](std::size_t p, int tooth, double t, double& height, double& rho) {
    const topomill::Vec3 c = path.centre(p, t);
    double qx = x - c.x(), qy = y - c.y();
    const double plan = std::hypot(qx, qy);
    if (plan >= R) return rho = plan, height = INFINITY, 0.0;
    height = c.z() - std::sqrt(R * R - plan * plan);
    double alpha = std::asin(plan / R);
    rho = plan;
    if (!path.pass(p).posture.vertical()) {
      // The ball point in the tool frame: x_t the workpiece's X projected normal to the axis,
      // y_t = a x x_t, polar angle from the tip (-a); beyond the tool's equator no edge.
      const topomill::Vec3 a = posture_axis(path, p, t);
      const topomill::Vec3 xt = (topomill::Vec3(1, 0, 0) - a.x() * a).normalized();
      const topomill::Vec3 yt = a.cross(xt), d(qx, qy, height - c.z());
      if (d.dot(a) > 0) return height = INFINITY, 0.0;
      qx = d.dot(xt), qy = d.dot(yt), rho = std::hypot(qx, qy);
      alpha = std::acos(std::clamp(-d.dot(a) / R, -1.0, 1.0));
    }
    const topomill::Vec3 e = tool.edge_point(tooth, alpha, path.spindle_angle(p, t));
    return wrap(std::atan2(e.y(), e.x()) - std::atan2(qy, qx));
  };
  for (std::size_t p = 0; p < path.passes(); ++p) {
    const double t_end = path.pass(p).t_end;
    for (int tooth = 0; tooth < tool.teeth(); ++tooth) {
      // Revolution by revolution, those in which the ball can reach below the uncut surface.
      for (double r0 = 0; r0 < t_end; r0 += rev) {
        const topomill::Vec3 c = path.centre(p, r0 + rev / 2);
        const double reach = std::hypot(x - c.x(), y - c.y()) - v * rev / 2;
        // The centre's lowest point in the revolution: it descends along a slope (2.6 um a
        // revolution at 0.5 deg), so its height at mid revolution is no bound.
        double z_low = c.z();
        for (int k = 0; k <= 64; ++k)
          z_low = std::min(z_low, path.centre(p, r0 + k * rev / 64).z());
        if (reach >= R ||
            z_low - std::sqrt(R * R - std::pow(std::max(reach, 0.0), 2)) >= best + 1e-3)
          continue;
        double t0 = r0, h0 = 0, rho0 = 0, g0 = phase(p, tooth, t0, h0, rho0);
        const double r1 = std::min(r0 + rev, t_end);
        while (t0 < r1) {
          // A fiftieth of a radian of the node's azimuth, a 4096th of a revolution: a step of a
          // fiftieth (1024th) lost a pair of crossings 24 nm below the rest with vibration.
          const double step = std::clamp(0.005 * rho0 / v, 1e-10 * rev, rev / 4096);
          const double t1 = std::min(t0 + step, r1);
          double h1 = 0, rho1 = 0;
          const double g1 = phase(p, tooth, t1, h1, rho1);
          if ((g0 < 0) != (g1 < 0) && std::abs(g1 - g0) < M_PI) {
            double lo = t0, hi = t1, glo = g0;
            for (int it = 0; it < 60; ++it) {
              const double mid = 0.5 * (lo + hi);
              double hm = 0, rm = 0;
              const double gm = phase(p, tooth, mid, hm, rm);
              ((gm < 0) == (glo < 0) ? lo : hi) = mid;
              if ((gm < 0) == (glo < 0)) glo = gm;
            }
            double hr = 0, rr = 0;
            phase(p, tooth, 0.5 * (lo + hi), hr, rr);
            best = std::min(best, hr);
          }
          // The tip is a point of every edge: a node on the line the tip follows is cut by it
          // (the pass's line for a vertical tool; R a off it in plan for a tilted one, where the
          // ball point over the node moves up to 1 / cos(alpha) as fast as the centre, alpha
          // the tilt from the vertical).
          if (path.pass(p).posture.vertical()) {
            // (CL data's passes go anywhere: there the axis over the node is the test itself.)
            const bool on_line =
                !path.pass(p).waypoints.empty() || std::abs(x - path.pass(p).x) < 1e-9;
            if (on_line && rho1 < v * step) best = std::min(best, h1);
          } else {
            const topomill::Vec3 a = posture_axis(path, p, t1), at = path.centre(p, t1);
            const bool along_y = path.pass(p).dy != 0;
            const double across = along_y ? x - (at.x() - R * a.x()) : y - (at.y() - R * a.y());
            if (std::abs(across) < 1e-9 && rho1 < v * step / a.z()) best = std::min(best, h1);
          }
          t0 = t1, g0 = g1, rho0 = rho1;
        }
      }
    }
  }
  return best;
}

}  // namespace testing
