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
  double start = 0.0;  // the spindle angle when the first pass starts (rad)
  double shift = 0.0;  // added for each pass after it (rad)

  static void add_keys(Schema& s) {
    s.add_number("start_angle", "Spindle angle of the first tooth when the first pass starts")
        .with_unit("deg")
        .with_default(0.0);
    s.add_number("phase_shift", "Spindle phase difference between adjacent passes (paper: 0)")
        .with_unit("deg")
        .with_default(0.0);
  }
  explicit PassPhase(const Params& p)
      : start(p.number("start_angle") * M_PI / 180), shift(p.number("phase_shift") * M_PI / 180) {}
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
// backwards where reversed(k) says so: it starts at the far end. Pass phases count from the
// first pass laid out, whichever way it feeds.
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
      const double angle = phase.start + static_cast<double>(k - k_lo) * phase.shift;
      if (reversed(k))
        add(x, y_last, x, y_first, angle);
      else
        add(x, y_first, x, y_last, angle);
    }
  } else {
    const long k_lo = static_cast<long>(std::floor((rq.s_lo - rq.s_c) / ae)) - 1;
    const long k_hi = static_cast<long>(std::ceil((rq.s_hi - rq.s_c) / ae)) + 1;
    const double span_k = (static_cast<double>(k_hi - k_lo) + 2) * ae;
    const double x_first = rq.x_lo - rq.run, x_last = rq.x_hi + rq.run;
    // Up to 1e7 bisections: many seconds, so a stop request is looked at.
    for (long k = k_lo; k <= k_hi && !((k & 1023) == 0 && rq.stopped()); ++k) {
      const double y = y_at_arc(*rq.surface, rq.s_c + static_cast<double>(k) * ae, rq.y_c, span_k);
      const double angle = phase.start + static_cast<double>(k - k_lo) * phase.shift;
      if (reversed(k))
        add(x_last, y, x_first, y, angle);
      else
        add(x_first, y, x_last, y, angle);
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
