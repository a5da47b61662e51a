#include "metrology/write_surface.hpp"

#include <cctype>
#include <filesystem>

#include "io/csv.hpp"
#include "io/gsf.hpp"
#include "io/sdf.hpp"
#include "io/x3p.hpp"
#include "topomill/error.hpp"

namespace topomill {

namespace {
std::string extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}
}  // namespace

void check_surface_format(const std::string& path, const std::string& option) {
  const std::string ext = extension(path);
  if (ext != ".x3p" && ext != ".gsf" && ext != ".sdf" && ext != ".csv")
    throw InputError(
        SourceRef{"command line"}, option,
        "cannot write '" + path + "': expected a name ending .x3p, .gsf, .sdf or .csv");
}

void write_surface(const std::string& path, const Surface& surface, const std::string& option,
                   const std::string& description) {
  check_surface_format(path, option);
  const SourceRef cli{"command line"};
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw InputError(cli, option,
                     "'" + path +
                         "' is a directory: expected a file name (a new one, or a file "
                         "to replace)");
  const std::string ext = extension(path);
  FileInfo info;
  info.title = "topomill processed surface";
  info.description = description;
  const std::size_t missing = surface.map.z.size() - surface.valid_count();
  if (missing > 0 && ext != ".x3p")
    throw InputError(cli, option,
                     "the surface has " + std::to_string(missing) + " missing points, which " +
                         ext + " cannot mark: expected a name ending .x3p");
  // Where the file cannot be made (no such directory, no permission, a read-only disk) the user
  // chose the place: said as bad input, at the option.
  try {
    if (ext == ".x3p") return write_x3p(path, surface.map, info, surface.valid);
    if (ext == ".gsf") return write_gsf(path, surface.map, info);
    if (ext == ".sdf") return write_sdf(path, surface.map, info);
    write_csv(path, surface.map, info);
  } catch (const std::filesystem::filesystem_error& e) {
    throw InputError(cli, option,
                     "cannot write '" + path + "': " + e.code().message() +
                         ": expected a file in a directory that exists and you may write");
  }
}

}  // namespace topomill
