#include "io/read_file.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>

#include "resources.hpp"
#include "topomill/error.hpp"

namespace topomill {

namespace {
// What measuring a map takes at its peak, per point: measured 121 bytes for --parameters all on
// a 2049 x 2049 map without missing points (the ACF's field padded 1.5x each way, its spectrum
// and sums; the PSD is held within 2^22 padded values), and about 55 more with missing points
// (the ACF counts each lag's pairs by a second transform).
constexpr double kBytesPerPoint = 180;
}

std::uint64_t readable_bytes() {
  return static_cast<std::uint64_t>(0.9 * static_cast<double>(available_memory()));
}

std::uint64_t regular_file_size(const std::string& path, std::uint64_t max_bytes,
                                const std::string& what) {
  struct stat st {};
  if (stat(path.c_str(), &st) != 0)
    throw InputError(SourceRef{path}, "",
                     std::string("cannot read the file: ") + std::strerror(errno));
  if (!S_ISREG(st.st_mode))
    throw InputError(SourceRef{path}, "",
                     std::string(S_ISDIR(st.st_mode) ? "is a directory"
                                                     : "is not a regular file "
                                                       "(a device or a pipe)") +
                         ": expected " + what);
  const auto size = static_cast<std::uint64_t>(st.st_size);
  if (size > max_bytes)
    throw InputError(SourceRef{path}, "",
                     "the file is " + format_bytes(static_cast<double>(size)) + ", more than the " +
                         format_bytes(static_cast<double>(max_bytes)) + " allowed: expected " +
                         what);
  return size;
}

std::string read_file_bounded(const std::string& path, std::uint64_t max_bytes,
                              const std::string& what) {
  const std::uint64_t size = regular_file_size(path, max_bytes, what);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(SourceRef{path}, "", "cannot read the file");
  std::string bytes(size, '\0');
  in.read(bytes.data(), static_cast<std::streamsize>(size));
  bytes.resize(static_cast<std::size_t>(in.gcount()));  // a file that shrank meanwhile
  return bytes;
}

void check_map_memory(const std::string& path, double points) {
  const double need = points * kBytesPerPoint;
  const double available = static_cast<double>(available_memory());
  if (need <= 0.9 * available) return;
  throw InputError(SourceRef{path}, "",
                   "the map has " + format_number(points) +
                       " points: reading and measuring it "
                       "needs about " +
                       format_bytes(need) + ", and " + format_bytes(available) +
                       " are available (TOPOMILL_MEMORY_LIMIT sets the limit)");
}

}  // namespace topomill
