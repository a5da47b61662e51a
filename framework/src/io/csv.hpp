// CSV height matrices: one line per grid row (y or s), x fastest, heights in micrometres, each
// the shortest text that reads back to the same double. A header of '#' lines carries the grid,
//   # x0_mm = -0.43
//   # dx_mm = 0.00084
// (and y0_mm, dy_mm), with the title and origin; `measure` reads it. A CSV without one (from
// elsewhere) needs the node spacing from the command line.
#pragma once

#include <string>

#include "io/file_info.hpp"
#include "metrology/surface.hpp"

namespace topomill {

// spacing_mm: 0 to take the grid from the header; else the spacing, which must then agree with
// the header's if there is one (exit 2 naming both).
Surface read_csv(const std::string& path, double spacing_mm);
void write_csv(const std::string& path, const HeightMap& map_mm, const FileInfo& info = {});

}  // namespace topomill
