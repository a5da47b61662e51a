// Charts for the studies (ablation bars, sweep lines, accuracy against time) and side-by-side
// heat maps, drawn with cairo and written atomically as PNG.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "topomill/types.hpp"

namespace topomill {

struct Series {
  std::string name;
  std::vector<double> x, y;  // non-finite points (failed cases) are skipped
};

struct ChartLabels {
  std::string title, x, y;
  bool log_x = false, log_y = false;
};

// Lines with markers, one colour per series, and a legend when there is more than one.
void write_line_chart(const std::string& path, const ChartLabels& labels,
                      const std::vector<Series>& series);

// One bar per (label, value); the value is printed on the bar.
void write_bar_chart(const std::string& path, const ChartLabels& labels,
                     const std::vector<std::pair<std::string, double>>& bars);

// Height maps (mm, shown in um about each map's mean) side by side on one colour scale.
void write_heatmap_panels(const std::string& path,
                          const std::vector<std::pair<std::string, HeightMap>>& panels);

}  // namespace topomill
