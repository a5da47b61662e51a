// Bull-nose (torus) end mill: a corner of radius r on a cutter of diameter D, the flat bottom
// inside. r = D/2 is the constant-lead ball end, to the bit.
#include "../common/torus_end_mill.hpp"
#include "topomill/plugin.hpp"

namespace topomill::plugins {

class BullNose : public TorusEndMill {
 public:
  static Schema schema() {
    Schema s = base_schema();
    s.add_number("corner_radius", "Corner radius r, up to D/2 (the ball end)")
        .with_unit("mm")
        .above(0)
        .is_required();
    return s;
  }
  explicit BullNose(const Params& p) : TorusEndMill(p, p.number("corner_radius")) {}
};

}  // namespace topomill::plugins

TOPOMILL_PLUGIN("bull_nose", "0.1.0") {
  registrar.add<topomill::ToolGeometry, topomill::plugins::BullNose>(
      "bull_nose", "Bull-nose (torus) end mill: diameter D, corner radius r, constant-lead edge");
}
