// Gwyddion simple field (.gsf): "Gwyddion Simple Field 1.0", Key = value lines (XRes, YRes
// required; XReal, YReal in metres), 1-4 NUL bytes to a 4-byte boundary, float32 little-endian
// heights in metres, x fastest.
#pragma once

#include <string>

#include "metrology/surface.hpp"

namespace topomill {

Surface read_gsf(const std::string& path);
void write_gsf(const std::string& path, const HeightMap& map_mm, const std::string& title);

}  // namespace topomill
