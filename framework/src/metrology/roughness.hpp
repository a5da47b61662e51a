// ISO 25178-2 areal parameters of a height map, no levelling or filtering, every node used.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "topomill/types.hpp"

namespace topomill {

// Heights and lengths in the map's units; Ssk, Sku, Sdq dimensionless; Sdr in percent.
//  Sdq: forward differences over all horizontal and vertical neighbour pairs,
//       sqrt(2 (sum (dz/dx)^2 + sum (dz/dy)^2) / n), n = (nx-1) ny + nx (ny-1).
//  Sdr: each of the (nx-1)(ny-1) cells split into two triangles along its (i, j)-(i+1, j+1)
//       diagonal (the refdata README's "two triangles per cell" value, 0.1920252626 % for
//       x3p-2.x3p).
//  Sdr_gwyddion: Gwyddion's surface area, which users compare with: each cell split into four
//       triangles from its edges to its centre at the corners' mean height, plus half-cell strips
//       beyond the border nodes (the heights carried outwards) and flat corner quarters, over the
//       nx ny cells of area dx dy around the nodes (0.1887367719 % for x3p-2.x3p). With invalid
//       nodes: only cells with four valid corners and strips along two valid nodes count.
struct Roughness {
  double mean = 0, Sa = 0, Sq = 0, Sp = 0, Sv = 0, Sz = 0, Ssk = 0, Sku = 0, Sdq = 0, Sdr = 0,
         Sdr_gwyddion = 0;
  // What the parameters were taken over: whether the heights vary beyond their round-off (Ssk
  // and Sku divide by Sq), the pairs of valid neighbours (Sdq), and the cells with four valid
  // corners (Sdr) and Gwyddion's cells and strips (Sdr_gwyddion). Where one is missing, its
  // parameters are undefined, not 0 or 1.
  bool relief = false;
  double pairs = 0, cells = 0, gwyddion_cells = 0;

  // One parameter as reported (summary.json, measure --json, the console).
  struct Reported {
    std::string name;
    double value;        // heights in um from a map in mm; the rest as computed
    std::string unit;    // "um", "%", or "1" (dimensionless)
    std::string method;  // the discretisation, where more than one is in use; else empty
  };
  // In the order the console prints them; the undefined ones left out.
  std::vector<Reported> reported() const;
  // The parameters undefined for this map, each with why.
  std::vector<std::pair<std::string, std::string>> undefined() const;
};

// `valid` (one per node, 1 = valid) restricts every sum to the valid nodes: slopes to pairs of
// valid neighbours, areas to cells with four valid corners. Empty: every node counts.
Roughness roughness(const HeightMap& map, const std::vector<std::uint8_t>& valid = {});

}  // namespace topomill
