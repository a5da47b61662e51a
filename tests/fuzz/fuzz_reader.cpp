// Fuzz target: one height-map reader (TOPOMILL_FUZZ_FORMAT: x3p, sdf, gsf or csv). The bytes are
// written to a file, as the readers take paths, and read. A refusal (InputError) is the expected
// answer to a damaged file; anything else escaping, a crash, a sanitizer report or a hang is a
// finding. A file that reads must hold only finite heights at its valid points.
#include <unistd.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <string>

#include "metrology/read_surface.hpp"
#include "topomill/error.hpp"

#ifndef TOPOMILL_FUZZ_FORMAT
#error "define TOPOMILL_FUZZ_FORMAT (x3p, sdf, gsf or csv)"
#endif
#define TOPOMILL_STR2(x) #x
#define TOPOMILL_STR(x) TOPOMILL_STR2(x)

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string path =
      "/tmp/topomill_fuzz_" + std::to_string(getpid()) + "." + TOPOMILL_STR(TOPOMILL_FUZZ_FORMAT);
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  try {
    const topomill::Surface s = topomill::read_surface(path, 0.001);
    for (std::size_t i = 0; i < s.map.z.size(); ++i)
      if (s.is_valid(i) && !std::isfinite(s.map.z[i]))
        throw std::logic_error("a valid point with a non-finite height");
  } catch (const topomill::InputError&) {
  }
  std::remove(path.c_str());
  return 0;
}
