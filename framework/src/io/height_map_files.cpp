#include "height_map_files.hpp"

#include <cstring>
#include <sstream>

#include "io/atomic_file.hpp"

namespace topomill {

void write_csv(const std::string& path, const HeightMap& map) {
  write_atomically(path, [&](std::ostream& out) {
    out.precision(9);
    for (std::size_t j = 0; j < map.grid.ny; ++j) {
      for (std::size_t i = 0; i < map.grid.nx; ++i) out << (i ? "," : "") << map.at(i, j) * 1e3;
      out << '\n';
    }
  });
}

void write_gsf(const std::string& path, const HeightMap& map, const std::string& title) {
  const Grid& g = map.grid;
  write_atomically(path, [&](std::ostream& out) {
    std::ostringstream h;
    h.precision(12);
    h << "Gwyddion Simple Field 1.0\n"
      << "XRes = " << g.nx << "\nYRes = " << g.ny << "\nXReal = " << g.dx * g.nx * 1e-3
      << "\nYReal = " << g.dy * g.ny * 1e-3 << "\nXOffset = " << g.x0 * 1e-3
      << "\nYOffset = " << g.y0 * 1e-3 << "\nXYUnits = m\nZUnits = m\nTitle = " << title << "\n";
    std::string header = h.str();
    header.append(4 - header.size() % 4, '\0');  // 1 to 4 NULs, data on a 4-byte boundary
    out.write(header.data(), static_cast<std::streamsize>(header.size()));
    for (double z : map.z) {
      const float f = static_cast<float>(z * 1e-3);
      unsigned char b[4];
      std::uint32_t u;
      std::memcpy(&u, &f, 4);
      for (int k = 0; k < 4; ++k) b[k] = static_cast<unsigned char>(u >> (8 * k));
      out.write(reinterpret_cast<const char*>(b), 4);
    }
  });
}

}  // namespace topomill
