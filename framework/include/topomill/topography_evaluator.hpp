// Slot: the height map swept by the cutting edges along the (corrected) tool path (Sec. 4).
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <map>
#include <string>

#include "topomill/model.hpp"
#include "topomill/tool_geometry.hpp"
#include "topomill/tool_path.hpp"
#include "topomill/types.hpp"

namespace topomill {

struct EvaluationRequest {
  const ToolGeometry* tool = nullptr;
  const ToolPath* path = nullptr;
  // Half-width kappa of the contact angle range (CATW, Eq. 39-42), rad: at a tool position over a
  // surface point of inclination lambda, edge points with polar angle within |lambda| +- kappa can
  // touch. Evaluators widen it by their own margin (Eq. 43) and clip it to [0, pi/2].
  double kappa = 0.0;
  // Largest |lambda| under the tool along the whole path, rad (for step-size rules).
  double lambda_max = 0.0;
  unsigned threads = 1;
  // Called now and then with the finished fraction in [0, 1]; may be empty.
  std::function<void(double)> progress;
  // Set when the user interrupts the run: return early (the map is then discarded). May be null.
  const std::atomic<bool>* stop = nullptr;
  bool stopped() const { return stop && stop->load(std::memory_order_relaxed); }
};

// Work done, reported in summary.json ("time_steps", "edge_points", "updates", ...).
using WorkCounts = std::map<std::string, std::uint64_t>;

// What evaluate() will cost for a request, estimated before any work, each part with the scene
// key that drives it: a scene too large for memory is refused naming that key, and before a
// run estimated to take over a minute a line says how long and what to turn.
struct EvaluationCost {
  double bytes = 0;         // allocated beyond the map itself (per-thread maps, tables)
  std::string bytes_key;    // e.g. "region.spacing", "cutting.stepover"
  double seconds = 0;       // on one thread; 0 when the evaluator cannot say
  std::string seconds_key;  // e.g. "evaluator.time_step"
};

class TOPOMILL_API TopographyEvaluator : public Model {
 public:
  // Lowers `map` (initialised by the core to the uncut surface) wherever an edge passes below it.
  // The result must not depend on `threads` or on the order of updates.
  virtual void evaluate(const EvaluationRequest& request, HeightMap& map,
                        WorkCounts& counts) const = 0;

  // Whether evaluate() follows a pass with this tool posture (other than vertical: edge points
  // turned by ToolPath::tool_frame). An evaluator must say so: by default only the vertical tool,
  // and the core refuses any other posture for it rather than let an evaluator written for the
  // vertical tool draw a wrong surface.
  virtual bool follows(const ToolPath::Posture& posture) const { return posture.vertical(); }
  // Whether evaluate() follows passes that are not all straight lines along one of X or Y at one
  // speed (ToolPath::feed_axis() None: cutter-location data, radial or spiral passes). By
  // default not, and the core refuses such a path for it.
  virtual bool follows_curves() const { return false; }
  // Whether evaluate() follows this cutter with this runout, at this posture (one that follows()
  // accepts). By default the ball end (ring 0) without per-edge runout at any posture, so that an
  // evaluator written for the ball is never handed another cutter: the core refuses any other
  // for it.
  virtual bool follows_cutter(const ToolGeometry& tool, const ToolPath::Runout& runout,
                              const ToolPath::Posture& posture) const {
    (void)posture;
    return tool.ring() == 0 && !runout.per_edge();
  }

  // The cost of evaluate() for this request (see EvaluationCost); by default unknown (zero).
  virtual EvaluationCost estimate_cost(const EvaluationRequest& request, const Grid& grid) const {
    (void)request, (void)grid;
    return {};
  }
};

template <>
struct SlotOf<TopographyEvaluator> {
  static constexpr Slot value = Slot::Evaluator;
};

}  // namespace topomill
