// Where ToolPath puts a cutter with a ring over a curved surface: its deepest point ap below the
// surface along the normal, as the ball's. Checked against the closed forms of a vertical
// bull-nose on a convex arc, and against a brute force over the tool's whole lower surface (tube
// and flat bottom) for tilted cutters on both arcs. The arcs are written here, not taken from the
// plugins.
#include <Eigen/Geometry>
#include <catch2/catch.hpp>

#include <cmath>
#include <memory>
#include <vector>

#include "topomill/surface_shape.hpp"
#include "topomill/tool_path.hpp"

namespace {

using topomill::Vec3;

// A circular arc of radius R about (0, -R) (convex, sign +1) or (0, R) (concave, sign -1), its
// top or bottom at the origin.
class Arc : public topomill::SurfaceShape {
 public:
  Arc(double R, int sign) : R_(R), k_(sign) {}
  double height(double y) const override { return k_ * (std::sqrt(R_ * R_ - y * y) - R_); }
  double inclination(double y) const override { return k_ * std::asin(y / R_); }
  double y_at_inclination(double l) const override { return k_ * R_ * std::sin(l); }
  double curvature_radius() const override { return k_ * R_; }
  double normal_residual(double y, double z, double depth) const override {
    return k_ * (std::hypot(y, z + k_ * R_) - R_) + depth;
  }
  double arc_coordinate(double y, double) const override { return y; }
  double y_min() const override { return -R_; }
  double y_max() const override { return R_; }
  // The signed distance of (y, z) from the arc: outside the material positive.
  double signed_distance(double y, double z) const { return normal_residual(y, z, 0.0); }

 private:
  double R_;
  int k_;
};

constexpr double kArc = 50.0, kRing = 3.0, kTube = 2.0, kDepth = 0.3;

// One pass along X over the foot point y (a line pass's posture).
topomill::ToolPath along_x(std::shared_ptr<const Arc> arc, double y, double lead = 0.0,
                           double tilt = 0.0) {
  topomill::ToolPath::Pass pass;
  pass.y_start = y, pass.t_end = 1.0, pass.dx = 1.0, pass.dy = 0.0;
  pass.posture.lead = lead, pass.posture.tilt = tilt;
  topomill::ToolPath path(arc, kTube - kDepth, 1.0, 100.0, {pass});
  path.set_ring(kRing);
  return path;
}

// The deepest point of the tool below the arc (mm), by brute force over its lower surface: the
// tube's lower half (ring angle phi, section angle psi from the lowest point) and the flat bottom
// (radius rho, phi), on a grid that is narrowed three times about its deepest cell.
double deepest(const Arc& arc, const Vec3& centre, const Vec3& axis) {
  const Vec3 e1 = (Vec3::UnitX() - axis.x() * axis).normalized(), e2 = axis.cross(e1);
  auto depth = [&](double phi, double u, bool bottom) {
    const Vec3 out = std::cos(phi) * e1 + std::sin(phi) * e2;
    const Vec3 p =
        bottom ? Vec3(centre + u * kRing * out - kTube * axis)
               : Vec3(centre + (kRing + kTube * std::sin(u)) * out - kTube * std::cos(u) * axis);
    return -arc.signed_distance(p.y(), p.z());
  };
  double best = -INFINITY;
  for (bool bottom : {false, true}) {
    double phi0 = 0, phi1 = 2 * M_PI, u0 = bottom ? 0.0 : -M_PI / 2, u1 = bottom ? 1.0 : M_PI / 2;
    constexpr int kCells = 200;
    for (int level = 0; level < 4; ++level) {
      double at_phi = phi0, at_u = u0, low = -INFINITY;
      for (int i = 0; i <= kCells; ++i)
        for (int j = 0; j <= kCells; ++j) {
          const double phi = phi0 + (phi1 - phi0) * i / kCells, u = u0 + (u1 - u0) * j / kCells;
          if (const double d = depth(phi, u, bottom); d > low) low = d, at_phi = phi, at_u = u;
        }
      best = std::max(best, low);
      const double dphi = 2 * (phi1 - phi0) / kCells, du = 2 * (u1 - u0) / kCells;
      phi0 = at_phi - dphi, phi1 = at_phi + dphi;
      u0 = std::max(bottom ? 0.0 : -M_PI / 2, at_u - du),
      u1 = std::min(bottom ? 1.0 : M_PI / 2, at_u + du);
    }
  }
  return best;
}

}  // namespace

