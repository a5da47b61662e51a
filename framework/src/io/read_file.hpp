// Bounded reading of user files. Every reader reads only what the file's real size and header
// allow, and refuses before it allocates: a device (/dev/zero was read forever), a pipe or a
// directory is not a file; a header claiming more points than the file can hold, or than memory
// can, is refused naming the file.
#pragma once

#include <cstdint>
#include <string>

namespace topomill {

// The size of `path`, which must be a regular file of at most `max_bytes` (InputError otherwise;
// `what` names what the file was expected to be, for the message).
std::uint64_t regular_file_size(const std::string& path, std::uint64_t max_bytes,
                                const std::string& what);

// The whole of a regular file of at most `max_bytes`: exactly as many bytes as its size said.
std::string read_file_bounded(const std::string& path, std::uint64_t max_bytes,
                              const std::string& what);

// What reading and measuring a height map costs: about 80 bytes a point (the map, its valid
// mask, form removal's and the filters' copies). Refused, naming the file, above 90 % of the
// memory available (as for `run`: MemAvailable, rlimits, TOPOMILL_MEMORY_LIMIT).
void check_map_memory(const std::string& path, double points);

// 90 % of the memory available: the largest file a reader may hold.
std::uint64_t readable_bytes();

}  // namespace topomill
