// Slot: the tool path. A path model lays out the passes that finish the patch; the core builds
// the ball centre's trajectory over each (docs/model.md Eq. 13-16: R - ap from the uncut surface
// along its normal) and adds the dynamic correction on top.
#pragma once

#include <atomic>
#include <string>
#include <vector>

#include "topomill/model.hpp"
#include "topomill/surface_shape.hpp"
#include "topomill/tool_path.hpp"

namespace topomill {

// What a path model is told about the cut and the patch it must finish.
struct PathRequest {
  const SurfaceShape* surface = nullptr;
  double stepover = 0.0;    // ae (mm)
  double radius = 0.0;      // the ball's R (mm)
  double offset = 0.0;      // R - ap: the ball centre's distance from the uncut surface (mm)
  double feed_speed = 0.0;  // vf (mm/s)
  // How far before and after the patch a pass must run along its feed (mm): a few revolutions'
  // feed and the depth, so that every node is finished by the teeth that pass it.
  double run = 0.0;
  // The patch: its nodes lie at x in [x_lo, x_hi] and y in [y_lo, y_hi]; along the surface it
  // spans the arc [s_lo, s_hi] around s_c, the arc coordinate of the point at region.lambda, whose
  // y is y_c (SurfaceShape::arc_coordinate; y_at_arc inverts it).
  double x_lo = 0.0, x_hi = 0.0, y_lo = 0.0, y_hi = 0.0;
  double s_lo = 0.0, s_hi = 0.0, s_c = 0.0, y_c = 0.0;
  // Set when the user interrupts the run: return early (the run then ends). May be null.
  const std::atomic<bool>* stop = nullptr;
  bool stopped() const { return stop && stop->load(std::memory_order_relaxed); }
};

// A point of cutter-location data as a path model read it: the ball centre, the unit tool axis,
// the speed to the next point (ToolPath::Waypoint), and where it was read (for messages: the
// layout refuses a point off the surface or tilted too far naming its file and line).
struct ClPoint {
  ToolPath::Waypoint at;
  int line = 0;
};

// One pass as a path model lays it out: the surface point under the ball moves in a straight line
// in plan from (x0, y0) to (x1, y1) at the feed speed, along X or along Y; or, when `points` is
// not empty, the ball centre goes through them (cutter-location data, read from `source`).
// `phase` is the spindle angle as it starts (rad).
// `posture` is the tool's over the pass (ToolPath::Posture; vertical by default, `given` with
// points whose axis is not vertical).
struct PassLine {
  double x0 = 0.0, y0 = 0.0, x1 = 0.0, y1 = 0.0;
  double phase = 0.0;
  ToolPath::Posture posture;
  std::vector<ClPoint> points;
  std::string source;
};

class TOPOMILL_API PathModel : public Model {
 public:
  // The passes, in the order the tool steps over. Throws ParamError naming the model's key for a
  // request it cannot serve.
  virtual std::vector<PassLine> passes(const PathRequest& request) const = 0;
};

template <>
struct SlotOf<PathModel> {
  static constexpr Slot value = Slot::Path;
};

// The y whose uncut surface point has arc coordinate s, searched within `span` of y_guess
// (bisection: arc_coordinate grows with y).
TOPOMILL_API double y_at_arc(const SurfaceShape& surface, double s, double y_guess, double span);

}  // namespace topomill
