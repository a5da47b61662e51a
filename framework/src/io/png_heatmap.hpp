// PNG heat map of a height map with axes in mm, a colour bar and its unit.
#pragma once

#include <string>

#include "topomill/types.hpp"

namespace topomill {

struct HeatmapLabels {
  std::string x = "x (mm)";
  std::string y = "s (mm)";
  std::string z = "h (um)";
};

// Heights in mm, shown in micrometres; axes start at 0 at the map's first node. Written with
// libpng's simplified API, atomically.
void write_png_heatmap(const std::string& path, const HeightMap& map_mm,
                       const HeatmapLabels& labels = {});

}  // namespace topomill
