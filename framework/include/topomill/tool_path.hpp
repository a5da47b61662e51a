// The tool-centre trajectory over a cylindrical surface (docs/model.md Eq. 13-16), from the passes
// a path model (path_model.hpp) lays out, plus the dynamic correction TC of Eq. 32-33. Owned by
// the core, read by evaluators.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <memory>
#include <vector>

#include "topomill/export.hpp"
#include "topomill/surface_shape.hpp"
#include "topomill/types.hpp"

namespace topomill {

class TOPOMILL_API ToolPath {
 public:
  // Every pass feeds along Y (the curvature: the paper's raster, forward or back) or every pass
  // along X (across it, along the cylinder's axis); None when some pass is not a straight line
  // along one of them at one speed (cutter-location data: radial, spiral, polylines).
  enum class FeedAxis { Y, X, None };

  // The tool's posture over a pass (docs/model.md, "Tool posture"): lead and tilt (rad), the
  // axis fixed in the workpiece frame (3-axis, a tilted head) or set from the surface normal at
  // the contact point (5-axis). Lead = tilt = 0 fixed is the paper's vertical tool.
  // Cutter-location data (cl_file) gives the axis at each waypoint instead (`given`). The
  // ToolPath sets `turns` where the axis turns over the pass: along the normal on a pass over
  // the curvature, or where the waypoints' axes differ.
  struct Posture {
    double lead = 0.0, tilt = 0.0;
    bool normal = false;
    bool given = false, turns = false;
    bool vertical() const { return !normal && !given && lead == 0 && tilt == 0; }
    // Whether the tool frame is the same all along the pass.
    bool fixed() const { return !turns; }
  };

  // A point of cutter-location data: the ball centre, the unit tool axis there, and the speed
  // (mm/s, along the centre's path) to the next. Between two, the centre moves in a straight
  // line at that speed and the axis turns linearly (normalised).
  struct Waypoint {
    Vec3 centre = Vec3::Zero();
    Vec3 axis = Vec3::UnitZ();
    double speed = 0.0;
  };

  // One pass starts at t = 0 over the surface point (x, y_start) and ends at t_end; that point
  // moves in plan along the unit (dx, dy) at the feed speed vf: (x + vf dx t, y_start + vf dy t)
  // (the paper's feed model: uniform in Y, not along the arc). `phase` is the spindle angle at
  // t = 0 (rad). Passes are along an axis: (0, +-1) or (+-1, 0).
  // A pass from cutter-location data has `waypoints` instead (two at least): the ball centre
  // goes through them from t = 0 (t_end is set from them); x and y_start are then its first
  // centre's x and foot point's y, and (dx, dy) its direction in plan (+-1 or 0) when it is a
  // straight line along X or Y at one speed, level or not (else zero).
  struct Pass {
    double x = 0.0;
    double y_start = 0.0;
    double t_end = 0.0;
    double phase = 0.0;
    double dx = 0.0, dy = 1.0;
    Posture posture;
    std::vector<Waypoint> waypoints;
  };

  // `offset` is R - ap, the distance of the ball centre from the uncut surface along its normal
  // (for a cutter with a ring, r - ap, and set_ring adds the ring's part);
  // `feed_speed` vf in mm/s; `spindle_rate` in rad/s, signed (negative = clockwise from above).
  // Throws std::invalid_argument for a line pass off the axes, or waypoints that do not move.
  ToolPath(std::shared_ptr<const SurfaceShape> surface, double offset, double feed_speed,
           double spindle_rate, std::vector<Pass> passes);

  std::size_t passes() const { return passes_.size(); }
  const Pass& pass(std::size_t p) const { return passes_[p]; }
  double feed_speed() const { return feed_speed_; }
  double spindle_rate() const { return spindle_rate_; }
  double offset() const { return offset_; }
  // A cutter whose tube is centred on a ring c about its axis (tool_geometry.hpp): its centre
  // is put on the normal through the foot point where the ring's nearest point lies r - ap from
  // the surface (its deepest point ap below it). On a plane whose normal is beta from the axis
  // that is c sin(beta) farther out than a ball of the tube's radius; over a curve the ring's
  // nearest point is found (ring_rest.hpp). None by default.
  void set_ring(double c);
  double ring() const { return ring_; }
  const SurfaceShape& surface() const { return *surface_; }

