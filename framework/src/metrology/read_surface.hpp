// Reads a height map in any supported format, chosen by the file's extension.
#pragma once

#include <string>

#include "metrology/surface.hpp"

namespace topomill {

// .x3p, .sdf, .gsf, .csv (which needs `csv_spacing_mm` > 0). Throws InputError otherwise.
Surface read_surface(const std::string& path, double csv_spacing_mm = 0);

}  // namespace topomill
