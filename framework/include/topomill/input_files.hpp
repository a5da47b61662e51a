// Files a model reads besides the scene (cutter-location data, a measured map, a table): a model
// that reads one names it here, and a run lists each in summary.json with a checksum of its
// bytes, so that a resumed sweep or study runs a case again when one of them changed (the
// scene's own time is not enough: the file may change under an unchanged scene).
#pragma once

#include <string>
#include <vector>

#include "topomill/export.hpp"

namespace topomill {

// Call from the model's constructor with the path it read (as opened). Thread-safe.
TOPOMILL_API void record_input_file(const std::string& path);

// The host's side: the files recorded since the last clear, in order, each once.
TOPOMILL_API std::vector<std::string> recorded_input_files();
TOPOMILL_API void clear_recorded_input_files();

}  // namespace topomill
