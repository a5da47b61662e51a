// PNG heat map of a height map: the map in its own coordinates (mm), a colour bar in µm with its
// ticks, and a title.
#pragma once

#include <string>

#include "topomill/types.hpp"

namespace topomill {

struct HeatmapLabels {
  std::string title;
  std::string x = "x (mm)";
  std::string y = "s (mm)";
  std::string z = "h (µm)";
};

// Heights in mm, shown in micrometres; the axes give the nodes' coordinates (grid x0, y0 on).
// Drawn with cairo, written atomically.
void write_png_heatmap(const std::string& path, const HeightMap& map_mm,
                       const HeatmapLabels& labels = {});

}  // namespace topomill
