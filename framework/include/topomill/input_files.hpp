// Files a model reads besides the scene (cutter-location data, a measured map, a table): a model
// that reads one names it here, and a run lists each in summary.json with a checksum of its
// bytes, so that a resumed sweep or study runs a case again when one of them changed (the
// scene's own time is not enough: the file may change under an unchanged scene).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "topomill/export.hpp"

namespace topomill {

// Call from the model's constructor with the path it read (as opened). Thread-safe.
TOPOMILL_API void record_input_file(const std::string& path);

// The bytes of an input file, bounded: it must be a regular file (a device, a pipe or a
// directory is refused without waiting on it) of at most `max_bytes`, read a chunk at a time
// with a stop request honoured between chunks (Interrupted). Refusals are InputError naming the
// file; `what` says what it was expected to be ("cutter-location data (CSV or APT CL)"). The
// file is recorded (record_input_file).
TOPOMILL_API std::string read_input_file(const std::string& path, std::uint64_t max_bytes,
                                         const std::string& what);

// The host's side: the files recorded since the last clear, in order, each once.
TOPOMILL_API std::vector<std::string> recorded_input_files();
TOPOMILL_API void clear_recorded_input_files();

}  // namespace topomill
