// One-way passes along the cylinder's axis: feeding along +X, stepping along the surface.
#include "../common/parallel_passes.hpp"
#include "topomill/plugin.hpp"

TOPOMILL_PLUGIN("raster_across", "0.1.0") {
  registrar.add<topomill::PathModel, topomill::plugins::OneWay<true>>(
      "raster_across",
      "One-way passes feeding along +X (the cylinder's axis), stepping along the surface by the "
      "arc length ae");
}
