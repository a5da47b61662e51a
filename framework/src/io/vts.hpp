// VTK XML structured grid (.vts) for ParaView: the height map as a surface, points in mm, with
// the height in micrometres as point data.
#pragma once

#include <string>

#include "topomill/types.hpp"

namespace topomill {

void write_vts(const std::string& path, const HeightMap& map_mm);

}  // namespace topomill
