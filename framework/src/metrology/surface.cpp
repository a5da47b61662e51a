#include "metrology/surface.hpp"

#include <algorithm>

namespace topomill {

std::size_t Surface::valid_count() const {
  if (valid.empty()) return map.z.size();
  return static_cast<std::size_t>(std::count(valid.begin(), valid.end(), std::uint8_t{1}));
}

}  // namespace topomill
