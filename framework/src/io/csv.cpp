#include "io/csv.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>

#include "io/atomic_file.hpp"
#include "io/read_file.hpp"
#include "topomill/error.hpp"

namespace topomill {

namespace {
// `word`, all of it, as a finite number; denormals (which strtod flags as a range error, and
// std::stod refused as "not finite") are numbers like any other.
bool whole_finite_number(const std::string& word, double& v) {
  if (word.empty()) return false;
  char* end = nullptr;
  errno = 0;
  v = std::strtod(word.c_str(), &end);
  return end == word.c_str() + word.size() && std::isfinite(v);
}
}  // namespace

Surface read_csv(const std::string& path, double spacing) {
  // Each value takes two bytes at least (a digit and a separator).
  const std::string text = read_file_bounded(path, readable_bytes(), "a CSV height map");
  check_map_memory(path, static_cast<double>(text.size()) / 2);
  std::istringstream in(text);
  std::vector<double> z;
  std::size_t nx = 0, ny = 0;
  std::string line;
  int line_no = 0;
  // The header's grid: key -> (value, line).
  std::map<std::string, std::pair<double, int>> header;
  while (std::getline(in, line)) {
    ++line_no;
    if (!line.empty() && line[0] == '#') {
      std::istringstream h(line.substr(1));
      std::string key, eq, value;
      if (h >> key >> eq >> value && eq == "=" &&
          (key == "x0_mm" || key == "y0_mm" || key == "dx_mm" || key == "dy_mm")) {
        double v = NAN;
        const bool step = key[0] == 'd';
        if (!whole_finite_number(value, v) || (step && !(v > 0)) || std::abs(v) > 1e6)
          throw InputError(SourceRef{path, line_no, 1}, key,
                           "expected " +
                               std::string(step ? "a spacing above 0" : "a finite coordinate") +
                               " in mm (at most 1e6), got '" + value + "'");
        header[key] = {v, line_no};
      }
      continue;
    }
    if (line.empty()) continue;
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
      double v = 0;
      if (!whole_finite_number(word, v)) {
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
  auto from_header = [&](const char* key, double& target) {
    const auto it = header.find(key);
    if (it == header.end()) return;
    if (spacing > 0 && key[0] == 'd' && std::abs(it->second.first - spacing) > 1e-9 * spacing)
      throw InputError(SourceRef{"command line"}, "--spacing",
                       "the file's header gives " + std::string(key) + " = " +
                           format_number(it->second.first) + " (" + path + ":" +
                           std::to_string(it->second.second) + "), not " + format_number(spacing) +
                           ": leave --spacing out to use the file's grid");
    target = it->second.first;
  };
  from_header("dx_mm", g.dx), from_header("dy_mm", g.dy);
  from_header("x0_mm", g.x0), from_header("y0_mm", g.y0);
  if (!(g.dx > 0 && g.dy > 0))
    throw InputError(SourceRef{path}, "--spacing",
                     "the file has no grid header (# dx_mm = ..., # dy_mm = ...): give the node "
                     "spacing in mm");
  s.map = HeightMap(g);
  s.map.z = std::move(z);
  return s;
}

void write_csv(const std::string& path, const HeightMap& map, const FileInfo& info) {
  const Grid& g = map.grid;
  write_atomically(path, [&](std::ostream& out) {
    out << "# " << one_line(info.title.empty() ? "height map" : info.title) << ", written by "
        << file_creator() << " at " << iso8601_utc(created_time(info)) << "\n";
    if (!info.description.empty()) out << "# " << one_line(info.description) << "\n";
    out << "# heights in um; row j at y = y0_mm + j dy_mm, column i at x = x0_mm + i dx_mm\n"
        << "# x0_mm = " << exact_text(g.x0) << "\n# y0_mm = " << exact_text(g.y0)
        << "\n# dx_mm = " << exact_text(g.dx) << "\n# dy_mm = " << exact_text(g.dy) << "\n";
    std::string row;
    for (std::size_t j = 0; j < g.ny; ++j) {
      row.clear();
      for (std::size_t i = 0; i < g.nx; ++i) {
        if (i) row += ',';
        row += exact_text(map.at(i, j) * 1e3);
      }
      row += '\n';
      out << row;
    }
  });
}

}  // namespace topomill
