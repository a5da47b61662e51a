#include "metrology/surface.hpp"

#include <algorithm>

namespace topomill {

std::size_t Surface::valid_count() const {
  if (valid.empty()) return map.z.size();
  return static_cast<std::size_t>(std::count(valid.begin(), valid.end(), std::uint8_t{1}));
}

double Surface::mean() const {
  double sum = 0, n = 0;
  for (std::size_t k = 0; k < map.z.size(); ++k)
    if (is_valid(k)) sum += map.z[k], n += 1;
  return n > 0 ? sum / n : 0.0;
}

}  // namespace topomill
