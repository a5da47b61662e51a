// Gwyddion simple field (.gsf): "Gwyddion Simple Field 1.0", Key = value lines (XRes, YRes
// required; XReal, YReal in metres), 1-4 NUL bytes to a 4-byte boundary, float32 little-endian
// heights in metres, x fastest.
#pragma once

#include <string>

#include "io/file_info.hpp"
#include "metrology/surface.hpp"

namespace topomill {

Surface read_gsf(const std::string& path);
// Gwyddion Simple Field: float32 metres; Title, and Creator, Date and Scene as extra header keys
// (Gwyddion keeps them as the channel's metadata).
void write_gsf(const std::string& path, const HeightMap& map_mm, const FileInfo& info = {});

}  // namespace topomill