TEST_CASE("a vertical bull-nose rests on a convex arc as its closed form says", "[ring]") {
  const auto arc = std::make_shared<Arc>(kArc, +1);
  const double clearance = kTube - kDepth;
  // Feet across the arc, and densely where the nearest point leaves the flat bottom for the
  // ring's end (y near 2.9): the ring seen along X is a segment covered twice, folded at its
  // ends, and next to a fold the least distance has two minima a bump apart, where a search that
  // stops on the bump is up to a micrometre off at single feet.
  std::vector<double> feet = {0.0, 0.5, -1.0, 3.1, -3.1, 6.0, 20.0, -35.0};
  for (int i = 0; i <= 2000; ++i) feet.push_back(2.8 + 2e-4 * i);
  for (double y : feet) {
    INFO("foot y " << y);
    const topomill::ToolPath path = along_x(arc, y);
    const Vec3 c = path.nominal_centre(0, 0.3);
    const double lambda = std::asin(y / kArc), sl = std::sin(lambda), cl = std::cos(lambda);
    // The centre on the normal through the foot point, R + s from the arc's centre.
    const double k = (c.z() + kArc) / cl;
    CHECK(c.y() == Approx(k * sl).margin(1e-12));
    // While the arc's top lies under the flat bottom, the bottom's point over it is nearest: the
    // centre stays at the clearance's height. Past that the ring's downhill end is nearest:
    // |k n - c sgn(y) e_y| = R + r - ap.
    const double expected = std::abs(k * sl) <= kRing
                                ? (kArc + clearance) / cl
                                : kRing * std::abs(sl) + std::sqrt(std::pow(kArc + clearance, 2) -
                                                                   std::pow(kRing * cl, 2));
    CHECK(k == Approx(expected).epsilon(0).margin(1e-11));
  }
}

TEST_CASE("a cutter with a ring reaches ap below a curved surface, deepest point by brute force",
          "[ring]") {
  struct Case {
    int sign;
    double y, lead, tilt;
  };
  const Case k = GENERATE(Case{+1, 3.1, 0, 0}, Case{+1, -12.0, 15, 10}, Case{+1, 0.0, 0, 25},
                          Case{-1, 2.0, 0, 0}, Case{-1, -8.0, 15, 10}, Case{-1, 0.0, 10, 0});
  INFO((k.sign > 0 ? "convex" : "concave")
       << " arc, foot y " << k.y << ", lead " << k.lead << ", tilt " << k.tilt);
  const auto arc = std::make_shared<Arc>(kArc, k.sign);
  const topomill::ToolPath path = along_x(arc, k.y, k.lead * M_PI / 180, k.tilt * M_PI / 180);
  const Vec3 c = path.nominal_centre(0, 0.4), a = path.axis(0, 0.4);
  CHECK(deepest(*arc, c, a) == Approx(kDepth).epsilon(0).margin(1e-9));
  // The centre lies on the normal through the foot point.
  const double lambda = arc->inclination(k.y);
  const Vec3 off = c - Vec3(c.x(), k.y, arc->height(k.y));
  CHECK(std::abs(off.y() * std::cos(lambda) - off.z() * std::sin(lambda)) < 1e-12);
}

TEST_CASE("the tangent plane would sit a ringed cutter up to 87 um too high on an arc", "[ring]") {
  // docs/cutters.md: a bull-nose of D 10, r 2 (c = 3) on a convex arc of r 50 at ap 0.3 laid by
  // the tangent plane at its foot (its centre c |sin(lambda)| farther out) stands above the place
  // where its deepest point is ap down; most at the foot where the ring's end leaves the top.
  const auto arc = std::make_shared<Arc>(kArc, +1);
  double most = 0;
  for (double y = 0; y <= 6; y += 0.01) {
    const Vec3 c = along_x(arc, y).nominal_centre(0, 0.0);
    const double lambda = std::asin(y / kArc);
    const double tangent =
        arc->height(y) + (kTube - kDepth + kRing * std::sin(lambda)) * std::cos(lambda);
    most = std::max(most, tangent - c.z());
  }
  CHECK(most == Approx(0.087).margin(0.001));
}

TEST_CASE("a ringed cutter's centre moves smoothly across a convex arc", "[ring]") {
  // Where the nearest point leaves the flat bottom for the ring's end (the ring seen along X is a
  // segment, or a thin ellipse under a small tilt, folded there), the least distance over the
  // ring has two minima a bump apart: a search that stops on the bump puts the centre up to a
  // micrometre off at single times. Over a convex arc the centre's height must bend no more than
  // the arc's offset does, about 1 / R (under 0.03 / mm here). (In a concave arc the ring rests
  // on both walls at the bottom and pivots from one to the other there: its centre's path has a
  // corner, as it must.)
  const double tilt = GENERATE(0.0, 2.0);
  INFO("tilt " << tilt);
  constexpr double kR = 60.0, kWide = 8.0, h = 0.002;
  const auto arc = std::make_shared<Arc>(kR, +1);
  topomill::ToolPath::Pass pass;
  pass.y_start = -20, pass.t_end = 40.0, pass.dx = 0.0, pass.dy = 1.0;
  pass.posture.tilt = tilt * M_PI / 180;
  topomill::ToolPath path(arc, kTube - kDepth, 1.0, 100.0, {pass});
  path.set_ring(kWide);
  double worst = 0, at = 0;
  for (double t = h; t + h <= 40; t += h) {
    const double z0 = path.nominal_centre(0, t - h).z(), z1 = path.nominal_centre(0, t).z(),
                 z2 = path.nominal_centre(0, t + h).z();
    if (const double bend = std::abs(z2 - 2 * z1 + z0) / (h * h); bend > worst)
      worst = bend, at = t;
  }
  INFO("most bent at foot y " << -20 + at);
  CHECK(worst < 0.1);
}
