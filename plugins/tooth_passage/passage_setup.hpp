// What every node needs from the tool, the path and the knobs, computed once per evaluation: the
// passes cut into straight windows, each with its centre table and the bounds the walks prove
// by (PassageGeometry reads them for one node).
#pragma once

#include <atomic>

#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>
#include <vector>

#include "blend_frame.hpp"
#include "centre_table.hpp"
#include "lag_shape.hpp"
#include "topomill/topography_evaluator.hpp"

namespace topomill::plugins {

constexpr double kTwoPi = 2 * M_PI;

// The guards the bounds are asked with. The lag's slope is bounded over the ball out to
// kRimFraction of its radius: at the rim itself the lag's rate has no bound (lag_shape.hpp).
constexpr double kRimFraction = 0.95;
// A proven inequality is asked with this much room, so that round-off in a bound cannot decide it.
constexpr double kRoom = 1.01;
// A bound's bottom is found to this part of a tooth period: a walk's stop by the bound holds only
// that far past it (PassageGeometry::ends_by_bound).
constexpr double kBottomTolerance = 0.05;
// Two roots of one tooth nearer than this part of a revolution are taken for the same passage:
// where the phase is monotone a tooth's next passage is at least half a revolution on.
constexpr double kSamePassage = 0.25;

// A corrected envelope's floor is trusted to this much less than it reads (round-off in the
// correction's box and the centre's table).
constexpr double kFloorSlack = 1e-9;  // mm

// The tip is a point of every edge, and the phase jumps by pi (not through zero) where the axis
// passes over a node: a node the axis passes within kOnAxis of is cut by the tip then.
constexpr double kOnAxis = 1e-9;  // mm

// To (-pi, pi].
inline double wrap(double a) {
  return a - kTwoPi * std::floor(a / kTwoPi + 0.5);
}

struct PassageSetup {
  // Every tooth of the request's cutter; or, with `edge` >= 0, that tooth alone on the profile a
  // per-edge runout gives it (ToolPath::Runout: its ring `edge` eps_r farther out, `edge` eps_a
  // higher), walked as a one-tooth cutter.
  PassageSetup(const EvaluationRequest& rq, double margin, int iterations, int edge = -1);

