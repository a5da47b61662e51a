// ISO 25178-2 areal parameters of a height map, no levelling or filtering, every node used.
#pragma once

#include <map>
#include <string>

#include "topomill/types.hpp"

namespace topomill {

// Heights and lengths in the map's units; Ssk, Sku, Sdq dimensionless; Sdr in percent.
//  Sdq: forward differences over all horizontal and vertical neighbour pairs,
//       sqrt(2 (sum (dz/dx)^2 + sum (dz/dy)^2) / n), n = (nx-1) ny + nx (ny-1).
//  Sdr: each cell split into four triangles around its centre (height = mean of its corners),
//       over the (nx-1)(ny-1) cells.
struct Roughness {
  double mean = 0, Sa = 0, Sq = 0, Sp = 0, Sv = 0, Sz = 0, Ssk = 0, Sku = 0, Sdq = 0, Sdr = 0;
  std::map<std::string, double> named() const;
};

Roughness roughness(const HeightMap& map);

}  // namespace topomill
