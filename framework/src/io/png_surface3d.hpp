// A shaded 3D view of a height map (the paper's figures 9b, 10b and 16 are such views): the
// surface seen from above one corner, lit from the upper left, coloured by height, with its
// vertical exaggeration written on the image.
#pragma once

#include <string>

#include "topomill/types.hpp"

namespace topomill {

// Heights in mm (shown in µm about their mean), lateral axes in mm from the grid's origin.
// Maps above 160 nodes a side are drawn from every k-th node. Written atomically.
void write_png_surface3d(const std::string& path, const HeightMap& map_mm, const std::string& title,
                         const std::string& x_label = "x (mm)",
                         const std::string& y_label = "s (mm)");

}  // namespace topomill