  // The spindle axis's segment in plan from a window's start to its end, and how far the centre
  // strays from it (the runout and the correction in plan): nodes farther than R more than that
  // cannot be cut by it.
  struct PlanSegment {
    double ax, ay, bx, by, slack;
    double distance(double x, double y) const;
  };
  // A line in plan that the centre, corrected or not, never strays from by more than `off`
  // (through (x, y) along the unit (ux, uy); off infinite when the window does not move in plan),
  // and the centre's top speed in plan. A node farther from the line than off + v / omega (times
  // the lag's sqrt(1 + Psi_u^2)) keeps G' within (0, 2 omega) all along the window (see gap_rho),
  // whatever the crossing's distance: on a straight pass, every node but those within about
  // v / omega of its line.
  struct PlanLine {
    double x, y, ux, uy, off, speed;
    // An ideal window of a vertical tool on a fixed frame whose centre always moves forwards
    // along the line (every pass the path models make): the least speed along it, and the
    // greatest in plan and across it, exact on the centre's table (PassageGeometry::line_rates).
    // along_lo is 0 for any other window.
    double along_lo = 0, speed_hi = INFINITY, across_hi = INFINITY;
  };
  // A window along the normal over the curvature (or of CL data whose axis turns: `blend`), the
  // frame's turn: the normal turns about X by the change of the surface's inclination under the
  // centre, theta(t) = lambda(t) - lambda(0), and with it the axis and the frame
  // (Q(t) = R_x(-theta) Q(0): docs/model.md). Bounds of |theta'| and |theta''| over the window
  // (rad/s, rad/s^2), from samples with a margin as the centre's acceleration
  // (CentreTable::accel_xy). `on` false: the frame is fixed. A window of cutter-location data
  // whose axis turns (`blend`) turns as BlendFrame says, and rate and accel bound its angular
  // velocity and that velocity's rate.
  struct Turn {
    bool on = false;
    double lambda0 = 0, rate = 0, accel = 0;
    bool blend = false;
    BlendFrame frame;
  };
  // What bounds the floor (PassageGeometry::floor_envelope) over a tail of a window, where its
  // nominal height bends down (a convex arc): then the floor can have two minima (the ball's
  // depth is flat over the correction's box, so the floor follows that height there) and a walk
  // cannot stop where it first rises above the best (PassageGeometry::tail_floor). `on` false:
  // the height never bends down by more than round-off, and the floor has a single minimum.
  // Of the floor's nominal (the spindle axis's with a runout): the line in plan (through (x, y),
  // the unit (ux, uy) from the window's start to its end), the least and greatest speed along it
  // (none known: NaN), how far it strays across it, and its height's Bend (CentreTable::z_bend);
  // and how far the correction's box reaches ahead along the line, behind, and to either side.
  struct FloorTail {
    bool on = false;
    double x = 0, y = 0, ux = 0, uy = 0, along_lo = NAN, along_hi = NAN, off = 0, bend = 0,
           jump = 0, ahead = 0, behind = 0, side = 0;
  };
  // Where a window lies in its pass: [t_lo, t_hi] of pass `pass`, from waypoint segment `segment`
  // (0 on a line pass).
  struct Extent {
    std::size_t pass;
    double t_lo, t_hi;
    std::size_t segment;
  };
  // The walks take a pass in straight stretches, windows: a pass that is one line (every pass
  // the path models make, and cutter-location passes written along one line) is one window,
  // [0, t_end]; a bent pass of cutter-location data is one window per run of collinear segments,
  // [t_k, t_m], whose tables continue its line beyond its ends (Stretch, centre_table.hpp). A
  // window's envelope over a node has a single minimum, as a line pass's; crossings count only
  // within their window, where the table is the pass, and together the windows cover the pass.
  struct Window : Extent {
    Window(const Extent& where, CentreTable table) : Extent(where), centre(std::move(table)) {}
    CentreTable centre;
    // With a runout, the spindle's axis (the centre less the runout): the floor's.
    std::optional<CentreTable> spindle_axis;
    double line = 0;  // parallel: the pass's nominal x (feeding along Y) or y
    PlanSegment segment{};
    PlanLine plan_line{};
    // Whether the tool is tilted, and then its frame's transpose (rows x_t, y_t, a: at t_lo when
    // the frame turns), and where its tip is in plan from the centre (-R a's x and y).
    bool tilted = false;
    Eigen::Matrix3d to_tool = Eigen::Matrix3d::Identity();
    std::pair<double, double> tip_offset{0.0, 0.0};
    Turn turn;
    // The range of the correction over the window and the runout's (zero when ideal): wherever
    // the centre is, it is within [shift_lo, shift_hi] of the spindle axis's nominal one.
    Vec3 shift_lo = Vec3::Zero(), shift_hi = Vec3::Zero();
    double lowest_centre = 0;   // a lower bound of the corrected centre's height
    double lowest_nominal = 0;  // the tabulated nominal centre's least height, exactly
    // The nominal centre's top speeds in plan and along z (mm/s).
    std::pair<double, double> nominal_speed{0.0, 0.0};
    // The distances from the axis [lo, hi] within which a crossing's next of the same tooth is at
    // least half a revolution away: |G' - omega| <= sqrt(1 + Psi_u^2) v / rho anywhere, so G'
    // stays within (0, 2 omega) while the centre, at its top speed v, stays farther than
    // sqrt(1 + Psi_u^2) v / omega and within kRimFraction R (the lag's slope bounded).
    std::pair<double, double> gap_rho{0.0, 0.0};
    FloorTail tail;
  };

