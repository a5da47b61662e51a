// Height-map writers: CSV matrix and Gwyddion simple field (.gsf).
#pragma once

#include <string>

#include "topomill/types.hpp"

namespace topomill {

// CSV: one line per grid row (y or s), x fastest, heights in micrometres, 9 significant digits.
void write_csv(const std::string& path, const HeightMap& map_mm);

// Gwyddion simple field: header lines, NUL padding to a 4-byte boundary, float32 little-endian
// heights in metres, x fastest. Lateral sizes in metres.
void write_gsf(const std::string& path, const HeightMap& map_mm, const std::string& title);

}  // namespace topomill
