// What code made a result: a checksum of the bytes of the program, the core library and the
// plugin libraries a run used. A resumed sweep compares it with the code it would run now, so a
// rebuild that changed any of them (and only that: not a touched file) reruns the case.
#pragma once

#include <string>
#include <vector>

namespace topomill {

// CRC-32 (hex) over the running program, this core library and `libraries` (in sorted order);
// a file that cannot be read counts as a distinct value, so it never matches a readable one.
std::string code_fingerprint(std::vector<std::string> libraries);

// CRC-32 (hex) of one file's bytes (an unreadable file: a value no readable file gives).
std::string file_checksum(const std::string& path);

}  // namespace topomill