  const ToolPath* path;
  const ToolGeometry* tool;
  std::vector<Window> window;
  // Whether every window is a whole pass along one of X or Y (the path's feed axis): then a
  // window's `line` orders them across, which the row sweep's stopping rule needs.
  bool parallel;
  // The cutter over a node (a vertical axis); R is its tube's radius (the ball's), `ringed`
  // whether it has a ring, where the probes read `profile` rather than the sphere.
  CutterProfile profile;
  bool ringed;
  bool windowed;  // whether the contact window (kappa) applies: the ball, its edges unmoved
  double R, R2, omega, speed;  // speed: the slowest feed in plan along a window (mm/s)
  double rev;                  // one spindle revolution, s
  double period;               // one tooth period, s
  double reach;  // the cutter's reach plus the largest correction: farther across, a pass cannot
                 // touch
  double margin, kappa;
  int iterations, teeth;
  bool along_y;  // parallel: the passes feed along Y (else along X)
  // The run's stop request (may be null): a row checks it at every node, since one row can take
  // seconds on a steep face or at a tiny step-over.
  const std::atomic<bool>* stop = nullptr;
  bool stopped() const { return stop && stop->load(std::memory_order_relaxed); }
  std::vector<double> tooth_angle;
  double sin_tip, lag_tip;  // below the tip angle the lag is held (ToolGeometry)
  LagShape lag_shape;       // bounds of the lag's turn, for the phase bounds
  // Whether the centre moves about a smooth path, by the correction (at the tooth period) or the
  // runout (a circle of radius `runout` at the spindle's rate): then the envelope wiggles and has
  // dips anywhere, and the walks bound passages by its floor instead (floor_envelope).
  bool wiggles;
  double runout;       // mm
  double gap_lag = 1;  // sqrt(1 + Psi_u^2) with the lag's slope over the ball to kRimFraction R

  // The windows that can cut (x, y), as (key, window) in the key's order: parallel, those whose
  // line is within `reach`, keyed by that distance across; else those whose segment is within R
  // and its slack, keyed by a lower bound of every height they can cut there (so that, once the
  // node's best height is at or below a key, no window from there on can lower it).
  void near(double x, double y, std::vector<std::pair<double, std::size_t>>& out) const;
  // Whether (x, y) lies on the line window w's tip follows (within kOnAxis).
  bool on_tip_line(std::size_t w, double x, double y) const;
  static Turn turn_bounds(const ToolPath& path, const Extent& w, double pad);
  // theta at t on a turning window, and theta' (the probes need the first only).
  double turn_angle(std::size_t w, double t) const;
  double turn_rate(std::size_t w, double t) const;
  // The tool frame's transpose at t (rows x_t, y_t, a): to_tool turned by theta on a turning
  // window.
  Eigen::Matrix3d to_tool_at(std::size_t w, double t) const;
  // The centre's top horizontal and vertical speed over [ta, tb] on window w.
  std::pair<double, double> top_speed(std::size_t w, double ta, double tb) const;

  // The window's time when its centre is level with (x, y) along the feed (secant steps).
  double level_time(std::size_t w, double x, double y) const;
  // Whether level_time reads y alone (parallel passes along Y), the same all along a row.
  bool level_by_y() const { return parallel && along_y; }
  // When its tip is: the centre level with (x, y) less the tip's offset (the level time for a
  // vertical tool).
  double tip_time(std::size_t w, double x, double y) const;
  // Parallel: the line in plan the tip follows (across the feed): the pass's own for a vertical
  // tool.
  double tip_line(std::size_t w) const {
    const Window& win = window[w];
    return win.line + (along_y ? win.tip_offset.first : win.tip_offset.second);
  }
  // The contact range [lo, hi] of polar angles at that time, as R sin(lo), R sin(hi).
  std::pair<double, double> contact_radii(std::size_t w, double t) const;

 private:
  // The window at `where`: its tables, frame and bounds.
  void add_window(const Extent& where, const std::shared_ptr<const CorrectionIndex>& index);
  // Its plan line and segment, and its gap radii, given the correction's range [lo, hi].
  void bound_window(Window& win, const Vec3& lo, const Vec3& hi);
  // Its FloorTail, on a wiggling path.
  void bound_floor_tail(Window& win) const;
};

}  // namespace topomill::plugins
