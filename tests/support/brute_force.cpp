#include "support/brute_force.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <vector>

namespace testing {

namespace {
constexpr double kTwoPi = 2 * M_PI;
// A slice is left out when its sphere's lowest stays this far above the lowest crossing found:
// round-off in the bound, which is otherwise strict.
constexpr double kSlack = 1e-9;
// Speeds are bounded with 10 % to spare: the ball centre's turn on a curve and the tool frame's.
constexpr double kSpeedMargin = 1.1;
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

namespace {

// One node's search: the ball over the node, the edge-minus-node azimuth, and the scans.
class NodeSearch {
 public:
  NodeSearch(const topomill::ToolGeometry& tool, const topomill::ToolPath& path, double x, double y)
      : tool_(tool),
        path_(path),
        x_(x),
        y_(y),
        R_(tool.radius()),
        rev_(kTwoPi / std::abs(path.spindle_rate())),
        uncut_(path.surface().height(y)),
        v_(plan_speed(path)),
        speed_(centre_speed(path)),
        best_(uncut_) {}

  double lowest() {
    for (const Revolution& r : revolutions()) {
      if (r.bound >= best_ + kSlack) break;  // sorted: the rest stay above too
      for (int tooth = 0; tooth < tool_.teeth(); ++tooth) scan(r, tooth);
    }
    return best_;
  }

 private:
  // A revolution is cut into slices, each with the lowest the sphere can be over the node in it:
  // with the centre anywhere within what its fastest speed covers in half a slice of where it is
  // at mid slice, the sphere over the node is at least that much lower and nearer.
  static constexpr int kSlices = 1024;
  struct Revolution {
    double bound;  // the lowest of its slices'
    std::size_t pass;
    double start, end;
    std::size_t first;  // its slices' bounds in slices_, from here
  };

  // Fastest the centre moves in plan, for the scan's steps: the feed (plus the offset's turn on a
  // curve, within 10 %) and the correction's steepest piece.
  static double plan_speed(const topomill::ToolPath& path) {
    double v = kSpeedMargin * path.feed_speed() *
               (1 + path.offset() / std::abs(path.surface().curvature_radius()));
    for (std::size_t p = 0; p < path.passes(); ++p) {
      const auto& c = path.correction_samples(p);
      for (std::size_t k = 0; k + 1 < c.values.size(); ++k)
        v = std::max(v, path.feed_speed() + std::hypot(c.values[k + 1].x() - c.values[k].x(),
                                                       c.values[k + 1].y() - c.values[k].y()) /
                                                c.dt);
    }
    return v;
  }

  // Fastest the centre moves in space, for the slices' bounds: the fastest feed along the path
  // (each CL segment has its own; a pass along Y keeps its plan speed, so on a face inclined by
  // lambda it moves 1 / cos(lambda) as fast) on the offset surface, the runout's circle and the
  // correction's steepest chord (it is interpolated linearly between its samples).
  static double centre_speed(const topomill::ToolPath& path) {
    double feed = path.feed_speed(), correction = 0;
    for (std::size_t p = 0; p < path.passes(); ++p) {
      for (const auto& w : path.pass(p).waypoints) feed = std::max(feed, w.speed);
      if (path.pass(p).waypoints.empty() && path.pass(p).dy != 0)
        for (int k = 0; k <= kInclinationSamples; ++k) {
          const double t = path.pass(p).t_end * k / kInclinationSamples;
          const double lambda = path.surface().inclination(path.surface_y(p, t));
          feed = std::max(feed, path.feed_speed() / std::cos(lambda));
        }
      const auto& c = path.correction_samples(p);
      for (std::size_t k = 0; k + 1 < c.values.size(); ++k)
        correction = std::max(correction, (c.values[k + 1] - c.values[k]).norm() / c.dt);
    }
    const double turn = 1 + std::abs(path.offset() / path.surface().curvature_radius());
    return kSpeedMargin *
           (feed * turn + path.runout().offset * std::abs(path.spindle_rate()) + correction);
  }
  // The inclination along a pass, sampled: it varies slowly (a 10 % margin covers the samples).
  static constexpr int kInclinationSamples = 256;

