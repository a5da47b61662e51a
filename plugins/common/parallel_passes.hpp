// What raster, raster_across and zigzag share: parallel passes over the patch, each one's
// direction chosen by the plugin, and their schema's common keys.
#pragma once

#include <cmath>
#include <vector>

#include "topomill/error.hpp"
#include "topomill/params.hpp"
#include "topomill/path_model.hpp"

namespace topomill::plugins {

struct PassPhase {
  double start = 0.0;  // the spindle angle as pass 0 starts (rad)
  double shift = 0.0;  // added for each pass after it (rad)

  // Parallel passes count k on the workpiece (pass 0 through x = 0); CL data's passes count from
  // the file's first.
  enum class Anchor { workpiece, first_point };
  static void add_keys(Schema& s, Anchor anchor = Anchor::workpiece) {
    const bool workpiece = anchor == Anchor::workpiece;
    s.add_number("start_angle",
                 workpiece ? "Spindle angle of the first tooth as pass 0 starts (the pass through "
                             "x = 0; feeding along X, the one through the patch's centre)"
                           : "Spindle angle of the first tooth when the first pass starts")
        .with_unit("deg")
        .with_default(0.0);
    s.add_number("phase_shift", workpiece
                                    ? "Spindle phase added per pass from pass 0: pass k starts at "
                                      "start_angle + k phase_shift (paper: 0)"
                                    : "Spindle phase difference between adjacent passes (paper: 0)")
        .with_unit("deg")
        .with_default(0.0);
  }
  // Each modulo a turn first (fmod is exact, and leaves an angle within a turn as it is), so that
  // k shift stays finite for any k a patch can lay out, whatever the numbers given.
  explicit PassPhase(const Params& p)
      : start(std::fmod(p.number("start_angle"), kTurn) * M_PI / 180),
        shift(std::fmod(p.number("phase_shift"), kTurn) * M_PI / 180) {}
  static constexpr double kTurn = 360.0;  // deg

  // Pass k's spindle angle as it starts, k counted on the workpiece (parallel_passes).
  double at(long k) const { return start + static_cast<double>(k) * shift; }
};

// The tool's posture on every pass (docs/model.md, "Tool posture").
struct PassPosture {
  static void add_keys(Schema& s) {
    s.add_number("lead",
                 "Lead angle: the tool axis leaned forward along each pass's feed (0: vertical, "
                 "or along the normal with posture = normal)")
        .with_unit("deg")
        .at_least(-80)
        .at_most(80)
        .with_default(0.0);
    s.add_number("tilt", "Tilt angle: the tool axis leaned sideways, towards feed x normal")
        .with_unit("deg")
        .at_least(-80)
        .at_most(80)
        .with_default(0.0);
    s.add_choice("posture", {"fixed", "normal"},
                 "fixed: lead and tilt from the vertical, the axis fixed over each pass (3-axis, "
                 "a tilted head); normal: from the surface normal at the contact point (5-axis)")
        .with_default(std::string("fixed"));
  }
  static ToolPath::Posture from(const Params& p) {
    ToolPath::Posture q;
    q.lead = p.number("lead") * M_PI / 180, q.tilt = p.number("tilt") * M_PI / 180;
    q.normal = p.string("posture") == "normal";
    return q;
  }
};

// Parallel passes, the paper's raster: feeding along Y and stepping along X by ae from one
// step-over before the patch to one after, each running `run` past the patch at both ends; or
// (across) feeding along X and stepping along the surface by the arc length ae, centred on the
// patch's centre. Pass k (k = 0 through x = 0, or through the patch's centre across) feeds
// backwards where reversed(k) says so: it starts at the far end. Pass k starts at the spindle
// angle start + k shift: counted from the pass through x = 0 (the workpiece's), not from the first
// the patch lays out, so that a wider patch leaves the phases of the passes it shares alone.
template <class Reversed>
std::vector<PassLine> parallel_passes(const PathRequest& rq, bool across, const PassPhase& phase,
                                      const ToolPath::Posture& posture, Reversed reversed) {
  const double ae = rq.stepover;
  std::vector<PassLine> passes;
  auto add = [&](double x0, double y0, double x1, double y1, double angle) {
    PassLine l;
    l.x0 = x0, l.y0 = y0, l.x1 = x1, l.y1 = y1, l.phase = angle, l.posture = posture;
    passes.push_back(l);
  };
  if (!across) {
    const long k_lo = static_cast<long>(std::floor(rq.x_lo / ae)) - 1;
    const long k_hi = static_cast<long>(std::ceil(rq.x_hi / ae)) + 1;
    const double y_first = rq.y_lo - rq.run, y_last = rq.y_hi + rq.run;
    for (long k = k_lo; k <= k_hi && !((k & 4095) == 0 && rq.stopped()); ++k) {
      const double x = static_cast<double>(k) * ae;
      if (reversed(k))
        add(x, y_last, x, y_first, phase.at(k));
      else
        add(x, y_first, x, y_last, phase.at(k));
    }
  } else {
    const long k_lo = static_cast<long>(std::floor((rq.s_lo - rq.s_c) / ae)) - 1;
    const long k_hi = static_cast<long>(std::ceil((rq.s_hi - rq.s_c) / ae)) + 1;
    const double span_k = (static_cast<double>(k_hi - k_lo) + 2) * ae;
    const double x_first = rq.x_lo - rq.run, x_last = rq.x_hi + rq.run;
    // Up to 1e7 bisections: many seconds, so a stop request is looked at.
    for (long k = k_lo; k <= k_hi && !((k & 1023) == 0 && rq.stopped()); ++k) {
      const double y = y_at_arc(*rq.surface, rq.s_c + static_cast<double>(k) * ae, rq.y_c, span_k);
      if (reversed(k))
        add(x_last, y, x_first, y, phase.at(k));
      else
        add(x_first, y, x_last, y, phase.at(k));
    }
  }
  return passes;
}

// raster (Across = false) and raster_across: every pass forward.
template <bool Across>
class OneWay : public PathModel {
 public:
  static Schema schema() {
    Schema s;
    PassPhase::add_keys(s);
    PassPosture::add_keys(s);
    return s;
  }
  explicit OneWay(const Params& p) : phase_(p), posture_(PassPosture::from(p)) {}

  std::vector<PassLine> passes(const PathRequest& rq) const override {
    return parallel_passes(rq, Across, phase_, posture_, [](long) { return false; });
  }

 private:
  PassPhase phase_;
  ToolPath::Posture posture_;
};

}  // namespace topomill::plugins
