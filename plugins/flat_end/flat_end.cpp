// Flat end mill: a radial end edge over the bottom, and a sharp corner or a small corner radius.
#include "../common/torus_end_mill.hpp"
#include "topomill/plugin.hpp"

namespace topomill::plugins {

class FlatEnd : public TorusEndMill {
 public:
  static Schema schema() {
    Schema s = base_schema();
    s.add_number("corner_radius", "Corner radius r: 0 for a sharp corner")
        .with_unit("mm")
        .at_least(0)
        .with_default(0.0);
    return s;
  }
  explicit FlatEnd(const Params& p) : TorusEndMill(p, p.number("corner_radius")) {}
};

}  // namespace topomill::plugins

TOPOMILL_PLUGIN("flat_end", "0.1.0") {
  registrar.add<topomill::ToolGeometry, topomill::plugins::FlatEnd>(
      "flat_end", "Flat end mill: diameter D, a sharp corner or a small corner radius");
}