  // Every revolution in which the sphere can reach below the uncut surface, lowest bound first,
  // so that the first crossings found are low and what stays above them is left out.
  std::vector<Revolution> revolutions() {
    std::vector<Revolution> out;
    for (std::size_t p = 0; p < path_.passes(); ++p)
      for (double r0 = 0; r0 < path_.pass(p).t_end; r0 += rev_) {
        Revolution r{INFINITY, p, r0, std::min(r0 + rev_, path_.pass(p).t_end), slices_.size()};
        const topomill::Vec3 c = path_.centre(p, (r.start + r.end) / 2);
        if (std::hypot(x_ - c.x(), y_ - c.y()) - speed_ * (r.end - r.start) / 2 >= R_) continue;
        const double width = (r.end - r.start) / kSlices, moved = speed_ * width / 2;
        for (int k = 0; k < kSlices; ++k) {
          const topomill::Vec3 mid = path_.centre(p, r.start + (k + 0.5) * width);
          const double reach = std::hypot(x_ - mid.x(), y_ - mid.y()) - moved;
          slices_.push_back(reach >= R_
                                ? INFINITY
                                : mid.z() - moved -
                                      std::sqrt(R_ * R_ - std::pow(std::max(reach, 0.0), 2)));
          r.bound = std::min(r.bound, slices_.back());
        }
        if (r.bound < uncut_ + kSlack)
          out.push_back(r);
        else
          slices_.resize(r.first);
      }
    std::sort(out.begin(), out.end(),
              [](const Revolution& a, const Revolution& b) { return a.bound < b.bound; });
    return out;
  }

  // The ball point over the node at t: its height, its distance rho from the tool's axis (in
  // plan for a vertical tool), and the edge's azimuth less the node's.
  double phase(std::size_t p, int tooth, double t, double& height, double& rho) const {
    const topomill::Vec3 c = path_.centre(p, t);
    double qx = x_ - c.x(), qy = y_ - c.y();
    const double plan = std::hypot(qx, qy);
    if (plan >= R_) return rho = plan, height = INFINITY, 0.0;
    height = c.z() - std::sqrt(R_ * R_ - plan * plan);
    double alpha = std::asin(plan / R_);
    rho = plan;
    if (!path_.pass(p).posture.vertical()) {
      // The ball point in the tool frame: x_t the workpiece's X projected normal to the axis,
      // y_t = a x x_t, polar angle from the tip (-a); beyond the tool's equator no edge.
      const topomill::Vec3 a = posture_axis(path_, p, t);
      const topomill::Vec3 xt = (topomill::Vec3(1, 0, 0) - a.x() * a).normalized();
      const topomill::Vec3 yt = a.cross(xt), d(qx, qy, height - c.z());
      if (d.dot(a) > 0) return height = INFINITY, 0.0;
      qx = d.dot(xt), qy = d.dot(yt), rho = std::hypot(qx, qy);
      alpha = std::acos(std::clamp(-d.dot(a) / R_, -1.0, 1.0));
    }
    const topomill::Vec3 e = tool_.edge_point(tooth, alpha, path_.spindle_angle(p, t));
    return wrap(std::atan2(e.y(), e.x()) - std::atan2(qy, qx));
  }

  // One tooth over one revolution, slice by slice: a slice whose sphere stays above the lowest
  // found is left out (any crossing in it would be higher); in the others every sign change of
  // the phase is bisected, and every dip of |phase| between two samples is searched for the pair
  // of crossings a grazing edge makes (closer together than any step).
  void scan(const Revolution& r, int tooth) {
    const double width = (r.end - r.start) / kSlices;
    bool before = false;  // (ta, ga): the sample before t0, in a slice scanned just before
    double ta = 0, ga = 0;
    for (int k = 0; k < kSlices; ++k) {
      if (slices_[r.first + k] >= best_ + kSlack) {
        before = false;
        continue;
      }
      double t0 = r.start + k * width, h0 = 0, rho0 = 0;
      const double t_end = k + 1 == kSlices ? r.end : r.start + (k + 1) * width;
      double g0 = phase(r.pass, tooth, t0, h0, rho0);
      while (t0 < t_end) {
        // A fiftieth of a radian of the node's azimuth, a 4096th of a revolution: a step of a
        // fiftieth (1024th) lost a pair of crossings 24 nm below the rest with vibration.
        const double step = std::clamp(0.005 * rho0 / v_, 1e-10 * rev_, rev_ / 4096);
        const double t1 = std::min(t0 + step, t_end);
        double h1 = 0, rho1 = 0;
        const double g1 = phase(r.pass, tooth, t1, h1, rho1);
        if ((g0 < 0) != (g1 < 0) && std::abs(g1 - g0) < M_PI)
          best_ = std::min(best_, bisect(r.pass, tooth, t0, t1, g0));
        else if (before && dips(ga, g0, g1))
          graze(r.pass, tooth, ta, t1, g0);
        tip(r.pass, t1, step, h1, rho1);
        ta = t0, ga = g0, before = true;
        t0 = t1, g0 = g1, rho0 = rho1;
      }
    }
  }

