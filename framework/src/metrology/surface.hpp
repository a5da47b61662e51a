// A measured or simulated height map with its valid-point mask, as the metrology code sees it.
// Lengths and heights in mm, like everything inside topomill.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "topomill/types.hpp"

namespace topomill {

struct Surface {
  HeightMap map;
  std::vector<std::uint8_t> valid;  // one per node, 1 = valid; empty = every node valid
  std::string source;               // file name, for messages

  bool is_valid(std::size_t index) const { return valid.empty() || valid[index] != 0; }
  std::size_t valid_count() const;
  // The mean of the valid heights (0 when there are none), summed in node order.
  double mean() const;
};

}  // namespace topomill
