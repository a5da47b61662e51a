#include "io/csv.hpp"

#include <cmath>
#include <fstream>
#include <sstream>

#include "io/atomic_file.hpp"
#include "topomill/error.hpp"

namespace topomill {

Surface read_csv(const std::string& path, double spacing) {
  std::ifstream in(path);
  if (!in) throw InputError(SourceRef{path}, "", "cannot read the file");
  std::vector<double> z;
  std::size_t nx = 0, ny = 0;
  std::string line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    if (line.empty() || line[0] == '#') continue;
    std::stringstream cells(line);
    std::string cell;
    std::size_t count = 0;
    while (std::getline(cells, cell, ',')) {
      std::size_t used = 0;
      double v = 0;
      try {
        v = std::stod(cell, &used);
      } catch (...) {
        used = 0;
      }
      if (used == 0 || !std::isfinite(v))
        throw InputError(SourceRef{path, line_no, static_cast<int>(count + 1)}, "",
                         "expected a finite number (um), got '" + cell + "'");
      z.push_back(v * 1e-3);
      ++count;
    }
    if (nx == 0) nx = count;
    if (count != nx)
      throw InputError(
          SourceRef{path, line_no, 1}, "",
          "row has " + std::to_string(count) + " values; the first has " + std::to_string(nx));
    ++ny;
  }
  if (nx == 0) throw InputError(SourceRef{path}, "", "no data");
  Surface s;
  s.source = path;
  Grid g;
  g.nx = nx, g.ny = ny, g.dx = spacing, g.dy = spacing;
  s.map = HeightMap(g);
  s.map.z = std::move(z);
  return s;
}

void write_csv(const std::string& path, const HeightMap& map) {
  write_atomically(path, [&](std::ostream& out) {
    out.precision(9);
    for (std::size_t j = 0; j < map.grid.ny; ++j) {
      for (std::size_t i = 0; i < map.grid.nx; ++i) out << (i ? "," : "") << map.at(i, j) * 1e3;
      out << '\n';
    }
  });
}

}  // namespace topomill
