// Versions. The ABI version changes whenever a public header changes a layout or a virtual
// function that plugins compile against; a plugin built for another ABI is refused at load time.
#pragma once

#include <cstdint>

#define TOPOMILL_VERSION_STRING "0.1.0"
#define TOPOMILL_ABI_VERSION 13u

namespace topomill {
inline constexpr std::uint32_t kAbiVersion = TOPOMILL_ABI_VERSION;
inline constexpr const char* kVersion = TOPOMILL_VERSION_STRING;
}  // namespace topomill
