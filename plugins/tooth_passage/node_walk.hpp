// The reference walk: each node from scratch, every pass within reach, the envelope's bottom by
// golden section, passages visited outwards until heights rise twice. The row walk
// (row_sweep.hpp) must give its heights.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "passage_geometry.hpp"

namespace topomill::plugins {

// Work done by one thread, added up at the end (summary.json's work counts).
struct NodeCounts {
  std::uint64_t passages = 0;       // tooth passages whose height was read
  std::uint64_t fallbacks = 0;      // node-pass pairs handed to the reference walk
  std::uint64_t exact_windows = 0;  // row walk: revolutions solved exactly (near the axis)
  std::uint64_t updates = 0;        // nodes lowered
  // Row walk, per node, the route it took: every passage followed from the node before; some
  // revolution solved exactly in place; some pass handed to the reference walk.
  std::uint64_t nodes_followed = 0, nodes_exact = 0, nodes_fallback = 0;
  NodeCounts& operator+=(const NodeCounts& o) {
    passages += o.passages, fallbacks += o.fallbacks, exact_windows += o.exact_windows;
    updates += o.updates, nodes_followed += o.nodes_followed, nodes_exact += o.nodes_exact;
    nodes_fallback += o.nodes_fallback;
    return *this;
  }
};

// The lowest edge height over (x, y), +inf if none; `order` and `roots` are the caller's
// scratch, so that a node allocates nothing.
double node_height_reference(const PassageSetup& s, double x, double y, NodeCounts& counts,
                             std::vector<std::pair<double, std::size_t>>& order,
                             std::vector<PassageGeometry::Crossing>& roots);

// The same by brute force, to check the walks' stopping rules: every pass within reach, every
// tooth, g sampled every `step` seconds over all the time the ball can be over the node, each
// sign change bisected. Finds every crossing (several per passage too, where a fast correction
// turns the node's azimuth back) whose roots lie more than a step apart. Thousands of times
// slower than the walks.
double node_height_scan(const PassageSetup& s, double x, double y, double step, NodeCounts& counts);

}  // namespace topomill::plugins
