// The library's one exported entry point: registers the model under its name and slot.
#include "topomill/plugin.hpp"
#include "ball_end_worn.hpp"

TOPOMILL_PLUGIN("ball_end_worn", "1.0.0") {
  registrar.add<topomill::ToolGeometry, worn::BallEndWorn>(
      "ball_end_worn", "Ball-end mill with radial flank wear (SDK template)");
}