  // |g| at its smallest at the middle of three samples of one sign, near zero: the edge may
  // have touched the node's azimuth and turned back between them. (Off the ball phase() gives
  // exactly 0, which is no dip.)
  static bool dips(double ga, double gb, double gc) {
    return gb != 0 && (ga < 0) == (gb < 0) && (gb < 0) == (gc < 0) &&
           std::abs(gb) <= std::abs(ga) && std::abs(gb) <= std::abs(gc) && std::abs(gb) < kGraze;
  }
  static constexpr double kGraze = 0.1;  // rad

  // The phase's extreme toward zero in [lo, hi] by golden section; where it passes zero, its two
  // crossings, each bisected.
  void graze(std::size_t p, int tooth, double lo, double hi, double g_mid) {
    const double sense = g_mid < 0 ? -1.0 : 1.0, golden = 0.5 * (std::sqrt(5.0) - 1);
    auto signed_phase = [&](double t) {
      double h = 0, rho = 0;
      return sense * phase(p, tooth, t, h, rho);
    };
    double a = lo, b = hi, c = b - golden * (b - a), d = a + golden * (b - a);
    double fc = signed_phase(c), fd = signed_phase(d);
    for (int it = 0; it < 100 && b - a > 1e-13 * rev_; ++it) {
      if (fc < fd)
        b = d, d = c, fd = fc, c = b - golden * (b - a), fc = signed_phase(c);
      else
        a = c, c = d, fc = fd, d = a + golden * (b - a), fd = signed_phase(d);
    }
    const double t = 0.5 * (a + b);
    if (!(signed_phase(t) < 0)) return;
    best_ = std::min({best_, bisect(p, tooth, lo, t, g_mid), bisect(p, tooth, t, hi, -g_mid)});
  }

  // The crossing's height, its time halved 60 times.
  double bisect(std::size_t p, int tooth, double lo, double hi, double glo) const {
    for (int it = 0; it < 60; ++it) {
      const double mid = 0.5 * (lo + hi);
      double hm = 0, rm = 0;
      const double gm = phase(p, tooth, mid, hm, rm);
      ((gm < 0) == (glo < 0) ? lo : hi) = mid;
      if ((gm < 0) == (glo < 0)) glo = gm;
    }
    double height = 0, rho = 0;
    phase(p, tooth, 0.5 * (lo + hi), height, rho);
    return height;
  }

  // The tip is a point of every edge: a node on the line the tip follows is cut by it (the pass's
  // line for a vertical tool; R a off it in plan for a tilted one, where the ball point over the
  // node moves up to 1 / cos(alpha) as fast as the centre, alpha the tilt from the vertical).
  void tip(std::size_t p, double t, double step, double height, double rho) {
    if (path_.pass(p).posture.vertical()) {
      // (CL data's passes go anywhere: there the axis over the node is the test itself.)
      const bool on_line =
          !path_.pass(p).waypoints.empty() || std::abs(x_ - path_.pass(p).x) < 1e-9;
      if (on_line && rho < v_ * step) best_ = std::min(best_, height);
    } else {
      const topomill::Vec3 a = posture_axis(path_, p, t), at = path_.centre(p, t);
      const bool along_y = path_.pass(p).dy != 0;
      const double across = along_y ? x_ - (at.x() - R_ * a.x()) : y_ - (at.y() - R_ * a.y());
      if (std::abs(across) < 1e-9 && rho < v_ * step / a.z()) best_ = std::min(best_, height);
    }
  }

  const topomill::ToolGeometry& tool_;
  const topomill::ToolPath& path_;
  const double x_, y_, R_, rev_, uncut_, v_, speed_;
  std::vector<double> slices_;
  double best_;
};

}  // namespace

double brute_force_height(const topomill::ToolGeometry& tool, const topomill::ToolPath& path,
                          double x, double y) {
  return NodeSearch(tool, path, x, y).lowest();
}

}  // namespace testing
