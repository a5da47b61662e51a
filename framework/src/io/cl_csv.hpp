// The tool path as cutter-location data (the `cl` output format, tool_path.csv): each pass's
// ball centre on the spindle's axis, in the CSV form cl_file reads with point = "centre", so a
// path can be taken to a CAM system's viewer, changed, and run again. Read back, a raster over a
// plate is the same path to the bit (tests/integration/cl_file_test.cpp).
#pragma once

#include <string>

#include "io/file_info.hpp"
#include "topomill/tool_path.hpp"

namespace topomill {

// Curved passes are written as chords whose sag from the path is at most `sag` (mm); the feed
// column f (mm/min) is written when the scene's feed alone would not give the path's times.
void write_cl_csv(const std::string& path, const ToolPath& tool_path, const FileInfo& info,
                  double sag = 1e-7);

}  // namespace topomill