  FeedAxis feed_axis() const { return axis_; }
  // Surface point under the tool centre at time t (its y; x moves likewise). For waypoints, the
  // foot point's y, linear between theirs and held beyond the ends (it sets the inclination the
  // CATW and the force model read; the centre itself is exact).
  double surface_y(std::size_t p, double t) const;
  // Unit feed direction (tangent to the surface along the pass) at time t.
  Vec3 feed_direction(std::size_t p, double t) const;
  // The time the centre reaches waypoint k of pass p (its length over its speed, summed).
  double waypoint_time(std::size_t p, std::size_t k) const { return timing_[p].t[k]; }
  // The feed speed at time t (mm/s): the waypoints' along the centre's path, or vf.
  double speed(std::size_t p, double t) const {
    return passes_[p].waypoints.empty() ? feed_speed_ : passes_[p].waypoints[segment(p, t)].speed;
  }
  // Whether the tool is vertical on every pass (the paper's): then the tool frame is the
  // workpiece frame, and evaluators and the core skip the rotation (and keep their bits).
  bool vertical() const { return vertical_; }
  // The tool axis a (unit, from the tip towards the spindle) at time t.
  Vec3 axis(std::size_t p, double t) const;
  // The tool frame at time t: columns x_t, y_t, a, with x_t the workpiece's +X projected onto
  // the plane normal to a (the spindle angle is measured about a from x_t towards y_t). A tool
  // frame vector v is Q v in the workpiece frame.
  Eigen::Matrix3d tool_frame(std::size_t p, double t) const;
  // The polar angle, from the tool's tip, of the ball point that touches the uncut surface at
  // time t: the angle between a and the surface normal (|lambda| for a vertical tool). The edge
  // points that can cut lie within the CATW's half-width of it.
  double contact_angle(std::size_t p, double t) const;
  // Ideal ball centre K (Eq. 15), moved by the runout.
  Vec3 nominal_centre(std::size_t p, double t) const;
  // Ball centre with the correction of Eq. 32-33 added (linear between correction samples).
  Vec3 centre(std::size_t p, double t) const;
  // The correction alone (zero when uncorrected), so that an evaluator can tabulate the smooth
  // nominal part and add this piecewise-linear part exactly.
  Vec3 correction(std::size_t p, double t) const;
  // The correction of one pass: sampled every `dt` from t = 0 (none when uncorrected), linear
  // between samples (so its extremes over any span are at samples or at the span's ends), held
  // beyond the last. Inline, so that an evaluator's inner loop can call it.
  struct Correction {
    double dt = 0.0;
    std::vector<Vec3> values;
    Vec3 at(double t) const {
      if (values.empty()) return Vec3::Zero();
      const double u = std::max(0.0, t / dt);
      const std::size_t k = static_cast<std::size_t>(u);
      if (k + 1 >= values.size()) return values.back();
      const double w = u - static_cast<double>(k);
      return (1.0 - w) * values[k] + w * values[k + 1];
    }
  };
  const Correction& correction_samples(std::size_t p) const { return corrections_[p]; }
  // Time between the correction's samples of pass p (0 when it has none).
  double correction_step(std::size_t p) const { return corrections_[p].dt; }
  double spindle_angle(std::size_t p, double t) const {
    return passes_[p].phase + spindle_rate_ * t;
  }

  // Radial runout: the tool's axis, and with it the ball centre, `offset` (mm) off the spindle
  // axis in the plane normal to it, in the direction spindle_angle + `angle`: it turns with the
  // spindle. Part of the nominal path (kinematics, not a response to force); none by default.
  // Per-edge runout, as Wang et al. (2023) and most of the literature give it: edge K (0-based)
  // K edge_radial mm farther from the axis and K edge_axial mm higher than edge 0.
  struct Runout {
    double offset = 0.0;
    double angle = 0.0;  // rad, the offset's direction when the spindle angle is 0
    double edge_radial = 0.0, edge_axial = 0.0;
    bool per_edge() const { return edge_radial != 0 || edge_axial != 0; }
  };
  void set_runout(const Runout& r) { runout_ = r; }
  const Runout& runout() const { return runout_; }
  // The runout's part of the nominal centre at t: the offset in its current direction (zero
  // when there is none).
  Vec3 runout_offset(std::size_t p, double t) const;

  // Corrections sampled every `dt` from t = 0 of pass p; beyond the last sample it is held.
  void set_correction(std::size_t p, double dt, std::vector<Vec3> samples);
  bool corrected() const { return corrected_; }
  // Largest |correction| component over all passes (mm): evaluators widen their margins by it.
  double max_correction() const { return max_correction_; }

 private:
  std::shared_ptr<const SurfaceShape> surface_;
  double offset_, feed_speed_, spindle_rate_;
  double ring_ = 0.0;
  // Per pass along X over a curve, its centre's distance from the surface (the foot point and
  // the axis stay put along it); NaN where it is found at each time.
  std::vector<double> ring_rest_;
  // The centre's distance from the surface along the normal at foot y (sin and cos of lambda).
  double ring_distance(std::size_t p, double t, double y, double sl, double cl) const;
  std::vector<Pass> passes_;
  FeedAxis axis_;
  std::vector<Correction> corrections_;
  Runout runout_;
  bool corrected_ = false;
  bool vertical_ = true;
  // Per pass with a fixed posture, its frame (constant over the pass: computed once, since the
  // runout's offset and both evaluators ask for it at every step).
  std::vector<Eigen::Matrix3d> fixed_frame_;
  // The frame of an axis a (columns x_t, y_t, a).
  static Eigen::Matrix3d frame_of(const Vec3& a);
  Vec3 axis_of(std::size_t p, double t) const;
  // Per pass from waypoints: each one's time and foot point's y (empty for a line pass).
  struct Timing {
    std::vector<double> t, foot_y;
    std::vector<Vec3> unit;  // per segment, its direction
  };
  std::vector<Timing> timing_;
  // The waypoint segment of pass p holding t (the first or last beyond the ends), and how far
  // along segment k t is, clamped to [0, 1].
  std::size_t segment(std::size_t p, double t) const;
  double fraction(std::size_t p, std::size_t k, double t) const;
  void set_waypoint_pass(std::size_t p);
  double max_correction_ = 0.0;
};

}  // namespace topomill
