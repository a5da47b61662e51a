// ISO 25178-2 areal parameters of a height map, no levelling or filtering, every node used.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "topomill/types.hpp"

namespace topomill {

// Heights and lengths in the map's units; Ssk, Sku, Sdq dimensionless; Sdr in percent.
//  Sdq: forward differences over all horizontal and vertical neighbour pairs,
//       sqrt(2 (sum (dz/dx)^2 + sum (dz/dy)^2) / n), n = (nx-1) ny + nx (ny-1).
//  Sdr: each of the (nx-1)(ny-1) cells split into two triangles along its (i, j)-(i+1, j+1)
//       diagonal (the refdata README's "two triangles per cell" value, 0.1920252626 % for
//       x3p-2.x3p; Gwyddion's four-triangle scheme with border strips gives 0.18874 %).
struct Roughness {
  double mean = 0, Sa = 0, Sq = 0, Sp = 0, Sv = 0, Sz = 0, Ssk = 0, Sku = 0, Sdq = 0, Sdr = 0;
  std::map<std::string, double> named() const;
  // As reported (summary.json, measure --json): heights in um from a map in mm, the rest as is.
  std::map<std::string, double> reported_um() const;
};

// `valid` (one per node, 1 = valid) restricts every sum to the valid nodes: slopes to pairs of
// valid neighbours, areas to cells with four valid corners. Empty: every node counts.
Roughness roughness(const HeightMap& map, const std::vector<std::uint8_t>& valid = {});

}  // namespace topomill
