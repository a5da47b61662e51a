// The keys every cutter's schema shares: its number of teeth and, where it has one, the helix.
#pragma once

#include <cstdint>

#include "topomill/params.hpp"

namespace topomill::plugins {

inline void add_teeth(Schema& s, const char* doc = "Number of teeth N, evenly spaced") {
  s.add_integer("teeth", doc).at_least(1).at_most(64).with_default(std::int64_t{2});
}

inline void add_helix(Schema& s, const char* doc) {
  s.add_number("helix_angle", doc).with_unit("deg").at_least(0).below(90).with_default(30.0);
}

}  // namespace topomill::plugins
