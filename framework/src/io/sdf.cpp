#include "io/sdf.hpp"

#include <cmath>
#include <cstring>
#include <ctime>
#include <fstream>
#include <map>
#include <sstream>

#include "io/atomic_file.hpp"
#include "io/read_file.hpp"
#include "topomill/error.hpp"

namespace topomill {

namespace {
[[noreturn]] void fail(const std::string& path, const std::string& why) {
  throw InputError(SourceRef{path}, "", why);
}

// Binary header: version[8] ManufacID[10] CreateDate[12] ModDate[12] NumPoints u16 NumProfiles
// u16 Xscale Yscale Zscale Zresolution (double) Compression DataType CheckType (u8): 81 bytes.
constexpr std::size_t kHeader = 81;
constexpr std::size_t kNumPoints = 42, kNumProfiles = 44, kXscale = 46, kYscale = 54, kZscale = 62,
                      kZres = 70, kDataType = 79;

template <class T>
T get(const std::string& b, std::size_t at) {
  T v;
  std::memcpy(&v, b.data() + at, sizeof v);
  return v;
}

void check_dims(const std::string& path, double nx, double ny) {
  if (!(nx >= 1 && ny >= 1 && nx <= 65535 && ny <= 65535 && nx == std::floor(nx) &&
        ny == std::floor(ny)))
    fail(path, "NumPoints and NumProfiles must be whole numbers from 1 to 65535, got " +
                   format_number(nx) + " and " + format_number(ny));
  check_map_memory(path, nx * ny);
}
}  // namespace

Surface read_sdf(const std::string& path) {
  const std::string bytes = read_file_bounded(path, readable_bytes(), "an SDF height map");
  Surface s;
  s.source = path;
  Grid g;
  double zscale = 1;
  if (bytes.rfind("aISO-1.0", 0) == 0) {
    std::istringstream text(bytes);
    std::string line;
    std::getline(text, line);
    std::map<std::string, double> keys;
    while (std::getline(text, line)) {
      if (!line.empty() && line.back() == '\r') line.pop_back();
      if (line == "*") break;
      const auto eq = line.find('=');
      if (eq == std::string::npos) continue;
      std::string key = line.substr(0, eq);
      key.erase(key.find_last_not_of(" \t") + 1);
      try {
        keys[key] = std::stod(line.substr(eq + 1));
      } catch (...) {  // ManufacID and dates are not numbers
      }
    }
    for (const char* k : {"NumPoints", "NumProfiles", "Xscale", "Yscale", "Zscale"})
      if (!keys.count(k)) fail(path, std::string("the header has no ") + k);
    check_dims(path, keys["NumPoints"], keys["NumProfiles"]);
    g.nx = static_cast<std::size_t>(keys["NumPoints"]);
    g.ny = static_cast<std::size_t>(keys["NumProfiles"]);
    g.dx = keys["Xscale"] * 1e3, g.dy = keys["Yscale"] * 1e3;
    zscale = keys["Zscale"];
    // Each point takes two bytes at least (a digit and a separator): a header claiming more than
    // the file can hold is refused before the map is allocated (fuzzing found a 147-byte file
    // asking for 2.2 GB).
    if (g.size() > bytes.size() / 2)
      fail(path, "the header says " + std::to_string(g.nx) + " x " + std::to_string(g.ny) +
                     " points, more than the file's " + std::to_string(bytes.size()) +
                     " bytes can hold");
    s.map = HeightMap(g);
    for (std::size_t i = 0; i < g.size(); ++i) {
      std::string word;
      if (!(text >> word) || word == "*")
        fail(path, "the data section holds " + std::to_string(i) + " points; the header says " +
                       std::to_string(g.size()));
      try {
        s.map.z[i] = std::stod(word) * zscale * 1e3;
      } catch (...) {
        fail(path, "point " + std::to_string(i) + " is not a number: '" + word + "'");
      }
    }
  } else if (bytes.rfind("bISO-1.0", 0) == 0) {
    if (bytes.size() < kHeader) fail(path, "the binary header is truncated");
    const double nx = get<std::uint16_t>(bytes, kNumPoints),
                 ny = get<std::uint16_t>(bytes, kNumProfiles);
    check_dims(path, nx, ny);
    g.nx = static_cast<std::size_t>(nx), g.ny = static_cast<std::size_t>(ny);
    g.dx = get<double>(bytes, kXscale) * 1e3, g.dy = get<double>(bytes, kYscale) * 1e3;
    zscale = get<double>(bytes, kZscale);
    const int type = static_cast<unsigned char>(bytes[kDataType]);
    const std::size_t width = type == 7 ? 8 : type == 6 ? 4 : type == 5 ? 2 : type == 3 ? 4 : 0;
    if (!width) fail(path, "unsupported DataType " + std::to_string(type) + " (5, 6, 3 or 7)");
    if (bytes.size() < kHeader + g.size() * width)
      fail(path, "the data are truncated: " + std::to_string(bytes.size() - kHeader) +
                     " bytes for " + std::to_string(g.size()) + " points of " +
                     std::to_string(width) + " bytes");
    s.map = HeightMap(g);
    for (std::size_t i = 0; i < g.size(); ++i) {
      const std::size_t at = kHeader + i * width;
      double v = 0;
      if (type == 7) v = get<double>(bytes, at);
      if (type == 6) v = get<float>(bytes, at);
      if (type == 5) v = get<std::int16_t>(bytes, at);
      if (type == 3) v = get<std::int32_t>(bytes, at);
      s.map.z[i] = v * zscale * 1e3;
    }
  } else {
    fail(path, "not an ISO 25178-71 file: it starts with neither aISO-1.0 nor bISO-1.0");
  }
  if (!(g.dx > 0 && g.dy > 0 && std::isfinite(g.dx) && std::isfinite(g.dy)))
    fail(path, "Xscale and Yscale must be positive");
  for (std::size_t i = 0; i < g.size(); ++i)
    if (!std::isfinite(s.map.z[i])) fail(path, "point " + std::to_string(i) + " is not finite");
  return s;
}

void write_sdf(const std::string& path, const HeightMap& map, const FileInfo& info) {
  const Grid& g = map.grid;
  if (g.nx > 65535 || g.ny > 65535)
    throw std::runtime_error("sdf holds at most 65535 x 65535 points");
  write_atomically(path, [&](std::ostream& out) {
    std::string h(kHeader, '\0');
    std::memcpy(&h[0], "bISO-1.0", 8);
    std::memcpy(&h[8], "topomill", 8);
    // CreateDate and ModDate: ddmmyyyyhhmm, UTC.
    const std::time_t t = created_time(info);
    std::tm tm{};
    gmtime_r(&t, &tm);
    char date[16];
    std::strftime(date, sizeof date, "%d%m%Y%H%M", &tm);
    std::memcpy(&h[18], date, 12);
    std::memcpy(&h[30], date, 12);
    const std::uint16_t nx = static_cast<std::uint16_t>(g.nx),
                        ny = static_cast<std::uint16_t>(g.ny);
    std::memcpy(&h[kNumPoints], &nx, 2);
    std::memcpy(&h[kNumProfiles], &ny, 2);
    const double xs = g.dx * 1e-3, ys = g.dy * 1e-3, zs = 1.0, zres = 1e-12;
    std::memcpy(&h[kXscale], &xs, 8);
    std::memcpy(&h[kYscale], &ys, 8);
    std::memcpy(&h[kZscale], &zs, 8);
    std::memcpy(&h[kZres], &zres, 8);
    h[kDataType] = 7;  // float64; Compression and CheckType stay 0
    out.write(h.data(), static_cast<std::streamsize>(h.size()));
    for (double z : map.z) {
      const double v = z * 1e-3;
      out.write(reinterpret_cast<const char*>(&v), 8);
    }
  });
}

}  // namespace topomill
