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
  // Vertical dashed lines at these x values, each labelled (e.g. the reference's time).
  std::vector<std::pair<std::string, double>> marks_x;
};

// Lines with markers, one colour per series, and a legend naming each.
void write_line_chart(const std::string& path, const ChartLabels& labels,
                      const std::vector<Series>& series);

// Groups of bars: per group (its label, one value per series), one colour per series, each
// value printed on its bar, a legend naming the series.
void write_bar_chart(const std::string& path, const ChartLabels& labels,
                     const std::vector<std::string>& series,
                     const std::vector<std::pair<std::string, std::vector<double>>>& groups);

// Height maps (mm, shown in µm about each map's mean) side by side on one colour scale, each
// with its axes in mm (its grid's own coordinates).
void write_heatmap_panels(const std::string& path,
                          const std::vector<std::pair<std::string, HeightMap>>& panels,
                          const std::string& x_label = "x (mm)",
                          const std::string& y_label = "s (mm)");

}  // namespace topomill
