#include "metrology/read_surface.hpp"

#include <filesystem>

#include "io/csv.hpp"
#include "io/gsf.hpp"
#include "io/sdf.hpp"
#include "io/x3p.hpp"
#include "topomill/error.hpp"

namespace topomill {

Surface read_surface(const std::string& path, double csv_spacing) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext == ".x3p") return read_x3p(path);
  if (ext == ".sdf") return read_sdf(path);
  if (ext == ".gsf") return read_gsf(path);
  if (ext == ".csv") {
    return read_csv(path, csv_spacing);  // its header's grid, else csv_spacing
  }
  throw InputError(SourceRef{path}, "",
                   "unknown format '" + ext + "': expected .x3p, .sdf, .gsf or .csv");
}

}  // namespace topomill
