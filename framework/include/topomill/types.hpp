// Small value types shared by the slots: vectors, the node grid, and height maps.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <vector>

namespace topomill {

// Positions in mm in the workpiece frame CS2 (X cross-feed, Y feed, Z up) unless stated.
using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;

// A regular grid of nodes over the XY projection; node (i, j) is at (x0 + i dx, y0 + j dy).
struct Grid {
  std::size_t nx = 0, ny = 0;
  double x0 = 0, y0 = 0, dx = 0, dy = 0;

  std::size_t size() const { return nx * ny; }
  double x(std::size_t i) const { return x0 + static_cast<double>(i) * dx; }
  double y(std::size_t j) const { return y0 + static_cast<double>(j) * dy; }
  std::size_t index(std::size_t i, std::size_t j) const { return j * nx + i; }
};

// Heights (mm) on a grid, x fastest.
struct HeightMap {
  Grid grid;
  std::vector<double> z;

  explicit HeightMap(const Grid& g = {}, double fill = 0.0) : grid(g), z(g.size(), fill) {}
  double& at(std::size_t i, std::size_t j) { return z[grid.index(i, j)]; }
  double at(std::size_t i, std::size_t j) const { return z[grid.index(i, j)]; }
};

}  // namespace topomill
