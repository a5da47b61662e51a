// The paper's tool path: one-way passes feeding along +Y over the curvature, stepping along +X.
#include "../common/parallel_passes.hpp"
#include "topomill/plugin.hpp"

TOPOMILL_PLUGIN("raster", "0.1.0") {
  registrar.add<topomill::PathModel, topomill::plugins::OneWay<false>>(
      "raster",
      "One-way passes feeding along +Y over the curvature, stepping along +X (the paper's)");
}
