// ISO 25178-72 XML surface files (.x3p): a zip of main.xml, bindata/data.bin (x fastest),
// optional bindata/valid.bin (packed bits, least significant first, 1 = valid) and
// md5checksum.hex. Read with every checksum verified; written with all of them.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "io/file_info.hpp"
#include "metrology/surface.hpp"

namespace topomill {

// Throws InputError naming the file and what is wrong (not a zip, missing entries, bad MD5,
// sizes that do not match, non-finite values).
Surface read_x3p(const std::string& path);

// Float64 data, incremental X and Y axes, absolute Z, metres; atomically. With `valid` (one per
// node, 0 = invalid; empty = all valid) also bindata/valid.bin, invalid points written as 0.
void write_x3p(const std::string& path, const HeightMap& map_mm, const FileInfo& info = {},
               const std::vector<std::uint8_t>& valid = {});

}  // namespace topomill
