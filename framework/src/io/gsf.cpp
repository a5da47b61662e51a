#include "io/gsf.hpp"

#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>

#include "io/atomic_file.hpp"
#include "io/read_file.hpp"
#include "topomill/error.hpp"

namespace topomill {

namespace {
constexpr const char* kMagic = "Gwyddion Simple Field 1.0\n";
[[noreturn]] void fail(const std::string& path, const std::string& why) {
  throw InputError(SourceRef{path}, "", why);
}
}  // namespace

Surface read_gsf(const std::string& path) {
  const std::string bytes = read_file_bounded(path, readable_bytes(), "a Gwyddion simple field");
  if (bytes.rfind(kMagic, 0) != 0) fail(path, "not a Gwyddion simple field: bad first line");
  const std::size_t nul = bytes.find('\0');
  if (nul == std::string::npos) fail(path, "the header is not terminated by NUL padding");
  std::map<std::string, std::string> keys;
  std::istringstream header(bytes.substr(std::strlen(kMagic), nul - std::strlen(kMagic)));
  std::string line;
  while (std::getline(header, line)) {
    const auto eq = line.find('=');
    if (eq == std::string::npos) continue;
    auto trim = [](std::string s) {
      s.erase(0, s.find_first_not_of(" \t"));
      s.erase(s.find_last_not_of(" \t\r") + 1);
      return s;
    };
    const std::string key = trim(line.substr(0, eq));
    if (!keys.emplace(key, trim(line.substr(eq + 1))).second)
      fail(path, key + " is given twice in the header: expected each key once");
  }
  auto number = [&](const char* key, double fallback) {
    auto it = keys.find(key);
    if (it == keys.end()) return fallback;
    try {
      return std::stod(it->second);
    } catch (...) {
      fail(path, std::string(key) + " is not a number: '" + it->second + "'");
    }
  };
  const double xres = number("XRes", -1), yres = number("YRes", -1);
  if (!keys.count("XRes") || !keys.count("YRes")) fail(path, "XRes and YRes must be given");
  for (const double res : {xres, yres})
    if (!(res >= 1 && res == std::floor(res) && res <= 1e8))
      fail(path, "XRes and YRes must be whole numbers from 1 to 1e8, got " + format_number(res));
  if (xres * yres > 4e8)
    fail(path, "XRes x YRes = " + format_number(xres * yres) + " points: expected at most 4e8");
  const std::size_t data_at = (nul / 4 + 1) * 4;  // the first 4-byte boundary after the header
  Grid g;
  g.nx = static_cast<std::size_t>(xres), g.ny = static_cast<std::size_t>(yres);
  g.dx = number("XReal", xres) / xres * 1e3, g.dy = number("YReal", yres) / yres * 1e3;
  g.x0 = number("XOffset", 0) * 1e3, g.y0 = number("YOffset", 0) * 1e3;
  if (!(g.dx > 0 && g.dy > 0)) fail(path, "XReal and YReal must be positive");
  if (bytes.size() < data_at + g.size() * 4)
    fail(path, "the data are truncated: " +
                   std::to_string(bytes.size() - std::min(bytes.size(), data_at)) + " bytes for " +
                   std::to_string(g.size()) + " float32 points");
  if (bytes.size() > data_at + g.size() * 4)
    fail(path, std::to_string(bytes.size() - data_at - g.size() * 4) + " bytes follow the " +
                   std::to_string(g.size()) +
                   " float32 points: expected none (is XRes or YRes wrong?)");
  check_map_memory(path, static_cast<double>(g.size()));
  Surface s;
  s.source = path;
  s.map = HeightMap(g);
  for (std::size_t i = 0; i < g.size(); ++i) {
    float f;
    std::memcpy(&f, bytes.data() + data_at + 4 * i, 4);
    if (!std::isfinite(f)) fail(path, "point " + std::to_string(i) + " is not finite");
    s.map.z[i] = static_cast<double>(f) * 1e3;
  }
  return s;
}

void write_gsf(const std::string& path, const HeightMap& map, const FileInfo& info) {
  const Grid& g = map.grid;
  write_atomically(path, [&](std::ostream& out) {
    std::ostringstream h;
    h.precision(12);
    h << kMagic << "XRes = " << g.nx << "\nYRes = " << g.ny << "\nXReal = " << g.dx * g.nx * 1e-3
      << "\nYReal = " << g.dy * g.ny * 1e-3 << "\nXOffset = " << g.x0 * 1e-3
      << "\nYOffset = " << g.y0 * 1e-3 << "\nXYUnits = m\nZUnits = m\nTitle = "
      << one_line(info.title.empty() ? "height" : info.title) << "\nCreator = " << file_creator()
      << "\nDate = " << iso8601_utc(created_time(info)) << "\n";
    if (!info.description.empty()) h << "Scene = " << one_line(info.description) << "\n";
    std::string header = h.str();
    header.append(4 - header.size() % 4, '\0');  // 1 to 4 NULs, data on a 4-byte boundary
    out.write(header.data(), static_cast<std::streamsize>(header.size()));
    for (double z : map.z) {
      const float f = static_cast<float>(z * 1e-3);
      out.write(reinterpret_cast<const char*>(&f), 4);  // x86-64 and aarch64: little-endian
    }
  });
}

}  // namespace topomill
