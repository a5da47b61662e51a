// ISO 25178-71 surface data files (.sdf): ASCII ("aISO-1.0": key = value lines, '*', the points,
// '*', optional trailer, '*') and binary ("bISO-1.0": an 81-byte little-endian header, then the
// points). Points are x fastest, z = value * Zscale metres.
#pragma once

#include <string>

#include "io/file_info.hpp"
#include "metrology/surface.hpp"

namespace topomill {

Surface read_sdf(const std::string& path);
// Binary, DataType 7 (float64), atomically.
// Binary (bISO-1.0), float64, metres; ManufacID "topomill" and the creation time in both dates
// (the header has no room for more: the scene is named in the x3p, gsf and CSV files).
void write_sdf(const std::string& path, const HeightMap& map_mm, const FileInfo& info = {});

}  // namespace topomill
