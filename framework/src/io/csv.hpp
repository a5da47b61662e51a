// CSV height matrices: one line per grid row (y or s), x fastest, heights in micrometres. CSV
// carries no lateral scale, so reading one needs the node spacing.
#pragma once

#include <string>

#include "metrology/surface.hpp"

namespace topomill {

Surface read_csv(const std::string& path, double spacing_mm);
void write_csv(const std::string& path, const HeightMap& map_mm);

}  // namespace topomill
