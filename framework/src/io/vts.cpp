#include "io/vts.hpp"

#include "io/atomic_file.hpp"

namespace topomill {

void write_vts(const std::string& path, const HeightMap& map) {
  const Grid& g = map.grid;
  write_atomically(path, [&](std::ostream& out) {
    const std::string extent =
        "0 " + std::to_string(g.nx - 1) + " 0 " + std::to_string(g.ny - 1) + " 0 0";
    out.precision(10);
    out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"StructuredGrid\" version=\"0.1\" "
           "byte_order=\"LittleEndian\">\n<StructuredGrid WholeExtent=\""
        << extent << "\">\n"
        << "<Piece Extent=\"" << extent << "\">\n<PointData Scalars=\"height_um\">\n"
        << "<DataArray type=\"Float64\" Name=\"height_um\" format=\"ascii\">\n";
    for (double z : map.z) out << z * 1e3 << '\n';
    out << "</DataArray>\n</PointData>\n<Points>\n"
        << "<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
    for (std::size_t j = 0; j < g.ny; ++j)
      for (std::size_t i = 0; i < g.nx; ++i)
        out << g.x(i) << ' ' << g.y(j) << ' ' << map.at(i, j) << '\n';
    out << "</DataArray>\n</Points>\n</Piece>\n</StructuredGrid>\n</VTKFile>\n";
  });
}

}  // namespace topomill
