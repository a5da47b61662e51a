// Fuzz target: cl_file's reader of cutter-location data, both forms (CSV and APT CL) on the same
// bytes. A refusal (ReadError) is the expected answer to a damaged file; anything else escaping,
// a crash, a sanitizer report or a hang is a finding. A file that reads must hold finite points,
// unit axes, positive feeds where given, and passes of two points at least.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "cl_file/cl_reader.hpp"

namespace cl = topomill::plugins::cl;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  for (const cl::Format f : {cl::Format::Csv, cl::Format::Apt}) {
    try {
      const cl::Data d = cl::read_text(text, f);
      for (const auto& pass : d.passes) {
        if (pass.size() < 2) throw std::logic_error("a pass of fewer than two points");
        for (const cl::Point& p : pass) {
          if (!p.position.allFinite()) throw std::logic_error("a point that is not finite");
          if (!(std::abs(p.axis.norm() - 1) < 1e-12)) throw std::logic_error("an axis not unit");
          if (!std::isnan(p.feed) && !(p.feed > 0 && std::isfinite(p.feed)))
            throw std::logic_error("a feed that is not positive");
        }
      }
    } catch (const cl::ReadError&) {
    }
  }
  return 0;
}
