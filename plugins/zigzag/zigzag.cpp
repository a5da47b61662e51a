// Alternate passes reversed: up- and down-milling side by side, with no return moves.
#include "../common/parallel_passes.hpp"
#include "topomill/plugin.hpp"

namespace topomill::plugins {

class Zigzag : public PathModel {
 public:
  static Schema schema() {
    Schema s;
    s.add_choice("feed_axis", {"y", "x"},
                 "y: passes along Y over the curvature, stepping along X (as raster); x: along X, "
                 "stepping along the surface by the arc length ae (as raster_across)")
        .with_default(std::string("y"));
    s.add_choice("even_passes", {"forward", "reverse"},
                 "Direction of the pass through the patch's centre and of every second pass "
                 "from it: forward (+Y, or +X) or reverse; the others go the other way")
        .with_default(std::string("forward"));
    PassPhase::add_keys(s);
    PassPosture::add_keys(s);
    return s;
  }
  explicit Zigzag(const Params& p)
      : across_(p.string("feed_axis") == "x"),
        even_back_(p.string("even_passes") == "reverse"),
        phase_(p),
        posture_(PassPosture::from(p)) {}

  std::vector<PassLine> passes(const PathRequest& rq) const override {
    return parallel_passes(rq, across_, phase_, posture_,
                           [this](long k) { return (k % 2 != 0) != even_back_; });
  }

 private:
  bool across_, even_back_;
  PassPhase phase_;
  ToolPath::Posture posture_;
};

}  // namespace topomill::plugins

TOPOMILL_PLUGIN("zigzag", "0.1.0") {
  registrar.add<topomill::PathModel, topomill::plugins::Zigzag>(
      "zigzag", "Parallel passes, every second one reversed (up- and down-milling side by side)");
}
