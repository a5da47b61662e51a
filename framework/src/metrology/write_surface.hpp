// Writes a processed surface in the format its file name's extension names (the formats
// read_surface reads), for `measure --out` and `compare`'s difference map.
#pragma once

#include <string>

#include "metrology/surface.hpp"

namespace topomill {

// Throws InputError naming `option` unless the extension is .x3p, .gsf, .sdf or .csv.
void check_surface_format(const std::string& path, const std::string& option);

// Atomically. Missing points survive only in .x3p (its valid.bin); a surface with any is refused
// in the other formats (InputError naming `option`), which have no way to mark them.
void write_surface(const std::string& path, const Surface& surface, const std::string& option,
                   const std::string& description);

}  // namespace topomill
