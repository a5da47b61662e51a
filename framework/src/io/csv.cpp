#include "io/csv.hpp"

#include <cmath>
#include <fstream>
#include <sstream>

#include "io/atomic_file.hpp"
#include "io/read_file.hpp"
#include "topomill/error.hpp"

namespace topomill {

Surface read_csv(const std::string& path, double spacing) {
  // Each value takes two bytes at least (a digit and a separator).
  const std::string text = read_file_bounded(path, readable_bytes(), "a CSV height map");
  check_map_memory(path, static_cast<double>(text.size()) / 2);
  std::istringstream in(text);
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
      // The whole cell is the number (blanks around it allowed): "1.5abc" is not 1.5, and a
      // line of "1;2;3" or "1 2 3" is not the value 1 (other separators are named).
      const auto first = cell.find_first_not_of(" \t\r");
      const auto last = cell.find_last_not_of(" \t\r");
      const std::string word =
          first == std::string::npos ? std::string() : cell.substr(first, last - first + 1);
      std::size_t used = 0;
      double v = 0;
      try {
        v = std::stod(word, &used);
      } catch (...) {
        used = 0;
      }
      if (used == 0 || used != word.size() || !std::isfinite(v)) {
        std::string hint;
        if (word.find_first_of(";\t ") != std::string::npos)
          hint = " (cells are separated by commas; this one holds ';', a tab or a space)";
        throw InputError(SourceRef{path, line_no, static_cast<int>(count + 1)}, "",
                         "expected a finite number (um), got '" + word + "'" + hint);
      }
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
